// Checking a triangle mesh before it is cut into blocks: nothing is changed silently.
#pragma once

#include <string>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace tem {

// A face whose area is at most this times the square of the bounding box's diagonal has zero
// area: its normal is round-off.
inline constexpr Real kFaceAreaTolerance = 1e-14;

struct MeshCheck {
  int vertices = 0;
  int faces = 0;
  bool closed = false;  // every edge shared by exactly two faces
  Real volume = 0;      // enclosed volume, from the surface (after any turning)
  bool turned = false;  // all faces pointed inwards and were turned (a warning, not an error)
  std::vector<std::string> warnings;
};

// Throws one MeshError for everything wrong with the mesh, naming mesh.source and, per kind of
// defect, how many there are and the first few (face, edge or vertex and where): no faces, a
// missing vertex, a non-finite coordinate, a degenerate face (repeated vertex, zero area), an
// open edge (not closed), an edge of more than two faces, inconsistently oriented neighbours, a
// vertex whose faces do not form one fan (not vertex-manifold), a closed surface of zero volume,
// two faces that intersect (other than along shared edges and vertices), nested surfaces that do
// not alternate; and the checks that defects kept it from making (docs/meshes.md, "Checking").
// A mesh whose faces all point inwards is turned in place and reported in `turned`/`warnings`.
MeshCheck check_mesh(TriangleMesh& mesh);

}  // namespace tem
