// include/tem/distributed.hpp over src/distributed/: built only with TEM_MPI, into its own
// library (tem_api_mpi), so that the public API's libtem.so and the Python module stay free of
// MPI.
#include "tem/distributed.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "api/output_steps.hpp"
#include "api/simulation_impl.hpp"
#include "distributed/distributed_run.hpp"
#include "distributed/mpi_session.hpp"
#include "world/state_hash.hpp"

namespace tem {
namespace {

// The exchange figures of every rank, reduced onto rank 0.
void gather_figures(const distributed::Domain& domain, DistributedRun& run) {
  const distributed::ExchangeStats& s = domain.stats();
  const double mine[3] = {static_cast<double>(domain.owned_count()), s.seconds,
                          static_cast<double>(s.bytes_sent)};
  double most[3], least[3];
  MPI_Reduce(mine, most, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  MPI_Reduce(mine, least, 3, MPI_DOUBLE, MPI_MIN, 0, MPI_COMM_WORLD);
  long long counts[3] = {s.migrated, s.ghosts, s.messages_sent}, totals[3] = {0, 0, 0};
  MPI_Reduce(counts, totals, 3, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  long long solve[2] = {0, 0}, solve_total[2] = {0, 0};
  if (const distributed::SharedSolve* shared = domain.shared_solve()) {
    solve[0] = shared->averages;
    solve[1] = shared->bytes_sent;
  }
  MPI_Reduce(solve, solve_total, 2, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
  run.ranks = domain.size();
  run.fewest_bodies = least[0];
  run.most_bodies = most[0];
  run.least_exchange_seconds = least[1];
  run.most_exchange_seconds = most[1];
  run.least_bytes_sent = least[2];
  run.most_bytes_sent = most[2];
  run.migrations = totals[0];
  run.ghosts = totals[1];
  run.messages = totals[2];
  run.balancings = s.balancings;
  run.shared_averagings = solve_total[0];
  run.shared_bytes_sent = solve_total[1];
}

}  // namespace

bool launched_by_mpi() { return distributed::launched_by_mpi(); }

struct MpiSession::Impl {
  distributed::MpiSession session{nullptr, nullptr};
};
MpiSession::MpiSession() : impl_(std::make_unique<Impl>()) {}
MpiSession::~MpiSession() = default;
int MpiSession::rank() const { return impl_->session.rank(); }
int MpiSession::size() const { return impl_->session.size(); }
int MpiSession::agreed(int code) const {
  int worst = 0;
  MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}
void MpiSession::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::abort();  // not reached: MPI_Abort ends the process
}

std::string distributed_unsupported_reason(const Simulation& sim) {
  return distributed::unsupported_reason(sim.scene());
}

DistributedRun run_distributed(const MpiSession& mpi, Simulation& sim, const std::string& directory,
                               const std::function<bool()>& stop_requested,
                               const std::function<void(long long, Real)>& progress) {
  Simulation::Impl& impl = sim.impl();
  const SceneDef& scene = impl.model.scene;
  const bool root = mpi.rank() == 0;
  distributed::RunPlan plan;
  plan.total_steps = sim.total_steps();
  plan.every = steps_per(scene.output.interval, scene.time_step);
  plan.checkpoint_every = scene.output.checkpoint_interval > 0
                              ? steps_per(scene.output.checkpoint_interval, scene.time_step)
                              : 0;
  plan.checkpoint_file = directory + "/checkpoint.bin";
  plan.output = root ? impl.output.get() : nullptr;
  plan.directory = directory;
  if (plan.output && plan.output->paraview()) plan.output->paraview()->use_pieces(mpi.size());

  DistributedRun run;
  const long long first_step = impl.state.step;
  const auto start = std::chrono::steady_clock::now();
  distributed::Domain domain(MPI_COMM_WORLD);
  domain.start(impl.model, impl.state, impl.workspace);
  const distributed::RunResult result =
      distributed::run_steps(domain, impl.model, impl.state, impl.workspace, plan, stop_requested,
                             progress);
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (root) impl.output.reset();  // flushed and closed
  run.steps = impl.state.step - first_step;
  run.end = result.end == distributed::RunEnd::stopped      ? DistributedRun::End::stopped
            : result.end == distributed::RunEnd::not_finite ? DistributedRun::End::not_finite
                                                            : DistributedRun::End::finished;
  if (run.end == DistributedRun::End::not_finite && result.bad_body >= 0 &&
      result.bad_body < static_cast<int>(impl.model.bodies.size()))
    run.bad_body = impl.model.bodies[result.bad_body].name;
  if (run.end != DistributedRun::End::finished) return run;
  if (root) {
    const Energies e = system_energies(impl.model, result.whole);
    run.energies = {e.kinetic, e.potential, result.whole.driven_work};
    run.hash_hex = hash_hex(state_hash(result.whole));
    run.solver = sim.run_statistics();
  }
  gather_figures(domain, run);
  return run;
}

}  // namespace tem
