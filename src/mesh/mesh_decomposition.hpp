// Cutting a checked closed mesh into convex blocks, exactly or approximately (docs/meshes.md).
#pragma once

#include <vector>

#include "geometry/block.hpp"
#include "mesh/triangle_mesh.hpp"
#include "tem/scene_def.hpp"

namespace tem {

struct MeshDecomposition {
  // Each block a convex polyhedron in the mesh's frame, ready for Block(); no two overlap.
  std::vector<PolyhedronDef> blocks;
  Real mesh_volume = 0;    // from the mesh's surface
  Real blocks_volume = 0;  // sum of the blocks' volumes
  // approximate: volume of the blocks outside the mesh (blocks_volume - mesh_volume, as blocks
  // never overlap and cover the mesh), and the largest distance from a block's surface to the
  // mesh's (sampled), in the mesh's length units. 0 for exact.
  Real over_coverage = 0;
  Real hausdorff = 0;
  int merged_slivers = 0;  // exact: thin pieces merged into a neighbour (or dropped, see docs)
  double seconds = 0;
  std::vector<std::string> warnings;
};

// Blocks whose union is the mesh, from CGAL's Nef-polyhedron convex decomposition. Throws
// MeshError when CGAL fails or its pieces cannot be made into valid blocks.
MeshDecomposition exact_decomposition(const TriangleMesh& mesh);

// At most `max_blocks` convex blocks, each the convex hull of the part of the mesh inside one
// cell of a tree of cutting planes (so blocks never overlap and keep the mesh's holes).
MeshDecomposition approximate_decomposition(const TriangleMesh& mesh, int max_blocks);

}  // namespace tem
