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
  int reflex_edges = 0;    // exact: edges where the surface turns inwards (CGAL cuts along each)
  int parts = 1;           // exact: parts of the mesh that CGAL decomposed one at a time
  int pieces = 0;          // exact: the convex pieces CGAL returned, before slivers and joins
  int recut_pieces = 0;    // exact: pieces no hull made a block of, re-cut into tetrahedra
  // exact: the volume the blocks gained (negative: lost) against CGAL's pieces, where corners
  // bent by the mesh's rounding were left out and pieces too thin for a block dropped.
  Real rounding_change = 0;
  double seconds = 0;
  std::vector<std::string> warnings;
};

// CGAL's convex decomposition takes longer per reflex edge the more reflex edges a solid has
// (docs/meshes.md: 12,946-face fandisk, over 400 s whole, 76 s in 256 parts), so a mesh with more
// than this many is first cut, exactly, into parts with at most this many each.
constexpr int kReflexEdgesPerPart = 64;

// Blocks whose union is the mesh, from CGAL's Nef-polyhedron convex decomposition, of the whole
// mesh or of the parts that exact cuts by axis-aligned planes make of it (at most
// `reflex_edges_per_part` reflex edges each). Throws MeshError when CGAL fails or its pieces
// cannot be made into valid blocks.
MeshDecomposition exact_decomposition(const TriangleMesh& mesh,
                                      int reflex_edges_per_part = kReflexEdgesPerPart);

// At most `max_blocks` convex blocks, each the convex hull of the part of the mesh inside one
// cell of a tree of cutting planes (so blocks never overlap and keep the mesh's holes).
MeshDecomposition approximate_decomposition(const TriangleMesh& mesh, int max_blocks);

}  // namespace tem
