// Contact detection with expectations worked out by hand: node-in-element, edge-through-face,
// patches (grouping, point, normal from A into B, depth) in the default and paper variants.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "collision/narrow_phase.hpp"
#include "contact/patches.hpp"
#include "geometry/primitives.hpp"

namespace tem {
namespace test_contacts {

constexpr Real kTight = 1e-12;

BlockPose pose_of(const Mat3& rotation, const Vec3& position) {
  return {rotation, rotation.transpose(), position};
}

Mat3 rotation_y(Real angle) { return Eigen::AngleAxis<Real>(angle, Vec3::UnitY()).matrix(); }

struct PairResult {
  bool touching = false;
  PairFeatures features;
  std::vector<ContactPatch> patches;
};

PairResult detect(const Block& a, const BlockPose& pa, const Block& b, const BlockPose& pb,
                  PatchVariant variant = NormalVariant::default_) {
  PairResult r;
  NarrowPhaseScratch scratch;
  PatchScratch patch_scratch;
  r.touching = block_pair_features(a, pa, b, pb, scratch, r.features);
  if (r.touching) pair_patches(a, pa, b, pb, r.features, variant, patch_scratch, r.patches);
  return r;
}

// Swapping A and B gives the same patches with opposite normals.
void expect_swap_symmetric(const Block& a, const BlockPose& pa, const Block& b,
                           const BlockPose& pb, PatchVariant variant) {
  const PairResult ab = detect(a, pa, b, pb, variant), ba = detect(b, pb, a, pa, variant);
  ASSERT_EQ(ab.patches.size(), ba.patches.size());
  for (size_t i = 0; i < ab.patches.size(); ++i) {
    EXPECT_LT((ab.patches[i].normal + ba.patches[i].normal).norm(), kTight);
    EXPECT_NEAR(ab.patches[i].depth, ba.patches[i].depth, kTight);
    EXPECT_LT((ab.patches[i].point - ba.patches[i].point).norm(), kTight);
  }
}

// A unit cube resting 0.01 deep in the top face of a 2-cube: one patch, normal -z (from A
// down into B), depth 0.01, in both variants; the 4 bottom nodes of A are inside B.
TEST(Contacts, CubeFaceOnCubeFace) {
  const Block a(box(Vec3(1, 1, 1))), b(box(Vec3(2, 2, 2)));
  const BlockPose pb = pose_of(Mat3::Identity(), Vec3::Zero());
  const BlockPose pa = pose_of(Mat3::Identity(), Vec3(0.3, -0.2, 1.5 - 0.01));
  const PairResult r = detect(a, pa, b, pb);
  ASSERT_TRUE(r.touching);
  EXPECT_EQ(r.features.a.nodes.size(), 4u);
  EXPECT_TRUE(r.features.b.nodes.empty());
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_LT((r.patches[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(r.patches[0].depth, 0.01, kTight);
  // The mean of the overlap's corners: 4 nodes at 0.99, 4 side-edge crossings at 1.
  EXPECT_LT((r.patches[0].point - Vec3(0.3, -0.2, 0.995)).norm(), kTight);
  expect_swap_symmetric(a, pa, b, pb, NormalVariant::default_);

  // Paper: A's side is the mean of its 4 bottom node normals (eq. 2, per triangle, so tilted by
  // the diagonals of A's faces). B has no node inside A, but the diagonal of its fanned top face
  // runs under A and crosses A's side faces: B's side is that edge's normal (eq. 3). Both
  // sides' points lie at fixed heights (A's nodes at 0.99, the crossings at 1), so the depth
  // is 0.01 along the normal.
  const PairResult paper = detect(a, pa, b, pb, NormalVariant::paper);
  ASSERT_EQ(paper.patches.size(), 1u);
  Vec3 node_normals = Vec3::Zero(), edge_normals = Vec3::Zero();
  for (const NodeHit& n : paper.features.a.nodes)
    node_normals += a.node_normal(n.node, NormalVariant::paper);
  ASSERT_EQ(paper.features.b.edges.size(), 2u);  // one diagonal, through two faces of A
  for (const EdgeHit& e : paper.features.b.edges) {
    EXPECT_FALSE(b.edges()[e.edge].polygon_boundary);
    edge_normals += b.edge_normal(e.edge, NormalVariant::paper);
  }
  const Vec3 expected = (node_normals.normalized() - edge_normals.normalized()).normalized();
  EXPECT_LT((paper.patches[0].normal - expected).norm(), kTight);
  EXPECT_NEAR(paper.patches[0].depth, -0.01 * expected.z(), kTight);
  EXPECT_GT(expected.z(), -1 + 1e-6);  // the per-triangle normals do tilt it
  expect_swap_symmetric(a, pa, b, pb, NormalVariant::paper);
}

// A cube standing on a corner, 0.01 into a face: one node inside, its three edges through the
// face; a one-sided patch (B has no feature) with the face's normal and the node's depth.
TEST(Contacts, CubeCornerIntoFace) {
  const Block a(box(Vec3(1, 1, 1))), b(box(Vec3(2, 2, 2)));
  // Turn the corner direction (-1,-1,-1)/sqrt3 onto -z.
  const Mat3 r = Eigen::Quaternion<Real>::FromTwoVectors(Vec3(-1, -1, -1), Vec3(0, 0, -1))
                     .toRotationMatrix();
  const Real half_diagonal = std::sqrt(3.0) / 2, d = 0.01;
  const BlockPose pa = pose_of(r, Vec3(0.1, 0.2, 1 + half_diagonal - d));
  const BlockPose pb = pose_of(Mat3::Identity(), Vec3::Zero());
  const PairResult res = detect(a, pa, b, pb);
  ASSERT_EQ(res.features.a.nodes.size(), 1u);
  EXPECT_NEAR(res.features.a.nodes[0].depth, d, kTight);
  EXPECT_TRUE(res.features.b.nodes.empty());
  EXPECT_TRUE(res.features.b.edges.empty());
  int polygon_edges = 0;
  for (const EdgeHit& h : res.features.a.edges) polygon_edges += a.edges()[h.edge].polygon_boundary;
  EXPECT_EQ(polygon_edges, 3);
  ASSERT_EQ(res.patches.size(), 1u);
  EXPECT_LT((res.patches[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(res.patches[0].depth, d, kTight);
  EXPECT_NEAR(res.patches[0].point.x(), 0.1, kTight);  // corner and its 3 symmetric crossings
  EXPECT_NEAR(res.patches[0].point.y(), 0.2, kTight);
  expect_swap_symmetric(a, pa, b, pb, NormalVariant::default_);
  expect_swap_symmetric(a, pa, b, pb, NormalVariant::paper);
}

// Two unit cubes turned 45 deg, A about x (lowest feature an edge along x), B about y (highest
// an edge along y), the edges crossed d deep: no node inside either body; one patch from the
// edges through faces alone, normal -z, depth d.
TEST(Contacts, CrossedEdgesWithNoNodeInside) {
  const Block cube(box(Vec3(1, 1, 1)));
  const Real h = std::sqrt(2.0) / 2, d = 0.02, pi = std::numbers::pi;
  const BlockPose pa = pose_of(rotation_x(pi / 4), Vec3(0, 0, 2 * h - d));
  const BlockPose pb = pose_of(rotation_y(pi / 4), Vec3::Zero());
  const PairResult r = detect(cube, pa, cube, pb);
  EXPECT_TRUE(r.features.a.nodes.empty());
  EXPECT_TRUE(r.features.b.nodes.empty());
  EXPECT_FALSE(r.features.a.edges.empty());
  EXPECT_FALSE(r.features.b.edges.empty());
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_LT((r.patches[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(r.patches[0].depth, d, kTight);
  EXPECT_LT((r.patches[0].point - Vec3(0, 0, h - d / 2)).norm(), kTight);
  expect_swap_symmetric(cube, pa, cube, pb, NormalVariant::default_);
  expect_swap_symmetric(cube, pa, cube, pb, NormalVariant::paper);
}

// No contact across a gap of 1e-9: a face plane separates the face-on-face pair; for crossed
// edges no face plane separates, and the element and edge tests find nothing.
TEST(Contacts, NoContactAcrossAGapOf1e9) {
  const Block a(box(Vec3(1, 1, 1))), b(box(Vec3(2, 2, 2)));
  const BlockPose pb = pose_of(Mat3::Identity(), Vec3::Zero());
  EXPECT_FALSE(detect(a, pose_of(Mat3::Identity(), Vec3(0.3, -0.2, 1.5 + 1e-9)), b, pb).touching);
  const Block cube(box(Vec3(1, 1, 1)));
  const Real h = std::sqrt(2.0) / 2, pi = std::numbers::pi;
  const PairResult r = detect(cube, pose_of(rotation_x(pi / 4), Vec3(0, 0, 2 * h + 1e-9)), cube,
                              pose_of(rotation_y(pi / 4), Vec3::Zero()));
  EXPECT_TRUE(r.features.empty());
  EXPECT_TRUE(r.patches.empty());
}

// method.md §5: cubes overlapping face to face by 0.002, offset sideways so that one corner of
// each is inside the other. The paper's rule averages two corner normals and is far off; the
// default takes the faces the corners went through and is exact.
TEST(Contacts, CornerOverlapNormalPaperVersusDefault) {
  const Block cube(box(Vec3(1, 1, 1)));
  const BlockPose pb = pose_of(Mat3::Identity(), Vec3::Zero());
  const BlockPose pa = pose_of(Mat3::Identity(), Vec3(0.5, 0.5, 1 - 0.002));
  const PairResult def = detect(cube, pa, cube, pb, NormalVariant::default_);
  ASSERT_EQ(def.features.a.nodes.size(), 1u);
  ASSERT_EQ(def.features.b.nodes.size(), 1u);
  ASSERT_EQ(def.patches.size(), 1u);
  EXPECT_LT((def.patches[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(def.patches[0].depth, 0.002, kTight);
  const PairResult paper = detect(cube, pa, cube, pb, NormalVariant::paper);
  ASSERT_EQ(paper.patches.size(), 1u);
  const Real angle = std::acos(-paper.patches[0].normal.z()) * 180 / std::numbers::pi;
  EXPECT_GT(angle, 30.0) << "paper normal " << paper.patches[0].normal.transpose();
  EXPECT_GT(paper.patches[0].depth, 0.05);
}

// A hexagonal coin (r 0.15, h 0.1) tilted 30 deg about x stands on the rim edge between two
// nodes of its lower cap, d = 0.003 below the floor z = 0: one patch, two nodes, depth d,
// normal -z by the default; the paper's normal tilts, and its depth is d along that normal.
TEST(Contacts, CoinRimOnTheFloor) {
  const Real r = 0.15, h = 0.1, d = 0.003, alpha = std::numbers::pi / 6;
  const Block coin(regular_prism(6, r, h, Axis::z));
  const Real lowest = -r * std::sqrt(3.0) / 2 * std::sin(alpha) - h / 2 * std::cos(alpha);
  const BlockPose pose = pose_of(rotation_x(alpha), Vec3(0.4, 0.5, -lowest - d));
  WallFeatures f;
  block_wall_features(coin, pose, Vec3::Zero(), Vec3::UnitZ(), f);
  ASSERT_EQ(f.nodes.size(), 2u);
  for (const NodeHit& n : f.nodes) EXPECT_NEAR(n.depth, d, kTight);
  PatchScratch scratch;
  std::vector<ContactPatch> def, paper;
  wall_patches(coin, pose, Vec3::Zero(), Vec3::UnitZ(), f, NormalVariant::default_, scratch, def);
  wall_patches(coin, pose, Vec3::Zero(), Vec3::UnitZ(), f, NormalVariant::paper, scratch, paper);
  ASSERT_EQ(def.size(), 1u);
  EXPECT_LT((def[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(def[0].depth, d, kTight);
  EXPECT_NEAR(def[0].point.x(), 0.4, kTight);  // the rim edge is symmetric about x = 0.4
  ASSERT_EQ(paper.size(), 1u);
  EXPECT_LT(paper[0].normal.z(), -0.5);
  EXPECT_GT((paper[0].normal - Vec3(0, 0, -1)).norm(), 0.01);  // tilted by the node normals
  EXPECT_NEAR(paper[0].depth, -d * paper[0].normal.z(), kTight);
}

}  // namespace test_contacts
}  // namespace tem
