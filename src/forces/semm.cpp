#include "forces/semm.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace tem {
namespace {

// One side of a contact point: the body's pseudo velocities (updated as impulses are applied),
// its response and the lever arm from its centre of mass. A wall or a fixed body has a zero
// response and stays still.
struct Side {
  BodyResponse* body = nullptr;
  Vec3 arm = Vec3::Zero();
};

// Velocity of the contact point on one side.
Vec3 point_velocity(const Side& s) {
  if (!s.body) return Vec3::Zero();
  return s.body->velocity + s.body->angular_velocity.cross(s.arm);
}

// Applies an impulse j (world) to one side.
void apply(Side& s, const Vec3& j) {
  if (!s.body) return;
  s.body->velocity += s.body->inverse_mass * j;
  s.body->angular_velocity += s.body->angular * s.arm.cross(j);
}

// K of one side: the change of its point velocity per unit impulse, I/M - R(r) Q R(r).
Mat3 point_response(const Side& s) {
  if (!s.body) return Mat3::Zero();
  const Mat3 r = cross_matrix(s.arm);
  return s.body->inverse_mass * Mat3::Identity() - r * s.body->angular * r;
}

struct Row {
  Side a, b;
  Mat3 frame;          // columns: normal, tangent1, tangent2
  Mat3 k;              // K in the contact frame
  Real target = 0;     // required normal relative velocity
  Eigen::Matrix<Real, 2, 1> start_slip = Eigen::Matrix<Real, 2, 1>::Zero();  // at step start
};

Side side_of(std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres, int body,
             const Vec3& point) {
  Side s;
  if (body >= 0 && bodies[body].inverse_mass > 0) {
    s.body = &bodies[body];
    s.arm = point - centres[body];
  }
  return s;
}

}  // namespace

Vec3 relative_velocity(const std::vector<BodyResponse>& bodies, const std::vector<Vec3>& centres,
                       const ContactPoint& c) {
  auto velocity = [&](int body) -> Vec3 {
    if (body < 0) return Vec3::Zero();
    const BodyResponse& r = bodies[body];
    return r.velocity + r.angular_velocity.cross(c.point - centres[body]);
  };
  return velocity(c.body_b) - velocity(c.body_a);
}

namespace {

// Projected Gauss-Seidel sweeps from the impulses already applied to the rows' bodies.
SolverReport sweep(std::vector<Row>& rows, const SolverSettings& settings,
                   std::vector<PointImpulse>& impulses) {
  SolverReport report;
  const Real mu = settings.friction;
  for (report.sweeps = 1; report.sweeps <= settings.max_sweeps; ++report.sweeps) {
    Real largest_change = 0, largest = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      Row& row = rows[i];
      PointImpulse& p = impulses[i];
      const PointImpulse before = p;
      // Normal: minimise along it, clamp at zero.
      Vec3 u = row.frame.transpose() * (point_velocity(row.b) - point_velocity(row.a));
      if (row.k(0, 0) > 0) {
        const Real normal = std::max<Real>(0, p.normal - (u.x() - row.target) / row.k(0, 0));
        const Real dn = normal - p.normal;
        p.normal = normal;
        apply(row.b, dn * row.frame.col(0));
        apply(row.a, -dn * row.frame.col(0));
      }
      // Tangent: the 2x2 minimiser, projected on the disc |t| <= mu * normal.
      if (mu > 0 && p.normal > 0) {
        u = row.frame.transpose() * (point_velocity(row.b) - point_velocity(row.a));
        const Eigen::Matrix<Real, 2, 2> ktt = row.k.bottomRightCorner<2, 2>();
        const Eigen::LDLT<Eigen::Matrix<Real, 2, 2>> solve(ktt);
        const Eigen::Matrix<Real, 2, 1> now(p.t1, p.t2);
        Eigen::Matrix<Real, 2, 1> t = now - solve.solve(u.tail<2>());
        // Sticking would push along the slip the point started the step with (the load turns
        // it round within the step): that impulse would add energy dt/2 t.(u_start + u_after).
        // Ask instead for the slip to end as it started, mirrored, which adds none.
        if (t.dot(row.start_slip) > 0) t = now - solve.solve(u.tail<2>() + row.start_slip);
        const Real limit = mu * p.normal;
        if (t.norm() > limit) t *= limit / t.norm();
        const Vec3 dj = row.frame.col(1) * (t.x() - p.t1) + row.frame.col(2) * (t.y() - p.t2);
        p.t1 = t.x();
        p.t2 = t.y();
        apply(row.b, dj);
        apply(row.a, -dj);
      } else if (p.t1 != 0 || p.t2 != 0) {
        const Vec3 dj = -(row.frame.col(1) * p.t1 + row.frame.col(2) * p.t2);
        p.t1 = p.t2 = 0;
        apply(row.b, dj);
        apply(row.a, -dj);
      }
      const Real change = std::abs(p.normal - before.normal) + std::abs(p.t1 - before.t1) +
                          std::abs(p.t2 - before.t2);
      largest_change = std::max(largest_change, change);
      largest = std::max(largest, std::abs(p.normal) + std::hypot(p.t1, p.t2));
    }
    report.change = largest > 0 ? largest_change / largest : 0;
    if (report.change <= settings.tolerance) return report;
  }
  report.sweeps = settings.max_sweeps;
  report.converged = false;
  return report;
}

// T(y) - T(y0) of the bodies' pseudo velocities: sum of 1/2 (y + y0).W^-1 (y - y0).
Real energy_change(const std::vector<BodyResponse>& now, const std::vector<BodyResponse>& start) {
  Real change = 0;
  for (size_t b = 0; b < now.size(); ++b) {
    if (start[b].inverse_mass == 0) continue;
    const Vec3 dv = now[b].velocity - start[b].velocity;
    const Vec3 dw = now[b].angular_velocity - start[b].angular_velocity;
    change += 0.5 * (now[b].velocity + start[b].velocity).dot(dv) / start[b].inverse_mass;
    change += 0.5 * (now[b].angular_velocity + start[b].angular_velocity)
                        .dot(start[b].angular.ldlt().solve(dw));
  }
  return change;
}

}  // namespace

SolverReport solve_semm(const std::vector<ContactPoint>& points,
                        const std::vector<Vec3>& start, const std::vector<BodyResponse>& input,
                        const std::vector<Vec3>& centres, const SolverSettings& settings,
                        std::vector<PointImpulse>& impulses) {
  const size_t n = points.size();
  impulses.resize(n);
  if (n == 0) return SolverReport{};
  std::vector<BodyResponse> bodies = input;  // pseudo velocities, updated in place

  std::vector<Row> rows(n);
  for (size_t i = 0; i < n; ++i) {
    const ContactPoint& c = points[i];
    Row& row = rows[i];
    row.a = side_of(bodies, centres, c.body_a, c.point);
    row.b = side_of(bodies, centres, c.body_b, c.point);
    row.frame.col(0) = c.normal;
    row.frame.col(1) = c.tangent1;
    row.frame.col(2) = c.tangent2;
    row.k = row.frame.transpose() * (point_response(row.a) + point_response(row.b)) * row.frame;
    // The normal relative velocity required after the step. An impact (approach faster than
    // the threshold) leaves at e times its approach speed; resting contact must not approach;
    // a point already separating may close again as fast as it was opening, no faster. Why the
    // last: over a step the contact impulse does the work dt/2 lambda (u_start + u_after), so a
    // push on a separating point (u_start > 0, u_after = 0) would add energy; with
    // u_after >= -u_start it adds none, and impacts and resting contacts only take energy out.
    const Real closing = -start[i].x();
    row.start_slip = start[i].tail<2>();
    row.target = closing > settings.restitution_threshold ? settings.restitution * closing
                 : closing < 0                            ? closing
                                                          : 0;
  }
  // Warm start: apply the initial guess.
  bool warm = false;
  for (size_t i = 0; i < n; ++i) {
    const PointImpulse& p = impulses[i];
    const Vec3 j = rows[i].frame * Vec3(p.normal, p.t1, p.t2);
    warm = warm || p.normal != 0 || p.t1 != 0 || p.t2 != 0;
    apply(rows[i].b, j);
    apply(rows[i].a, -j);
  }
  SolverReport report = sweep(rows, settings, impulses);
  if (!report.converged && warm && energy_change(bodies, input) > 0) {
    std::copy(input.begin(), input.end(), bodies.begin());  // the rows point into `bodies`
    std::fill(impulses.begin(), impulses.end(), PointImpulse{});
    const int first_sweeps = report.sweeps;
    report = sweep(rows, settings, impulses);
    report.sweeps += first_sweeps;
  }
  return report;
}

SolverReport solve_semm_paper(const std::vector<ContactPoint>& points,
                              const std::vector<BodyResponse>& bodies,
                              const std::vector<Vec3>& centres,
                              std::vector<PointImpulse>& impulses) {
  SolverReport report;
  report.sweeps = 1;
  const int n = static_cast<int>(points.size());
  impulses.assign(n, PointImpulse{});
  if (n == 0) return report;
  // K_cd = sum over shared bodies of J_c diag(1/M, Q) J_d^T, with J the impulse directions
  // (+n on B, -n on A) and their moments; D_c = -(normal relative pseudo velocity).
  auto moment_row = [&](int c, int body, Real sign) {
    Eigen::Matrix<Real, 6, 1> j = Eigen::Matrix<Real, 6, 1>::Zero();
    if (body < 0 || bodies[body].inverse_mass == 0) return j;
    const ContactPoint& p = points[c];
    j.head<3>() = sign * p.normal;
    j.tail<3>() = sign * (p.point - centres[body]).cross(p.normal);
    return j;
  };
  auto mobility = [&](int body) {
    Eigen::Matrix<Real, 6, 6> w = Eigen::Matrix<Real, 6, 6>::Zero();
    w.topLeftCorner<3, 3>() = bodies[body].inverse_mass * Mat3::Identity();
    w.bottomRightCorner<3, 3>() = bodies[body].angular;
    return w;
  };
  Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> k =
      Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>::Zero(n, n);
  Eigen::Matrix<Real, Eigen::Dynamic, 1> d(n);
  for (int c = 0; c < n; ++c) {
    d(c) = -points[c].normal.dot(relative_velocity(bodies, centres, points[c]));
    for (int e = 0; e < n; ++e)
      for (int body : {points[c].body_a, points[c].body_b}) {
        if (body < 0 || bodies[body].inverse_mass == 0) continue;
        if (body != points[e].body_a && body != points[e].body_b) continue;
        const Real sc = body == points[c].body_b ? 1 : -1;
        const Real se = body == points[e].body_b ? 1 : -1;
        k(c, e) += moment_row(c, body, sc).dot(mobility(body) * moment_row(e, body, se));
      }
  }
  // K is symmetric positive semi-definite; a complete orthogonal decomposition gives the
  // minimum-norm minimiser where two contacts are redundant (K singular).
  const Eigen::Matrix<Real, Eigen::Dynamic, 1> s = k.completeOrthogonalDecomposition().solve(d);
  for (int c = 0; c < n; ++c) impulses[c].normal = s(c);
  report.change = (k * s - d).norm() / std::max<Real>(d.norm(), 1e-300);
  return report;
}

}  // namespace tem
