// The self-intersection test of a triangle soup, behind plain types: CGAL's headers stay in
// crossing_faces.cpp (and the exact decomposition's in exact_decomposition.cpp).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace tem {

// Every pair of faces (i < j, sorted) that intersect other than at the vertices they share by
// number and the edges between those: a triangle-soup test, so that a mesh with open or
// non-manifold edges, inconsistent orientation or pinched vertices can be checked too (CGAL
// 5.5's PMP has no soup version). Faces with `left_out[f]` set are skipped; every other face must
// have three distinct vertices in range with finite coordinates and a non-zero area. The search
// stops at `max_pairs` pairs (a soup of many copies of one triangle has n^2 / 2).
std::vector<std::pair<int, int>> crossing_faces(const TriangleMesh& mesh,
                                                const std::vector<char>& left_out,
                                                std::size_t max_pairs);

}  // namespace tem
