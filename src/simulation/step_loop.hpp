// One step as every driver takes it: tem::Simulation (and through it `tem run` and the Python
// module) and the run over MPI ranks. The table of contents of a step, in order (method.md,
// "The step"):
//   a. where the step begins, the driver's own work (StepHooks::step_begins: a checkpoint;
//      over MPI ranks, rebalancing);
//   b. the external loads made current;
//   1-4. the contact forces of the state (find_contact_forces: broad phase, narrow phase and
//      patches, forces), between StepHooks::before_forces and after_forces (over MPI ranks:
//      the ghosts' states in, their forces back);
//   c. the driver's rows of that state, with those forces (StepHooks::forces_found);
//   5-6. integration over the step and its sub-steps, the overlap correction (advance);
//   0. the population of the state the step leaves (process/population.hpp): outlets and
//      removed_at, then inlets; the bodies that left are handed to StepHooks::bodies_left.
// A new stage goes here, once, for every driver.
#pragma once

#include <vector>

#include "process/population.hpp"
#include "simulation/step.hpp"

namespace tem {

// What a driver adds between the stages; each does nothing unless overridden.
class StepHooks {
 public:
  virtual ~StepHooks() = default;
  virtual void step_begins(const Model& /*model*/, State& /*state*/, Workspace& /*w*/) {}
  virtual void before_forces(const Model& /*model*/, State& /*state*/, Workspace& /*w*/) {}
  virtual void after_forces(Workspace& /*w*/) {}
  virtual void forces_found(const Model& /*model*/, const State& /*state*/,
                            const Workspace& /*w*/) {}
  virtual void bodies_left(const std::vector<RemovedBody>& /*removed*/) {}
};

// Stages b and 1-4 with their hooks: the contact forces of `state` (also for a driver's rows of
// a state no step starts from, such as the last).
void find_forces(const Model& model, State& state, Workspace& w, StepHooks& hooks);

// One step, stages a to 0. `removed` gathers the bodies that leave (handed to the hooks, then
// cleared); only scenes where bodies come and go change `model`.
void take_step(Model& model, State& state, Workspace& w, std::vector<RemovedBody>& removed,
               StepHooks& hooks);

}  // namespace tem
