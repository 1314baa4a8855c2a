// `mpirun -np N tem run SCENE --out DIR`: the run of run_command.cpp over N ranks
// (tem/distributed.hpp). Built only with TEM_MPI. Every rank loads the scene; rank 0 writes the
// files and prints; every decision that ends the run (a bad scene, a file that cannot be
// written, a signal, a state gone non-finite) is agreed by all ranks, so none waits forever for
// another that has left.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"
#include "tem/distributed.hpp"

namespace tem::cli {
namespace {

void print_distributed_summary(const DistributedRun& r) {
  const double per = static_cast<double>(std::max<long long>(r.steps, 1));
  if (r.shared_averagings > 0)
    std::fprintf(stderr,
                 "  shared solve: %.1f averagings of shared bodies per step, %.0f bytes sent per "
                 "step per rank in them\n",
                 static_cast<double>(r.shared_averagings) / r.ranks / per,
                 static_cast<double>(r.shared_bytes_sent) / r.ranks / per);
  std::fprintf(stderr,
               "  %d ranks: %.0f-%.0f bodies each at the end; %.1f ghosts and %.2f migrations "
               "per step in all; exchanges %.2f-%.2f us per step (%.1f%% of the step at most), "
               "%.0f-%.0f bytes sent per step per rank in %.2f messages; %lld balancings\n",
               r.ranks, r.fewest_bodies, r.most_bodies, r.ghosts / per, r.migrations / per,
               1e6 * r.least_exchange_seconds / per, 1e6 * r.most_exchange_seconds / per,
               100 * r.most_exchange_seconds / std::max(r.wall, 1e-9), r.least_bytes_sent / per,
               r.most_bytes_sent / per, r.messages / per / r.ranks, r.balancings);
}

}  // namespace

int run_distributed_command(const std::string& scene_file, const std::string& out_dir,
                            bool contacts, bool resume, bool hash, int threads) {
  MpiSession mpi;
  const bool root = mpi.rank() == 0;
  Simulation::set_threads(threads <= 0 ? 1 : threads);  // ranks, not threads, share the cores

  // Every rank loads the scene (and the checkpoint); rank 0 also opens the files.
  std::optional<Simulation> run;
  int code = kExitOk;
  try {
    const std::string checkpoint_file = out_dir + "/checkpoint.bin";
    if (resume)
      run.emplace(root ? Simulation::resume_recording(scene_file, out_dir, contacts)
                       : Simulation::resume(scene_file, checkpoint_file));
    else
      run.emplace(Simulation::load(scene_file));
    const std::string unsupported = distributed_unsupported_reason(*run);
    if (!unsupported.empty()) {
      if (root) std::cerr << scene_file << ": " << unsupported << "\n";
      code = kExitBadInput;
    }
  } catch (const SceneLoadError& e) {
    if (root) std::cerr << e.what() << "\n";
    code = kExitBadInput;
  } catch (const std::exception& e) {
    if (root) std::cerr << "tem run: " << e.what() << "\n";
    code = kExitBadInput;
  }
  if ((code = mpi.agreed(code)) != kExitOk) return code;
  Simulation& sim = *run;
  if (root) {
    for (const std::string& warning : sim.warnings())
      std::cerr << scene_file << ": warning: " << warning << "\n";
    if (resume)
      std::cerr << "tem run: resuming at step " << sim.step_count() << " (t = " << sim.time()
                << " s) from " << out_dir << "/checkpoint.bin on " << mpi.size() << " ranks\n";
  }
  try {
    if (root && !resume) sim.record(out_dir, contacts);
  } catch (const std::exception& e) {
    std::cerr << "tem run: " << e.what() << "\n";
    code = kExitFailed;
  }
  if ((code = mpi.agreed(code)) != kExitOk) return code;

  const SceneDef& scene = sim.scene();
  StopOnSignal stop;
  std::optional<Progress> progress;
  if (root)
    progress.emplace(static_cast<double>(sim.total_steps()) * sim.time_step(), sim.step_count());
  try {
    const DistributedRun result = run_distributed(
        mpi, sim, out_dir, [&] { return stop.requested(); },
        [&](long long step, Real time) { progress->update(step, time); });
    if (progress) progress->finish();
    if (result.end == DistributedRun::End::stopped) {
      if (root)
        std::cerr << "tem run: stopped by signal at step " << sim.step_count()
                  << " (t = " << sim.time() << " s); every file in " << out_dir
                  << " is complete up to there.\n  continue with: mpirun -np N tem run "
                  << scene_file << " --out " << out_dir << (contacts ? " --contacts" : "")
                  << " --resume (any N, or without mpirun)\n";
      return kExitInterrupted;
    }
    if (result.end == DistributedRun::End::not_finite) {
      if (root)
        std::cerr << scene_file << ": the state of body '" << result.bad_body
                  << "' stopped being finite at step " << sim.step_count()
                  << "; the results up to the last output row are in " << out_dir << "\n";
      return kExitFailed;
    }
    if (root) {
      const SystemEnergies& e = result.energies;
      std::fprintf(stderr,
                   "tem run: %lld steps to t = %.6g s in %.3f s on %d ranks (%.0f steps/s, "
                   "%.2f us/step)\n  final energy: kinetic %.9g, potential %.9g, total %.9g\n",
                   result.steps, sim.time(), result.wall, mpi.size(),
                   static_cast<double>(result.steps) / std::max(result.wall, 1e-9),
                   1e6 * result.wall / static_cast<double>(std::max<long long>(result.steps, 1)),
                   e.kinetic, e.potential, e.total());
      // The solver's figures are the ranks' shared ones (every rank sweeps as often).
      const RunStatistics& t = result.solver;
      if (scene.contact.model != ContactModel::penalty)
        std::fprintf(
            stderr,
            "  contact solver: %.2f sweeps per step on average, %d at most, %lld steps "
            "unconverged, %lld scaled to add no energy, %lld overlap corrections\n",
            static_cast<double>(t.solver_iterations) /
                static_cast<double>(std::max<long long>(t.steps, 1)),
            t.max_solver_iterations, t.unconverged_steps, t.scaled_steps, t.corrected_steps);
      if (scene.contact.model != ContactModel::penalty)
        std::fprintf(stderr, "  contact solver: %d sweeps per step at the median\n",
                     t.median_solver_iterations);
      print_distributed_summary(result);
      std::cerr << "tem run: results in " << out_dir << "/ (bodies.csv, energy.csv"
                << (contacts ? ", contacts.csv" : "") << ", scene.json, checkpoint.bin"
                << (scene.output.paraview ? ", tem.pvd and paraview/ for ParaView" : "") << ")\n";
      if (hash) std::cout << "hash: " << result.hash_hex << std::endl;
    }
  } catch (const std::exception& e) {
    // A failure here (a file that cannot be written) is rank 0's; the others are waiting in a
    // collective call that will never complete: end them all.
    std::cerr << "tem run (rank " << mpi.rank() << "): " << e.what() << "\n";
    mpi.abort(kExitFailed);
  }
  return kExitOk;
}

}  // namespace tem::cli
