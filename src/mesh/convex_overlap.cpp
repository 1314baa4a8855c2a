#include "mesh/convex_overlap.hpp"

#include <limits>

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

std::array<Vec3, 2> bounding_box(const std::vector<Vec3>& points) {
  std::array<Vec3, 2> box{Vec3::Constant(std::numeric_limits<Real>::infinity()),
                          Vec3::Constant(-std::numeric_limits<Real>::infinity())};
  for (const Vec3& p : points) {
    box[0] = box[0].cwiseMin(p);
    box[1] = box[1].cwiseMax(p);
  }
  return box;
}

bool boxes_meet(const std::array<Vec3, 2>& a, const std::array<Vec3, 2>& b, Real eps) {
  return (a[0].array() <= b[1].array() + eps).all() && (b[0].array() <= a[1].array() + eps).all();
}

}  // namespace tem
