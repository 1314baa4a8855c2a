// Everything TEM asks of CGAL, behind plain types: CGAL's headers are included by
// cgal_operations.cpp alone (they are heavy to compile).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "mesh/mesh_decomposition.hpp"
#include "mesh/triangle_mesh.hpp"

namespace tem {

// Pairs of faces (i < j) that intersect other than along the edges and vertices they share, at
// most `max_pairs` of them (CGAL's Polygon_mesh_processing::self_intersections).
std::vector<std::pair<int, int>> self_intersecting_faces(const TriangleMesh& mesh, int max_pairs);

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
