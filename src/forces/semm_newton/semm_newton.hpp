// SEMM solved by Newton's method on the primal problem (contact.solver "newton", the default;
// method.md, "SEMM by Newton"): the impulses that minimise the system's energy at the next step,
// normal impulses >= 0, each patch's friction, twist and rolling resistance inside their Coulomb
// limits, with an iteration count that does not grow with the height of a column.
//
// The unknowns are the bodies' pseudo velocities y after the step (body_response.hpp), six per
// body; the objective is
//   l(y) = 1/2 (y - y_free).M (y - y_free) + sum over rows phi(J y),
// M = diag(mass, Q^-1) the metric in which SEMM's energy is measured and phi each row's convex
// term (newton_rows.hpp), regularised by R and drawn to the row's last impulse. At the minimum
// M (y - y_free) = sum J^T gamma, so the impulses gamma are read off the rows. Each Newton
// iteration solves H dy = -grad l with H the whole island's Hessian, factorised
// (island_factor.hpp): the top grain's weight reaches the floor in one iteration; on an island
// of hundreds of grains whose factor fills in, by conjugate gradients to 1e-2 instead. An exact line
// search along dy (l is convex and piecewise smooth; its slope along dy is monotone) never lets
// l rise. Islands, bodies joined by contacts, are solved on their own and shared among the
// threads, each on one thread: the same bits at any thread count.
//
// Two stages per island (semm_newton.cpp, solve_island):
// - the regularised answer: soft rows (R 1e-3 w normal, 1e-1 w friction, 1e-2 w friction in an
//   island at rest), friction limits from the last step's normal impulses and then once from the
//   answer's (or from an iterate of the first pass where they have settled short of it); a
//   pour's islands converge in a few iterations where stiff rows stalled (docs/benchmarks.md);
// - the polish: each friction row held in the stick or slip the regularised answer found, R
//   1e-6 w in stick and 1e-4 w in slip (newton_rows.hpp, kSlipRegularisation), solved again;
//   rows held in stick beyond their limit are let go. Converged, friction is exact Coulomb
//   within the limits set (no lift of a sliding body, no creep at the friction angle; the
//   limits are not their fixed point, docs/method.md); should an iteration fail to
//   halve the gradient (Newton's local rate: the polish starts next to its answer or nowhere
//   near it), or kMaxPolishIterations pass, the regularised answer stands.
//   It takes one iteration at least, which lands a body at rest on round-off.
// The warm start is the lowest of y_free, the last step's impulses and the bodies' start
// velocities (solve_island).
//
// Stopping rule: Newton stops when the momentum the impulses fail to give the bodies,
// |grad l| in the norm of M^-1, is at most `tolerance` times the impulses' own size
// (|y - y_free|_M), or at round-off (semm_newton.cpp, balanced).
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
    bool polished = false;  // its friction made exact (semm_newton.cpp, the polish)
    bool at_rest = false;   // no body starts faster than its free motion changes (semm_newton.cpp)
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

// The largest number of Newton iterations one island's regularised answer may take (reached,
// the island is left to the row solver), and how many more its polish may take (reached, or an
// iteration that fails to halve the gradient, and the regularised answer stands). With 30, 16 of
// a 100-coin pour's 600 steps left an island to the row solver; with 50, none, and 22 of the
// 1,000-coin pour's first 200 steps (docs/benchmarks.md, "The iteration budget").
inline constexpr int kMaxNewtonIterations = 50;
inline constexpr int kMaxPolishIterations = 10;
// The most bodies of a moving island (not at rest) that the polish makes exact; a larger one
// keeps its regularised answer, and an island at rest is polished whatever its size. Why: on a
// moving island of more than 30 bodies the polish failed half the time (1,460 of 3,061 runs on
// the 31-100-coin islands of a 100-coin pour, two factorisations each), and took some four
// iterations where it converged; on 11-30 bodies 7 % failed, on fewer under 2 %. Kept out of
// the large moving islands, twelve 100-coin pours took a fifth fewer iterations, and seed 8's,
// whose one tipping coin kept its island's polish failing in every sub-step, slept with the
// others (docs/benchmarks.md, "The polish of moving islands").
inline constexpr int kMovingPolishBodies = 30;

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
