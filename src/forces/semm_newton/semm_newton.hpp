// SEMM solved by Newton's method on the primal problem (contact.solver "newton", opt-in;
// method.md, "SEMM by Newton"): the same contact impulses as the row solver's (semm_rows.hpp) —
// the ones that minimise the system's energy at the next step, normal impulses >= 0, each
// patch's friction, twist and rolling resistance inside their Coulomb limits — with an
// iteration count that does not grow with the height of a column. Islands of a pour still stall
// (the redundant points of face contacts, method.md) and fall back to the row solver.
//
// The unknowns are the bodies' pseudo velocities y after the step (body_response.hpp), six per
// body; the objective is
//   l(y) = 1/2 (y - y_free).M (y - y_free) + sum over rows phi(J y),
// M = diag(mass, Q^-1) the metric in which SEMM's energy is measured and phi each row's convex
// term (newton_rows.hpp). Its minimiser is the answer of the dual problem the row solver sweeps,
// regularised by R (newton_rows.hpp): at the minimum M (y - y_free) = sum J^T gamma, so the
// impulses gamma are read off the rows. Each Newton iteration solves H dy = -grad l with H the
// whole island's Hessian, factorised (island_factor.hpp): the top grain's weight reaches the
// floor in one iteration. An exact line search along dy (l is convex and piecewise smooth; its
// slope along dy is monotone) never lets l rise. Islands, bodies joined by contacts, are solved
// on their own and shared among the threads, each on one thread: the same bits at any thread
// count.
//
// Coulomb friction is exact, not the convex cone of SAP or MuJoCo, which lets a sliding body rise
// off what it slides on by mu |slip| dt per step: each patch's friction limit mu (sum of its normal
// impulses) is held fixed while Newton solves (a disc of fixed radius, a convex problem: Tresca
// friction), then set from the new normal impulses, until the limits no longer change by more
// than the tolerance (a fixed point, as the row solver's sweeps reach it). It starts from the
// last step's impulses (warm start), so a pile at rest needs one pass.
//
// Stopping rule: a Newton pass stops when the momentum the impulses fail to give the bodies,
// |grad l| in the norm of M^-1, is at most `tolerance` times the impulses' own size
// (|y - y_free|_M), or at round-off (semm_newton.cpp, balanced); the fixed point stops when no
// patch's friction limit changed by more than `tolerance` of the largest and no row took the
// energy rule.
#pragma once

#include <vector>

#include "forces/semm.hpp"
#include "forces/semm_rows/semm_rows.hpp"
#include "forces/semm_newton/island_factor.hpp"

namespace tem {

// The solver's memory, kept between steps so that a running pile allocates little.
struct NewtonSolverMemory {
  struct Island {
    std::vector<int> bodies;   // global body indices; island-local index = position here
    std::vector<int> patches;  // the patches it solves
    std::vector<newton::Row> rows;
    newton::IslandFactor factor;
    int iterations = 0;  // Newton iterations of its last solve
    bool converged = true;
    Real scale = 1;
  };
  std::vector<Island> islands;
  std::vector<int> island_of_body, local_of_body, parent;
  // The warm start, kept for islands that fall back to the row solver, and that solver's
  // problem and memory.
  std::vector<PointImpulse> warm_impulses;
  std::vector<PatchFriction> warm_patches;
  struct Fallback {
    std::vector<ContactPoint> points;
    std::vector<Real> start, targets;
    std::vector<PatchFriction> patches;
    std::vector<PointImpulse> impulses;
    std::vector<int> patch_of;  // the caller's patch of each of its patches
    RowSolverMemory rows;
  } fallback;
};

// The largest number of Newton iterations (all passes of the friction fixed point together)
// and of passes one island's solve may take; reached, the solve reports not converged.
inline constexpr int kMaxNewtonIterations = 30;
inline constexpr int kMaxFrictionPasses = 30;

// Default SEMM by Newton's method. Arguments as solve_semm_rows (semm_rows.hpp): `start` each
// point's normal relative velocity at the start of the step, `targets` from normal_targets();
// `patches` and `impulses` the warm start on entry and the result on return. The report's
// `sweeps` is the largest number of Newton iterations any island took. Should the answer add
// energy over the step (the work of the friction impulses against the slip the step started
// with can), the island's impulses are scaled down until it adds none (report.scale < 1).
// An island that Newton's method does not converge within kMaxNewtonIterations (a pour's
// impacts with many sliding contacts can take more) is solved again by the row solver
// (semm_rows.hpp) from the step's warm start, with the scene's sweeps and tolerance, and counted
// in report.fallback_islands: its answer is then the row solver's, never an unconverged
// iterate's. settings.sync and settings.held are not read (not distributed; not for the overlap
// correction).
SolverReport solve_semm_newton(const std::vector<ContactPoint>& points,
                               const std::vector<Real>& start, const std::vector<Real>& targets,
                               const std::vector<BodyResponse>& bodies,
                               const std::vector<Vec3>& centres, const SolverSettings& settings,
                               std::vector<PatchFriction>& patches,
                               std::vector<PointImpulse>& impulses, NewtonSolverMemory& memory);

}  // namespace tem
