// Contact before overlap, the geometry (block_manifold.hpp): gaps and patches of separated and
// overlapping convex blocks, worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "collision/block_manifold.hpp"
#include "geometry/primitives.hpp"

namespace tem {
namespace {

constexpr Real kTight = 1e-12;

BlockPose pose_of(const Mat3& rotation, const Vec3& position) {
  return {rotation, rotation.transpose(), position};
}

Mat3 about(const Vec3& axis, Real angle) { return Eigen::AngleAxis<Real>(angle, axis).matrix(); }

Manifold manifold(const Block& a, const BlockPose& pa, const Block& b, const BlockPose& pb,
                  Real margin, bool expect_found = true) {
  ManifoldScratch scratch;
  Manifold m;
  EXPECT_EQ(block_manifold(a, pa, b, pb, margin, scratch, m), expect_found);
  return m;
}

// A unit cube 0.01 above the top face of a 2-cube (A), shifted sideways: four points, the
// corners of the cube's bottom face, normal +z from A up into the cube.
TEST(BlockManifold, FaceAboveFaceGivesFourCornersWithTheGap) {
  const Block big(box(Vec3(2, 2, 2))), cube(box(Vec3(1, 1, 1)));
  const BlockPose below = pose_of(Mat3::Identity(), Vec3::Zero());
  const BlockPose above = pose_of(Mat3::Identity(), Vec3(0.3, -0.2, 1.5 + 0.01));
  const Manifold m = manifold(big, below, cube, above, 0.05);
  ASSERT_EQ(m.count, 4);
  EXPECT_LT((m.normal - Vec3::UnitZ()).norm(), kTight);  // from A (below) into B (above)
  for (int k = 0; k < m.count; ++k) {
    EXPECT_NEAR(m.gap[k], 0.01, kTight);
    EXPECT_NEAR(m.point[k].z(), 1.005, kTight);  // midway between the two faces
    EXPECT_NEAR(std::abs(m.point[k].x() - 0.3), 0.5, kTight);
    EXPECT_NEAR(std::abs(m.point[k].y() + 0.2), 0.5, kTight);
  }
  // Swapped, the same points with the opposite normal.
  const Manifold s = manifold(cube, above, big, below, 0.05);
  ASSERT_EQ(s.count, 4);
  EXPECT_LT((s.normal + Vec3::UnitZ()).norm(), kTight);
  for (int k = 0; k < s.count; ++k) EXPECT_NEAR(s.gap[k], 0.01, kTight);
}

// Overlapping by 0.002 the gaps are -0.002; beyond the margin there is no patch.
TEST(BlockManifold, OverlapIsANegativeGapAndFarIsNothing) {
  const Block big(box(Vec3(2, 2, 2))), cube(box(Vec3(1, 1, 1)));
  const BlockPose below = pose_of(Mat3::Identity(), Vec3::Zero());
  const Manifold m =
      manifold(big, below, cube, pose_of(Mat3::Identity(), Vec3(0.3, -0.2, 1.5 - 0.002)), 0.05);
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < m.count; ++k) EXPECT_NEAR(m.gap[k], -0.002, kTight);
  manifold(big, below, cube, pose_of(Mat3::Identity(), Vec3(0.3, -0.2, 1.5 + 0.06)), 0.05,
           /*expect_found=*/false);
}

// A cube hanging over the edge of another: the patch is clipped to the overlap of the two
// faces in plan, half of the upper face.
TEST(BlockManifold, PatchIsClippedToTheFacesOverlap) {
  const Block cube(box(Vec3(1, 1, 1)));
  const BlockPose below = pose_of(Mat3::Identity(), Vec3::Zero());
  const BlockPose above = pose_of(Mat3::Identity(), Vec3(0.5, 0, 1.0 + 0.02));
  const Manifold m = manifold(cube, below, cube, above, 0.05);
  ASSERT_EQ(m.count, 4);
  for (int k = 0; k < m.count; ++k) {
    EXPECT_NEAR(m.gap[k], 0.02, kTight);
    EXPECT_GE(m.point[k].x(), 0.0 - kTight);  // [0, 0.5] x [-0.5, 0.5]
    EXPECT_LE(m.point[k].x(), 0.5 + kTight);
  }
}

// Two cubes edge on edge, crossed at right angles (one turned 45 degrees about x, the other
// about y), 0.03 apart: one point between the edges, normal along z, gap 0.03.
TEST(BlockManifold, CrossedEdgesGiveOnePointWithTheirDistance) {
  const Block cube(box(Vec3(1, 1, 1)));
  const Real half_diagonal = std::sqrt(0.5);
  const BlockPose lower =
      pose_of(about(Vec3::UnitX(), std::numbers::pi / 4), Vec3(0, 0, -half_diagonal));
  const BlockPose upper =
      pose_of(about(Vec3::UnitY(), std::numbers::pi / 4), Vec3(0.1, 0.05, half_diagonal + 0.03));
  const Manifold m = manifold(cube, lower, cube, upper, 0.05);
  ASSERT_EQ(m.count, 1);
  EXPECT_LT((m.normal - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_NEAR(m.gap[0], 0.03, kTight);
  EXPECT_LT((m.point[0] - Vec3(0.1, 0, 0.015)).norm(), 1e-12);
}

// A cube tilted about x over the floor: the points are the corners of its lowest face within
// the margin, each with its own height as gap; the normal is the wall's, reversed.
TEST(BlockManifold, WallPatchIsTheLowFaceWithinTheMargin) {
  const Block cube(box(Vec3(1, 1, 1)));
  const Real angle = 0.01;  // radians
  const Real lowest = 0.5 * (std::cos(angle) + std::sin(angle));
  const BlockPose pose = pose_of(about(Vec3::UnitX(), angle), Vec3(0, 0, lowest + 0.004));
  ManifoldScratch scratch;
  Manifold m;
  ASSERT_TRUE(wall_manifold(cube, pose, Vec3::Zero(), Vec3::UnitZ(), 0.02, scratch, m));
  EXPECT_LT((m.normal + Vec3::UnitZ()).norm(), kTight);
  ASSERT_EQ(m.count, 4);
  Real smallest = 1;
  for (int k = 0; k < m.count; ++k) {
    smallest = std::min(smallest, m.gap[k]);
    EXPECT_NEAR(m.point[k].z(), m.gap[k] / 2, kTight);  // midway between node and floor
  }
  EXPECT_NEAR(smallest, 0.004, kTight);
  // With a margin below the upper corners' height only the low edge's two corners remain.
  ASSERT_TRUE(wall_manifold(cube, pose, Vec3::Zero(), Vec3::UnitZ(), 0.006, scratch, m));
  EXPECT_EQ(m.count, 2);
  EXPECT_FALSE(wall_manifold(cube, pose, Vec3::Zero(), Vec3::UnitZ(), 0.003, scratch, m));
}

// Of a hexagon's six corners the reduction keeps four: the deepest, and three that span the
// largest area with it (two thirds of the hexagon's: a rectangle of its four side corners).
TEST(BlockManifold, ReductionKeepsTheDeepestAndTheArea) {
  std::array<Vec3, 6> points;
  std::array<Real, 6> gaps{};
  for (int k = 0; k < 6; ++k) {
    const Real phi = k * std::numbers::pi / 3;
    points[k] = Vec3(std::cos(phi), std::sin(phi), 0);
    gaps[k] = 0.01 + 0.001 * k;
  }
  gaps[2] = -0.001;  // the deepest
  std::array<int, kManifoldPoints> kept{};
  const int n = reduce_points(Vec3::UnitZ(), Vec3::UnitX(), 1e-4, points.data(), gaps.data(), 6,
                              kept);
  ASSERT_EQ(n, 4);
  EXPECT_EQ(kept[0], 2);
  EXPECT_EQ(kept[1], 5);  // opposite the deepest
  // Kept quadrilateral's area (two triangles on either side of the diagonal 2-5).
  const Vec3 d = points[5] - points[2];
  const Real area = 0.5 * (std::abs(d.cross(points[kept[2]] - points[2]).z()) +
                           std::abs(d.cross(points[kept[3]] - points[2]).z()));
  EXPECT_NEAR(area, std::sqrt(3.0), 1e-12);  // the hexagon's is 3 sqrt(3) / 2
}

// A face lying flat on a face: twelve corners at one depth to round-off (two hexagons, one
// turned 7 degrees). Trembling by 1e-12 in place and depth, as a resting coin does from step to
// step, must not change which four are kept (the warm start finds a point again only where it
// was), while one corner deeper by more than `equal_depth` is always kept first.
TEST(BlockManifold, ReductionOfAFlatFaceDoesNotFlicker) {
  constexpr int kCorners = 12;
  std::array<Vec3, kCorners> points;
  std::array<Real, kCorners> gaps{};
  for (int k = 0; k < kCorners; ++k) {
    const Real phi = k * std::numbers::pi / 6 + (k % 2 ? 0.061 : 0);
    points[k] = Vec3(std::cos(phi), std::sin(phi), 0);
  }
  const Vec3 edge = points[1] - points[0];
  std::array<int, kManifoldPoints> first{};
  ASSERT_EQ(reduce_points(Vec3::UnitZ(), edge, 1e-4, points.data(), gaps.data(), kCorners, first),
            4);
  std::mt19937 random(7);
  std::uniform_real_distribution<Real> tremor(-1e-12, 1e-12);
  int changed = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    std::array<Vec3, kCorners> moved = points;
    std::array<Real, kCorners> moved_gaps{};
    for (int k = 0; k < kCorners; ++k) {
      moved[k] += Vec3(tremor(random), tremor(random), 0);
      moved_gaps[k] = tremor(random);
    }
    std::array<int, kManifoldPoints> kept{};
    reduce_points(Vec3::UnitZ(), edge, 1e-4, moved.data(), moved_gaps.data(), kCorners, kept);
    changed += kept != first;
  }
  EXPECT_EQ(changed, 0);
  // A corner 1e-3 deeper than the rest: kept first, wherever it is.
  for (int deep = 0; deep < kCorners; ++deep) {
    std::array<Real, kCorners> tilted{};
    tilted[deep] = -1e-3;
    std::array<int, kManifoldPoints> kept{};
    reduce_points(Vec3::UnitZ(), edge, 1e-4, points.data(), tilted.data(), kCorners, kept);
    EXPECT_EQ(kept[0], deep);
  }
}

}  // namespace
}  // namespace tem
