// A `mesh` shape made ready for the core: the file read and checked, the mesh cut into convex
// blocks, and the mesh's own mass properties for the cross-check that `tem info` prints.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "mass/mass_properties.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/mesh_decomposition.hpp"
#include "tem/scene_def.hpp"

namespace tem {

struct MeshBody {
  std::string file_path;  // the file read
  // FNV-1a of the file's bytes as read: a checkpoint records it, so that a run resumed after
  // the file changed is refused (io/checkpoint.hpp).
  std::uint64_t content_hash = 0;
  Real scale = 1;
  MeshCutting cutting = MeshCutting::approximate;
  int max_blocks = 0;
  MeshCheck check;                  // vertices, faces, closedness, volume, warnings
  MassProperties surface;           // unit density, from the mesh's surface (mesh frame)
  MeshDecomposition decomposition;  // the convex blocks, in the mesh's frame
  double read_seconds = 0;          // reading and checking
};

// Reads, checks and cuts a mesh file. A process-wide cache keyed by the file (its path, size
// and modification time) and the settings hands every later request the same MeshBody, so the
// copies made by `fill` and bodies sharing a file share one decomposition. Throws MeshError.
std::shared_ptr<const MeshBody> load_mesh_body(const std::string& file_path, Real scale,
                                               MeshCutting cutting, int max_blocks);

}  // namespace tem
