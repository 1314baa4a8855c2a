#include "forces/semm_newton/semm_newton.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include "support/parallel.hpp"

namespace tem {
namespace {

using newton::Jacobian;
using newton::Mat2;
using newton::Mat6;
using newton::Row;
using newton::RowResponse;
using newton::size_of;
using newton::Vec2;
using newton::Vec6;
using Island = NewtonSolverMemory::Island;
using Vector = Eigen::VectorXd;

bool is_unknown(const std::vector<BodyResponse>& bodies, int b) {
  return b >= 0 && bodies[b].inverse_mass > 0 && !bodies[b].driven;
}

int root_of(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// Islands: bodies joined by patches both of whose sides are unknowns, in the order of their
// first patch; a body touching only walls, fixed or driven bodies is an island of its own.
void find_islands(const std::vector<PatchFriction>& patches,
                  const std::vector<BodyResponse>& bodies, NewtonSolverMemory& m) {
  const int n = static_cast<int>(bodies.size());
  m.parent.resize(n);
  std::iota(m.parent.begin(), m.parent.end(), 0);
  for (const PatchFriction& p : patches) {
    if (p.last == p.first || !is_unknown(bodies, p.body_a) || !is_unknown(bodies, p.body_b))
      continue;
    const int a = root_of(m.parent, p.body_a), b = root_of(m.parent, p.body_b);
    if (a != b) m.parent[std::max(a, b)] = std::min(a, b);
  }
  m.island_of_body.assign(n, -1);  // indexed by root while patches are assigned
  int count = 0;
  std::vector<int> island_patches;
  for (size_t k = 0; k < patches.size(); ++k) {
    const PatchFriction& p = patches[k];
    if (p.last == p.first) continue;
    const int body = is_unknown(bodies, p.body_a)   ? p.body_a
                     : is_unknown(bodies, p.body_b) ? p.body_b
                                                    : -1;
    if (body < 0) continue;  // between bodies that do not move in answer: nothing to solve
    int& island = m.island_of_body[root_of(m.parent, body)];
    if (island < 0) {
      island = count++;
      if (static_cast<int>(m.islands.size()) < count) m.islands.emplace_back();
      m.islands[island].bodies.clear();
      m.islands[island].patches.clear();
    }
    m.islands[island].patches.push_back(static_cast<int>(k));
  }
  m.islands.resize(static_cast<size_t>(count));
  m.local_of_body.assign(n, -1);
  for (int b = 0; b < n; ++b) {
    if (!is_unknown(bodies, b)) continue;
    const int island = m.island_of_body[root_of(m.parent, b)];
    if (island < 0) continue;
    m.local_of_body[b] = static_cast<int>(m.islands[island].bodies.size());
    m.islands[island].bodies.push_back(b);
  }
}

// The pieces of one island's problem besides its rows.
struct IslandProblem {
  std::vector<Mat6> metric;  // M per body: diag(mass, Q^-1)
  Vector free;               // y_free
  std::vector<std::pair<int, int>> pairs;
  // Per patch of the island: its rows [first, first + normals) are normal, then slip, twist,
  // rolling rows (-1: none), and its limits per unit normal impulse.
  struct PatchRows {
    int patch = 0, first = 0, normals = 0, slip = -1, twist = -1, rolling = -1;
    Real mu = 0, rolling_limit = 0;
  };
  std::vector<PatchRows> patch_rows;
};

// One direction of a row on one side: a linear part (along which the side's centre velocity
// is read) and an angular part (along which its pseudo angular velocity is). An unknown body
// fills the Jacobian; a driven body adds its own velocity to the row's constant; walls and fixed
// bodies stand still.
struct RowBuilder {
  const std::vector<BodyResponse>& bodies;
  const std::vector<int>& local;

  void add(Row& row, int component, int s, int body, const Vec3& linear,
           const Vec3& angular) const {
    if (body < 0) return;
    if (local[body] >= 0) {
      row.side[s] = local[body];
      row.jacobian[s].block<1, 3>(component, 0) = linear.transpose();
      row.jacobian[s].block<1, 3>(component, 3) = angular.transpose();
    } else if (bodies[body].driven) {
      row.constant(component) +=
          linear.dot(bodies[body].velocity) + angular.dot(bodies[body].angular_velocity);
    }
  }
  // R: a fraction of the row's Delassus diagonal w (the mean over its components), `friction`
  // for the friction, twist and rolling rows (newton_rows.hpp).
  void regularise(Row& row, const std::vector<int>& island_bodies, Real friction) const {
    Real w = 0;
    for (int s = 0; s < 2; ++s) {
      if (row.side[s] < 0) continue;
      const BodyResponse& b = bodies[island_bodies[row.side[s]]];
      for (int c = 0; c < row.dim; ++c) {
        const Vec3 l = row.jacobian[s].block<1, 3>(c, 0).transpose();
        const Vec3 a = row.jacobian[s].block<1, 3>(c, 3).transpose();
        w += b.inverse_mass * l.squaredNorm() + a.dot(b.angular * a);
      }
    }
    row.delassus = std::max<Real>(w / row.dim, 1e-300);
    row.regularisation =
        (row.kind == Row::Kind::normal ? newton::kNormalRegularisation : friction) * row.delassus;
  }
};

// An island at rest: none of its bodies starts the step faster than one step of its free motion
// changes its velocity (g dt under gravity alone). Its contacts hold as they did, so friction
// near Coulomb's converges in a few Newton iterations there, and soft friction would only let
// the island creep (newton_rows.hpp, kRestingFrictionRegularisation). A pour's islands, with
// bodies landing or sliding, keep the soft friction that lets their active set settle.
bool at_rest(const Island& island, const std::vector<BodyResponse>& bodies) {
  for (const int b : island.bodies) {
    const BodyResponse& body = bodies[b];
    if (body.start_velocity.norm() > (body.velocity - body.start_velocity).norm()) return false;
  }
  return true;
}

void build_island(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                  const std::vector<Real>& targets, const std::vector<BodyResponse>& bodies,
                  const std::vector<Vec3>& centres, const SolverSettings& settings,
                  const std::vector<PatchFriction>& patches, const std::vector<int>& local,
                  Island& island, IslandProblem& problem) {
  const size_t nb = island.bodies.size();
  problem.metric.resize(nb);
  problem.free.resize(static_cast<Eigen::Index>(6 * nb));
  for (size_t k = 0; k < nb; ++k) {
    const BodyResponse& b = bodies[island.bodies[k]];
    Mat6& m = problem.metric[k];
    m.setZero();
    m.topLeftCorner<3, 3>().diagonal().setConstant(1 / b.inverse_mass);
    m.bottomRightCorner<3, 3>() = b.angular.inverse();
    problem.free.segment<3>(static_cast<Eigen::Index>(6 * k)) = b.velocity;
    problem.free.segment<3>(static_cast<Eigen::Index>(6 * k + 3)) = b.angular_velocity;
  }
  const RowBuilder builder{bodies, local};
  auto arm = [&](int body, const Vec3& p) {
    return body >= 0 ? Vec3(p - centres[body]) : Vec3::Zero();
  };
  island.rows.clear();
  problem.patch_rows.clear();
  problem.pairs.clear();
  for (const int k : island.patches) {
    const PatchFriction& p = patches[k];
    IslandProblem::PatchRows pr;
    pr.patch = k;
    pr.first = static_cast<int>(island.rows.size());
    pr.normals = p.last - p.first;
    pr.mu = friction_of(settings, p);
    pr.rolling_limit = rolling_limit_of(settings, p);
    // Normal rows: u = n . (v_B(point) - v_A(point)) >= target.
    for (int i = p.first; i < p.last; ++i) {
      const ContactPoint& c = points[i];
      Row row;
      row.kind = Row::Kind::normal;
      row.dim = 1;
      row.patch = k;
      row.point = i;
      row.target = targets[i];
      row.lever = (c.point - p.centre).norm();
      row.start.x() = start[i];
      builder.add(row, 0, 0, c.body_a, -c.normal, -arm(c.body_a, c.point).cross(c.normal));
      builder.add(row, 0, 1, c.body_b, c.normal, arm(c.body_b, c.point).cross(c.normal));
      island.rows.push_back(row);
    }
    if (pr.mu > 0) {
      Row slip;  // (t1, t2) . (v_B - v_A) at the centre, plus the sliding surfaces' slip
      slip.kind = Row::Kind::slip;
      slip.dim = 2;
      slip.patch = k;
      slip.constant = p.surface_slip.head<2>();
      slip.start = p.start_slip.head<2>();
      const Vec3 ra = arm(p.body_a, p.centre), rb = arm(p.body_b, p.centre);
      const Vec3 tangents[2] = {p.tangent1, p.tangent2};
      for (int c = 0; c < 2; ++c) {
        builder.add(slip, c, 0, p.body_a, -tangents[c], -ra.cross(tangents[c]));
        builder.add(slip, c, 1, p.body_b, tangents[c], rb.cross(tangents[c]));
      }
      pr.slip = static_cast<int>(island.rows.size());
      island.rows.push_back(slip);
      Row twist;  // n . (w_B - w_A)
      twist.kind = Row::Kind::twist;
      twist.dim = 1;
      twist.patch = k;
      twist.constant.x() = p.surface_slip.z();
      twist.start.x() = p.start_slip.z();
      builder.add(twist, 0, 0, p.body_a, Vec3::Zero(), -p.normal);
      builder.add(twist, 0, 1, p.body_b, Vec3::Zero(), p.normal);
      if (twist.side[0] >= 0 || twist.side[1] >= 0) {
        pr.twist = static_cast<int>(island.rows.size());
        island.rows.push_back(twist);
      }
    }
    if (pr.rolling_limit > 0) {
      Row roll;  // (t1, t2) . (w_B - w_A)
      roll.kind = Row::Kind::rolling;
      roll.dim = 2;
      roll.patch = k;
      roll.start = Vec2(p.start_roll1, p.start_roll2);
      const Vec3 tangents[2] = {p.tangent1, p.tangent2};
      for (int c = 0; c < 2; ++c) {
        builder.add(roll, c, 0, p.body_a, Vec3::Zero(), -tangents[c]);
        builder.add(roll, c, 1, p.body_b, Vec3::Zero(), tangents[c]);
      }
      pr.rolling = static_cast<int>(island.rows.size());
      island.rows.push_back(roll);
    }
    problem.patch_rows.push_back(pr);
  }
  // Regularisation, and the Hessian's off-diagonal blocks: one per pair of unknowns a row joins.
  island.at_rest = at_rest(island, bodies);
  const Real friction =
      island.at_rest ? newton::kRestingFrictionRegularisation : newton::kFrictionRegularisation;
  for (Row& row : island.rows) {
    builder.regularise(row, island.bodies, friction);
    if (row.side[0] >= 0 && row.side[1] >= 0)
      problem.pairs.emplace_back(std::max(row.side[0], row.side[1]),
                                 std::min(row.side[0], row.side[1]));
  }
  std::sort(problem.pairs.begin(), problem.pairs.end());
  problem.pairs.erase(std::unique(problem.pairs.begin(), problem.pairs.end()), problem.pairs.end());
  for (Row& row : island.rows) {
    if (row.side[0] < 0 || row.side[1] < 0) continue;
    const std::pair<int, int> key(std::max(row.side[0], row.side[1]),
                                  std::min(row.side[0], row.side[1]));
    row.pair = static_cast<int>(std::lower_bound(problem.pairs.begin(), problem.pairs.end(), key) -
                                problem.pairs.begin());
  }
  island.factor.set_pattern(static_cast<int>(nb), problem.pairs);
}

// `from` + J y, summed side by side.
Vec2 add_jacobian_times(const Row& row, const Vector& y, Vec2 from) {
  for (int s = 0; s < 2; ++s)
    if (row.side[s] >= 0) from += row.jacobian[s] * y.segment<6>(6 * row.side[s]);
  return from;
}

// A row's velocity u at the bodies' velocities y.
Vec2 row_velocity(const Row& row, const Vector& y) {
  return add_jacobian_times(row, y, row.constant);
}

// J dy: the change of a row's velocity that a change dy of the bodies' velocities makes.
Vec2 row_change(const Row& row, const Vector& dy) {
  return add_jacobian_times(row, dy, Vec2::Zero());
}

// The friction limits of each patch from its normal impulses: mu times their sum (slip), mu
// times their moments about the centre (twist), mu_r R times their sum (rolling); one per friction
// row (0 for the normal rows), with the factor that turns it into a force (the twist limit is a
// moment: compared as the force that gives it at the mean lever; 0 where there is none).
struct Limits {
  std::vector<Real> value, as_force;
};

void friction_limits(const IslandProblem& problem, const std::vector<Row>& rows,
                     const std::vector<Real>& normal_impulse, Limits& out) {
  out.value.assign(rows.size(), 0);
  out.as_force.assign(rows.size(), 1);
  for (const IslandProblem::PatchRows& pr : problem.patch_rows) {
    Real total = 0, reach = 0;
    for (int r = pr.first; r < pr.first + pr.normals; ++r) {
      total += normal_impulse[r];
      reach += normal_impulse[r] * rows[r].lever;
    }
    if (pr.slip >= 0) out.value[pr.slip] = pr.mu * total;
    if (pr.twist >= 0) {
      out.value[pr.twist] = pr.mu * reach;
      out.as_force[pr.twist] = reach > 0 && total > 0 ? total / reach : 0;
    }
    if (pr.rolling >= 0) out.value[pr.rolling] = pr.rolling_limit * total;
  }
}

// How far limits `to` lie from `from` (the largest change, as a force), and the largest slip or
// rolling limit of `to`. `from(r)`: row r's limit to compare with.
template <class From>
void limits_apart(const std::vector<Row>& rows, const Limits& to, const From& from, Real& change,
                  Real& largest) {
  change = largest = 0;
  for (size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].kind == Row::Kind::normal) continue;
    change = std::max(change, std::abs(to.value[r] - from(r)) * to.as_force[r]);
    if (rows[r].kind != Row::Kind::twist) largest = std::max(largest, to.value[r]);
  }
}

// The rows' limits set to `limits` (friction_limits); `change` and `largest` as limits_apart.
void set_limits(const Limits& limits, std::vector<Row>& rows, Real& change, Real& largest) {
  limits_apart(
      rows, limits, [&](size_t r) { return rows[r].radius; }, change, largest);
  for (size_t r = 0; r < rows.size(); ++r)
    if (rows[r].kind != Row::Kind::normal) rows[r].radius = limits.value[r];
}

// One iterate of an island: y, the Newton step and the gradient there, and each row's velocity,
// its change along the step and its response; the Hessian's blocks; the normal impulses that
// set the friction limits.
struct NewtonState {
  Vector y, step, gradient, rhs;
  std::vector<Vec2> u, du;
  std::vector<RowResponse> response;
  std::vector<Mat6> diagonal, off_diagonal;
  std::vector<Real> normal_impulse;
};

// Each normal row's impulse at the iterate `s` (0 for the other rows): what sets the limits.
void normal_impulses(const std::vector<Row>& rows, const NewtonState& s,
                     std::vector<Real>& normal) {
  normal.resize(rows.size());
  for (size_t r = 0; r < rows.size(); ++r)
    normal[r] = rows[r].kind == Row::Kind::normal ? s.response[r].impulse.x() : 0;
}

// l(y) and, with `gradient`, its gradient; each row's velocity and response kept in `s`.
Real evaluate(const Island& island, const IslandProblem& problem, NewtonState& s, Real band,
              bool gradient) {
  const std::vector<Row>& rows = island.rows;
  const size_t nb = island.bodies.size();
  s.u.resize(rows.size());
  s.response.resize(rows.size());
  Real value = 0;
  if (gradient) s.gradient.resize(s.y.size());
  for (size_t k = 0; k < nb; ++k) {
    const Vec6 d = s.y.segment<6>(static_cast<Eigen::Index>(6 * k)) -
                   problem.free.segment<6>(static_cast<Eigen::Index>(6 * k));
    const Vec6 md = problem.metric[k] * d;
    value += 0.5 * d.dot(md);
    if (gradient) s.gradient.segment<6>(static_cast<Eigen::Index>(6 * k)) = md;
  }
  for (size_t r = 0; r < rows.size(); ++r) {
    s.u[r] = row_velocity(rows[r], s.y);
    s.response[r] = newton::respond(rows[r], s.u[r], band);
    value += s.response[r].value;
    if (!gradient) continue;
    for (int side = 0; side < 2; ++side)
      if (rows[r].side[side] >= 0)
        s.gradient.segment<6>(6 * rows[r].side[side]) -=
            rows[r].jacobian[side].transpose() * s.response[r].impulse;
  }
  return value;
}

void assemble(const Island& island, const IslandProblem& problem, NewtonState& s) {
  s.diagonal = problem.metric;
  s.off_diagonal.assign(problem.pairs.size(), Mat6::Zero());
  for (size_t r = 0; r < island.rows.size(); ++r) {
    const Row& row = island.rows[r];
    const Mat2& g = s.response[r].curvature;
    if (g.isZero(0)) continue;
    for (int a = 0; a < 2; ++a) {
      if (row.side[a] < 0) continue;
      const Eigen::Matrix<Real, 6, 2> jg = row.jacobian[a].transpose() * g;
      s.diagonal[row.side[a]] += jg * row.jacobian[a];
    }
    if (row.pair >= 0) {
      // The block (i, j), i > j: J_i^T G J_j.
      const int i = row.side[0] > row.side[1] ? 0 : 1;
      s.off_diagonal[row.pair] += row.jacobian[i].transpose() * g * row.jacobian[1 - i];
    }
  }
}

// The slope of l along the step at y + alpha step, its curvature, and the size of the terms the
// slope sums (its round-off is some epsilon of that).
struct Slope {
  Real slope = 0, curvature = 0, terms = 0;
};

Slope slope_at(const Island& island, const NewtonState& s, Real base, Real metric_step,
               Real alpha) {
  Slope out{base + alpha * metric_step, metric_step, std::abs(base) + alpha * metric_step};
  for (size_t r = 0; r < island.rows.size(); ++r) {
    if (s.du[r].isZero(0)) continue;
    const RowResponse q = newton::respond(island.rows[r], s.u[r] + alpha * s.du[r]);
    const Real push = s.du[r].dot(q.impulse);
    out.slope -= push;
    out.terms += std::abs(push);
    out.curvature += s.du[r].dot(q.curvature * s.du[r]);
  }
  return out;
}

inline constexpr Real kLongestStep = 1 << 20;
// A slope within this many epsilons of the terms it sums is zero to round-off.
inline constexpr Real kSlopeRoundOff = 64 * std::numeric_limits<Real>::epsilon();

// The exact line search: the alpha > 0 where l's slope along the step vanishes (it rises
// monotonically, l being convex), by Newton's method safeguarded by bisection. It stops where
// the slope is 1e-12 of its start or zero to round-off: near an answer (a resting island's
// step) the start's slope is itself near round-off, and the relative rule alone bisected on to
// a bracket of 1e-14, some 30 evaluations of every row a search on a resting column.
Real line_search(const Island& island, const IslandProblem& problem, NewtonState& s) {
  const size_t nb = island.bodies.size();
  Real base = 0, metric_step = 0;
  for (size_t k = 0; k < nb; ++k) {
    const Eigen::Index at = static_cast<Eigen::Index>(6 * k);
    const Vec6 m_step = problem.metric[k] * s.step.segment<6>(at);
    base += m_step.dot(s.y.segment<6>(at) - problem.free.segment<6>(at));
    metric_step += m_step.dot(s.step.segment<6>(at));
  }
  s.du.resize(island.rows.size());
  for (size_t r = 0; r < island.rows.size(); ++r) s.du[r] = row_change(island.rows[r], s.step);
  // The slope at alpha = 0 is the gradient's along the step (newton_iterations evaluated it at
  // y), one evaluation of every row fewer a line search.
  const Real slope0 = s.gradient.dot(s.step);
  if (!(slope0 < 0)) return 0;  // no descent left (round-off)
  auto flat = [&](const Slope& at) {
    return std::abs(at.slope) <= std::max(1e-12 * -slope0, kSlopeRoundOff * at.terms);
  };
  // Where the slope is still falling at 1 (the Hessian overestimated a row's curvature), the
  // bracket grows until it rises.
  Real lo = 0, hi = 1;
  Slope at = slope_at(island, s, base, metric_step, hi);
  while (at.slope < 0 && !flat(at) && hi < kLongestStep) {
    lo = hi;
    hi *= 2;
    at = slope_at(island, s, base, metric_step, hi);
  }
  if (at.slope <= 0 || flat(at)) return hi;
  Real alpha = hi;
  for (int k = 0; k < 100; ++k) {
    Real next = at.curvature > 0 ? alpha - at.slope / at.curvature : -1;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    alpha = next;
    at = slope_at(island, s, base, metric_step, alpha);
    if (at.slope > 0)
      hi = alpha;
    else
      lo = alpha;
    if (flat(at) || hi - lo <= 1e-14) break;
  }
  return alpha;
}

// W sum J^T gamma over the rows of the island, gamma each row's impulse in `s`: the change of
// velocity the impulses make, W = diag(1 / mass, Q) per body.
Vector mobility_times(const Island& island, const std::vector<BodyResponse>& bodies,
                      const IslandProblem& problem, const NewtonState& s) {
  Vector push = Vector::Zero(problem.free.size());
  for (size_t r = 0; r < island.rows.size(); ++r)
    for (int side = 0; side < 2; ++side)
      if (island.rows[r].side[side] >= 0)
        push.segment<6>(6 * island.rows[r].side[side]) +=
            island.rows[r].jacobian[side].transpose() * s.response[r].impulse;
  for (size_t k = 0; k < island.bodies.size(); ++k) {
    const Eigen::Index at = static_cast<Eigen::Index>(6 * k);
    const BodyResponse& b = bodies[island.bodies[k]];
    push.segment<3>(at) *= b.inverse_mass;
    push.segment<3>(at + 3) = b.angular * Vec3(push.segment<3>(at + 3));
  }
  return push;
}

// The first pass's early stop (solve_island): the balance its iterate must meet, and how much of
// their move the limits it gives may still change from one iterate to the next.
inline constexpr Real kLimitsBalance = 1e-1;
inline constexpr Real kLimitsSettled = 5e-2;

// The stopping rule. The gradient of l is M (y - y_free) - sum J^T gamma: the momentum the
// impulses read off the rows fail to give the bodies. Converged when it is, in the norm of M^-1,
// at most `tolerance` of the impulses' own (|M (y - y_free)|) or at the round-off that the rows'
// 1/R amplifies (kRoundOff times |y|_M): the impulses then move the bodies to y, to that
// tolerance, whatever the regularisation.
inline constexpr Real kRoundOff =
    100 * std::numeric_limits<Real>::epsilon() / newton::kExactRegularisation;

// The gradient's size in the norm of M^-1 (`residual`), and what it must fall to at a tolerance:
// that of the impulses' own momentum (`made`, |M (y - y_free)|) plus the round-off of |y|_M
// (`size`).
struct Balance {
  Real residual = 0, made = 0, size = 0;
  Real allowed(Real tolerance) const { return tolerance * made + kRoundOff * size; }
  bool met(Real tolerance) const { return residual <= allowed(tolerance); }
};

Balance balance(const Island& island, const std::vector<BodyResponse>& bodies,
                const IslandProblem& problem, const NewtonState& s) {
  Real residual = 0, made = 0, size = 0;
  for (size_t k = 0; k < island.bodies.size(); ++k) {
    const Eigen::Index at = static_cast<Eigen::Index>(6 * k);
    const BodyResponse& b = bodies[island.bodies[k]];
    const Vec6 g = s.gradient.segment<6>(at);
    residual +=
        b.inverse_mass * g.head<3>().squaredNorm() + g.tail<3>().dot(b.angular * g.tail<3>());
    const Vec6 d = s.y.segment<6>(at) - problem.free.segment<6>(at);
    made += d.dot(problem.metric[k] * d);
    const Vec6 y = s.y.segment<6>(at);
    size += y.dot(problem.metric[k] * y);
  }
  return {std::sqrt(residual), std::sqrt(made), std::sqrt(size)};
}

// How a run of Newton's iterations may end: at the stopping rule (`solve`); or, in the polish,
// only after one iteration at least (`polish_budget`), and also as soon as two iterations in a
// row fail to halve the gradient (`polish`).
enum class Iterations { solve, polish_budget, polish };

// Newton's iterations on one island until l's gradient balances (the stopping rule) or the
// island has taken `budget` iterations in all (false). With Iterations::polish, also false as
// soon as two iterations in a row fail to halve the gradient: started next to its answer, the
// polish converges at Newton's local rate or not at all; one iteration may cross a kink first (a
// box pushed along the floor: the load moves among its corners as the normal rows turn exact,
// the gradient stays, and the next iteration lands). In the polish at least one iteration is
// taken.
// Why the one: the polish's start (the regularised answer) often meets the tolerance already,
// and the impulses read off the rows there are off by the gradient, up to the tolerance: a box
// at rest would move at up to 3e-10 cm/s in some steps. One Newton step from there lands on
// the exact answer of its stick and slip to round-off (l is quadratic on that piece).
// `stop_early`, given every iterate that misses the tolerance and its balance, may end them there
// (true): the regularised answer's first pass, whose limits are about to move (solve_island).
bool newton_iterations(
    Island& island, const std::vector<BodyResponse>& bodies, const IslandProblem& problem,
    NewtonState& s, Real band, Real tolerance, int budget, Iterations rule = Iterations::solve,
    const std::function<bool(const NewtonState&, const Balance&)>& stop_early = {}) {
  Real last = std::numeric_limits<Real>::infinity();
  bool halved_before = true;
  const int first = island.iterations;
  while (true) {
    evaluate(island, problem, s, island.iterations == 0 ? band : -1, true);
    const Balance b = balance(island, bodies, problem, s);
    if (b.met(tolerance) && !(rule != Iterations::solve && island.iterations == first)) return true;
    if (stop_early && stop_early(s, b)) return true;
    const bool halved = b.residual <= 0.5 * last;
    if (island.iterations >= budget || (rule == Iterations::polish && !halved && !halved_before))
      return false;
    halved_before = halved;
    last = b.residual;
    assemble(island, problem, s);
    if (!island.factor.factorise(s.diagonal, s.off_diagonal)) return false;
    s.rhs = -s.gradient;
    island.factor.solve(s.rhs, s.step);
    ++island.iterations;
    const Real alpha = line_search(island, problem, s);
    if (alpha == 0) return true;  // no descent left: round-off
    s.y += alpha * s.step;
  }
}

// The work the impulses of `s` do over the step: each row's gamma . (u_start + u_after) / 2,
// u_after what the impulses read off the rows give the bodies (y, to the tolerance); that of the
// friction, twist and rolling rows alone; and its part quadratic in the impulses,
// gamma . (u_after - u_free) / 2 (`curvature`).
struct StepWork {
  Real added = 0, by_friction = 0, curvature = 0;
  // Beyond round-off: the velocities after the step carry that of their change, so the work
  // carries some epsilon of the curvature; a body held exactly at rest (the polish lands there)
  // would otherwise add energy in most steps.
  bool beyond_round_off(Real work) const {
    return work > 64 * std::numeric_limits<Real>::epsilon() * std::abs(curvature);
  }
};

StepWork step_work(const Island& island, const std::vector<BodyResponse>& bodies,
                   const IslandProblem& problem, const NewtonState& s) {
  // The impulses' change of the bodies' velocities, and the rows' velocities it gives.
  const Vector change = mobility_times(island, bodies, problem, s);
  const Vector given = problem.free + change;
  StepWork work;
  for (size_t r = 0; r < island.rows.size(); ++r) {
    const Row& row = island.rows[r];
    const Vec2& gamma = s.response[r].impulse;
    if (gamma.isZero(0)) continue;
    // u without the mirrored start: the row's real velocity.
    const Vec2 shift = row.mirrored ? row.start : Vec2::Zero();
    const Real done = gamma.dot(row.start + row_velocity(row, given) - shift) / 2;
    work.added += done;
    if (row.kind != Row::Kind::normal) work.by_friction += done;
    work.curvature += gamma.dot(row_change(row, change)) / 2;
  }
  return work;
}

// The energy rule of friction, applied to the island's friction rows together: should their
// impulses add energy over the step, each friction, twist or rolling row whose impulse pushes
// along the slip the step started with (the work gamma . (u_start + u_after) / 2 > 0) asks from
// now on for its start velocity mirrored (u_after = -u_start, no work) instead of none. Returns
// whether a row was mirrored. Why not row by row, as the row solver (semm.cpp, friction_block):
// the regularised friction leaves a resting row the creep R (c - gamma), and a row whose impulse
// pushes along last step's creep was mirrored: some 800 of the settled 1,000-coin pile's 2,940
// slip rows in every step, while its friction as a whole took energy out. Each mirror cost the
// island another pass (a resting column took four iterations a step instead of one) and kept
// the row's creep, reversed, instead of ending it. Why not the whole island's work: on a pile at
// rest its normal rows' regularisation error does some 2e-10 erg, which no mirror of friction
// removes; gated on it, 1,300-1,500 rows were mirrored in every step at rest, seven iterations a
// step instead of three (docs/benchmarks.md, "The energy rule of friction, per island, and
// friction of an island at rest").
bool mirror_rows(Island& island, const std::vector<BodyResponse>& bodies,
                 const IslandProblem& problem, const NewtonState& s) {
  const StepWork work = step_work(island, bodies, problem, s);
  if (!work.beyond_round_off(work.by_friction)) return false;
  std::vector<Row>& rows = island.rows;
  bool mirrored = false;
  for (size_t r = 0; r < rows.size(); ++r) {
    Row& row = rows[r];
    if (row.kind == Row::Kind::normal || row.mirrored ||
        !(s.response[r].impulse.dot(row.start) > 0))
      continue;
    row.mirrored = true;
    row.constant += row.start;
    mirrored = true;
  }
  return mirrored;
}

// One island: the warm start, the regularised answer, its polish, the energy check.
void solve_island(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                  const std::vector<Real>& targets, const std::vector<BodyResponse>& bodies,
                  const std::vector<Vec3>& centres, const SolverSettings& settings,
                  std::vector<PatchFriction>& patches, std::vector<PointImpulse>& impulses,
                  const std::vector<int>& local, Island& island) {
  IslandProblem problem;
  build_island(points, start, targets, bodies, centres, settings, patches, local, island, problem);
  std::vector<Row>& rows = island.rows;
  NewtonState s;

  // The warm start, whichever of three places has the lowest l: y_free; y_free moved by the
  // last step's impulses (each row's proximal centre); and the bodies' velocities at the start
  // of the step, the contacts holding every body as it was. On a resting pile the last is
  // nearly the answer while the impulses are not: a point that moved or appeared since the
  // last step takes no impulse (warm_start.hpp), and a coin whose other points keep theirs is
  // pushed into its neighbour at 10 cm/s (docs/benchmarks.md, "SEMM by Newton").
  std::vector<Real>& normal = s.normal_impulse;
  normal.assign(rows.size(), 0);
  for (size_t r = 0; r < rows.size(); ++r)
    if (rows[r].kind == Row::Kind::normal) normal[r] = impulses[rows[r].point].normal;
  Real change = 0, largest = 0;
  Limits limits;
  friction_limits(problem, rows, normal, limits);
  set_limits(limits, rows, change, largest);
  NewtonState warm;
  warm.response.assign(rows.size(), RowResponse{});
  for (const IslandProblem::PatchRows& pr : problem.patch_rows) {
    const PatchFriction& p = patches[pr.patch];
    for (int r = pr.first; r < pr.first + pr.normals; ++r)
      warm.response[r].impulse = Vec2(normal[r], 0);
    if (pr.slip >= 0) warm.response[pr.slip].impulse = Vec2(p.t1, p.t2);
    if (pr.twist >= 0) warm.response[pr.twist].impulse = Vec2(p.twist, 0);
    if (pr.rolling >= 0) warm.response[pr.rolling].impulse = Vec2(p.roll1, p.roll2);
  }
  for (size_t r = 0; r < rows.size(); ++r) rows[r].centre = warm.response[r].impulse;
  warm.y = problem.free + mobility_times(island, bodies, problem, warm);
  NewtonState held;
  held.y = problem.free;
  for (size_t k = 0; k < island.bodies.size(); ++k)
    held.y.segment<3>(static_cast<Eigen::Index>(6 * k)) = bodies[island.bodies[k]].start_velocity;
  s.y = problem.free;
  Real lowest = evaluate(island, problem, s, -1, false);
  for (NewtonState* candidate : {&warm, &held}) {
    const Real at = evaluate(island, problem, *candidate, -1, false);
    if (at < lowest) {
      lowest = at;
      s.y = candidate->y;
    }
  }

  // How near its target a normal row counts as pushing in the first Hessian (newton_rows.hpp):
  // a millionth of the largest velocity change a row asks of the free motion.
  Real ask = 0;
  for (const Row& row : rows)
    if (row.kind == Row::Kind::normal)
      ask = std::max(ask, std::abs(row.target - row_velocity(row, problem.free).x()));
  const Real band = 1e-6 * ask;

  const Real tolerance = settings.tolerance;
  island.iterations = 0;
  island.polished = false;
  // The regularised answer. Its friction limits are the last step's normal impulses' at first,
  // then, once, those of the answer with them: a contact that pushes as it did has its exact
  // limit, and the fixed point of the limits, which contracts by only about 0.27 a pass on a
  // pour (docs/benchmarks.md), is not chased. Passes follow while the energy rule mirrors rows.
  // The first pass stops short of the tolerance where a second one is to follow anyway: where
  // its iterate balances to kLimitsBalance, the limits its normal impulses give lie beyond the
  // tolerance from the ones set, and they moved by at most kLimitsSettled of that since the last
  // iterate. The limits are then taken from there and the second pass converges to the
  // tolerance with them. Solving the first pass further would sharpen limits that are off by the
  // unchased fixed point anyway (a quarter of their move); in a flow it took the iterations of
  // Newton's quadratic end that the second pass takes again. A resting island's limits move
  // little, and 5 % of a small move settles only next to the answer: the box at the friction
  // angle still holds (docs/benchmarks.md, "The first pass's early stop").
  bool early = false;
  Limits trial, last_trial;
  const auto limits_move = [&](const NewtonState& at, const Balance& b) {
    // Every iterate's limits, for the next one's "since"; compared only where it balances.
    normal_impulses(rows, at, normal);
    std::swap(trial, last_trial);
    friction_limits(problem, rows, normal, trial);
    if (last_trial.value.empty() || !b.met(kLimitsBalance)) return false;
    Real moved = 0, top = 0, since = 0, unused = 0;
    limits_apart(
        rows, trial, [&](size_t r) { return rows[r].radius; }, moved, top);
    limits_apart(
        rows, trial, [&](size_t r) { return last_trial.value[r]; }, since, unused);
    early = moved > tolerance * top && since <= kLimitsSettled * moved;
    return early;
  };
  bool solved = newton_iterations(island, bodies, problem, s, band, tolerance, kMaxNewtonIterations,
                                  Iterations::solve, limits_move);
  if (solved) {
    // Stopped early, `trial` holds the limits of the iterate it stopped at.
    if (early) {
      std::swap(limits, trial);
    } else {
      normal_impulses(rows, s, normal);
      friction_limits(problem, rows, normal, limits);
    }
    set_limits(limits, rows, change, largest);
    // Stopped early, the energy rule waits for the converged answer of the second pass.
    bool again = early || mirror_rows(island, bodies, problem, s) || change > tolerance * largest;
    while (solved && again) {
      solved = newton_iterations(island, bodies, problem, s, band, tolerance, kMaxNewtonIterations);
      again = solved && mirror_rows(island, bodies, problem, s);
    }
  }
  island.converged = solved;

  // The polish (as OSQP polishes its ADMM answer): each normal row's R made a millionth of w
  // with its centre at the regularised answer; each friction row held in the state that answer
  // found, stick or slip, with R a millionth of w in stick and kSlipRegularisation in slip and
  // its centre at that answer; and Newton solves again. A held row that then needs more than its
  // limit is let go and slips; the normal rows are drawn to their impulses until their velocities
  // meet the targets; the friction limits are taken once from the polished normal impulses. Why
  // the normal rows: left at the regularised answer's R, a thousandth of w drawn to the last
  // step's impulse, a landing coin ended 2.9e-5 cm inside the floor, a rebound was 0.4 % short
  // of its restitution, and a box on a belt slid 1e-3 slower than mu g in its first step (its
  // friction limit from the soft normal impulse); the row solver has all three to 1e-9.
  // If two iterations in a row fail to halve the gradient, or the polish takes more than
  // kMaxPolishIterations, the normal rows alone are made exact, at the regularised answer's R,
  // with the friction rows as that answer has them and only the budget to stop them (a spinning
  // coin on a shaker, whose slip turns with the iterate, failed the full polish in one sub-step
  // of twenty-five, and the regularised normal rows left it 5e-11 cm off the plate); failing
  // that, the regularised answer stands. A large moving island keeps its regularised answer
  // (kMovingPolishBodies).
  const auto polish_rows = [&](bool friction) {
    for (size_t r = 0; r < rows.size(); ++r) {
      Row& row = rows[r];
      if (row.kind == Row::Kind::normal) {
        row.centre = s.response[r].impulse;
        if (friction) row.regularisation = newton::kExactRegularisation * row.delassus;
        continue;
      }
      if (!friction || !(row.radius > 0)) continue;
      row.centre = s.response[r].impulse;
      row.held = size_of(row, row.centre) < row.radius * (1 - tolerance);
      row.regularisation =
          (row.held ? newton::kExactRegularisation : newton::kSlipRegularisation) * row.delassus;
    }
    const int budget = island.iterations + kMaxPolishIterations;
    const Iterations rule = friction ? Iterations::polish : Iterations::polish_budget;
    bool limits_polished = false;
    Real last_miss = std::numeric_limits<Real>::infinity();
    bool polished = newton_iterations(island, bodies, problem, s, band, tolerance, budget, rule);
    while (polished) {
      bool let_go = false;
      for (size_t r = 0; r < rows.size(); ++r)
        if (rows[r].held &&
            size_of(rows[r], s.response[r].impulse) > rows[r].radius * (1 + tolerance)) {
          rows[r].held = false;
          rows[r].regularisation = newton::kSlipRegularisation * rows[r].delassus;
          let_go = true;
        }
      // While a normal row's velocity misses its target by more than the tolerance of the
      // largest velocity change asked (R (c - gamma), newton_rows.hpp), the normal rows are
      // drawn to their polished impulses (a proximal point step): the miss shrinks by about
      // R / w a pass. Judged by the miss, not by the impulses' move: the points of a flat
      // contact share its load in any of many ways. And only while the largest miss halves from
      // pass to pass: where the load drifts among a contact's points by the same amount in every
      // pass, so does the miss, and the passes went on to the budget without making the
      // velocities any better (a box resting on another, whose corners share its weight).
      Real miss = 0;
      for (size_t r = 0; r < rows.size(); ++r)
        if (rows[r].kind == Row::Kind::normal)
          miss = std::max(miss, rows[r].regularisation *
                                    std::abs(s.response[r].impulse.x() - rows[r].centre.x()));
      const bool recentred = miss > tolerance * ask && miss <= 0.5 * last_miss;
      last_miss = miss;
      if (recentred)
        for (size_t r = 0; r < rows.size(); ++r)
          if (rows[r].kind == Row::Kind::normal) rows[r].centre = s.response[r].impulse;
      // Once, the friction limits of the polished normal impulses: a sliding body's friction is
      // then mu times the normal impulse it gets, not the one the regularised answer gave. Not
      // chased further: a spinning coin's limits then moved by some 1e-12 of their size from
      // pass to pass, the round-off of the polished answer, and used up the polish's budget.
      bool limits_moved = false;
      if (!limits_polished) {
        limits_polished = true;
        normal_impulses(rows, s, normal);
        friction_limits(problem, rows, normal, limits);
        set_limits(limits, rows, change, largest);
        limits_moved = change > tolerance * largest;
      }
      if (!mirror_rows(island, bodies, problem, s) && !let_go && !recentred && !limits_moved) break;
      polished = newton_iterations(island, bodies, problem, s, band, tolerance, budget, rule);
    }
    return polished;
  };
  const bool polish =
      island.at_rest || static_cast<int>(island.bodies.size()) <= kMovingPolishBodies;
  if (solved && polish) {
    const Vector soft_y = s.y;
    const std::vector<Row> soft_rows = rows;
    island.polished = polish_rows(true);
    if (!island.polished) {
      s.y = soft_y;
      rows = soft_rows;
      evaluate(island, problem, s, -1, false);
      const bool normals = polish_rows(false);
      if (!normals) {
        s.y = soft_y;
        rows = soft_rows;
      }
    }
  }
  evaluate(island, problem, s, -1, false);
  // Energy over the step (semm_rows.cpp, energy_scale): should the impulses still add energy,
  // every impulse of the island is scaled by the largest s with s B + s^2 A <= 0 (A the work's
  // curvature, B its part linear in the impulses).
  const StepWork work = step_work(island, bodies, problem, s);
  island.scale = 1;
  if (work.beyond_round_off(work.added)) {
    const Real linear = work.added - work.curvature;
    island.scale =
        linear < 0 && work.curvature > 0 ? std::clamp<Real>(-linear / work.curvature, 0, 1) : 0;
  }

  // The impulses, back in the caller's places.
  const Real scale = island.scale;
  for (const IslandProblem::PatchRows& pr : problem.patch_rows) {
    PatchFriction& p = patches[pr.patch];
    for (int r = pr.first; r < pr.first + pr.normals; ++r)
      impulses[rows[r].point].normal = scale * s.response[r].impulse.x();
    const Vec2 slip = pr.slip >= 0 ? Vec2(scale * s.response[pr.slip].impulse) : Vec2::Zero();
    p.t1 = slip.x();
    p.t2 = slip.y();
    p.twist = pr.twist >= 0 ? scale * s.response[pr.twist].impulse.x() : 0;
    const Vec2 roll = pr.rolling >= 0 ? Vec2(scale * s.response[pr.rolling].impulse) : Vec2::Zero();
    p.roll1 = roll.x();
    p.roll2 = roll.y();
  }
}

// The islands Newton did not converge, solved together by the row solver from the step's warm
// start; their results written back in the caller's places.
SolverReport solve_by_rows(const std::vector<ContactPoint>& points, const std::vector<Real>& start,
                           const std::vector<Real>& targets,
                           const std::vector<BodyResponse>& bodies,
                           const std::vector<Vec3>& centres, const SolverSettings& settings,
                           std::vector<PatchFriction>& patches, std::vector<PointImpulse>& impulses,
                           NewtonSolverMemory& memory) {
  NewtonSolverMemory::Fallback& f = memory.fallback;
  f.points.clear();
  f.start.clear();
  f.targets.clear();
  f.patches.clear();
  f.impulses.clear();
  f.patch_of.clear();
  for (const Island& island : memory.islands) {
    if (island.converged) continue;
    for (const int k : island.patches) {
      PatchFriction p = memory.warm_patches[k];
      const int first = p.first;
      p.first = static_cast<int>(f.points.size());
      for (int i = first; i < memory.warm_patches[k].last; ++i) {
        ContactPoint c = points[i];
        c.patch = static_cast<int>(f.patches.size());
        f.points.push_back(c);
        f.start.push_back(start[i]);
        f.targets.push_back(targets[i]);
        f.impulses.push_back(memory.warm_impulses[i]);
      }
      p.last = static_cast<int>(f.points.size());
      f.patches.push_back(p);
      f.patch_of.push_back(k);
    }
  }
  const SolverReport report = solve_semm_rows(f.points, f.start, f.targets, bodies, centres,
                                              settings, f.patches, f.impulses, f.rows);
  for (size_t j = 0; j < f.patches.size(); ++j)
    copy_patch_result(f.patches[j], f.impulses, patches[f.patch_of[j]], impulses);
  return report;
}

}  // namespace

SolverReport solve_semm_newton(const std::vector<ContactPoint>& points,
                               const std::vector<Real>& start, const std::vector<Real>& targets,
                               const std::vector<BodyResponse>& bodies,
                               const std::vector<Vec3>& centres, const SolverSettings& settings,
                               std::vector<PatchFriction>& patches,
                               std::vector<PointImpulse>& impulses, NewtonSolverMemory& memory) {
  impulses.resize(points.size());
  SolverReport report;
  report.sweeps = 0;
  if (points.empty()) return report;
  // Points on patches that no island solves (between bodies that do not answer) push nothing.
  for (const PatchFriction& p : patches)
    if (!is_unknown(bodies, p.body_a) && !is_unknown(bodies, p.body_b))
      for (int i = p.first; i < p.last; ++i) impulses[i].normal = 0;
  memory.warm_impulses = impulses;
  memory.warm_patches = patches;
  find_islands(patches, bodies, memory);
  // Each island on one thread, taken one by one (islands differ much in size).
  parallel_for(
      static_cast<long long>(memory.islands.size()), 1,
      [&](long long k) {
        solve_island(points, start, targets, bodies, centres, settings, patches, impulses,
                     memory.local_of_body, memory.islands[k]);
      },
      true);
  for (const Island& island : memory.islands) {
    report.sweeps = std::max(report.sweeps, island.iterations);
    if (island.converged)
      report.scale = std::min(report.scale, island.scale);
    else
      ++report.fallback_islands;
    if (island.converged && !island.polished) ++report.regularised_islands;
    if (island.factor.supernodal()) ++report.supernodal_islands;
  }
  if (report.fallback_islands > 0) {
    const SolverReport rows =
        solve_by_rows(points, start, targets, bodies, centres, settings, patches, impulses, memory);
    report.converged = rows.converged;
    report.scale = std::min(report.scale, rows.scale);
  }
  return report;
}

}  // namespace tem
