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

// The mesh's faces as corner triangles, for surface integrals such as surface_mass_properties().
inline std::vector<std::array<Vec3, 3>> corner_triangles(const TriangleMesh& mesh) {
  std::vector<std::array<Vec3, 3>> triangles;
  triangles.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces)
    triangles.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
  return triangles;
}

// A mesh that cannot become a body. what() names the file and why; a mesh refused by
// check_mesh() gets one message for everything wrong with it, e.g. "parts/nut.obj: refused:
// 6 open edges, 1 pinched vertex", then the first places of each kind (mesh_check.hpp).
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tem
