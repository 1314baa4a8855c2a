#include "distributed/distributed_run.hpp"

#include <mpi.h>

#include "io/checkpoint.hpp"
#include "simulation/step_loop.hpp"

namespace tem::distributed {
namespace {

// Rank 0's checkpoint of the current state and the memory the next step starts from.
void write_distributed_checkpoint(const Domain& domain, const Model& model, const State& state,
                                  const Workspace& w, const RunPlan& plan) {
  State whole;
  ContactForces memory;
  domain.gather_state(model, state, whole);
  domain.gather_memory(model, w.forces, memory);
  if (domain.rank() != 0) return;
  const OutputSizes sizes = plan.output ? plan.output->sizes() : OutputSizes{0, 0, -1};
  write_checkpoint(plan.checkpoint_file, make_checkpoint(model.scene, whole, memory, {}, sizes));
}

// Rank 0's rows for the current state, with the contacts of the step that starts from it.
void write_rows(const Domain& domain, const Model& model, const State& state, const Workspace& w,
                const RunPlan& plan) {
  if (model.scene.output.paraview) {
    // This rank's piece first: rank 0 lists the pieces once the gathers below have completed,
    // that is once every rank has written its own.
    std::vector<ContactPatch> patches;
    std::vector<PatchForce> forces;
    for (size_t k = 0; k < w.patches.size(); ++k)
      if (w.subset.owned[w.patches[k].body_a]) {
        patches.push_back(w.patches[k]);
        forces.push_back(w.forces.patch_forces[k]);
      }
    ParaviewOutput::write_piece(plan.directory, model, state, w.subset.owned, patches, forces,
                                domain.rank());
  }
  State whole;
  Workspace gathered;
  domain.gather_state(model, state, whole);
  domain.gather_contacts(w, gathered.patches, gathered.forces.patch_forces);
  if (domain.rank() == 0 && plan.output) plan.output->write(model, whole, gathered);
}

// The run's work between the stages of a step (simulation/step_loop.hpp): a checkpoint and
// rebalancing where a step begins, the ghosts around the forces, rank 0's rows.
class RankHooks : public StepHooks {
 public:
  RankHooks(Domain& domain, const RunPlan& plan, long long first_step)
      : domain_(domain), plan_(plan), first_step_(first_step) {}
  void step_begins(const Model& model, State& state, Workspace& w) override {
    // As one process (Simulation::Impl): a checkpoint where a step begins, before its rows.
    const long long k = state.step;
    if (plan_.checkpoint_every > 0 && k % plan_.checkpoint_every == 0 && k != first_step_)
      write_distributed_checkpoint(domain_, model, state, w, plan_);
    domain_.balance_if_needed(model, state, w);
  }
  void before_forces(const Model& model, State& state, Workspace& w) override {
    domain_.exchange(model, state, w);
  }
  void after_forces(Workspace& w) override { domain_.return_ghost_forces(w); }
  void forces_found(const Model& model, const State& state, const Workspace& w) override {
    if (state.step % plan_.every == 0 && written_step_ != state.step) write(model, state, w);
  }
  void write(const Model& model, const State& state, const Workspace& w) {
    write_rows(domain_, model, state, w, plan_);
    written_step_ = state.step;
  }
  long long written_step() const { return written_step_; }

 private:
  Domain& domain_;
  const RunPlan& plan_;
  long long first_step_;
  long long written_step_ = -1;
};

bool any_rank(MPI_Comm comm, bool mine) {
  int flag = mine ? 1 : 0, any = 0;
  MPI_Allreduce(&flag, &any, 1, MPI_INT, MPI_LOR, comm);
  return any != 0;
}

}  // namespace

// The force model's reason comes last: a process scene that names no solver (Newton, the
// default, is not distributed) would otherwise be told to name the rows, and then be refused
// again for its processes.
std::string unsupported_reason(const SceneDef& scene) {
  // Each sub-step's solve would need the ghosts' forces returned between the sub-steps.
  if (scene.contact.substeps > 1 || scene.contact.max_substeps > 1)
    return "over MPI ranks TEM does not yet run sub-steps (contact.substeps or "
           "contact.max_substeps > 1): run this scene without mpirun (threads: --threads N), or "
           "with one sub-step";
  // Granular processes change the bodies or watch them as a whole: not yet shared among ranks
  // (materials are: each contact's coefficients are its own).
  bool process = !scene.inlets.empty() || !scene.outlets.empty() || !scene.sensors.empty();
  for (const BodyDef& b : scene.bodies) process = process || b.motion || b.removed_at;
  for (const WallDef& w : scene.walls) process = process || w.removed_at.has_value();
  if (process)
    return "over MPI ranks TEM does not yet run granular processes (inlets, outlets, sensors, "
           "prescribed motion, removed_at): run this scene without mpirun (threads: --threads N)";
  // An island can span ranks, and whether it sleeps would need every rank's timers.
  if (scene.sleep)
    return "over MPI ranks TEM does not put bodies to sleep: islands of bodies at rest can span "
           "ranks; remove the scene's `sleep`, or run it without mpirun (threads: --threads N)";
  return force_model(scene.contact).not_distributed_because();
}

RunResult run_steps(Domain& domain, Model& model, State& state, Workspace& w, const RunPlan& plan,
                    const std::function<bool()>& stop_requested,
                    const std::function<void(long long, Real)>& progress) {
  RunResult result;
  RankHooks hooks(domain, plan, state.step);
  std::vector<RemovedBody> removed;  // none: scenes where bodies come and go are refused
  while (state.step < plan.total_steps) {
    if (any_rank(MPI_COMM_WORLD, stop_requested())) {
      write_distributed_checkpoint(domain, model, state, w, plan);
      result.end = RunEnd::stopped;
      domain.gather_state(model, state, result.whole);
      return result;
    }
    take_step(model, state, w, removed, hooks);
    const int bad = domain.first_non_finite_body(state);
    if (bad >= 0) {
      result.end = RunEnd::not_finite;
      result.bad_body = bad;
      return result;
    }
    if (domain.rank() == 0 && progress) progress(state.step, state.time);
  }
  // The checkpoint of the last state, then its rows (as `tem run` on one process).
  write_distributed_checkpoint(domain, model, state, w, plan);
  if (hooks.written_step() != state.step) {
    find_forces(model, state, w, hooks);
    hooks.write(model, state, w);
  }
  domain.gather_state(model, state, result.whole);
  return result;
}

}  // namespace tem::distributed
