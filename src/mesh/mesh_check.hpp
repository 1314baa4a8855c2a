// Checking a triangle mesh before it is cut into blocks: nothing is changed silently.
#pragma once

#include <string>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace tem {

struct MeshCheck {
  int vertices = 0;
  int faces = 0;
  bool closed = false;  // every edge shared by exactly two faces
  Real volume = 0;      // enclosed volume, from the surface (after any turning)
  bool turned = false;  // all faces pointed inwards and were turned (a warning, not an error)
  std::vector<std::string> warnings;
};

// Throws MeshError (naming mesh.source, the face or vertex, and why) at the first of: a
// degenerate face (repeated vertex, zero area), an edge shared by more than two faces or an open
// edge (not closed), a vertex whose faces do not form one fan (not vertex-manifold),
// inconsistently oriented neighbours, two faces that intersect (other than along shared edges
// and vertices), a zero or negative volume that turning cannot fix, a non-finite coordinate.
// A mesh whose faces all point inwards is turned in place and reported in `turned`/`warnings`.
MeshCheck check_mesh(TriangleMesh& mesh);

}  // namespace tem
