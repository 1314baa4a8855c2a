// The narrow phase of one block pair (§4 of the paper): which nodes of each block lie inside the
// other, and which edges of each block pass through the other's surface triangles.
//
// Node inside element (eqs. 19-20). A node p of A is brought into B's block frame once; the
// paper then solves p = s a1 + t a2 + u a3 for every element of B with the precomputed E^-1 and
// flags the node when s, t, u > 0 and s + t + u < 1. For a convex B the elements tile the block,
// so "inside some element" is "on the inner side of every face plane": TEM tests the planes
// (one dot product per face, and the same distances serve the edge test and the separating
// plane test below), then finds the element that holds the node with E^-1 for the record. For a
// non-convex block (accepted with allow_nonconvex) the planes do not bound it, and the
// element test of the paper is used as printed.
//
// Edge through face (eq. 21). An edge a->b of A crosses the plane of a polygon of B when its end
// nodes' plane distances differ in sign; the crossing point is then tested against the
// polygon's triangles with the barycentric (s, t) of eq. 21, s, t >= 0, s + t <= 1, and recorded
// with the triangle (the paper's "face number") it went through. An edge may cross several.
//
// Separating plane. If all nodes of A lie strictly outside one face plane of a convex B (or
// the other way round), the blocks cannot touch and the pair is dropped before any element
// test: the cheap rejection the paper left for future work (its ref. 26, GJK), in its simplest
// exact form. A gap of 1e-9 is a separating plane.
#pragma once

#include <vector>

#include "collision/block_pose.hpp"
#include "geometry/block.hpp"

namespace tem {

// A node of one block found inside the other block.
struct NodeHit {
  int node;         // node of the block it belongs to
  int element;      // element of the other block that holds it (eqs. 19-20)
  int polygon;      // the other block's face nearest to it: the face it went in through
  Real depth;       // its distance inside that face's plane (> 0)
  Vec3 point;       // world position
  Vec3 face_normal; // world outward normal of that face of the other block
};

// An edge of one block passing through a surface triangle of the other.
struct EdgeHit {
  int edge;          // edge of the block it belongs to
  int triangle;      // triangle of the other block it goes through (eq. 21)
  Vec3 point;        // world intersection point, on the other block's surface
  Vec3 face_normal;  // world outward normal of that triangle
};

// What one side of a pair found: its own nodes inside the other, its edges through the other.
struct SideFeatures {
  std::vector<NodeHit> nodes;
  std::vector<EdgeHit> edges;
  void clear() {
    nodes.clear();
    edges.clear();
  }
  bool empty() const { return nodes.empty() && edges.empty(); }
};

struct PairFeatures {
  SideFeatures a;  // A's nodes in B, A's edges through B (steps 2 and 4 of §4.3)
  SideFeatures b;  // the same with A and B swapped (steps 3 and 5)
  bool empty() const { return a.empty() && b.empty(); }
};

// Reusable scratch memory of the narrow phase.
struct NarrowPhaseScratch {
  std::vector<Vec3> nodes_in_other;  // one block's nodes in the other's frame
  std::vector<Real> distance;        // [node * polygons + polygon] signed plane distances
};

// Finds the features of one block pair. Returns false (and empty features) when a face plane
// separates the blocks.
bool block_pair_features(const Block& a, const BlockPose& pose_a, const Block& b,
                         const BlockPose& pose_b, NarrowPhaseScratch& scratch,
                         PairFeatures& out);

// A wall is a plane; a node behind it is inside, an edge that crosses it goes through it.
struct WallFeatures {
  std::vector<NodeHit> nodes;  // element = polygon = -1, face_normal = the wall's normal
  std::vector<EdgeHit> edges;  // triangle = -1
  bool empty() const { return nodes.empty(); }
};

void block_wall_features(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                         const Vec3& wall_normal, WallFeatures& out);

}  // namespace tem
