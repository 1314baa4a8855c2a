// Grouping the flagged features of a pair into contact patches, and each patch's point, normal
// and depth (§4.4 of the paper, method.md §5).
//
// Grouping is a union-find over the nodes of both blocks. Within a block, an edge joins its end
// nodes when either end is flagged or the edge itself is flagged; so flagged nodes joined by an
// edge are one group (step 1), a flagged edge joins its flagged end nodes and the flagged edges
// that share an end node or a triangle with it (step 2), and two flagged nodes with a common
// neighbour are one group (step 3, fig. 11). Across the pair, an edge of A through a triangle of
// B joins the group of B that touches that triangle (step 4, fig. 13); a group with no partner
// on the other side is a one-sided patch (a corner of A in a face of B).
//
// Geometry, paper variant: per side, the mean of its flagged nodes (else of its edges'
// intersection points, else of the other side's intersection points on its surface) and the
// mean of their node normals (else edge normals, else the crossed faces' normals); the patch
// point is the midpoint, the normal n = normalise(n_A - n_B), the depth the normal component of
// the difference of the two sides' points.
//
// Geometry, default variant: the vertices (nodes inside the other side, polygon edges'
// intersections; not the diagonals of planar polygons) are the corners of the overlap region.
// The normal is chosen among the normals of the faces the flagged features went through (the
// face nearest a node inside, the triangle an edge crosses), turned to point from A into B,
// their sum, and the cross products of crossing edges of A and B: the one along which the
// overlap region is thinnest, the shortest way out. The depth is the overlap's extent along it,
// the point the mean of the vertices. A plain sum of face normals is not enough: in a shallow
// face-on-face overlap offset sideways, the polygon edges inside the overlap cross side faces
// and tilt the sum by 30 degrees or more.
// This fixes the paper's normal where corners overlap (method.md §5: 54.7 degrees off and a depth
// of 0.19 for an overlap of 0.002).
#pragma once

#include <vector>

#include "collision/narrow_phase.hpp"
#include "contact/contact_patch.hpp"
#include "geometry/block.hpp"

namespace tem {

using PatchVariant = NormalVariant;

// Scratch memory reused between pairs.
struct PatchScratch {
  std::vector<int> parent;
  std::vector<char> active;
  std::vector<char> flagged_node;
  std::vector<char> flagged_edge;
  std::vector<int> group_of_root;
};

// Patches of one block pair (body indices left at -1 for the caller to fill).
void pair_patches(const Block& a, const BlockPose& pose_a, const Block& b,
                  const BlockPose& pose_b, const PairFeatures& features, PatchVariant variant,
                  PatchScratch& scratch, std::vector<ContactPatch>& out);

// Patches of a block against a wall (body_a, wall left for the caller to fill).
void wall_patches(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                  const Vec3& wall_normal, const WallFeatures& features, PatchVariant variant,
                  PatchScratch& scratch, std::vector<ContactPatch>& out);

// Merges patches of the same body pair (or body and wall) whose overlap regions touch: the
// blocks of one body that touch another body at one place give one patch. Keeps the order of
// first appearance.
void merge_touching_patches(std::vector<ContactPatch>& patches);

}  // namespace tem
