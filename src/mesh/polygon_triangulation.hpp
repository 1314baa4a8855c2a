// Splitting one polygon face of a mesh file (an OBJ, OFF or PLY n-gon) into triangles.
#pragma once

#include <array>
#include <vector>

#include "tem/types.hpp"

namespace tem {

// The polygon's n corners in order, their positions in space. Returns n - 2 triangles of corner
// numbers (0 .. n-1), each turning the polygon's way round, so that the faces keep pointing to
// where the polygon pointed. A polygon of five corners or more is projected onto its own plane
// (Newell's normal: the plane its area vector defines, the best-fit plane of a nearly planar
// polygon). Then:
// - a quad: the fan from its reflex corner if it has one (the one diagonal inside it), else from
//   corner 0; on a non-planar quad, the corner whose two angles to the opposite corner add up
//   to more than pi (assimp's test);
// - convex (every corner turns the same way strictly): the fan from corner 0;
// - otherwise ear clipping: a corner that turns the polygon's way and whose triangle holds no
//   other corner is cut off, again and again. A polygon that has no such ear (it crosses itself)
//   or would take more than 5e7 point tests has its rest cut as a fan; the mesh checks then say
//   what is wrong with the faces.
// This is what assimp did for triangles and quads, so that decompositions of such files do not
// change; for five corners and more assimp clipped ears where TEM fans a convex polygon.
std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec3>& corners);

}  // namespace tem
