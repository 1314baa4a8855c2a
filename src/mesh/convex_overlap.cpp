#include "mesh/convex_overlap.hpp"

namespace tem {
namespace {

// Whether some polygon plane of `p` has all of `points` on its outer side, within eps. The
// normal is taken about the polygon's first corner, so that it does not carry the round-off of
// coordinates far from the origin (as Block does).
bool some_plane_has_all_outside(const PolyhedronDef& p, const std::vector<Vec3>& points,
                                Real eps) {
  for (const std::vector<int>& polygon : p.polygons) {
    const Vec3& first = p.points[polygon[0]];
    Vec3 normal = Vec3::Zero();
    for (size_t i = 1; i + 1 < polygon.size(); ++i)
      normal += (p.points[polygon[i]] - first).cross(p.points[polygon[i + 1]] - first);
    const Real length = normal.norm();
    if (!(length > 0)) continue;
    normal /= length;
    const Real offset = normal.dot(first) - eps;
    bool all = true;
    for (const Vec3& q : points)
      if (normal.dot(q) < offset) {
        all = false;
        break;
      }
    if (all) return true;
  }
  return false;
}

}  // namespace

bool convex_insides_apart(const PolyhedronDef& a, const PolyhedronDef& b, Real eps) {
  return some_plane_has_all_outside(a, b.points, eps) ||
         some_plane_has_all_outside(b, a.points, eps);
}

}  // namespace tem
