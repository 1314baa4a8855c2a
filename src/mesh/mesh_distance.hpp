// Distances from points to a closed mesh's solid, for measuring how far approximate blocks
// stray outside the mesh: a bounding-volume tree over the triangles for the nearest point, and
// angle-weighted pseudo-normals (Baerentzen and Aanaes, 2005) for inside or outside.
#pragma once

#include <array>
#include <vector>

#include "geometry/block.hpp"
#include "mesh/triangle_mesh.hpp"

namespace tem {

class MeshDistance {
 public:
  explicit MeshDistance(const TriangleMesh& mesh);

  // Distance from p to the mesh's surface, negative inside the solid.
  Real signed_distance(const Vec3& p) const;

  // signed_distance(p) where it is above `bar` (>= 0); else `bar`, or the distance where no
  // triangle lies within bar of p (deep inside). The search stops at the first triangle within
  // bar, which already bounds the distance by bar: a largest distance over many points needs
  // no more of the points below it, and most points of a block lie on the mesh, where such a
  // triangle is found at once.
  Real signed_distance_above(const Vec3& p, Real bar) const;

 private:
  struct Node {
    Vec3 lo, hi;
    int first, count;  // leaf: triangles order_[first .. first + count - 1]; else count = 0
    int right;         // inner node: left child is the next node, right child here
  };
  int build(int first, int count);
  // The search of both: the nearest point, or stop at one within sqrt(stop2) (returns false).
  bool nearest(const Vec3& p, Real stop2, Real& best2, Vec3& best_point, int& best_face,
               int& best_feature) const;
  Real signed_from(const Vec3& p, Real best2, const Vec3& best_point, int best_face,
                   int best_feature) const;

  std::vector<std::array<Vec3, 3>> corners_;
  std::vector<Vec3> face_normal_;
  // Pseudo-normals per triangle corner (angle-weighted vertex normals) and edge (k: k -> k+1).
  std::vector<std::array<Vec3, 3>> vertex_normal_, edge_normal_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

// The largest distance from a point of the blocks' surfaces to the mesh's solid (0 for points
// inside it), to within `precision`: the true value lies between the result and the result
// plus `precision`. Each face's triangles are halved until the distance at their corners plus
// their size (the distance changes no faster than the point moves) cannot beat a first
// estimate by more than `precision`, or they are that small; faces inside the mesh stop at once.
Real largest_outside_distance(const MeshDistance& distance, const std::vector<PolyhedronDef>& blocks,
                              Real precision);

// A quick lower bound of largest_outside_distance for one block: the largest distance at its
// faces' corners, centres and edge midpoints (a fan of triangles per face), not refined. Good
// enough to rank candidate blocks against each other, not to report.
Real sampled_outside_distance(const MeshDistance& distance, const PolyhedronDef& block);

}  // namespace tem
