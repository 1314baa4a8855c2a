// `mpirun -np N tem run SCENE --out DIR`: the run of run_command.cpp over N ranks
// (src/distributed/). Built only with TEM_MPI. Every rank loads the scene; rank 0 writes the
// files and prints; every decision that ends the run (a bad scene, a file that cannot be
// written, a signal, a state gone non-finite) is agreed by all ranks, so none waits forever for
// another that has left.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

#include "api/simulation_impl.hpp"
#include "commands.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/mpi_session.hpp"
#include "progress.hpp"
#include "stop_signal.hpp"
#include "support/parallel.hpp"
#include "world/state_hash.hpp"

namespace tem::cli {
namespace {

// The worst exit code of all ranks (0: all went well).
int agreed_code(int mine) {
  int worst = 0;
  MPI_Allreduce(&mine, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}

void print_distributed_summary(const distributed::Domain& domain, long long steps, double wall) {
  const distributed::ExchangeStats& s = domain.stats();
  // Per rank: owned bodies, seconds in exchanges, bytes sent; min and max over ranks.
  const double mine[3] = {static_cast<double>(domain.owned_count()), s.seconds,
                          static_cast<double>(s.bytes_sent)};
  double most[3], least[3];
  MPI_Reduce(mine, most, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  MPI_Reduce(mine, least, 3, MPI_DOUBLE, MPI_MIN, 0, MPI_COMM_WORLD);
  long long counts[3] = {s.migrated, s.ghosts, s.messages_sent}, totals[3];
  MPI_Reduce(counts, totals, 3, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  long long solve[2] = {0, 0}, solve_total[2] = {0, 0};
  if (const distributed::SharedSolve* shared = domain.shared_solve()) {
    solve[0] = shared->averages;
    solve[1] = shared->bytes_sent;
  }
  MPI_Reduce(solve, solve_total, 2, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  if (domain.rank() != 0) return;
  const double per = static_cast<double>(std::max<long long>(steps, 1));
  if (solve_total[0] > 0)
    std::fprintf(stderr,
                 "  shared solve: %.1f averagings of shared bodies per step, %.0f bytes sent per "
                 "step per rank in them\n",
                 static_cast<double>(solve_total[0]) / domain.size() / per,
                 static_cast<double>(solve_total[1]) / domain.size() / per);
  std::fprintf(stderr,
               "  %d ranks: %.0f-%.0f bodies each at the end; %.1f ghosts and %.2f migrations "
               "per step in all; exchanges %.2f-%.2f us per step (%.1f%% of the step at most), "
               "%.0f-%.0f bytes sent per step per rank in %.2f messages; %lld balancings\n",
               domain.size(), least[0], most[0], totals[1] / per, totals[0] / per,
               1e6 * least[1] / per, 1e6 * most[1] / per, 100 * most[1] / std::max(wall, 1e-9),
               least[2] / per, most[2] / per, totals[2] / per / domain.size(), s.balancings);
}

}  // namespace

int run_distributed_command(const std::string& scene_file, const std::string& out_dir,
                            bool contacts, bool resume, bool hash, int threads) {
  distributed::MpiSession mpi(nullptr, nullptr);
  const bool root = mpi.rank() == 0;
  set_threads(threads <= 0 ? 1 : threads);  // ranks, not threads, share the cores

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
    const std::string unsupported = distributed::unsupported_reason(run->scene());
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
  if ((code = agreed_code(code)) != kExitOk) return code;
  Simulation& sim = *run;
  Simulation::Impl& impl = sim.impl();
  if (root) {
    for (const std::string& warning : resume ? impl.model.warnings : sim.warnings())
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
  if ((code = agreed_code(code)) != kExitOk) return code;

  const SceneDef& scene = impl.model.scene;
  distributed::RunPlan plan;
  plan.total_steps = sim.total_steps();
  plan.every = std::max<long long>(1, std::llround(scene.output.interval / scene.time_step));
  plan.checkpoint_every =
      scene.output.checkpoint_interval > 0
          ? std::max<long long>(1, std::llround(scene.output.checkpoint_interval / scene.time_step))
          : 0;
  plan.checkpoint_file = out_dir + "/checkpoint.bin";
  plan.output = root ? impl.output.get() : nullptr;
  plan.directory = out_dir;
  if (root && plan.output && plan.output->paraview())
    plan.output->paraview()->use_pieces(mpi.size());

  StopOnSignal stop;
  const long long first_step = sim.step_count();
  std::optional<Progress> progress;
  if (root) progress.emplace(static_cast<double>(plan.total_steps) * sim.time_step(), first_step);
  distributed::RunResult result;
  const auto start = std::chrono::steady_clock::now();
  try {
    distributed::Domain domain(MPI_COMM_WORLD);
    domain.start(impl.model, impl.state, impl.workspace);
    result = distributed::run_steps(
        domain, impl.model, impl.state, impl.workspace, plan, [&] { return stop.requested(); },
        [&](long long step, Real time) { progress->update(step, time); });
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress->finish();
    if (root) impl.output.reset();  // flushed and closed
    const long long steps = impl.state.step - first_step;
    if (result.end == distributed::RunEnd::stopped) {
      if (root)
        std::cerr << "tem run: stopped by signal at step " << impl.state.step
                  << " (t = " << impl.state.time << " s); every file in " << out_dir
                  << " is complete up to there.\n  continue with: mpirun -np N tem run "
                  << scene_file << " --out " << out_dir << (contacts ? " --contacts" : "")
                  << " --resume (any N, or without mpirun)\n";
      return kExitInterrupted;
    }
    if (result.end == distributed::RunEnd::not_finite) {
      if (root)
        std::cerr << scene_file << ": the state of body '"
                  << impl.model.bodies[result.bad_body].name << "' stopped being finite at step "
                  << impl.state.step << "; the results up to the last output row are in " << out_dir
                  << "\n";
      return kExitFailed;
    }
    if (root) {
      const Energies e = system_energies(impl.model, result.whole);
      std::fprintf(stderr,
                   "tem run: %lld steps to t = %.6g s in %.3f s on %d ranks (%.0f steps/s, "
                   "%.2f us/step)\n  final energy: kinetic %.9g, potential %.9g, total %.9g\n",
                   steps, impl.state.time, wall, mpi.size(),
                   static_cast<double>(steps) / std::max(wall, 1e-9),
                   1e6 * wall / static_cast<double>(std::max<long long>(steps, 1)), e.kinetic,
                   e.potential, e.total());
      // The solver's figures are the ranks' shared ones (every rank sweeps as often).
      const StageTimes& t = impl.workspace.times;
      if (scene.contact.model != ContactModel::penalty)
        std::fprintf(
            stderr,
            "  contact solver: %.2f sweeps per step on average, %d at most, %lld steps "
            "unconverged, %lld scaled to add no energy, %lld overlap corrections\n",
            static_cast<double>(t.sweeps) / static_cast<double>(std::max<long long>(t.steps, 1)),
            t.max_sweeps, t.unconverged_steps, t.scaled_steps, t.corrected_steps);
    }
    print_distributed_summary(domain, steps, wall);
    if (root) {
      std::cerr << "tem run: results in " << out_dir << "/ (bodies.csv, energy.csv"
                << (contacts ? ", contacts.csv" : "") << ", scene.json, checkpoint.bin"
                << (scene.output.paraview ? ", tem.pvd and paraview/ for ParaView" : "") << ")\n";
      if (hash) std::cout << "hash: " << hash_hex(state_hash(result.whole)) << std::endl;
    }
  } catch (const std::exception& e) {
    // A failure here (a file that cannot be written) is rank 0's; the others are waiting in a
    // collective call that will never complete: end them all.
    std::cerr << "tem run (rank " << mpi.rank() << "): " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, kExitFailed);
  }
  return kExitOk;
}

}  // namespace tem::cli
