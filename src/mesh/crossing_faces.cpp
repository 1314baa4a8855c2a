// The triangle-soup intersection test of check_mesh() (CGAL's box intersection with filtered
// exact predicates). Its own translation unit, apart from the exact decomposition: it needs only
// the light inexact kernel, and the mesh fuzz target links it without the Nef machinery.
#include "mesh/crossing_faces.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>

namespace tem {

using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace {

// Whether faces f and g of a soup meet anywhere but at the vertices they share by number (and,
// for two shared vertices, the edge between them). Exact: Epick's predicates are filtered.
bool faces_cross(const std::vector<Inexact::Point_3>& p, const std::array<int, 3>& f,
                 const std::array<int, 3>& g) {
  int shared = 0, fi[3], gi[3];  // fi[k], gi[k]: the corner of f and of g at shared vertex k
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (f[a] == g[b]) {
        fi[shared] = a;
        gi[shared] = b;
        ++shared;
      }
  const Inexact::Triangle_3 tf(p[f[0]], p[f[1]], p[f[2]]), tg(p[g[0]], p[g[1]], p[g[2]]);
  switch (shared) {
    case 0:
      return CGAL::do_intersect(tf, tg);
    case 1: {
      // Both contain the shared vertex v; they meet elsewhere exactly when the edge of one
      // opposite v meets the other (the part they share is convex and runs from v to a point
      // on one of those edges).
      const Inexact::Segment_3 ef(p[f[(fi[0] + 1) % 3]], p[f[(fi[0] + 2) % 3]]);
      const Inexact::Segment_3 eg(p[g[(gi[0] + 1) % 3]], p[g[(gi[0] + 2) % 3]]);
      return CGAL::do_intersect(ef, tg) || CGAL::do_intersect(eg, tf);
    }
    case 2: {
      // Sharing the edge p-q, they overlap exactly when they lie in one plane on one side of it.
      const auto& a = p[f[fi[0]]];
      const auto& b = p[f[fi[1]]];
      const auto& r = p[f[3 - fi[0] - fi[1]]];
      const auto& s = p[g[3 - gi[0] - gi[1]]];
      return CGAL::coplanar(a, b, r, s) && CGAL::coplanar_orientation(a, b, r, s) == CGAL::POSITIVE;
    }
    default:
      return true;  // the same three vertices: the faces coincide
  }
}

}  // namespace

std::vector<std::pair<int, int>> crossing_faces(const TriangleMesh& mesh,
                                                const std::vector<char>& left_out,
                                                std::size_t max_pairs) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;
  std::vector<Inexact::Point_3> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<Box> boxes;
  boxes.reserve(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (left_out[f]) continue;
    const auto& t = mesh.faces[f];
    boxes.emplace_back(points[t[0]].bbox() + points[t[1]].bbox() + points[t[2]].bbox(),
                       static_cast<int>(f));
  }
  std::vector<std::pair<int, int>> pairs;
  struct Enough {};  // thrown to stop the sweep at max_pairs
  // Boxes are closed: faces that only touch are candidates, and the exact test decides.
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
      const int i = a.info(), j = b.info();
      if (faces_cross(points, mesh.faces[i], mesh.faces[j])) {
        pairs.emplace_back(std::min(i, j), std::max(i, j));
        if (pairs.size() >= max_pairs) throw Enough{};
      }
    });
  } catch (const Enough&) {
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace tem
