#include "forces/contact_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tem {

Vec3 any_orthogonal(const Vec3& n) {
  // Cross with the axis least aligned with n: never degenerate.
  const Vec3 a = std::abs(n.x()) < 0.57735 ? Vec3::UnitX()
                 : std::abs(n.y()) < 0.57735 ? Vec3::UnitY()
                                              : Vec3::UnitZ();
  return n.cross(a).normalized();
}

void patch_points(const ContactPatch& patch, int index, bool one_per_patch,
                  std::vector<ContactPoint>& out) {
  ContactPoint base;
  base.patch = index;
  base.body_a = patch.body_a;
  base.body_b = patch.body_b;
  base.wall = patch.wall;
  base.normal = patch.normal;
  base.tangent1 = any_orthogonal(patch.normal);
  base.tangent2 = patch.normal.cross(base.tangent1);
  base.depth = patch.depth;
  base.point = patch.point;
  if (patch.manifold.count > 0) {
    // Contact before overlap: the patch's own points, each with its own gap.
    for (int k = 0; k < patch.manifold.count; ++k) {
      ContactPoint p = base;
      p.point = patch.manifold.point[k];
      p.depth = -patch.manifold.gap[k];
      out.push_back(p);
    }
    return;
  }
  if (one_per_patch || patch.vertices.size() < 2) {
    out.push_back(base);
    return;
  }
  // The corner reaching furthest along each of eight tangent directions, projected onto the
  // plane through the patch point; repeated corners are kept once.
  const Real diagonal = std::sqrt(0.5);
  const std::array<Vec3, 8> directions = {
      base.tangent1,  -base.tangent1, base.tangent2, -base.tangent2,
      diagonal * (base.tangent1 + base.tangent2),  diagonal * (base.tangent1 - base.tangent2),
      diagonal * (-base.tangent1 + base.tangent2), diagonal * (-base.tangent1 - base.tangent2)};
  const Real size = (patch.bounds_max - patch.bounds_min).norm();
  Real shallowest = patch.normal.dot(patch.vertices[0]);
  for (const Vec3& v : patch.vertices) shallowest = std::min(shallowest, patch.normal.dot(v));
  const size_t first = out.size();
  // A node inside and the crossing of its edge with the other surface lie one above the other:
  // equally far along a tangent direction. Of such a tie the deeper one is the corner (it bears
  // the load); taking the crossing would leave that corner without depth.
  const Real tie = 1e-9 * size;
  for (const Vec3& d : directions) {
    size_t best = 0;
    for (size_t k = 1; k < patch.vertices.size(); ++k) {
      const Real reach = d.dot(patch.vertices[k]), best_reach = d.dot(patch.vertices[best]);
      if (reach > best_reach + tie ||
          (reach > best_reach - tie &&
           patch.normal.dot(patch.vertices[k]) > patch.normal.dot(patch.vertices[best])))
        best = k;
    }
    const Vec3& v = patch.vertices[best];
    ContactPoint p = base;
    p.point = v - patch.normal.dot(v - patch.point) * patch.normal;
    p.depth = patch.normal.dot(v) - shallowest;
    bool repeated = false;
    for (size_t k = first; k < out.size() && !repeated; ++k)
      repeated = (out[k].point - p.point).norm() <= 1e-9 * size;
    if (!repeated) out.push_back(p);
  }
}

}  // namespace tem
