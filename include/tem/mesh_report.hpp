// A mesh file read, checked and cut into convex blocks the way a scene's `mesh` shape is, with
// the figures that say how well the blocks stand for the mesh (`tem mesh` prints them).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "tem/scene_def.hpp"
#include "tem/types.hpp"

namespace tem {

// A mesh that cannot be read, checked or cut: what() names the file and says why.
class MeshLoadError : public std::runtime_error {
 public:
  explicit MeshLoadError(const std::string& message) : std::runtime_error(message) {}
};

struct MeshReport {
  std::string file;
  int vertices = 0, faces = 0;
  bool closed = false;
  bool turned = false;  // all faces pointed inwards and were turned
  Real volume = 0;      // enclosed by the surface
  MeshCutting cutting = MeshCutting::approximate;
  int max_blocks = 0;   // the approximate cut's limit
  int blocks = 0;
  Real blocks_volume = 0;
  Real smallest_block_volume = 0;
  Real diagonal = 0;  // of the blocks' (and the mesh's) bounding box
  // Approximate: the blocks' volume outside the mesh, and the largest distance from a block's
  // surface to the mesh's (sampled). 0 for exact.
  Real over_coverage = 0, hausdorff = 0;
  // Exact: slivers merged into a neighbour, edges where the surface turns inwards, parts cut
  // one at a time, pieces re-cut into tetrahedra.
  int merged_slivers = 0, reflex_edges = 0, parts = 1, recut_pieces = 0;
  double read_seconds = 0, cut_seconds = 0;
  std::vector<std::string> warnings;  // of the check, then of the cut
};

// Reads, checks and cuts `file` (OBJ, STL, PLY, OFF), every vertex multiplied by `scale`.
// With `blocks_vtu` not empty, writes the blocks there for ParaView (cell data `block`).
// A bad mesh throws MeshLoadError; blocks that cannot be built, or a file that cannot be
// written, throw std::runtime_error.
MeshReport report_mesh(const std::string& file, MeshCutting cutting, int max_blocks, Real scale,
                       const std::string& blocks_vtu = "");

}  // namespace tem
