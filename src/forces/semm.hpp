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
//   the unconstrained minimiser clamped at 0, the tangential one the 2x2 minimiser projected on
//   the cone's disc. Each sweep lowers T; it stops when no impulse changed by more than
//   `tolerance` of the largest, and reports the sweeps and that last change.
//
// - semm-paper: the paper's K S = D (eqs. 30-31, 36-39): normal direction only, one point per
//   patch, impulses of either sign, one dense symmetric solve.
#pragma once

#include <vector>

#include "forces/body_response.hpp"
#include "forces/contact_points.hpp"

namespace tem {

// Impulse at one contact point, in its frame (normal, tangent1, tangent2). The impulse on B is
// normal * n + t1 * tangent1 + t2 * tangent2; on A its opposite.
struct PointImpulse {
  Real normal = 0;
  Real t1 = 0;
  Real t2 = 0;
};

struct SolverSettings {
  Real friction = 0;
  Real restitution = 0;
  Real restitution_threshold = 0;  // approach speeds below this are resting contact (e = 0)
  int max_sweeps = 500;
  Real tolerance = 1e-7;  // relative change of the impulses that ends the sweeps
};

struct SolverReport {
  int sweeps = 0;       // Gauss-Seidel sweeps, or 1 for the direct solve
  Real change = 0;      // largest impulse change of the last sweep, relative to the largest
  bool converged = true;
};

// Relative velocity (B minus A, world) of the pseudo velocities y at a point, before any
// contact impulse: what the objective's gradient sees.
Vec3 relative_velocity(const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                       const ContactPoint& c);

// Default SEMM by projected Gauss-Seidel. `start` holds, per point, the relative velocity at
// the start of the step in the point's frame (for restitution and the energy rule). `impulses` is the starting guess (warm start)
// and the result. Should the sweeps stop short of convergence with more energy than no impulse
// at all would leave (a warm start that no longer fits), the solve starts again from zero,
// from where every sweep can only lower the energy.
SolverReport solve_semm(const std::vector<ContactPoint>& points,
                        const std::vector<Vec3>& start, const std::vector<BodyResponse>& bodies,
                        const std::vector<Vec3>& centres, const SolverSettings& settings,
                        std::vector<PointImpulse>& impulses);

// The paper's unconstrained normal-only SEMM: K S = D, solved directly.
SolverReport solve_semm_paper(const std::vector<ContactPoint>& points,
                              const std::vector<BodyResponse>& bodies,
                              const std::vector<Vec3>& centres,
                              std::vector<PointImpulse>& impulses);

}  // namespace tem
