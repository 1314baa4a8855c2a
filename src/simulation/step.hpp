// One simulation step, the table of contents of TEM (architecture.md): broad phase, narrow
// phase and patches, forces, integration, with the time each stage took. Everything a step
// needs besides the Model and the State lives in the Workspace, reused from step to step.
#pragma once

#include <vector>

#include "contact/detect_contacts.hpp"
#include "contact/refreshed_patches.hpp"
#include "simulation/sleep.hpp"
#include "forces/contact_forces.hpp"
#include "forces/solver_sync.hpp"
#include "forces/system_energies.hpp"
#include "world/model.hpp"

namespace tem {

// Seconds spent in each stage, summed over the steps since the workspace was made.
struct StageTimes {
  double broad_phase = 0;
  double narrow_phase = 0;  // narrow phase and patches, interleaved pair by pair
  double forces = 0;
  double integrate = 0;
  long long steps = 0;
  // The most Gauss-Seidel sweeps (or Newton iterations) one step took, their sum (for the mean),
  // and how many steps took each count (for the median).
  int max_sweeps = 0;
  long long sweeps = 0;
  std::vector<long long> steps_by_sweeps;
  long long unconverged_steps = 0;
  long long fallback_islands = 0;  // contact.solver "newton": islands left to the row solver
  long long regularised_islands = 0;  // and islands that kept the regularised answer
  long long scaled_steps = 0;  // steps whose impulses were scaled down to add no energy
  long long corrected_steps = 0;  // steps whose overlap correction moved bodies
  long long outran_margin = 0;    // bodies that moved farther in a step than their reach
  long long substeps = 0;         // sub-steps, summed over the steps, and the most one step took
  int max_substeps = 0;
  long long patches = 0;          // contact patches and points, summed over the steps
  long long points = 0;
  // Block pairs tested with contact before overlap, and those that took last step's features
  // (contact.pair_cache), summed over the steps.
  long long block_pairs = 0, cached_pairs = 0, apart_pairs = 0;
};

struct Workspace {
  ContactWorkspace contact;
  std::vector<ContactPatch> patches;  // of the last step, at the state it started from
  ContactForces forces;               // of the last step
  StageTimes times;
  std::vector<BodyState> before;  // the bodies at the (sub-)step's start (reach, external work)
  // With contact.substeps > 1: the bodies at the step's detection, and the detected patches
  // rebuilt at the current sub-step (refreshed_patches.hpp) with their scratch.
  std::vector<BodyState> detected;
  // The sub-steps of the step find_contact_forces found the forces for (substep_count.hpp).
  int substeps = 1;
  std::vector<ContactPatch> substep_patches;
  RefreshScratch refreshed;
  // Forces and torques from outside (the public API's external_force / external_torque), held
  // until changed; empty: none. Sized to the bodies when set.
  ExternalLoads loads;
  // Under domain decomposition (src/distributed/), the bodies this process holds: contact is
  // sought only among resident bodies, for pairs with an owned one, and only owned bodies are
  // moved. Empty: every body (one process).
  BodySubset subset;
  // With a subset whose contacts are solved together by all ranks (SEMM): how they agree.
  SolverSync* sync = nullptr;
  // With the scene's `sleep`: who is left out this step (simulation/sleep.hpp).
  SleepWorkspace sleep;
};

// Stages 1-4 at `state`: the patches and the contact forces of the step that starts there. It
// changes the state only in the velocities of bodies with a prescribed motion, which it sets to
// those of the step's own sub-step once their count is chosen (process/motion.hpp).
void find_contact_forces(const Model& model, State& state, Workspace& workspace);

// Stage 5: integrates with the forces of the last find_contact_forces, which must have been
// called on this same state, and the workspace's external loads.
void advance(const Model& model, State& state, Workspace& workspace);

// Stages 1-6 of one step: find_contact_forces, then advance; no population, no hooks. For
// tests of the core on a fixed set of bodies; drivers and benchmarks take take_step
// (step_loop.hpp), the step users run.
void step(const Model& model, State& state, Workspace& workspace);

// The first body whose state is not finite, or -1.
int first_non_finite_body(const State& state);

}  // namespace tem
