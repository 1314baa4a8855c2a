// SEMM: the contact impulses of one step are the ones that minimise the system's energy at the
// next step (method.md §6), written T(lambda) = 1/2 lambda.K lambda + lambda.u_free + const with
// K and u_free from body_response.hpp. Two solvers:
//
// - semm (default mode): every contact point has a normal impulse >= 0 (no adhesion) and a
//   tangential impulse inside the Coulomb cone mu * normal: minimising energy under the cone is
//   the maximum-dissipation principle that defines Coulomb friction. An optional restitution e
//   asks for the normal relative velocity after the step to be at least -e times the one
//   before (an impact), and nothing otherwise (resting contact). This convex quadratic
//   programme is solved by projected Gauss-Seidel: contact by contact, the normal impulse is
//   the unconstrained minimiser clamped at 0; each patch's friction (PatchFriction) is the
//   2x2 minimiser of its tangential impulse scaled into the disc mu * (patch normal impulse),
//   then the minimiser of its twist clamped likewise. Each sweep lowers T; it stops when no impulse changed by more than
//   `tolerance` of the largest, and reports the sweeps and that last change.
//
// - semm-paper: the paper's K S = D (eqs. 30-31, 36-39), in semm_paper/.
#pragma once

#include <vector>

#include "forces/body_response.hpp"
#include "forces/contact_points.hpp"

namespace tem {

struct RowSolverMemory;

// Normal impulse at one contact point: on B along +normal, on A along -normal.
struct PointImpulse {
  Real normal = 0;
};

// Friction of one patch, acting at its centre in its frame: a tangential impulse (t1, t2) on B
// (the opposite on A) and a twisting impulse about the normal. Why per patch and not per point:
// a face resting on an incline at the friction angle needs every point's friction at its limit
// and pointing the same way; per-point friction makes that a degenerate problem that an
// iterative solver approaches only asymptotically (the box creeps), while the patch's total
// friction limit mu * (sum of its normal impulses) is met exactly by one 2x2 solve. The twist is
// limited by mu * sum(normal impulse x distance from the centre), the most torque the points'
// friction could give.
struct PatchFriction {
  int first = 0, last = 0;  // its points: [first, last)
  int body_a = -1, body_b = -1, wall = -1;
  Vec3 centre = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ(), tangent1 = Vec3::UnitX(), tangent2 = Vec3::UnitY();
  // Relative velocity (B minus A) at the centre along tangent1, tangent2 and relative spin about
  // the normal, at the start of the step.
  Vec3 start_slip = Vec3::Zero();
  // The starting guess (warm start), then the result.
  Real t1 = 0, t2 = 0, twist = 0;
  // Rolling resistance (materials.hpp): the angular impulse on B (the opposite on A) about
  // tangent1 and tangent2, warm start then result, as t1, t2; and the relative rolling
  // velocity (B's spin minus A's along tangent1, tangent2) at the start of the step.
  Real roll1 = 0, roll2 = 0;
  Real start_roll1 = 0, start_roll2 = 0;
  // The patch's coefficients, from the materials of its two sides (Model::coefficients), set
  // each step by compute_contact_forces and read where SolverSettings::per_patch is set:
  // friction mu, restitution e, rolling resistance mu_r and the rolling radius R (the rolling
  // torque is at most mu_r R times the normal force; mu_r R = 0: no rolling row). Derived
  // each step from the Model and the State, so not part of the contact memory (checkpoint,
  // messages), unlike the impulses above.
  Real friction = 0, restitution = 0, rolling_resistance = 0, rolling_radius = 0;
  // Slip that sliding surfaces (conveyor belts, motion.surface_velocity) add along tangent1 and
  // tangent2 (B's minus A's; z 0), included in start_slip and in every slip the solvers
  // measure. Derived each step, not contact memory.
  Vec3 surface_slip = Vec3::Zero();
};

class SolverSync;  // solver_sync.hpp

struct SolverSettings {
  // Scene-wide coefficients, for every patch unless `per_patch`: then each patch's own (its
  // PatchFriction's friction, restitution and rolling resistance, from its materials), and
  // `friction` and `restitution` here are not read.
  Real friction = 0;
  Real restitution = 0;
  bool per_patch = false;
  Real restitution_threshold = 0;  // approach speeds below this are resting contact (e = 0)
  int max_sweeps = 500;
  Real tolerance = 1e-9;  // relative change of the impulses that ends the sweeps
  bool colour_sweeps = false;  // sweep by colours (threads share them) instead of patch order
  Real time_step = 0;  // for the gaps of contact before overlap (a gap s may close by s)
  // Shared among MPI ranks (solver_sync.hpp): the scalar-row solver's bodies are already split
  // and it synchronises after every sweep. Null: one process.
  SolverSync* sync = nullptr;
  // Whether the result is impulses whose energy is checked (false: the overlap correction's
  // move).
  bool energy_check = true;
  // Per point, whether its normal impulse may take either sign: the overlap correction holds
  // the points already in contact, so that its move opens none of them (overlap_correction.hpp).
  // Read by the scalar-row solver only, and not for patches on bodies that several MPI ranks
  // share (semm_rows.cpp); null: every normal impulse >= 0.
  const std::vector<char>* held = nullptr;
  // Nonsmooth nonlinear conjugate gradients over the sweeps (semm_rows.cpp: sweeps).
  bool conjugate_gradients = false;
};

struct SolverReport {
  int sweeps = 0;       // Gauss-Seidel sweeps, or 1 for the direct solve
  Real change = 0;      // largest impulse change of the last sweep, relative to the largest
  bool converged = true;
  Real scale = 1;       // < 1: impulses scaled down so as to add no energy (semm_rows.hpp)
  int fallback_islands = 0;  // Newton: islands it did not converge, solved by the rows solver
  int regularised_islands = 0;  // Newton: islands that kept the regularised answer (unpolished)
  int supernodal_islands = 0;   // Newton: islands factorised by CHOLMOD's supernodal Cholesky
};

// A patch's friction coefficient, restitution, and rolling torque limit per unit normal impulse
// (mu_r R, a length; 0 without per-patch coefficients: no rolling resistance).
inline Real friction_of(const SolverSettings& s, const PatchFriction& p) {
  return s.per_patch ? p.friction : s.friction;
}
inline Real restitution_of(const SolverSettings& s, const PatchFriction& p) {
  return s.per_patch ? p.restitution : s.restitution;
}
inline Real rolling_limit_of(const SolverSettings& s, const PatchFriction& p) {
  return s.per_patch ? p.rolling_resistance * p.rolling_radius : 0;
}

// Relative velocity (B minus A, world) of the pseudo velocities y at a point, before any
// contact impulse: what the objective's gradient sees.
Vec3 relative_velocity(const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                       const ContactPoint& c);

// The normal relative velocity each point asks for after the step (restitution, resting
// contact, the energy rule for separating points, the gap of contact before overlap), from
// `start`, the normal relative velocity at the start of the step. semm.cpp says why.
// `start_linear`, if not empty, is the part of `start` due to the centres' velocities alone
// (the gap of contact before overlap closes by their mean over the step, by the end spin).
// With settings.per_patch, each point's restitution is its patch's (`patches`, indexed by
// ContactPoint::patch).
void normal_targets(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                    const std::vector<Real>& start_linear, const SolverSettings& settings,
                    std::vector<Real>& targets,
                    const std::vector<PatchFriction>* patches = nullptr);

// T(y) - T(y0) of the bodies' pseudo velocities y against y0: sum of 1/2 (y + y0).W^-1 (y - y0).
Real pseudo_energy_change(const std::vector<BodyResponse>& now,
                          const std::vector<BodyResponse>& start);

// Default SEMM by projected Gauss-Seidel. `start` holds, per point, the normal relative velocity
// at the start of the step (for restitution and the energy rule); `patches` the friction of each
// patch (their results are written there); every point belongs to one of them, and a patch has
// at most eight points. `impulses` is the starting guess (warm start)
// and the result. Should the sweeps stop short of convergence with more energy than no impulse
// at all would leave (a warm start that no longer fits), the solve starts again from zero,
// from where every sweep can only lower the energy.
SolverReport solve_semm(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                        const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                        const SolverSettings& settings, std::vector<PatchFriction>& patches,
                        std::vector<PointImpulse>& impulses);

// The pseudo velocities (`velocities`: the bodies' with their own set to zero on entry, their
// result on return) that separate the points at the given normal speeds, impulses >= 0, no
// friction: what the overlap correction moves the bodies by. `patches` is a working copy of the
// step's patches (their friction is cleared), `impulses` scratch: both the caller's, so that a
// running pile allocates nothing here. With `rows`, by the scalar-row solver (semm_rows.hpp) in
// that memory, else by patch blocks.
SolverReport solve_separation(const std::vector<ContactPoint>& points,
                              const std::vector<Real>& targets,
                              const std::vector<BodyResponse>& bodies,
                              const std::vector<Vec3>& centres,
                              std::vector<PatchFriction>& patches,
                              std::vector<PointImpulse>& impulses,
                              std::vector<BodyResponse>& velocities,
                              const SolverSettings& stopping = SolverSettings{},
                              RowSolverMemory* rows = nullptr);

// A patch's result solved in another layout (a solver's own copy of the points and patches)
// copied back: its points' normal impulses, from `solved_impulses` at `solved`'s run to
// `impulses` at `patch`'s, and its friction, twist and rolling impulses.
inline void copy_patch_result(const PatchFriction& solved,
                              const std::vector<PointImpulse>& solved_impulses,
                              PatchFriction& patch, std::vector<PointImpulse>& impulses) {
  for (int r = 0; r < patch.last - patch.first; ++r)
    impulses[patch.first + r] = solved_impulses[solved.first + r];
  patch.t1 = solved.t1;
  patch.t2 = solved.t2;
  patch.twist = solved.twist;
  patch.roll1 = solved.roll1;
  patch.roll2 = solved.roll2;
}

}  // namespace tem
