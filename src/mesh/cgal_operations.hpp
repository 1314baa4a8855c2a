// Everything TEM asks of CGAL, behind plain types: CGAL's headers are included by
// cgal_operations.cpp alone (they are heavy to compile).
#pragma once

#include <utility>
#include <vector>

#include "mesh/mesh_decomposition.hpp"
#include "mesh/triangle_mesh.hpp"

namespace tem {

// Pairs of faces (i < j) that intersect other than along the edges and vertices they share, at
// most `max_pairs` of them (CGAL's Polygon_mesh_processing::self_intersections).
std::vector<std::pair<int, int>> self_intersecting_faces(const TriangleMesh& mesh, int max_pairs);

}  // namespace tem
