// Blocks: topology, elements that tile the block, normals in both variants, rejection of
// blocks that cannot be simulated, and the convex hull of point clouds.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/block.hpp"
#include "geometry/primitives.hpp"

namespace tem {
namespace test_block {

// Barycentric coordinates (s, t, u) of p in element e (eq. 19): p = s a1 + t a2 + u a3.
Vec3 element_coordinates(const Element& e, const Vec3& p) { return e.inverse * p; }

bool inside_element(const Vec3& stu) { return stu.minCoeff() > 0 && stu.sum() < 1; }

bool inside_block(const Block& b, const Vec3& p) {
  for (const Polygon& poly : b.polygons())
    if (poly.normal.dot(p) - poly.offset > 0) return false;
  return true;
}

TEST(Block, CubeTopology) {
  const Block cube(box(Vec3(1, 2, 3)));
  EXPECT_EQ(cube.nodes().size(), 8u);
  EXPECT_EQ(cube.polygons().size(), 6u);
  EXPECT_EQ(cube.triangles().size(), 12u);
  EXPECT_EQ(cube.elements().size(), 12u);
  EXPECT_EQ(cube.edges().size(), 18u);  // 12 polygon edges + 6 diagonals
  int boundary = 0;
  for (const Edge& e : cube.edges()) boundary += e.polygon_boundary;
  EXPECT_EQ(boundary, 12);
  // Euler's formula for a closed genus-0 triangulated surface.
  EXPECT_EQ(static_cast<int>(cube.nodes().size() - cube.edges().size() + cube.triangles().size()),
            2);
  EXPECT_NEAR(cube.volume(), 6.0, 1e-14);
  EXPECT_TRUE(cube.convex());
  EXPECT_NEAR(cube.bounding_radius(), std::sqrt(1 + 4 + 9) / 2, 1e-14);
  EXPECT_LT((cube.bounds_max() - Vec3(0.5, 1, 1.5)).norm(), 1e-15);
  EXPECT_LT((cube.bounds_min() + Vec3(0.5, 1, 1.5)).norm(), 1e-15);
}

TEST(Block, CentroidIsTheOriginOfTheBlockFrame) {
  PolyhedronDef def = box(Vec3(1, 1, 1));
  for (Vec3& p : def.points) p += Vec3(3, -2, 5);
  const Block b(def);
  EXPECT_LT((b.centroid_in_input() - Vec3(3, -2, 5)).norm(), 1e-14);
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : b.nodes()) mean += p;
  EXPECT_LT(mean.norm(), 1e-14);
}

// The elements of a convex block tile it: every interior point lies in exactly one element, and
// the element inverse reproduces the point (eq. 19). Points outside lie in no element.
TEST(Block, ElementsTileTheBlock) {
  for (const PolyhedronDef& def : {regular_prism(6, 0.15, 0.1, Axis::y), box(Vec3(1, 2, 3)),
                                   polygonal_ring(16, 6, 0.15, 0.05, 16, Axis::z, false)[3]}) {
    const Block b(def);
    Real sum = 0;
    for (const Element& e : b.elements()) {
      EXPECT_GT(e.volume, 0);
      sum += e.volume;
    }
    EXPECT_NEAR(sum, b.volume(), 1e-14 * b.volume());
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<Real> u(-1, 1);
    int inside = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Vec3 p = 1.2 * b.bounding_radius() * Vec3(u(rng), u(rng), u(rng));
      int hits = 0;
      for (const Element& e : b.elements()) {
        const Vec3 stu = element_coordinates(e, p);
        if (!inside_element(stu)) continue;
        ++hits;
        const auto& tri = b.triangles()[e.triangle];
        const Vec3 back = stu[0] * b.nodes()[tri.nodes[0]] + stu[1] * b.nodes()[tri.nodes[1]] +
                          stu[2] * b.nodes()[tri.nodes[2]];
        EXPECT_LT((back - p).norm(), 1e-13);
      }
      EXPECT_EQ(hits, inside_block(b, p) ? 1 : 0) << "point " << p.transpose();
      inside += hits;
    }
    EXPECT_GT(inside, 100);  // the sample did probe the interior
  }
}

TEST(Block, NormalsOfABoxCornerAndEdge) {
  const Block cube(box(Vec3(2, 2, 2)));
  // The default normal is exact at every corner; the paper's per-triangle sum (eq. 2) depends
  // on the diagonals, and tilts the normal at a corner where diagonals meet.
  int tilted = 0;
  for (size_t i = 0; i < cube.nodes().size(); ++i) {
    const int node = static_cast<int>(i);
    const Vec3 expected = cube.nodes()[i].normalized();  // corners of a cube centred at 0
    EXPECT_LT((cube.node_normal(node, NormalVariant::default_) - expected).norm(), 1e-14);
    tilted += (cube.node_normal(node, NormalVariant::paper) - expected).norm() > 0.1;
  }
  EXPECT_GT(tilted, 0);
  for (size_t k = 0; k < cube.edges().size(); ++k) {
    const Edge& e = cube.edges()[k];
    const Vec3 mid = (cube.nodes()[e.nodes[0]] + cube.nodes()[e.nodes[1]]) / 2;
    Vec3 expected = mid;  // a cube edge's normal bisects its faces; a diagonal's is the face's
    if (!e.polygon_boundary) expected = cube.triangles()[e.triangles[0]].normal;
    EXPECT_LT(
        (cube.edge_normal(static_cast<int>(k), NormalVariant::default_) - expected.normalized())
            .norm(),
        1e-14);
  }
}

// A hexagonal prism's cap is fanned from its node 0, so that node touches four cap triangles and
// its neighbour one: the paper's per-triangle sum (eq. 2) tilts their normals differently, while
// the default angle-weighted normal is the same at every node up to the prism's symmetry and
// equals the closed form (120 deg of cap, 90 deg of each side face).
TEST(Block, NodeNormalsOfAHexagonalPrism) {
  const Real r = 0.15, h = 0.1;
  const Block coin(regular_prism(6, r, h, Axis::z));
  const Real pi = std::numbers::pi;
  for (int k = 0; k < 6; ++k) {
    const int top = 6 + k;
    const Real phi = 2 * pi * k / 6;
    const Vec3 s1(std::cos(phi - pi / 6), std::sin(phi - pi / 6), 0);  // side normals
    const Vec3 s2(std::cos(phi + pi / 6), std::sin(phi + pi / 6), 0);
    const Vec3 expected = (2 * pi / 3 * Vec3::UnitZ() + pi / 2 * (s1 + s2)).normalized();
    EXPECT_LT((coin.node_normal(top, NormalVariant::default_) - expected).norm(), 1e-14);
  }
  const Vec3 paper0 = coin.node_normal(6, NormalVariant::paper);
  const Vec3 paper1 = coin.node_normal(7, NormalVariant::paper);
  EXPECT_GT(std::abs(paper0.z() - paper1.z()), 0.1);
  // Paper edge normal (eq. 3) is the mean of its end nodes' normals.
  for (size_t k = 0; k < coin.edges().size(); ++k) {
    const Edge& e = coin.edges()[k];
    const Vec3 mean = (coin.node_normal(e.nodes[0], NormalVariant::paper) +
                       coin.node_normal(e.nodes[1], NormalVariant::paper))
                          .normalized();
    EXPECT_LT((coin.edge_normal(static_cast<int>(k), NormalVariant::paper) - mean).norm(), 1e-15);
  }
}

TEST(Primitives, AxisSelection) {
  const Real r = 0.15, h = 0.1;
  struct Case {
    Axis axis;
    int along, first;  // coordinate of the symmetry axis, direction of the first node
  };
  for (const Case c : {Case{Axis::x, 0, 1}, Case{Axis::y, 1, 2}, Case{Axis::z, 2, 0}}) {
    const PolyhedronDef def = regular_prism(6, r, h, c.axis);
    for (const Vec3& p : def.points) EXPECT_NEAR(std::abs(p[c.along]), h / 2, 1e-15);
    EXPECT_NEAR(def.points[0][c.first], r, 1e-15);
    EXPECT_NEAR(axis_rotation(c.axis).determinant(), 1.0, 1e-15);
    EXPECT_NEAR(Block(def).volume(), 1.5 * std::sqrt(3.0) * r * r * h, 1e-15);
  }
}

TEST(Primitives, RingBlocks) {
  // One block per segment: every block convex. The paper's 8 blocks: each non-convex.
  for (const PolyhedronDef& def : polygonal_ring(16, 6, 0.15, 0.05, 16, Axis::y, false))
    EXPECT_TRUE(Block(def).convex());
  const auto eight = polygonal_ring(16, 6, 0.15, 0.05, 8, Axis::y, false);
  ASSERT_EQ(eight.size(), 8u);
  EXPECT_THROW(Block{eight[0]}, GeometryError);
  auto allowed = polygonal_ring(16, 6, 0.15, 0.05, 8, Axis::y, true);
  const Block b(allowed[0]);
  EXPECT_FALSE(b.convex());
  // A 22.5 deg bend between the block's two segments: the first segment's inner face plane
  // leaves the far end's inner node outside by about segment length * sin(22.5 deg).
  EXPECT_GT(b.nonconvexity(), 0.005);
  EXPECT_LT(b.nonconvexity(), 0.05);
}

TEST(BlockErrors, RejectsWhatCannotBeSimulated) {
  auto message = [](const PolyhedronDef& def) {
    try {
      Block b(def);
    } catch (const GeometryError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  PolyhedronDef repeated = box(Vec3(1, 1, 1));
  repeated.points[3] = repeated.points[0];
  EXPECT_NE(message(repeated).find("points 0 and 3 coincide"), std::string::npos);

  PolyhedronDef open = box(Vec3(1, 1, 1));
  open.polygons.pop_back();
  EXPECT_NE(message(open).find("not closed"), std::string::npos);

  PolyhedronDef inward = box(Vec3(1, 1, 1));
  for (auto& loop : inward.polygons) std::reverse(loop.begin(), loop.end());
  EXPECT_NE(message(inward).find("negative volume"), std::string::npos);

  PolyhedronDef bent = box(Vec3(1, 1, 1));
  bent.points[7] += Vec3(0, 0, 0.1);  // lifts one corner of the top face off its plane
  EXPECT_NE(message(bent).find("not planar"), std::string::npos);

  PolyhedronDef flipped = box(Vec3(1, 1, 1));
  std::reverse(flipped.polygons[0].begin(), flipped.polygons[0].end());
  EXPECT_NE(message(flipped).find("same direction"), std::string::npos);

  PolyhedronDef too_few;
  too_few.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_NE(message(too_few).find("at least 4 points"), std::string::npos);
}

// A block's checks measure its own size, so moving it must not change the verdict. A small
// tetrahedron with a sliver face, as approximate cutting makes near a mesh's surface: computed
// from the coordinates as they stand, the sliver's normal carried round-off of the offset
// (0.5 here) and its third corner seemed 1e-10 off a plane the block measures to 6e-13.
TEST(Block, ValidityDoesNotDependOnWhereTheBlockSits) {
  const Real length = 1e-3, width = 1e-6, height = 2e-4;
  PolyhedronDef sliver;
  sliver.points = {Vec3(0, 0, 0), Vec3(length, 0, 0), Vec3(length / 2, width, 0),
                   Vec3(length / 2, width / 3, height)};
  sliver.polygons = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  const Real volume = length * width * height / 6;
  for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(0.5, 0.6, 0.5), Vec3(-3.0, 7.0, 11.0)}) {
    PolyhedronDef moved = sliver;
    for (Vec3& p : moved.points) p += offset;
    SCOPED_TRACE(offset.transpose());
    Real moved_volume = 0;
    EXPECT_NO_THROW(moved_volume = Block(moved).volume());
    EXPECT_NEAR(moved_volume, volume, 1e-6 * volume);
  }
}

TEST(ConvexHull, CubeWithRedundantPoints) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  pts.push_back(Vec3(0.5, 0.5, 1.0));  // on a face: not a node, harmless
  pts.push_back(Vec3(1.0, 0.5, 0.0));  // on an edge
  const Block cube(convex_hull(pts));
  EXPECT_EQ(cube.nodes().size(), 8u);
  EXPECT_EQ(cube.polygons().size(), 6u);  // Qhull's coplanar facets merged into squares
  EXPECT_NEAR(cube.volume(), 1.0, 1e-14);
  EXPECT_LT((cube.centroid_in_input() - Vec3(0.5, 0.5, 0.5)).norm(), 1e-14);
}

TEST(ConvexHull, RejectsDegenerateAndNonConvexPointSets) {
  auto message = [](const std::vector<Vec3>& pts) {
    try {
      convex_hull(pts);
    } catch (const GeometryError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 3, 0}}).find("coplanar"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}).find("coplanar or collinear"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}}).find("coincide"),
            std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}).find("at least 4"), std::string::npos);
  EXPECT_NE(message({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 0.1}})
                .find("point 4 lies inside"),
            std::string::npos);
}

}  // namespace test_block
}  // namespace tem
