// A closed triangle mesh as read from a user's file, and the errors found in one.
//
// This is the input of a `mesh` shape (docs/meshes.md): vertices and triangles, welded (each
// position once) and, once check_mesh() has passed, closed, edge-manifold, oriented outwards
// (counter-clockwise seen from outside), free of self-intersections and degenerate faces, with a
// positive volume. Face and vertex numbers in messages count from 0 in this welded list.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "tem/types.hpp"

namespace tem {

struct TriangleMesh {
  std::string source;  // the file it came from, for messages
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> faces;
};

// A mesh that cannot become a body. what() names the file, the face or vertex, and why, e.g.
// "parts/nut.obj: face 12 (vertices 4, 9, 17): its edge 9-17 is shared by 3 faces (not
// edge-manifold)".
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tem
