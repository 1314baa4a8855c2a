// Step 4 of a simulation step (architecture.md): from the contact patches to the force and
// torque on every body, by the scene's force model (force_model.hpp), and the results and
// memory the models keep between steps.
#pragma once

#include <vector>

#include "contact/contact_patch.hpp"
#include "forces/body_response.hpp"
#include "forces/contact_points.hpp"
#include "forces/force_model.hpp"
#include "forces/penalty/penalty.hpp"
#include "forces/semm.hpp"
#include "forces/semm_newton/semm_newton.hpp"
#include "forces/semm_rows/semm_rows.hpp"
#include "world/model.hpp"

namespace tem {

// Magnitudes of the force on body_a at one patch, averaged over the step.
struct PatchForce {
  Real normal = 0;
  Real tangential = 0;
};

// Scratch and results of the force stage, reused between steps, and each model's memory (its
// own fields, read and written through its ForceModel by everything outside its folder).
struct ContactForces {
  std::vector<ContactPoint> points;
  std::vector<BodyResponse> responses;
  std::vector<Vec3> centres;
  std::vector<Real> approach;  // normal relative velocity at each point at the step's start
  std::vector<Real> approach_linear;  // its part from the centres' velocities alone
  std::vector<Real> targets;   // normal relative velocity each point asks for after the step
  std::vector<PatchFriction> friction;  // one per patch (default SEMM)
  RowSolverMemory rows;                 // the scalar-row solver's memory
  NewtonSolverMemory newton;            // the Newton solver's memory
  // The overlap correction's working vectors (overlap_correction.cpp), kept between steps.
  struct Correction {
    std::vector<Real> targets;
    std::vector<char> held;
    std::vector<BodyResponse> still, moved;
    std::vector<PatchFriction> patches;
    std::vector<PointImpulse> impulses;
  } correction;
  std::vector<Real> patch_depth;         // one per patch
  std::vector<PointImpulse> impulses;
  // The last step's points and impulses, for the warm start; how far a point may move and still
  // be the same contact, per body (1% of its size).
  std::vector<ContactPoint> previous_points;
  std::vector<PointImpulse> previous_impulses;
  std::vector<PatchFriction> previous_friction;
  std::vector<Real> match_radius;
  std::vector<PenaltySpring> springs;  // penalty: the tangential springs' memory
  std::vector<Real> normal_magnitude, tangential_magnitude;
  // Results: per body, world force and torque about its centre of mass, held through the step.
  std::vector<Vec3> force, torque;
  std::vector<PatchForce> patch_forces;  // per patch
  SolverReport solver;
};

// Fills out.force, out.torque (one per body) and out.patch_forces (one per patch).
// `loads`: the external forces and torques acting through the step (none when null), which the
// contact impulses must answer as they answer gravity.
// With `sync` (a run shared among MPI ranks, solver_sync.hpp) the patches are this rank's and
// the solve is the ranks' together: every rank calls it, with patches or without.
// `dt`: the time the forces act over, the scene's time step or, with sub-steps, one sub-step.
void compute_contact_forces(const Model& model, const State& state,
                            const std::vector<ContactPatch>& patches, Real dt, ContactForces& out,
                            const ExternalLoads* loads = nullptr, SolverSync* sync = nullptr);

}  // namespace tem
