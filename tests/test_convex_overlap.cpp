// convex_insides_apart (mesh/convex_overlap.hpp): blocks that touch along a face or an edge are
// apart, blocks that share any inside volume are not, and the one case its polygon planes cannot
// settle (two blocks crossed edge to edge) is answered "overlap", the safe side for a merge.
#include <gtest/gtest.h>

#include "geometry/aabb.hpp"
#include "mesh/convex_overlap.hpp"

namespace tem {
namespace test_convex_overlap {

// An axis-aligned box from lo to hi, polygons counter-clockwise about their outward normals.
PolyhedronDef box(const Vec3& lo, const Vec3& hi) {
  PolyhedronDef def;
  for (int k = 0; k < 8; ++k)
    def.points.push_back(Vec3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                              k & 4 ? hi.z() : lo.z()));
  def.polygons = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return def;
}

// A bar of square section 0.2, 2 long along x (or y), turned 45 degrees about its own axis so
// that an edge points up and one down (a diamond section), its centre at height z.
PolyhedronDef diamond_bar(bool along_x, Real z) {
  PolyhedronDef def = along_x ? box(Vec3(-1, -0.1, -0.1), Vec3(1, 0.1, 0.1))
                              : box(Vec3(-0.1, -1, -0.1), Vec3(0.1, 1, 0.1));
  const Real c = std::sqrt(0.5);
  for (Vec3& p : def.points) {
    Real& across = along_x ? p.y() : p.x();
    const Real a = across, h = p.z();
    across = c * (a - h);
    p.z() = c * (a + h) + z;
  }
  return def;
}

TEST(ConvexOverlap, TouchingBlocksAreApartOverlappingOnesAreNot) {
  const PolyhedronDef unit = box(Vec3::Zero(), Vec3::Ones());
  const Real eps = 1e-9;
  EXPECT_TRUE(convex_insides_apart(unit, box(Vec3(1, 0, 0), Vec3(2, 1, 1)), eps));  // a face
  EXPECT_TRUE(convex_insides_apart(unit, box(Vec3(1, 1, 0), Vec3(2, 2, 1)), eps));  // an edge
  EXPECT_TRUE(convex_insides_apart(unit, box(Vec3(3, 3, 3), Vec3(4, 4, 4)), eps));  // far
  // Into each other by 1e-6 along x, and by half a box.
  EXPECT_FALSE(convex_insides_apart(unit, box(Vec3(1 - 1e-6, 0, 0), Vec3(2, 1, 1)), eps));
  EXPECT_FALSE(convex_insides_apart(unit, box(Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)), eps));
  EXPECT_FALSE(convex_insides_apart(unit, box(Vec3(0.2, 0.2, 0.2), Vec3(0.8, 0.8, 0.8)), eps));
  // Touching within eps counts as touching: the cutter's neighbours meet on a cut plane, with
  // their coordinates' round-off.
  EXPECT_TRUE(convex_insides_apart(unit, box(Vec3(1 - 1e-10, 0, 0), Vec3(2, 1, 1)), eps));
  EXPECT_EQ(convex_insides_apart(unit, box(Vec3(1, 0, 0), Vec3(2, 1, 1)), eps),
            convex_insides_apart(box(Vec3(1, 0, 0), Vec3(2, 1, 1)), unit, eps));
}

TEST(ConvexOverlap, BarsCrossedEdgeToEdgeAreCalledOverlapping) {
  // One diamond bar along x, one along y above it, edge over edge 1e-3 apart: truly apart, but
  // only the two edges' cross product (z) separates them, and no polygon plane does.
  const Real tip = 0.1 * std::sqrt(2.0);  // centre to edge
  const PolyhedronDef lower = diamond_bar(true, 0), upper = diamond_bar(false, 2 * tip + 1e-3);
  Real top = -1, bottom = 1;
  for (const Vec3& p : lower.points) top = std::max(top, p.z());
  for (const Vec3& p : upper.points) bottom = std::min(bottom, p.z());
  ASSERT_NEAR(bottom - top, 1e-3, 1e-12);
  EXPECT_FALSE(convex_insides_apart(lower, upper, 1e-9));
  // Lifted by a bar's half length, the upper bar's lower faces (at 45 degrees) clear the whole
  // of the lower bar.
  EXPECT_TRUE(convex_insides_apart(lower, diamond_bar(false, 2 * tip + 1.0), 1e-9));
}

TEST(ConvexOverlap, BoundingBoxes) {
  const Aabb b = Aabb::around({Vec3(1, -2, 3), Vec3(-1, 5, 0), Vec3(0, 0, 4)});
  EXPECT_EQ(b.min, Vec3(-1, -2, 0));
  EXPECT_EQ(b.max, Vec3(1, 5, 4));
  EXPECT_TRUE(b.within({Vec3(1, 5, 4), Vec3(2, 6, 5)}, 0));       // a corner
  EXPECT_TRUE(b.overlaps({Vec3(1, 5, 4), Vec3(2, 6, 5)}));
  EXPECT_FALSE(b.within({Vec3(1.1, 5, 4), Vec3(2, 6, 5)}, 0.05));  // 0.1 apart
  EXPECT_FALSE(b.overlaps({Vec3(1.1, 5, 4), Vec3(2, 6, 5)}));
  EXPECT_TRUE(b.within({Vec3(1.1, 5, 4), Vec3(2, 6, 5)}, 0.2));
  Aabb grown = Aabb::empty();
  EXPECT_FALSE(grown.overlaps(b));  // the empty box meets nothing
  grown.add(b);
  grown.add(Vec3(3, 0, 0));
  EXPECT_EQ(grown.min, Vec3(-1, -2, 0));
  EXPECT_EQ(grown.max, Vec3(3, 5, 4));
}

}  // namespace test_convex_overlap
}  // namespace tem
