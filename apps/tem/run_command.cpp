// `tem run`: simulates a scene and writes its results (interface.md) into a directory, then
// prints a summary: steps, speed, the time of each stage of the step, the contact solver's
// sweeps.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "commands.hpp"
#include "contact/initial_overlap.hpp"
#include "forces/penalty.hpp"
#include "io/checkpoint.hpp"
#include "io/run_output.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"
#include "support/parallel.hpp"
#include "world/state_hash.hpp"
#include "simulation/step.hpp"

namespace tem::cli {
namespace {

void print_summary(const Model& model, const State& state, const Workspace& w, double wall) {
  const StageTimes& t = w.times;
  const double steps = static_cast<double>(std::max<long long>(t.steps, 1));
  const Energies e = system_energies(model, state);
  std::fprintf(stderr,
               "tem run: %lld steps to t = %.6g s in %.3f s (%.0f steps/s, %.2f us/step)\n"
               "  per step: broad phase %.2f us, narrow phase + patches %.2f us, forces %.2f us, "
               "integration %.2f us\n"
               "  contact solver: %.2f sweeps per step on average, %d at most, %lld steps "
               "unconverged, %lld scaled to add no energy\n"
               "  contacts: %.1f patches and %.1f points per step on average, %.2f us per patch "
               "(all stages)\n"
               "  final energy: kinetic %.9g, potential %.9g, total %.9g\n",
               t.steps, state.time, wall, t.steps / std::max(wall, 1e-9), 1e6 * wall / steps,
               1e6 * t.broad_phase / steps, 1e6 * t.narrow_phase / steps, 1e6 * t.forces / steps,
               1e6 * t.integrate / steps, static_cast<double>(t.sweeps) / steps, t.max_sweeps,
               t.unconverged_steps, t.scaled_steps, t.patches / steps, t.points / steps,
               t.patches > 0 ? 1e6 * wall / static_cast<double>(t.patches) : 0.0, e.kinetic,
               e.potential, e.total());
  if (t.outran_margin > 0)
    std::fprintf(stderr,
                 "  warning: %lld times a body moved farther in one step than its contact margin "
                 "covered (it may have met a contact already overlapping); a smaller time_step "
                 "or a larger contact.margin avoids it\n",
                 t.outran_margin);
}

// The penalty model is explicit: above a tenth of the contact's period it goes unstable.
void warn_about_time_step(const std::string& scene_file, const Model& model) {
  const SceneDef& scene = model.scene;
  if (scene.contact.model != ContactModel::penalty) return;
  const Real limit = penalty_time_step_limit(model);
  if (scene.time_step > limit)
    std::cerr << scene_file << ": warning: time_step " << scene.time_step
              << " is above the penalty contact's stable limit " << limit
              << " (a tenth of the contact oscillation period 2 pi sqrt(m/k) of the lightest "
                 "body); bodies may bounce off or pass through each other\n";
}

}  // namespace

int run_command(const std::string& scene_file, const std::string& out_dir, bool contacts,
                bool resume, bool hash, int threads) {
  // One thread unless asked: several `tem run` side by side (a parameter sweep, ctest -j) each
  // spinning up a thread per core would fight over the cores.
  if (threads < 0 && !std::getenv("OMP_NUM_THREADS")) threads = 1;
  if (threads == 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  set_threads(threads);
  const std::optional<Model> loaded = load_model(scene_file);
  if (!loaded) return kExitBadInput;
  const Model& model = *loaded;
  print_warnings(scene_file, model);
  const SceneDef& scene = model.scene;
  warn_about_time_step(scene_file, model);

  const long long total_steps = std::llround(scene.duration / scene.time_step);
  const long long every = std::max<long long>(1, std::llround(scene.output.interval / scene.time_step));
  const long long checkpoint_every =
      scene.output.checkpoint_interval > 0
          ? std::max<long long>(1, std::llround(scene.output.checkpoint_interval / scene.time_step))
          : 0;
  const std::string checkpoint_file = out_dir + "/checkpoint.bin";
  State state;
  Workspace workspace;
  std::optional<Checkpoint> resumed;
  try {
    if (resume) {
      resumed = read_checkpoint(checkpoint_file);
      if (resumed->scene_fingerprint != scene_fingerprint(scene))
        throw std::runtime_error(checkpoint_file + " was taken of another scene than " +
                                 scene_file + " (only duration and checkpoint_interval may change)");
      if (resumed->state.bodies.size() != model.bodies.size() ||
          resumed->state.step > total_steps)
        throw std::runtime_error(checkpoint_file + " is at step " +
                                 std::to_string(resumed->state.step) + ", beyond the scene's " +
                                 std::to_string(total_steps) + " steps");
      if ((resumed->sizes.contacts >= 0) != contacts)
        throw std::runtime_error(std::string("the run in ") + out_dir + " was started " +
                                 (contacts ? "without" : "with") +
                                 " --contacts; resume it the same way");
      state = resumed->state;
      restore_memory(*resumed, workspace.forces);
      std::cerr << "tem run: resuming at step " << state.step << " (t = " << state.time
                << " s) from " << checkpoint_file << "\n";
    } else {
      state = initial_state(model);
      for (const InitialOverlap& o : deep_initial_overlaps(model))
        std::cerr << scene_file << ": warning: " << describe(model, o) << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "tem run: " << e.what() << "\n";
    return kExitBadInput;
  }

  StopOnSignal stop;
  try {
    RunOutput output(out_dir, model, contacts, resumed ? &*resumed : nullptr);
    auto save_checkpoint = [&] {
      write_checkpoint(checkpoint_file,
                       make_checkpoint(scene, state, workspace.forces, output.sizes()));
    };
    const long long first_step = state.step;
    Progress progress(static_cast<double>(total_steps) * scene.time_step, first_step);
    const auto start = std::chrono::steady_clock::now();
    for (long long k = first_step;; ++k) {
      // Checkpoints are taken where a step begins, before its rows are written: resuming from
      // one redoes that step's rows exactly.
      if (stop.requested()) {
        save_checkpoint();
        progress.finish();
        std::cerr << "tem run: stopped by signal at step " << k << " (t = " << state.time
                  << " s); every file in " << out_dir << " is complete up to there.\n"
                  << "  continue with: tem run " << scene_file << " --out " << out_dir
                  << (contacts ? " --contacts" : "") << " --resume\n";
        return kExitInterrupted;
      }
      if ((checkpoint_every > 0 && k % checkpoint_every == 0 && k != first_step) ||
          k == total_steps)
        save_checkpoint();
      find_contact_forces(model, state, workspace);
      if (k % every == 0 || k == total_steps) output.write(model, state, workspace);
      if (k == total_steps) break;
      advance(model, state, workspace);
      const int bad = first_non_finite_body(state);
      if (bad >= 0) {
        progress.finish();
        std::cerr << scene_file << ": the state of body '" << model.bodies[bad].name
                  << "' stopped being finite at step " << state.step << " (t = " << state.time
                  << " s); the results up to the last output row are in " << out_dir << "\n";
        return kExitFailed;
      }
      progress.update(state.step, state.time);
    }
    progress.finish();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    print_summary(model, state, workspace, wall);
    std::cerr << "tem run: results in " << out_dir << "/ (bodies.csv, energy.csv"
              << (contacts ? ", contacts.csv" : "") << ", scene.json, checkpoint.bin"
              << (scene.output.paraview ? ", tem.pvd and paraview/ for ParaView" : "") << ")\n";
    if (hash) std::cout << "hash: " << hash_hex(state_hash(state)) << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "tem run: " << e.what() << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace tem::cli
