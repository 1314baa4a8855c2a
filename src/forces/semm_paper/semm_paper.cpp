#include "forces/semm_paper/semm_paper.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace tem {

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
