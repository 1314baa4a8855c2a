#include "forces/semm_rows/semm_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>

#include "forces/solver_sync.hpp"

namespace tem {
namespace {

using Memory = RowSolverMemory;
using Vec2 = Eigen::Matrix<Real, 2, 1>;

// The slot of a body in the solver's velocity arrays: its own if it moves, else the still one.
int slot_of(const std::vector<BodyResponse>& bodies, int body) {
  // Bodies that impulses move, and driven ones (prescribed motion), which keep their own
  // velocity; walls and fixed bodies share the still slot.
  return body >= 0 && (bodies[body].inverse_mass > 0 || bodies[body].driven)
             ? body
             : static_cast<int>(bodies.size());
}

// The normal block of a patch of three or four points not on one line: K's pseudo-inverse.
//
// Why: a face resting on a face is held by three or four points whose normal impulses are
// strongly coupled (each one's push tilts the face over the others). Scalar rows resolve that
// coupling one point at a time, and a stack of coins needs hundreds of sweeps before the
// corners stop rocking: with 20 sweeps a column of ten coins at dt 5e-4 topples (docs/
// benchmarks.md). The points of a patch share its normal, so their normal velocities are
// u = A^T g with g = (normal velocity at the centre, relative spin about t1, about t2) and A's
// column for point i = (1, (d_i x n).t1, (d_i x n).t2), d_i from the patch's centre to the
// point; and K = A^T K3 A with K3 the 3x3 response of g to a normal force at the centre and
// moments about t1, t2. With A of full rank, K's pseudo-inverse is A^T S K3^-1 S A,
// S = (A A^T)^-1: the impulses that reach given normal velocities in one solve, spread over
// the points with the least norm (equivalent points share the load), from 3x3 algebra only,
// where the regularised inverse of the singular K would amplify round-off.
void patch_block(const std::vector<ContactPoint>& points, const PatchFriction& p, Real inv_a,
                 Real inv_b, const Mat3& q_a, const Mat3& q_b, const Vec3& arm_a,
                 const Vec3& arm_b, Memory::FrictionRow& f) {
  f.block = false;
  const int m = p.last - p.first;
  if (m < 3 || m > 4) return;
  const Vec3 &n = p.normal, &t1 = p.tangent1, &t2 = p.tangent2;
  Eigen::Matrix<Real, 3, 4> a = Eigen::Matrix<Real, 3, 4>::Zero();
  for (int i = 0; i < m; ++i) {
    const Vec3 dxn = (points[p.first + i].point - p.centre).cross(n);
    a.col(i) = Vec3(1, dxn.dot(t1), dxn.dot(t2));
  }
  const Mat3 aat = a * a.transpose();
  // Three or four points on one line (an edge on a face) leave a turn about that line free.
  // Only the eigenvalues' ratio is read, against thresholds far above round-off: the closed
  // form (computeDirect) serves, at a fraction of the iterative solver's cost per patch and
  // sub-step.
  Eigen::SelfAdjointEigenSolver<Mat3> shape;
  shape.computeDirect(aat, Eigen::EigenvaluesOnly);
  if (!(shape.eigenvalues()(0) > 1e-8 * shape.eigenvalues()(2))) return;
  Mat3 k3 = Mat3::Zero();
  auto add_side = [&](Real inverse_mass, const Mat3& q, const Vec3& arm) {
    const Vec3 cn = arm.cross(n), q_cn = q * cn, q_t1 = q * t1, q_t2 = q * t2;
    k3(0, 0) += inverse_mass + cn.dot(q_cn);
    k3(0, 1) += cn.dot(q_t1);
    k3(0, 2) += cn.dot(q_t2);
    k3(1, 1) += t1.dot(q_t1);
    k3(1, 2) += t1.dot(q_t2);
    k3(2, 2) += t2.dot(q_t2);
  };
  add_side(inv_a, q_a, arm_a);
  add_side(inv_b, q_b, arm_b);
  k3(1, 0) = k3(0, 1);
  k3(2, 0) = k3(0, 2);
  k3(2, 1) = k3(1, 2);
  // Neither side turns or moves (both still, or driven): nothing to solve.
  Eigen::SelfAdjointEigenSolver<Mat3> response;
  response.computeDirect(k3, Eigen::EigenvaluesOnly);
  if (!(response.eigenvalues()(0) > 1e-12 * response.eigenvalues()(2))) return;
  const Mat3 s = aat.inverse();
  const Mat3 middle = s * k3.inverse() * s;
  f.k_pseudo_inverse = a.transpose() * middle * a;
  f.block = true;
}

// Builds patch k's rows (laid out at [first, first + its points)) and its friction row.
void build_patch(const std::vector<ContactPoint>& points, const std::vector<Real>& targets,
                 const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                 const PatchFriction& p, const std::vector<PointImpulse>& impulses, int first,
                 const std::vector<char>* held, Memory& m, Memory::FrictionRow& f) {
  const int still = static_cast<int>(bodies.size());
  const int a = slot_of(bodies, p.body_a), b = slot_of(bodies, p.body_b);
  const Real inv_a = m.inverse_mass[a], inv_b = m.inverse_mass[b];
  const Mat3 q_a = a == still ? Mat3::Zero() : bodies[a].angular;
  const Mat3 q_b = b == still ? Mat3::Zero() : bodies[b].angular;
  const Vec3 centre_a = a == still ? Vec3::Zero() : centres[a];
  const Vec3 centre_b = b == still ? Vec3::Zero() : centres[b];
  for (int i = p.first; i < p.last; ++i) {
    const ContactPoint& c = points[i];
    Memory::NormalRow& row = m.rows[first + (i - p.first)];
    row.a = a;
    row.b = b;
    row.normal = c.normal;
    row.arm_a_x_n = a == still ? Vec3::Zero() : Vec3((c.point - centre_a).cross(c.normal));
    row.arm_b_x_n = b == still ? Vec3::Zero() : Vec3((c.point - centre_b).cross(c.normal));
    row.turn_a = q_a * row.arm_a_x_n;
    row.turn_b = q_b * row.arm_b_x_n;
    const Real k = inv_a + inv_b + row.arm_a_x_n.dot(row.turn_a) + row.arm_b_x_n.dot(row.turn_b);
    row.inverse_k = k > 0 ? 1 / k : 0;
    row.target = targets[i];
    row.floor = held && (*held)[i] ? -std::numeric_limits<Real>::infinity() : 0;
    row.impulse = impulses[i].normal;
    row.lever = (c.point - p.centre).norm();
    m.point_of_row[first + (i - p.first)] = i;
  }
  f.a = a;
  f.b = b;
  f.first = first;
  f.last = first + (p.last - p.first);
  f.tangent1 = p.tangent1;
  f.tangent2 = p.tangent2;
  f.normal = p.normal;
  const Vec3 arm_a = a == still ? Vec3::Zero() : Vec3(p.centre - centre_a);
  const Vec3 arm_b = b == still ? Vec3::Zero() : Vec3(p.centre - centre_b);
  f.arm_a_x_t1 = arm_a.cross(p.tangent1);
  f.arm_a_x_t2 = arm_a.cross(p.tangent2);
  f.arm_b_x_t1 = arm_b.cross(p.tangent1);
  f.arm_b_x_t2 = arm_b.cross(p.tangent2);
  f.turn_a_t1 = q_a * f.arm_a_x_t1;
  f.turn_a_t2 = q_a * f.arm_a_x_t2;
  f.turn_b_t1 = q_b * f.arm_b_x_t1;
  f.turn_b_t2 = q_b * f.arm_b_x_t2;
  f.turn_a_n = q_a * p.normal;
  f.turn_b_n = q_b * p.normal;
  // K's tangential block at the centre: d(slip_r) / d(impulse along t_c).
  Eigen::Matrix<Real, 2, 2> k;
  k(0, 0) = inv_a + inv_b + f.arm_a_x_t1.dot(f.turn_a_t1) + f.arm_b_x_t1.dot(f.turn_b_t1);
  k(1, 1) = inv_a + inv_b + f.arm_a_x_t2.dot(f.turn_a_t2) + f.arm_b_x_t2.dot(f.turn_b_t2);
  k(0, 1) = k(1, 0) = f.arm_a_x_t1.dot(f.turn_a_t2) + f.arm_b_x_t1.dot(f.turn_b_t2);
  const Real det = k.determinant();
  f.inverse_k_slip = det > 0 ? Eigen::Matrix<Real, 2, 2>(k.inverse())
                             : Eigen::Matrix<Real, 2, 2>::Zero();
  const Real k_twist = p.normal.dot(f.turn_a_n + f.turn_b_n);
  f.inverse_k_twist = k_twist > 0 ? 1 / k_twist : 0;
  f.start_slip = p.start_slip;
  f.surface_slip = p.surface_slip;
  f.t1 = p.t1;
  f.t2 = p.t2;
  f.twist = p.twist;
  patch_block(points, p, inv_a, inv_b, q_a, q_b, arm_a, arm_b, f);
}

// Builds the rolling row of a patch (materials.hpp): its angular block K = t_i.(Q_a + Q_b) t_j.
void build_rolling(const std::vector<BodyResponse>& bodies, const PatchFriction& p, Real limit,
                   const Memory::FrictionRow& f, Memory::RollingRow& r) {
  const int still = static_cast<int>(bodies.size());
  const Mat3 q_a = f.a == still ? Mat3::Zero() : bodies[f.a].angular;
  const Mat3 q_b = f.b == still ? Mat3::Zero() : bodies[f.b].angular;
  r.a = f.a;
  r.b = f.b;
  r.tangent1 = p.tangent1;
  r.tangent2 = p.tangent2;
  r.turn_a1 = q_a * p.tangent1;
  r.turn_a2 = q_a * p.tangent2;
  r.turn_b1 = q_b * p.tangent1;
  r.turn_b2 = q_b * p.tangent2;
  Eigen::Matrix<Real, 2, 2> k;
  k(0, 0) = p.tangent1.dot(r.turn_a1 + r.turn_b1);
  k(1, 1) = p.tangent2.dot(r.turn_a2 + r.turn_b2);
  k(0, 1) = k(1, 0) = p.tangent1.dot(r.turn_a2 + r.turn_b2);
  const Real det = k.determinant();
  r.inverse_k = det > 0 ? Eigen::Matrix<Real, 2, 2>(k.inverse())
                        : Eigen::Matrix<Real, 2, 2>::Zero();
  r.limit = det > 0 ? limit : 0;
  r.radius = p.rolling_radius;
  r.start = Vec2(p.start_roll1, p.start_roll2);
  r.r1 = det > 0 ? p.roll1 : 0;
  r.r2 = det > 0 ? p.roll2 : 0;
}

// Applies a rolling angular impulse d (about tangent1, tangent2) on B, its opposite on A.
inline void apply_rolling(Memory& m, const Memory::RollingRow& r, int still, const Vec2& d) {
  // A driven body's turn is zero, and shared by the patches of one level or colour.
  if (r.b != still && m.inverse_mass[r.b] != 0)
    m.slots[r.b].angular += d.x() * r.turn_b1 + d.y() * r.turn_b2;
  if (r.a != still && m.inverse_mass[r.a] != 0)
    m.slots[r.a].angular -= d.x() * r.turn_a1 + d.y() * r.turn_a2;
}

// Relative rolling velocity (B's spin minus A's about tangent1, tangent2) in slots s.
inline Vec2 rolling_velocity(const Memory::RollingRow& r, const std::vector<SlotVelocity>& s) {
  const Vec3 dw = s[r.b].angular - s[r.a].angular;
  return Vec2(r.tangent1.dot(dw), r.tangent2.dot(dw));
}

// Scales v into the disc of the given radius (a friction cone's or a rolling limit's), if it is
// outside.
inline void into_disc(Vec2& v, Real radius) {
  const Real length = v.norm();
  if (length > radius) v *= radius / length;
}

// Adds a linear impulse j (world) at a row's arm on slot `s`, turning it by `turn`.
inline void push(Memory& m, int s, int still, const Vec3& j, const Vec3& turn) {
  // A driven body's velocity is not the impulses' to change (and, shared by the patches of one
  // colour, must not be written by two threads).
  if (s == still || m.inverse_mass[s] == 0) return;
  m.slots[s].linear += m.inverse_mass[s] * j;
  m.slots[s].angular += turn;
}

// Applies a friction impulse (t1, t2, twist) on B, its opposite on A.
inline void apply_friction(Memory& m, const Memory::FrictionRow& f, int still, const Vec3& d) {
  const Vec3 j = d.x() * f.tangent1 + d.y() * f.tangent2;
  push(m, f.b, still, j, d.x() * f.turn_b_t1 + d.y() * f.turn_b_t2 + d.z() * f.turn_b_n);
  push(m, f.a, still, -j, -(d.x() * f.turn_a_t1 + d.y() * f.turn_a_t2 + d.z() * f.turn_a_n));
}

// The sweeps' two parts of it: a tangential impulse (d1, d2), and a twist about the normal,
// which only turns the bodies. Why apart: the whole impulse with its missing part zero pushed
// and turned both bodies by zeros (apart, a pour's crash takes 9 % fewer instructions).
inline void apply_slip(Memory& m, const Memory::FrictionRow& f, int still, Real d1, Real d2) {
  const Vec3 j = d1 * f.tangent1 + d2 * f.tangent2;
  push(m, f.b, still, j, d1 * f.turn_b_t1 + d2 * f.turn_b_t2);
  push(m, f.a, still, -j, -(d1 * f.turn_a_t1 + d2 * f.turn_a_t2));
}

inline void apply_twist(Memory& m, const Memory::FrictionRow& f, int still, Real d) {
  if (f.b != still && m.inverse_mass[f.b] != 0) m.slots[f.b].angular += d * f.turn_b_n;
  if (f.a != still && m.inverse_mass[f.a] != 0) m.slots[f.a].angular -= d * f.turn_a_n;
}

inline void apply_normal(Memory& m, const Memory::NormalRow& r, int still, Real d) {
  push(m, r.b, still, d * r.normal, d * r.turn_b);
  push(m, r.a, still, -d * r.normal, -d * r.turn_a);
}

// Slip (t1, t2) and spin of B over A at a friction row's centre.
inline Vec3 slip(const Memory& m, const Memory::FrictionRow& f) {
  const Vec3 dv = m.slots[f.b].linear - m.slots[f.a].linear;
  return Vec3(f.tangent1.dot(dv) + f.arm_b_x_t1.dot(m.slots[f.b].angular) -
                  f.arm_a_x_t1.dot(m.slots[f.a].angular),
              f.tangent2.dot(dv) + f.arm_b_x_t2.dot(m.slots[f.b].angular) -
                  f.arm_a_x_t2.dot(m.slots[f.a].angular),
              f.normal.dot(m.slots[f.b].angular - m.slots[f.a].angular)) +
         f.surface_slip;
}

// One patch: its normal rows, each clamped at zero, then its friction within its Coulomb limits
// and its rolling resistance within mu_r R (last, so that a converged sweep leaves them obeying
// their energy rule at the final velocities, as in solve_semm).
void update_patch(Memory& m, int k, int still, SweepSize& size) {
  Memory::FrictionRow& f = m.friction[k];
  const Real mu = f.mu;
  if (f.block) {
    // The patch's normal impulses together (patch_block), where they all still push after it;
    // the scalar rows below then take what is left (and the patch where some would not push).
    const int count = f.last - f.first;
    Eigen::Matrix<Real, 4, 1> error = Eigen::Matrix<Real, 4, 1>::Zero();
    for (int i = 0; i < count; ++i) {
      const Memory::NormalRow& r = m.rows[f.first + i];
      error(i) = r.target - (r.normal.dot(m.slots[r.b].linear - m.slots[r.a].linear) +
                             r.arm_b_x_n.dot(m.slots[r.b].angular) -
                             r.arm_a_x_n.dot(m.slots[r.a].angular));
    }
    const Eigen::Matrix<Real, 4, 1> d = f.k_pseudo_inverse * error;
    bool pushing = true;
    for (int i = 0; i < count; ++i)
      pushing = pushing && m.rows[f.first + i].impulse + d(i) >= m.rows[f.first + i].floor;
    if (pushing) {
      for (int i = 0; i < count; ++i) {
        Memory::NormalRow& r = m.rows[f.first + i];
        r.impulse += d(i);
        apply_normal(m, r, still, d(i));
        size.add(std::abs(d(i)), std::abs(r.impulse));
      }
    }
  }
  for (int i = f.first; i < f.last; ++i) {
    Memory::NormalRow& r = m.rows[i];
    const Real u = r.normal.dot(m.slots[r.b].linear - m.slots[r.a].linear) +
                   r.arm_b_x_n.dot(m.slots[r.b].angular) -
                   r.arm_a_x_n.dot(m.slots[r.a].angular);
    const Real after = std::max<Real>(r.floor, r.impulse - (u - r.target) * r.inverse_k);
    const Real d = after - r.impulse;
    r.impulse = after;
    apply_normal(m, r, still, d);
    size.add(std::abs(d), std::abs(after));
  }
  if (mu > 0) {
    Real total = 0, reach = 0;
    for (int i = f.first; i < f.last; ++i) {
      total += m.rows[i].impulse;
      reach += m.rows[i].impulse * m.rows[i].lever;
    }
    const Vec3 before(f.t1, f.t2, f.twist);
    Vec3 u = slip(m, f);
    // The minimiser of the tangential block, scaled into the disc; if sticking would push along
    // the slip the step started with, ask for that slip mirrored instead (semm.cpp: no energy
    // added).
    const Vec2 now(f.t1, f.t2), start = f.start_slip.head<2>();
    Vec2 t = now - f.inverse_k_slip * u.head<2>();
    if (t.dot(start) > 0) t = now - f.inverse_k_slip * (u.head<2>() + start);
    into_disc(t, mu * total);
    apply_slip(m, f, still, t.x() - f.t1, t.y() - f.t2);
    f.t1 = t.x();
    f.t2 = t.y();
    if (f.inverse_k_twist > 0) {
      const Real spin = f.normal.dot(m.slots[f.b].angular - m.slots[f.a].angular);
      Real twist = f.twist - spin * f.inverse_k_twist;
      if (twist * f.start_slip.z() > 0) twist = f.twist - (spin + f.start_slip.z()) * f.inverse_k_twist;
      twist = std::clamp(twist, -mu * reach, mu * reach);
      apply_twist(m, f, still, twist - f.twist);
      f.twist = twist;
    }
    const Real scale = reach > 0 && total > 0 ? total / reach : 0;
    size.add((Vec2(f.t1, f.t2) - before.head<2>()).norm() + scale * std::abs(f.twist - before.z()),
             Vec2(f.t1, f.t2).norm());
  }
  if (f.rolling >= 0) {
    // As the tangential block: the minimiser, the mirrored start if it would push along the
    // rolling the step started with (no energy added), scaled into the disc.
    Memory::RollingRow& r = m.rolling[f.rolling];
    Real total = 0;
    for (int i = f.first; i < f.last; ++i) total += m.rows[i].impulse;
    const Vec2 u = rolling_velocity(r, m.slots), now(r.r1, r.r2);
    Vec2 h = now - r.inverse_k * u;
    if (h.dot(r.start) > 0) h = now - r.inverse_k * (u + r.start);
    into_disc(h, r.limit * total);
    apply_rolling(m, r, still, h - now);
    r.r1 = h.x();
    r.r2 = h.y();
    // An angular impulse: on the patch's scale, divided by the rolling radius.
    size.add((h - now).norm() / r.radius, h.norm() / r.radius);
  }
}

// The impulses that conjugate gradients move: every normal row's, then each friction row's
// (t1, t2).
void gather(const Memory& m, std::vector<Real>& x) {
  const size_t rows = m.rows.size();
  x.resize(rows + 2 * m.friction.size());
  for (size_t i = 0; i < rows; ++i) x[i] = m.rows[i].impulse;
  for (size_t j = 0; j < m.friction.size(); ++j) {
    x[rows + 2 * j] = m.friction[j].t1;
    x[rows + 2 * j + 1] = m.friction[j].t2;
  }
}

// Patch k moved along beta times the search direction, kept feasible (normal impulses >= 0,
// friction inside mu times the new normal total); the direction becomes the move made plus the
// sweep's own step (`step`, the sweep's change of the impulses).
void accelerate_patch(Memory& m, int k, int still, Real beta, const std::vector<Real>& step) {
  Memory::FrictionRow& f = m.friction[k];
  Real total = 0;
  for (int i = f.first; i < f.last; ++i) {
    Memory::NormalRow& r = m.rows[i];
    const Real after = std::max<Real>(r.floor, r.impulse + beta * m.direction[i]);
    const Real d = after - r.impulse;
    r.impulse = after;
    total += after;
    apply_normal(m, r, still, d);
    m.direction[i] = d + step[i];
  }
  const size_t t = m.rows.size() + 2 * static_cast<size_t>(k);
  if (f.mu > 0) {
    Vec2 now(f.t1, f.t2), next = now + beta * Vec2(m.direction[t], m.direction[t + 1]);
    into_disc(next, f.mu * total);
    const Vec2 d = next - now;
    apply_slip(m, f, still, d.x(), d.y());
    f.t1 = next.x();
    f.t2 = next.y();
    m.direction[t] = d.x() + step[t];
    m.direction[t + 1] = d.y() + step[t + 1];
  }
}

SolverReport sweeps(Memory& m, const std::vector<int>& colours, const SolverSettings& settings,
                    int still) {
  SolverReport report;
  m.sizes.resize(static_cast<size_t>(max_threads()));
  // Nonsmooth nonlinear conjugate gradients (Silcowitz, Niebe and Erleben 2010): each sweep's
  // change of the impulses is taken as the negative gradient, and the impulses move further
  // along a direction that remembers the earlier sweeps' (Fletcher-Reeves beta, restarted when
  // the step grows). A column's weight then reaches the floor in far fewer sweeps than
  // Gauss-Seidel's one layer per sweep.
  const bool cg = settings.conjugate_gradients;
  Real last_gradient = 0;
  if (cg) {
    gather(m, m.before);
    m.direction.assign(m.before.size(), 0);
  }
  std::vector<Real>& step = m.before;
  // Plain Gauss-Seidel on one process: every sweep in one parallel region.
  auto sweep_size = [&]() {
    SweepSize total;
    for (const SweepSize& s : m.sizes) total.add(s.change, s.largest);
    return total.largest > 0 ? total.change / total.largest : 0;
  };
  if (!cg && !settings.sync) {
    report.sweeps = sweep_by_colour(
        colours, m.sizes, settings.max_sweeps,
        [&](int k, SweepSize& size) { update_patch(m, k, still, size); },
        [&](const std::vector<SweepSize>&) { return sweep_size() <= settings.tolerance; });
    report.change = sweep_size();
    report.converged = report.change <= settings.tolerance;
    return report;
  }
  for (report.sweeps = 1; report.sweeps <= settings.max_sweeps; ++report.sweeps) {
    std::fill(m.sizes.begin(), m.sizes.end(), SweepSize{});
    by_colour(colours, m.sizes,
              [&](int k, SweepSize& size) { update_patch(m, k, still, size); });
    SweepSize total;
    for (const SweepSize& s : m.sizes) total.add(s.change, s.largest);
    // Over ranks: the copies of shared bodies agree again, and every rank stops at the same
    // sweep.
    if (settings.sync) {
      settings.sync->average(m.slots);
      total = settings.sync->largest(total);
    }
    report.change = total.largest > 0 ? total.change / total.largest : 0;
    if (report.change <= settings.tolerance) return report;
    if (!cg || report.sweeps == settings.max_sweeps) continue;
    // step = after - before, in place; its squared length, summed in one order.
    const size_t rows = m.rows.size();
    Real gradient = 0;
    for (size_t i = 0; i < rows; ++i) {
      step[i] = m.rows[i].impulse - step[i];
      gradient += step[i] * step[i];
    }
    for (size_t j = 0; j < m.friction.size(); ++j) {
      step[rows + 2 * j] = m.friction[j].t1 - step[rows + 2 * j];
      step[rows + 2 * j + 1] = m.friction[j].t2 - step[rows + 2 * j + 1];
      gradient += step[rows + 2 * j] * step[rows + 2 * j] +
                  step[rows + 2 * j + 1] * step[rows + 2 * j + 1];
    }
    if (settings.sync) gradient = settings.sync->sum(gradient);
    const Real beta = last_gradient > 0 ? gradient / last_gradient : -1;
    last_gradient = gradient;
    if (beta < 0) {
      m.direction = step;  // the first sweep: its own step
    } else if (beta < 1) {
      by_colour(colours, m.sizes,
                [&](int k, SweepSize&) { accelerate_patch(m, k, still, beta, step); });
      if (settings.sync) settings.sync->average(m.slots);
    } else {
      std::fill(m.direction.begin(), m.direction.end(), 0);  // restart
    }
    gather(m, m.before);
  }
  report.sweeps = settings.max_sweeps;
  report.converged = false;
  return report;
}

// Sets the slots' pseudo velocities to the bodies' before any impulse.
void reset_velocities(Memory& m, const std::vector<BodyResponse>& bodies) {
  const size_t n = bodies.size();
  for (size_t b = 0; b < n; ++b) {
    m.slots[b].linear = bodies[b].velocity;
    m.slots[b].angular = bodies[b].angular_velocity;
  }
  m.slots[n] = SlotVelocity{};
}

// Applies every row's current impulse (the warm start); whether any was not zero. Every normal
// row, then every friction row, then every rolling row, each pass colour by colour (or level by
// level) as the sweeps go, so that each body's velocity sums its rows in the serial sweep's order
// at any thread count.
bool apply_all(Memory& m, const std::vector<int>& colours, int still) {
  bool any = false;
  for (const Memory::NormalRow& r : m.rows) any = any || r.impulse != 0;
  for (const Memory::FrictionRow& f : m.friction)
    any = any || f.t1 != 0 || f.t2 != 0 || f.twist != 0;
  for (const Memory::RollingRow& r : m.rolling) any = any || r.r1 != 0 || r.r2 != 0;
  if (!any) return false;
  by_colour(colours, m.sizes, [&](int k, SweepSize&) {
    const Memory::FrictionRow& f = m.friction[k];
    for (int i = f.first; i < f.last; ++i) apply_normal(m, m.rows[i], still, m.rows[i].impulse);
  });
  by_colour(colours, m.sizes, [&](int k, SweepSize&) {
    const Memory::FrictionRow& f = m.friction[k];
    apply_friction(m, f, still, Vec3(f.t1, f.t2, f.twist));
  });
  if (!m.rolling.empty()) {
    by_colour(colours, m.sizes, [&](int k, SweepSize&) {
      if (m.friction[k].rolling < 0) return;
      const Memory::RollingRow& r = m.rolling[m.friction[k].rolling];
      apply_rolling(m, r, still, Vec2(r.r1, r.r2));
    });
  }
  return true;
}

// Normal relative velocity of a row, and slip of a friction row, in slots s.
inline Real row_velocity(const Memory::NormalRow& r, const std::vector<SlotVelocity>& s) {
  return r.normal.dot(s[r.b].linear - s[r.a].linear) + r.arm_b_x_n.dot(s[r.b].angular) -
         r.arm_a_x_n.dot(s[r.a].angular);
}

inline Vec3 row_slip(const Memory::FrictionRow& f, const std::vector<SlotVelocity>& s) {
  const Vec3 dv = s[f.b].linear - s[f.a].linear;
  const Vec3 &wa = s[f.a].angular, &wb = s[f.b].angular;
  return Vec3(f.tangent1.dot(dv) + f.arm_b_x_t1.dot(wb) - f.arm_a_x_t1.dot(wa),
              f.tangent2.dot(dv) + f.arm_b_x_t2.dot(wb) - f.arm_a_x_t2.dot(wa),
              f.normal.dot(wb - wa)) +
         f.surface_slip;
}

// The energy the impulses add over the step, and the scale that takes it back to none.
//
// Over a step an impulse j on a row does the work j (u_start + u_after) / 2 (semm.cpp), so the
// step's energy changes by E = sum of j (u_start + u_after) / 2 over all rows, normal and
// friction: exactly, since the velocities are linear in the impulses. At convergence every row
// obeys the rules that make its term <= 0; stopped short of convergence (a pile's sweeps are
// few, and a ring on a column can make Gauss-Seidel cycle), the sum can come out slightly
// positive. Scaling every impulse by s gives E(s) = s B + s^2 A with A = 1/2 j.K j >= 0 and
// B = E - A; the largest s with E(s) <= 0 is -B/A. Every constraint's sign survives the scaling
// (normal impulses stay >= 0, friction inside its cone), only the push is a hair weaker.
Real energy_scale(Memory& m, const std::vector<BodyResponse>& bodies,
                  const std::vector<Real>& start, std::vector<SlotVelocity>& free,
                  SolverSync* sync) {
  const size_t n = bodies.size();
  free.resize(n + 1);
  for (size_t b = 0; b < n; ++b) {
    free[b].linear = bodies[b].velocity;
    free[b].angular = bodies[b].angular_velocity;
  }
  free[n] = SlotVelocity{};
  // Each row's terms on its own, shared among the threads; then summed in the serial sweep's
  // order (serial_order), rows without impulse left out, the same bits at any thread count.
  std::vector<Memory::EnergyTerm>& rows = m.row_energy;
  std::vector<Memory::EnergyTerm>& patches = m.patch_energy;
  rows.resize(m.rows.size());
  patches.resize(m.friction.size());
  parallel_for(static_cast<long long>(m.friction.size()), 64, [&](long long p) {
    const Memory::FrictionRow& f = m.friction[p];
    for (int r = f.first; r < f.last; ++r) {
      const Memory::NormalRow& row = m.rows[r];
      if (row.impulse == 0) continue;
      const Real after = row_velocity(row, m.slots);
      rows[r] = {row.impulse * (start[m.point_of_row[r]] + after) / 2,
                 row.impulse * (after - row_velocity(row, free)) / 2};
    }
    const Vec3 j(f.t1, f.t2, f.twist);
    if (j == Vec3::Zero()) return;
    const Vec3 after = row_slip(f, m.slots);
    patches[p] = {j.dot(f.start_slip + after) / 2, j.dot(after - row_slip(f, free)) / 2};
  });
  Real added = 0, curvature = 0;
  for (const int p : m.serial_order) {
    for (int r = m.friction[p].first; r < m.friction[p].last; ++r) {
      if (m.rows[r].impulse == 0) continue;
      added += rows[r].added;
      curvature += rows[r].curvature;
    }
  }
  for (const int p : m.serial_order) {
    const Memory::FrictionRow& f = m.friction[p];
    if (Vec3(f.t1, f.t2, f.twist) == Vec3::Zero()) continue;
    added += patches[p].added;
    curvature += patches[p].curvature;
  }
  // Rolling rows: the angular impulse does the work h.(w_start + w_after) / 2 likewise (few
  // patches have them).
  for (const int p : m.serial_order) {
    if (m.friction[p].rolling < 0) continue;
    const Memory::RollingRow& r = m.rolling[m.friction[p].rolling];
    const Vec2 h(r.r1, r.r2);
    if (h == Vec2::Zero()) continue;
    const Vec2 after = rolling_velocity(r, m.slots);
    added += h.dot(r.start + after) / 2;
    curvature += h.dot(after - rolling_velocity(r, free)) / 2;
  }
  if (sync) {  // each row is on one rank: the step's sums are the ranks' sums
    added = sync->sum(added);
    curvature = sync->sum(curvature);
  }
  if (!(added > 0)) return 1;
  const Real linear = added - curvature;
  return linear < 0 && curvature > 0 ? std::clamp<Real>(-linear / curvature, 0, 1) : 0;
}

// Whether the solver's copy of a body (index into both lists, or -1: a wall) has a share of
// its mass only: several ranks' rows push on it (solver_sync.hpp, split).
bool split_here(const std::vector<BodyResponse>& given, const std::vector<BodyResponse>& bodies,
                int body) {
  return body >= 0 && bodies[body].inverse_mass != given[body].inverse_mass;
}

}  // namespace

SolverReport solve_semm_rows(const std::vector<ContactPoint>& points,
                             const std::vector<Real>& start, const std::vector<Real>& targets,
                             const std::vector<BodyResponse>& given,
                             const std::vector<Vec3>& centres, const SolverSettings& settings,
                             std::vector<PatchFriction>& patches,
                             std::vector<PointImpulse>& impulses, RowSolverMemory& m) {
  impulses.resize(points.size());
  SolverSync* const sync = settings.sync;
  if (points.empty() && !sync) return SolverReport{};  // over ranks, the others may have some
  // Over ranks, bodies shared with other ranks' rows are split among them (solver_sync.hpp).
  const std::vector<BodyResponse>& bodies = sync ? sync->split(points, given) : given;
  const size_t n = bodies.size();
  const int still = static_cast<int>(n);
  m.slots.resize(n + 1);
  m.inverse_mass.resize(n + 1);
  for (size_t b = 0; b < n; ++b) m.inverse_mass[b] = bodies[b].inverse_mass;
  m.inverse_mass[n] = 0;
  reset_velocities(m, bodies);

  // The order of the sweeps: by colour; or patch order, level by level where threads share
  // the levels (level_patches: the serial sweep's bits) and the levels are wide enough to pay;
  // or patch order as one serial colour, on one thread (its rows in patch order lie closer in
  // memory: 6 % faster than by level), for narrow levels, and for conjugate gradients, whose
  // sums run over the rows' layout.
  Colouring& colouring = m.colouring;
  bool levels = !settings.colour_sweeps && !settings.conjugate_gradients && max_threads() > 1;
  if (levels) {
    level_patches(patches, bodies, colouring);
    levels = worth_sharing(colouring.start);
  }
  if (settings.colour_sweeps) {
    colour_patches(patches, bodies, colouring);
  } else if (!levels) {
    colouring.order.resize(patches.size());
    for (size_t k = 0; k < patches.size(); ++k) colouring.order[k] = static_cast<int>(k);
    colouring.start.assign({0, 0, static_cast<int>(patches.size())});
  }
  // Rows laid out in that order, each patch's contiguous; built in parallel, patch by patch.
  const size_t n_patches = colouring.order.size();
  m.rows.resize(points.size());
  m.point_of_row.resize(points.size());
  m.friction.resize(n_patches);
  m.patch_of_friction.resize(n_patches);
  m.serial_order.resize(n_patches);
  int next = 0, rolling = 0;
  for (size_t j = 0; j < n_patches; ++j) {
    const PatchFriction& p = patches[colouring.order[j]];
    m.friction[j].first = next;
    next += p.last - p.first;
    // A rolling row where the patch has rolling resistance and one of its sides turns.
    const bool rolls =
        rolling_limit_of(settings, p) > 0 &&
        (slot_of(bodies, p.body_a) != still || slot_of(bodies, p.body_b) != still);
    m.friction[j].rolling = rolls ? rolling++ : -1;
  }
  m.rolling.resize(static_cast<size_t>(rolling));
  parallel_for(static_cast<long long>(n_patches), 64, [&](long long j) {
    Memory::FrictionRow& f = m.friction[j];
    const PatchFriction& p = patches[colouring.order[j]];
    // Over ranks, a patch on a body that several ranks' rows share is not held: the ranks agree
    // on such a body's velocity by averaging after every sweep, and rows that may pull as well
    // as push kept a 3-rank pile jittering at 1-2 cm/s where unilateral ones let it rest.
    const std::vector<char>* held =
        sync && (split_here(given, bodies, p.body_a) || split_here(given, bodies, p.body_b))
            ? nullptr
            : settings.held;
    build_patch(points, targets, bodies, centres, p, impulses, f.first, held, m, f);
    f.mu = friction_of(settings, p);
    if (!(f.mu > 0)) f.t1 = f.t2 = f.twist = 0;
    if (f.rolling >= 0)
      build_rolling(bodies, p, rolling_limit_of(settings, p), f, m.rolling[f.rolling]);
    m.patch_of_friction[j] = colouring.order[j];
    // Levels reproduce the sweep in patch order; colours are a serial order of their own.
    m.serial_order[levels ? colouring.order[j] : j] = static_cast<int>(j);
  });

  m.sizes.resize(static_cast<size_t>(max_threads()));
  bool warm = apply_all(m, colouring.start, still);
  if (sync) {
    sync->average(m.slots);
    warm = sync->sum(warm ? 1 : 0) > 0;
  }
  SolverReport report = sweeps(m, colouring.start, settings, still);
  // Stopped short with more energy than no impulse at all would leave (a warm start that no
  // longer fits): start again from zero, from where every sweep can only lower the energy.
  // The energy checks are for impulses, not for the overlap correction's move; over ranks a
  // rank may have no rows (an empty `start`) while the others check.
  const bool impulses_checked = settings.energy_check && (sync || !start.empty());
  if (!report.converged && warm && impulses_checked) {
    std::vector<BodyResponse>& now = m.now;
    now = bodies;
    for (size_t b = 0; b < n; ++b) {
      now[b].velocity = m.slots[b].linear;
      now[b].angular_velocity = m.slots[b].angular;
    }
    // Over ranks: each body once, with its own (not split) mass, summed over the ranks.
    Real change = 0;
    if (sync) {
      const std::vector<BodyResponse>& whole = sync->unsplit();
      for (size_t b = 0; b < n; ++b) {
        if (!sync->owns(static_cast<int>(b)) || whole[b].inverse_mass == 0) continue;
        const std::vector<BodyResponse> one_now{now[b]}, one_start{whole[b]};
        change += pseudo_energy_change(one_now, one_start);
      }
      change = sync->sum(change);
    } else {
      change = pseudo_energy_change(now, bodies);
    }
    if (change > 0) {
      reset_velocities(m, bodies);
      for (Memory::NormalRow& r : m.rows) r.impulse = 0;
      for (Memory::FrictionRow& f : m.friction) f.t1 = f.t2 = f.twist = 0;
      for (Memory::RollingRow& r : m.rolling) r.r1 = r.r2 = 0;
      const int first_sweeps = report.sweeps;
      report = sweeps(m, colouring.start, settings, still);
      report.sweeps += first_sweeps;
    }
  }
  if (impulses_checked)
    report.scale = energy_scale(m, bodies, start, m.free, sync);
  // Results back in the caller's order, patch by patch.
  parallel_for(static_cast<long long>(n_patches), 256, [&](long long j) {
    for (int r = m.friction[j].first; r < m.friction[j].last; ++r)
      impulses[m.point_of_row[r]].normal = report.scale * m.rows[r].impulse;
    PatchFriction& p = patches[m.patch_of_friction[j]];
    p.t1 = report.scale * m.friction[j].t1;
    p.t2 = report.scale * m.friction[j].t2;
    p.twist = report.scale * m.friction[j].twist;
    const int r = m.friction[j].rolling;
    p.roll1 = r >= 0 ? report.scale * m.rolling[r].r1 : 0;
    p.roll2 = r >= 0 ? report.scale * m.rolling[r].r2 : 0;
  });
  return report;
}

}  // namespace tem
