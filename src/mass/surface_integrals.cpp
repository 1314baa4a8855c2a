#include "mass/surface_integrals.hpp"

namespace tem {
namespace {

// Sums of monomials of one coordinate over a triangle's three vertex values w0, w1, w2:
// f1 = sum w, f2 = sum of degree-2 monomials, f3 = of degree 3; g_i = f2 + w_i (f1 + w_i).
struct Subexpressions {
  Real f1, f2, f3, g0, g1, g2;
  Subexpressions(Real w0, Real w1, Real w2) {
    const Real t0 = w0 + w1;
    const Real t1 = w0 * w0;
    const Real t2 = t1 + w1 * t0;
    f1 = t0 + w2;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  }
};

}  // namespace

MassProperties surface_mass_properties(const std::vector<std::array<Vec3, 3>>& triangles) {
  // Integrals of 1, x, y, z, x^2, y^2, z^2, xy, yz, zx over the volume.
  std::array<Real, 10> in{};
  for (const auto& t : triangles) {
    const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
    const Vec3 d = e1.cross(e2);  // twice the area times the outward normal
    const Subexpressions sx(t[0].x(), t[1].x(), t[2].x());
    const Subexpressions sy(t[0].y(), t[1].y(), t[2].y());
    const Subexpressions sz(t[0].z(), t[1].z(), t[2].z());
    in[0] += d.x() * sx.f1;
    in[1] += d.x() * sx.f2;
    in[2] += d.y() * sy.f2;
    in[3] += d.z() * sz.f2;
    in[4] += d.x() * sx.f3;
    in[5] += d.y() * sy.f3;
    in[6] += d.z() * sz.f3;
    in[7] += d.x() * (t[0].y() * sx.g0 + t[1].y() * sx.g1 + t[2].y() * sx.g2);
    in[8] += d.y() * (t[0].z() * sy.g0 + t[1].z() * sy.g1 + t[2].z() * sy.g2);
    in[9] += d.z() * (t[0].x() * sz.g0 + t[1].x() * sz.g1 + t[2].x() * sz.g2);
  }
  const std::array<Real, 10> scale{1.0 / 6,  1.0 / 24, 1.0 / 24,  1.0 / 24,  1.0 / 60,
                                   1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (size_t i = 0; i < in.size(); ++i) in[i] *= scale[i];

  MassProperties m;
  m.volume = m.mass = in[0];
  m.center = Vec3(in[1], in[2], in[3]) / in[0];
  const Vec3& c = m.center;
  Mat3& s = m.second_moment;
  s(0, 0) = in[4] - m.mass * c.x() * c.x();
  s(1, 1) = in[5] - m.mass * c.y() * c.y();
  s(2, 2) = in[6] - m.mass * c.z() * c.z();
  s(0, 1) = s(1, 0) = in[7] - m.mass * c.x() * c.y();
  s(1, 2) = s(2, 1) = in[8] - m.mass * c.y() * c.z();
  s(0, 2) = s(2, 0) = in[9] - m.mass * c.z() * c.x();
  return m;
}

}  // namespace tem
