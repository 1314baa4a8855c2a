// `tem run`: simulates a scene and writes its results (interface.md) into a directory, then
// prints a summary: steps, speed, the time of each stage of the step, the contact solver's
// sweeps.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"
#include "tem/simulation.hpp"
#ifdef TEM_MPI
#include "tem/distributed.hpp"
#endif

namespace tem::cli {
namespace {

void print_summary(const Simulation& sim, double wall) {
  const RunStatistics t = sim.run_statistics();
  const SceneDef& scene = sim.scene();
  const double steps = static_cast<double>(std::max<long long>(t.steps, 1));
  const SystemEnergies e = sim.energies();
  const char* iterations =
      scene.contact.solver == ContactSolver::newton ? "Newton iterations" : "sweeps";
  std::fprintf(stderr,
               "tem run: %lld steps to t = %.6g s in %.3f s (%.0f steps/s, %.2f us/step)\n"
               "  per step: broad phase %.2f us, narrow phase + patches %.2f us, forces %.2f us, "
               "integration %.2f us\n"
               "  contact solver: %.2f %s per step on average, %d at most, %lld steps "
               "unconverged, %lld scaled to add no energy\n"
               "  contact solver: %d %s per step at the median\n"
               "  contacts: %.1f patches and %.1f points per step on average, %.2f us per patch "
               "(all stages)\n"
               "  final energy: kinetic %.9g, potential %.9g, total %.9g\n",
               t.steps, sim.time(), wall, t.steps / std::max(wall, 1e-9), 1e6 * wall / steps,
               1e6 * t.broad_phase / steps, 1e6 * t.narrow_phase / steps, 1e6 * t.forces / steps,
               1e6 * t.integrate / steps, static_cast<double>(t.solver_iterations) / steps,
               iterations,
               t.max_solver_iterations, t.unconverged_steps, t.scaled_steps,
               t.median_solver_iterations, iterations, t.patches / steps,
               t.points / steps, t.patches > 0 ? 1e6 * wall / static_cast<double>(t.patches) : 0.0,
               e.kinetic, e.potential, e.total());
  if (scene.contact.max_substeps > scene.contact.substeps)
    std::fprintf(stderr, "  sub-steps: %.2f per step on average, %d at most\n",
                 static_cast<double>(t.substeps) / steps, t.max_substeps);
  if (t.fallback_islands > 0)
    std::fprintf(stderr,
                 "  Newton: %lld islands not converged in %d iterations were solved by the row "
                 "solver instead\n",
                 t.fallback_islands, t.newton_iteration_limit);
  if (t.regularised_islands > 0)
    std::fprintf(stderr,
                 "  Newton: %lld islands kept the regularised answer (moving islands of more "
                 "than %d bodies, which are not polished, and those whose polish to exact "
                 "friction did not converge)\n",
                 t.regularised_islands, t.moving_polish_bodies);
  if (t.corrected_steps > 0)
    std::fprintf(stderr, "  overlap correction: bodies moved apart in %lld of %lld steps\n",
                 t.corrected_steps, t.steps);
  if (t.block_pairs > 0 && scene.contact.pair_cache)
    std::fprintf(stderr,
                 "  pair cache: of %.1f block pairs per step, %.1f %% took last step's features "
                 "and %.1f %% were kept apart by last step's separating face\n",
                 static_cast<double>(t.block_pairs) / steps,
                 100.0 * static_cast<double>(t.cached_pairs) / static_cast<double>(t.block_pairs),
                 100.0 * static_cast<double>(t.apart_pairs) / static_cast<double>(t.block_pairs));
  if (scene.sleep)
    std::fprintf(stderr, "  sleep: %lld of %d bodies asleep at the end\n", t.sleeping_bodies,
                 sim.body_count());
  // Patch order shares the row solver's sweeps level by level, but the block solver and
  // conjugate gradients keep them on one thread: say so where threads were asked for and the
  // sweeps were a real part of the work.
  const ContactDef& contact = scene.contact;
  if (Simulation::threads() > 1 && contact.model == ContactModel::semm && !contact.colour_sweeps &&
      (contact.solver == ContactSolver::blocks || contact.conjugate_gradients) &&
      static_cast<double>(t.solver_iterations) / steps > 4)
    std::fprintf(stderr,
                 "  note: the contact solver's sweeps ran on one thread (contact.sweep_order "
                 "\"patches\" with %s); \"colours\" shares them among the %d threads\n",
                 contact.solver == ContactSolver::blocks ? "solver \"blocks\""
                                                         : "acceleration \"conjugate_gradients\"",
                 Simulation::threads());
  if (t.outran_margin > 0)
    std::fprintf(stderr,
                 "  warning: %lld times a body moved farther in one step than its contact margin "
                 "covered (it may have met a contact already overlapping); a smaller time_step "
                 "or a larger contact.margin avoids it\n",
                 t.outran_margin);
}

}  // namespace

int run_command(const std::string& scene_file, const std::string& out_dir, bool contacts,
                bool resume, bool hash, int threads) {
#ifdef TEM_MPI
  // Started by mpirun: the run is shared among its ranks (run_distributed.cpp).
  if (launched_by_mpi())
    return run_distributed_command(scene_file, out_dir, contacts, resume, hash, threads);
#endif
  // One thread unless asked: several `tem run` side by side (a parameter sweep, ctest -j) each
  // spinning up a thread per core would fight over the cores.
  if (threads < 0 && !std::getenv("OMP_NUM_THREADS")) threads = 1;
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  if (threads == 0) threads = cores;
  if (cores > 0 && threads > cores) {
    // More would only take turns on the cores, and each would still be started and waited on.
    std::cerr << "tem run: warning: --threads " << threads << " is more than this machine's "
              << cores << " cores; using " << cores << " (the results are the same)\n";
    threads = cores;
  }
  Simulation::set_threads(threads);
  // The run goes through the public API: `tem run` is a client of tem::Simulation like any
  // other program. A scene's problems come back one per line, as load_model prints them.
  std::optional<Simulation> run;
  try {
    run.emplace(resume ? Simulation::resume_recording(scene_file, out_dir, contacts)
                       : Simulation::load(scene_file));
  } catch (const SceneLoadError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "tem run: " << e.what() << "\n";
    return kExitBadInput;
  }
  // Warnings: the accepted defects, and (on a fresh start) bodies overlapping at the start.
  for (const std::string& warning : run->warnings())
    std::cerr << scene_file << ": warning: " << warning << "\n";
  if (resume)
    std::cerr << "tem run: resuming at step " << run->step_count() << " (t = " << run->time()
              << " s) from " << out_dir << "/checkpoint.bin\n";
  Simulation& sim = *run;
  const SceneDef& scene = sim.scene();
  const long long total_steps = sim.total_steps();
  const std::string checkpoint_file = out_dir + "/checkpoint.bin";

  StopOnSignal stop;
  try {
    if (!resume) {
      const std::vector<std::string> removed = sim.record(out_dir, contacts);
      if (!removed.empty()) {
        std::cerr << "tem run: removed an earlier run's files from " << out_dir << "/ that this run "
                  << "does not write again:";
        for (size_t i = 0; i < removed.size(); ++i) std::cerr << (i ? ", " : " ") << removed[i];
        std::cerr << "\n";
      }
    }
    const long long first_step = sim.step_count();
    Progress progress(static_cast<double>(total_steps) * sim.time_step(), first_step);
    const auto start = std::chrono::steady_clock::now();
    while (sim.step_count() < total_steps) {
      if (stop.requested()) {
        sim.write_checkpoint(checkpoint_file);
        progress.finish();
        std::cerr << "tem run: stopped by signal at step " << sim.step_count()
                  << " (t = " << sim.time() << " s); every file in " << out_dir
                  << " is complete up to there.\n"
                  << "  continue with: tem run " << scene_file << " --out " << out_dir
                  << (contacts ? " --contacts" : "") << " --resume\n";
        return kExitInterrupted;
      }
      sim.step();
      const int bad = sim.first_non_finite_body();
      if (bad >= 0) {
        progress.finish();
        std::cerr << scene_file << ": the state of body '" << sim.body_name(bad)
                  << "' stopped being finite at step " << sim.step_count() << " (t = "
                  << sim.time() << " s); the results up to the last output row are in "
                  << out_dir << "\n";
        return kExitFailed;
      }
      progress.update(sim.step_count(), sim.time());
    }
    // The checkpoint of the last state, then its rows (resuming with a longer duration redoes
    // them, as at every checkpoint).
    sim.write_checkpoint(checkpoint_file);
    sim.finish_recording();
    progress.finish();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    print_summary(sim, wall);
    for (const Simulation::InletDelivery& d : sim.inlet_deliveries())
      std::cerr << "  inlet '" << d.name << "': placed " << d.placed << " of the " << d.due
                << " copies due by t = " << sim.time() << " s (" << d.count << " in all)"
                << (d.placed < d.due ? "; " + std::to_string(d.due - d.placed) +
                                           " found no room in its region yet"
                                     : std::string())
                << "\n";
    std::cerr << "tem run: results in " << out_dir << "/ (bodies.csv, energy.csv"
              << (contacts ? ", contacts.csv" : "")
              << (sim.bodies_come_and_go() ? ", removed.csv" : "")
              << (scene.sensors.empty() ? "" : ", sensors.csv") << ", scene.json, checkpoint.bin"
              << (scene.output.paraview ? ", tem.pvd and paraview/ for ParaView" : "")
              << ")\n";
    if (hash) std::cout << "hash: " << sim.state_hash_hex() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "tem run: " << e.what() << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace tem::cli
