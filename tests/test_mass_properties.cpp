// Mass properties from elements (eqs. 4-7) against closed forms and against the independent
// surface-integral computation, to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>

#include "geometry/primitives.hpp"
#include "world/shape_blocks.hpp"
#include "mass/mass_properties.hpp"
#include "mass/surface_integrals.hpp"
#include "world/model.hpp"

namespace tem {
namespace test_mass_properties {

constexpr Real kRoundOff = 1e-12;  // relative

Real relative(const Mat3& a, const Mat3& b) { return (a - b).norm() / b.norm(); }

// Prints a measured error so that the suite's log carries the figures quoted in docs.
void report(const std::string& what, Real value) {
  std::cout << "[ measured ] " << what << ": " << value << "\n";
}

// The body's surface triangles in the scene's body frame, for the surface-integral check.
std::vector<std::array<Vec3, 3>> surface(const Model& model, const Body& body) {
  std::vector<std::array<Vec3, 3>> tris;
  for (const BlockInstance& bi : body.blocks) {
    const Block& b = model.blocks[bi.block];
    for (const Triangle& t : b.triangles()) {
      std::array<Vec3, 3> tri;
      for (int k = 0; k < 3; ++k)
        tri[k] = bi.rotation * b.nodes()[t.nodes[k]] + bi.offset - body.origin_offset;
      tris.push_back(tri);
    }
  }
  return tris;
}

BodyDef body_of(ShapeDef shape, Real density = 2.5) {
  BodyDef b;
  b.name = "b";
  b.path = "bodies[0]";
  shape.path = "bodies[0].shape";
  b.shape = std::move(shape);
  b.density = density;
  return b;
}

Model model_of(std::vector<BodyDef> bodies) {
  SceneDef scene;
  scene.bodies = std::move(bodies);
  return build_model(scene);
}

// Inertia of a solid box about its centre, principal axes along its edges.
Mat3 box_inertia(Real m, const Vec3& s) {
  return m / 12 *
         Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
              s.x() * s.x() + s.y() * s.y())
             .asDiagonal();
}

TEST(MassProperties, BoxClosedForm) {
  const Vec3 size(0.3, 1.7, 2.9);
  const Real rho = 2.5;
  const MassProperties m = block_mass_properties(Block(box(size)), rho);
  const Real volume = size.prod();
  EXPECT_NEAR(m.volume, volume, kRoundOff * volume);
  EXPECT_NEAR(m.mass, rho * volume, kRoundOff * rho * volume);
  const Real error =
      relative(inertia_from_second_moment(m.second_moment), box_inertia(m.mass, size));
  report("box inertia, relative error", error);
  EXPECT_LT(error, kRoundOff);
}

// Regular hexagonal prism of side a, height h (method.md §2): V = (3 sqrt3 / 2) a^2 h,
// I_axis = 5 m a^2 / 12, I_transverse = m (5 a^2 / 24 + h^2 / 12), along every axis choice.
TEST(MassProperties, HexagonalPrismClosedForm) {
  const Real a = 0.15, h = 0.1, rho = 7.0;
  for (Axis axis : {Axis::x, Axis::y, Axis::z}) {
    const MassProperties m = block_mass_properties(Block(regular_prism(6, a, h, axis)), rho);
    const Real volume = 1.5 * std::sqrt(3.0) * a * a * h;
    const Real mass = rho * volume;
    EXPECT_NEAR(m.volume, volume, kRoundOff * volume);
    const int k = axis == Axis::x ? 0 : axis == Axis::y ? 1 : 2;
    Vec3 diag = Vec3::Constant(mass * (5 * a * a / 24 + h * h / 12));
    diag[k] = 5 * mass * a * a / 12;
    const Real error = relative(inertia_from_second_moment(m.second_moment), diag.asDiagonal());
    report("hexagonal prism inertia, relative error", error);
    EXPECT_LT(error, kRoundOff);
  }
}

// A regular n-gon prism in general: polar moment of the n-gon of circumradius r per unit area is
// r^2 (1 + 2 cos^2(pi/n)) / 6 (sum of the n isosceles triangles).
TEST(MassProperties, RegularPrismAnySides) {
  const Real r = 0.4, h = 0.25;
  for (int n : {3, 4, 5, 8, 17, 64}) {
    const MassProperties m = block_mass_properties(Block(regular_prism(n, r, h, Axis::z)), 1.0);
    const Real area = 0.5 * n * r * r * std::sin(2 * std::numbers::pi / n);
    const Real c = std::cos(std::numbers::pi / n);
    const Real polar = area * h * r * r * (1 + 2 * c * c) / 6;
    EXPECT_NEAR(m.volume, area * h, kRoundOff * area * h) << n;
    const Mat3 inertia = inertia_from_second_moment(m.second_moment);
    EXPECT_NEAR(inertia(2, 2), polar, kRoundOff * polar) << n;
    // A regular polygon's in-plane second moments are isotropic (n >= 3).
    EXPECT_NEAR(inertia(0, 0), polar / 2 + area * h * h * h / 12, kRoundOff * polar) << n;
    EXPECT_NEAR(inertia(0, 0), inertia(1, 1), kRoundOff * polar) << n;
  }
}

// Two boxes side by side, one turned: closed form from each box's own inertia tensor and the
// parallel-axis rule for inertia tensors, M (|t|^2 I - t t^T) (the second form of method.md §2).
TEST(MassProperties, CompoundOfTwoBoxesClosedForm) {
  const Vec3 s1(2, 1, 1), s2(1, 1, 3);
  const Vec3 p1(0, 0, 0), p2(1.5, 0.2, 1.0);
  const Mat3 r2 = rotation_z(0.7) * rotation_x(0.3);
  ShapeDef a, b, compound;
  a.type = b.type = ShapeType::box;
  a.size = s1;
  b.size = s2;
  a.position = p1;
  b.position = p2;
  b.rotation = r2;
  compound.type = ShapeType::compound;
  compound.parts = {a, b};
  const Real rho = 3.0;
  const Model model = model_of({body_of(compound, rho)});
  const Body& body = model.bodies[0];

  const Real m1 = rho * s1.prod(), m2 = rho * s2.prod(), m = m1 + m2;
  const Vec3 c = (m1 * p1 + m2 * p2) / m;
  auto shift = [](Real mass, const Vec3& t) {
    return Mat3(mass * (t.squaredNorm() * Mat3::Identity() - t * t.transpose()));
  };
  const Mat3 expected = box_inertia(m1, s1) + shift(m1, p1 - c) +
                        r2 * box_inertia(m2, s2) * r2.transpose() + shift(m2, p2 - c);
  EXPECT_NEAR(body.inertia.mass, m, kRoundOff * m);
  EXPECT_NEAR(body.volume, s1.prod() + s2.prod(), kRoundOff * body.volume);
  EXPECT_LT((-body.origin_offset - c).norm(), kRoundOff);
  report("compound of two boxes inertia, relative error", relative(body.inertia.inertia, expected));
  EXPECT_LT(relative(body.inertia.inertia, expected), kRoundOff);
  EXPECT_LT(relative(body.inertia.inertia * body.inertia.inertia_inv, Mat3::Identity()), kRoundOff);

  // Eq. 7 as printed (M t t^T added to inertia tensors) is measurably wrong: the erratum.
  Mat3 printed = box_inertia(m1, s1) + m1 * (p1 - c) * (p1 - c).transpose() +
                 r2 * box_inertia(m2, s2) * r2.transpose() + m2 * (p2 - c) * (p2 - c).transpose();
  EXPECT_GT(relative(printed, expected), 0.1);
}

// Polygonal ring: V = N A_section R sin(2 pi / N), the section being the regular polygon in the
// mitre plane (each segment is a prism of perpendicular section A cos(pi/N) and length
// 2 R sin(pi/N) along its centroid line). Same for every block split.
TEST(MassProperties, RingVolumeClosedFormAndSurfaceIntegrals) {
  const int n = 16, m = 6;
  const Real radius = 0.15, rs = 0.05;
  const Real section = 0.5 * m * rs * rs * std::sin(2 * std::numbers::pi / m);
  const Real volume = n * section * radius * std::sin(2 * std::numbers::pi / n);
  for (int blocks : {16, 8, 4}) {
    ShapeDef ring;
    ring.type = ShapeType::ring;
    ring.segments = n;
    ring.sides = m;
    ring.radius = radius;
    ring.section_radius = rs;
    ring.blocks = blocks;
    ring.allow_nonconvex = true;
    ring.axis = Axis::y;
    const Model model = model_of({body_of(ring)});
    const Body& body = model.bodies[0];
    report("ring volume (" + std::to_string(blocks) + " blocks), relative error",
           std::abs(body.volume - volume) / volume);
    EXPECT_NEAR(body.volume, volume, kRoundOff * volume) << blocks;
    EXPECT_LT(body.origin_offset.norm(), kRoundOff * radius);  // symmetric: centre at origin
    const MassProperties ref = surface_mass_properties(surface(model, body));
    EXPECT_NEAR(ref.volume, body.volume, kRoundOff * volume);
    EXPECT_LT(relative(body.inertia.inertia / body.density,
                       inertia_from_second_moment(ref.second_moment)),
              kRoundOff);
    // Symmetric about its axis (y): equal moments about x and z, none mixed.
    const Mat3& a = body.inertia.inertia;
    EXPECT_NEAR(a(0, 0), a(2, 2), kRoundOff * a.norm());
    EXPECT_LT(std::abs(a(0, 1)) + std::abs(a(0, 2)) + std::abs(a(1, 2)), kRoundOff * a.norm());
    EXPECT_EQ(model.warnings.size(), blocks == 16 ? 0u : 1u);  // one per shape
  }
}

TEST(MassProperties, CompoundAgreesWithSurfaceIntegrals) {
  ShapeDef prism, ring, hull, compound;
  prism.type = ShapeType::prism;
  prism.sides = 6;
  prism.radius = 0.05;
  prism.height = 0.4;
  prism.axis = Axis::x;
  prism.position = Vec3(0.7, -0.1, 0.05);  // clear of the ring and the hull
  prism.rotation = euler_zxz(0.2, 1.1, -0.4);
  ring.type = ShapeType::ring;
  ring.segments = 12;
  ring.sides = 5;
  ring.radius = 0.2;
  ring.section_radius = 0.03;
  ring.rotation = rotation_x(0.4);
  hull.type = ShapeType::convex;
  hull.points = {{1, 0, 0}, {1.2, 0, 0}, {1, 0.3, 0}, {1, 0, 0.25}, {1.15, 0.2, 0.2}};
  compound.type = ShapeType::compound;
  compound.parts = {prism, ring, hull};
  const Model model = model_of({body_of(compound, 1.0)});
  const Body& body = model.bodies[0];
  const MassProperties ref = surface_mass_properties(surface(model, body));
  EXPECT_NEAR(body.volume, ref.volume, kRoundOff * ref.volume);
  // The scene's body frame has the centre of mass at -origin_offset.
  EXPECT_LT((ref.center + body.origin_offset).norm(), kRoundOff);
  EXPECT_LT(relative(body.inertia.inertia, inertia_from_second_moment(ref.second_moment)),
            kRoundOff);
}

TEST(MassProperties, RandomConvexHullsAgreeWithSurfaceIntegrals) {
  std::mt19937_64 rng(2006);
  Real worst = 0;
  std::normal_distribution<Real> gauss;
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<Vec3> pts;
    const Vec3 scale(1 + trial % 3, 0.5, 0.2 + 0.1 * trial);
    const Vec3 shift(trial, -2.0 * trial, 0.5);
    for (int i = 0; i < 40; ++i) {
      Vec3 p(gauss(rng), gauss(rng), gauss(rng));
      pts.push_back(shift + scale.cwiseProduct(p.normalized()));  // on an ellipsoid: all nodes
    }
    const PolyhedronDef def = convex_hull(pts);
    const Block block(def);
    // The surface integrals of x^2 lose digits far from the origin (|shift| up to 65 here
    // against a size of 1), so the reference is evaluated about the cloud's first point.
    const Vec3 origin = def.points[0];
    std::vector<std::array<Vec3, 3>> tris;
    for (const Triangle& t : block.triangles())
      tris.push_back({def.points[t.nodes[0]] - origin, def.points[t.nodes[1]] - origin,
                      def.points[t.nodes[2]] - origin});
    const MassProperties ref = surface_mass_properties(tris);
    EXPECT_NEAR(block.volume(), ref.volume, kRoundOff * ref.volume) << trial;
    EXPECT_LT((block.centroid_in_input() - origin - ref.center).norm(), kRoundOff * scale.norm())
        << trial;
    worst = std::max(worst, relative(block.second_moment(), ref.second_moment));
    EXPECT_LT(relative(block.second_moment(), ref.second_moment), kRoundOff) << trial;
  }
  report("random hulls, second moment vs surface integrals, worst relative difference", worst);
}

}  // namespace test_mass_properties
}  // namespace tem
