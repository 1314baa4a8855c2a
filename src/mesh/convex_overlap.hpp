// Whether two convex blocks share inside volume. Blocks of one body may touch along a cut but
// must not overlap (a node inside both would be pushed out twice, and the blocks' volume would
// count the overlap twice); the approximate cutter asks this before merging two blocks that are
// not siblings of its tree, whose joint hull can reach across into a third.
#pragma once

#include "geometry/block.hpp"

namespace tem {

// True when a polygon plane of one polyhedron has every corner of the other on its outer side,
// to within `eps`: their insides are then apart (they may touch). Only polygon planes are tried,
// not the edge-pair axes a full separating-axis test adds, so two blocks crossed edge to edge
// count as overlapping: the answer errs only towards "they overlap". Polygons counter-clockwise
// about their outward normals, as Block and hull_polyhedron give them.
bool convex_insides_apart(const PolyhedronDef& a, const PolyhedronDef& b, Real eps);

}  // namespace tem
