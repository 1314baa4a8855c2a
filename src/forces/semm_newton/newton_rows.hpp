// The constraint rows of SEMM by Newton (semm_newton.hpp), in the primal form: each row reads
// a relative velocity u = J y (+ what sides that are not unknowns contribute) of the bodies'
// pseudo velocities y, and adds to the objective a convex term phi(u) whose negative gradient
// is the row's impulse gamma(u) and whose (generalised) Hessian G(u) is positive semi-definite.
//
// Four kinds, as the row solver has them (semm_rows.hpp):
// - normal, one per contact point: gamma = max(0, c + (target - u) / R), phi = R gamma^2 / 2.
//   In the limit R -> 0 this is the constraint u >= target with a normal impulse >= 0; at finite
//   R it leaves u - target = R (c - gamma).
// - slip (2-D, at the patch centre), twist (1-D, about the normal) and rolling (2-D, angular
//   about the tangents): a disc of radius r, the friction limit. gamma = P(c - u / R), P the
//   projection on the disc: inside it the row sticks (its curvature 1/R), on its rim it slips
//   (the most the limit allows, against the slip; curvature only across the slip). phi is the
//   matching Moreau envelope, max over gamma in the disc of -gamma.u - R |gamma - c|^2 / 2.
//   A row `held` in stick answers gamma = c - u / R whatever its size (the polish,
//   semm_newton.hpp).
//
// c, the row's proximal centre, is the impulse the row is drawn to: the last step's impulse,
// so that a contact that pushes (or holds) as it did keeps no regularisation error, and a body at
// rest neither sinks nor creeps (with c = 0 a box on the floor sank at 7.1e-7 cm/s).
//
// R is a fraction of the row's own Delassus diagonal w = J W J^T: kNormalRegularisation for the
// normal rows and kFrictionRegularisation for the others while Newton finds the regularised
// answer (soft enough that the active set of a pour's island settles in a few iterations;
// MuJoCo's default impedance gives R = 0.11 w), kRestingFrictionRegularisation for the friction
// of an island at rest (semm_newton.cpp, at_rest), kExactRegularisation for friction held in
// stick in the polish (a millionth: the creep it leaves is far below anything a test or a user
// could see) and kSlipRegularisation for friction that slips in it.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>

#include "world/model.hpp"

namespace tem::newton {

using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Mat2 = Eigen::Matrix<Real, 2, 2>;
using Vec6 = Eigen::Matrix<Real, 6, 1>;
using Mat6 = Eigen::Matrix<Real, 6, 6>;
using Jacobian = Eigen::Matrix<Real, 2, 6>;  // rows beyond the row's dimension are zero

inline constexpr Real kNormalRegularisation = 1e-3;
inline constexpr Real kFrictionRegularisation = 1e-1;
// Why a hundredth for an island at rest: at a tenth, the settled 1,000-coin pile's polish failed
// in every step, and the regularised answer left 700-850 of its 2,940 slip rows sliding on their
// limits; the pile sank into overlap, the overlap correction lifted it in every step and it never
// came to rest. At a hundredth the pile rests within 0.11 s of its restart and sleeps (at rest,
// the polish converges in 98 of 100 steps); at 1e-3, 1e-4 and 1e-6 the pile's islands (and at
// 1e-3 the 100-coin pours') began to spend the iteration budget (docs/benchmarks.md, "The energy
// rule of friction, per island, and friction of an island at rest").
inline constexpr Real kRestingFrictionRegularisation = 1e-2;
inline constexpr Real kExactRegularisation = 1e-6;
// R of a friction row that slips in the polish. A slipping row's impulse is on its limit
// whatever R; R only sets how its direction, that of c - u / R, follows the slip u: a slip
// slower than R r (some 1e-4 mu g dt on a resting coin) leaves it near the regularised
// answer's direction c, a faster one turns it against the slip. At 1e-6 the rows on their
// limits in a resting pile slip at round-off speeds, their direction swings from iterate to
// iterate, and the polish failed in nearly every step: a 100-coin pile never came to rest.
// At the regularised answer's R, at 1e-3 and at 1e-5 two or three of twelve 100-coin pours
// were still moving at 0.3 s; at 1e-4 all twelve slept by then, at the cost of more rows let
// go in a settled pile's polish (docs/benchmarks.md, "Friction that slips in the polish").
inline constexpr Real kSlipRegularisation = 1e-4;

struct Row {
  enum class Kind : std::uint8_t { normal, slip, twist, rolling };
  Kind kind = Kind::normal;
  int dim = 1;                      // 1 or 2
  int side[2] = {-1, -1};           // island-local body of A and B, or -1 (not an unknown)
  int pair = -1;                    // with both sides unknowns: their pair's Hessian block
  Jacobian jacobian[2] = {Jacobian::Zero(), Jacobian::Zero()};  // d u / d y of each side
  Vec2 constant = Vec2::Zero();     // u's part from bodies that are not unknowns, surface slip
  Real target = 0;                  // normal rows: the least u
  Real regularisation = 0;          // R
  Real delassus = 0;                // w, the row's Delassus diagonal (mean over its components)
  Vec2 centre = Vec2::Zero();       // c, the proximal centre (normal rows: x only)
  Real radius = 0;                  // disc rows: the friction limit r (set by the solver)
  int patch = 0;                    // the contact patch of the row
  int point = -1;                   // normal rows: the contact point
  Real lever = 0;                   // normal rows: the point's distance from the patch centre
  Vec2 start = Vec2::Zero();        // u at the start of the step (the energy rule)
  // Disc rows: whether the row asks for its start velocity mirrored instead of none (its
  // constant then holds + start): semm_newton.cpp, the energy rule of friction.
  bool mirrored = false;
  bool held = false;  // disc rows: held in stick (the polish)
};

// The size of a row's impulse (or velocity): its length, or the absolute value of a 1-D row's.
inline Real size_of(const Row& row, const Vec2& v) {
  return row.dim == 2 ? v.norm() : std::abs(v.x());
}

// The impulse gamma(u) of a row and its generalised Hessian G(u) (dim x dim, top left of a 2x2).
// `at_kink_active`: a normal row exactly at (or within `band` of) its target counts as pushing
// in G (semismooth Newton may pick either branch there; picking "pushing" lets one Newton step
// carry a resting column's weight to the floor instead of one layer per iteration).
struct RowResponse {
  Vec2 impulse = Vec2::Zero();
  Mat2 curvature = Mat2::Zero();
  Real value = 0;  // phi(u)
};
// `band` < 0: the exact G (0 at the kink).
RowResponse respond(const Row& row, const Vec2& u, Real band = -1);

}  // namespace tem::newton
