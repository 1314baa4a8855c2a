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

 private:
  struct Node {
    Vec3 lo, hi;
    int first, count;  // leaf: triangles order_[first .. first + count - 1]; else count = 0
    int right;         // inner node: left child is the next node, right child here
  };
  int build(int first, int count);

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
