// A cut can leave a side of a part in several pieces: the legs below a waist, the two sides of
// a hole cut across twice, an arm's end beyond a bend. One hull over them all covers the gap
// between them too; a hull for each piece does not. These find the pieces of a part and group
// them so that every group's hull stays clear of every other's (blocks never overlap).
#pragma once

#include <vector>

#include "mesh/plane_cut.hpp"

namespace tem {

// The connected pieces of a part cut with its surface kept (cut_part's keep_surface), each a
// part of its own: its surface polygons, caps and corners, and its volume. Pieces touching at
// a single point count as one. A part whose pieces cannot be told apart consistently (a piece
// that would have no volume) comes back whole.
std::vector<MeshPart> connected_components(const MeshPart& part);

// Whether a plane separates the convex hulls of the two point sets with a gap wider than `gap`.
// False when they meet, and also when they come so close that this cannot tell within its
// iterations: the answer errs only towards "not apart".
bool hulls_apart(const std::vector<Vec3>& a, const std::vector<Vec3>& b, Real gap);

// The part's pieces gathered into groups whose hulls are apart from one another: pieces whose
// hulls meet, and pieces smaller than `smallest_volume`, join the group nearest them. One group
// (the part whole) when the part is connected.
std::vector<MeshPart> separate_groups(const MeshPart& part, Real smallest_volume, Real gap);

}  // namespace tem
