#include "forces/contact_points.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "support/parallel.hpp"

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

void all_patch_points(const std::vector<ContactPatch>& patches, bool one_per_patch,
                      std::vector<std::vector<ContactPoint>>& runs,
                      std::vector<ContactPoint>& out) {
  const size_t n = patches.size();
  if (max_threads() == 1) {  // no copies where no thread shares the work
    for (size_t i = 0; i < n; ++i)
      patch_points(patches[i], static_cast<int>(i), one_per_patch, out);
    return;
  }
  constexpr size_t kRun = 256;  // patches per run: enough work to be worth sharing
  runs.resize((n + kRun - 1) / kRun);
  parallel_for(static_cast<long long>(runs.size()), 1, [&](long long r) {
    std::vector<ContactPoint>& run = runs[static_cast<size_t>(r)];
    run.clear();
    const size_t first = static_cast<size_t>(r) * kRun, last = std::min(n, first + kRun);
    for (size_t i = first; i < last; ++i)
      patch_points(patches[i], static_cast<int>(i), one_per_patch, run);
  });
  for (const std::vector<ContactPoint>& run : runs) out.insert(out.end(), run.begin(), run.end());
}

}  // namespace tem
