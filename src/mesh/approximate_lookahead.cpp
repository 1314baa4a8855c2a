// The approximate cutter's look ahead (approximate_lookahead.hpp).
#include "mesh/approximate_lookahead.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include <Eigen/Eigenvalues>

#include "mesh/hull_polyhedron.hpp"

namespace tem {
namespace {

// Grid cells along the part's longest extent for the thinned cloud: enough to see a ring's
// hole or an L's corner, few enough that a hull costs a fraction of a millisecond.
constexpr int kCloudCells = 12;

struct CellHash {
  size_t operator()(const std::array<long long, 3>& k) const {
    return static_cast<size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
  }
};

// Hull volume of the cloud's points below the plane (normal . x < offset), with those less
// than `cell` above it moved onto it.
Real hull_below(const std::vector<Vec3>& cloud, const Vec3& normal, Real offset, Real cell) {
  std::vector<Vec3> side;
  for (const Vec3& p : cloud) {
    const Real d = normal.dot(p) - offset;
    if (d <= 0) side.push_back(p);
    else if (d < cell) side.push_back(p - d * normal);
  }
  return hull_volume(side);
}

}  // namespace

std::vector<Vec3> thinned_cloud(const std::vector<Vec3>& points, int cells) {
  if (points.empty()) return {};
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Real cell = (hi - lo).maxCoeff() / cells;
  if (!(cell > 0)) return {points[0]};
  std::unordered_set<std::array<long long, 3>, CellHash> taken;
  std::vector<Vec3> cloud;
  for (const Vec3& p : points) {
    const Vec3 c = (p - lo) / cell;
    if (taken.insert({static_cast<long long>(c.x()), static_cast<long long>(c.y()),
                      static_cast<long long>(c.z())}).second)
      cloud.push_back(p);
  }
  return cloud;
}

Real lookahead_gain(const std::vector<Vec3>& corners) {
  if (corners.size() < 4) return 0;
  Vec3 lo = corners[0], hi = corners[0];
  for (const Vec3& p : corners) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Real cell = (hi - lo).maxCoeff() / kCloudCells;
  if (!(cell > 0)) return 0;
  const std::vector<Vec3> cloud = thinned_cloud(corners, kCloudCells);
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : cloud) mean += p;
  mean /= static_cast<Real>(cloud.size());
  Mat3 spread = Mat3::Zero();
  for (const Vec3& p : cloud) spread += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(spread);
  const Real whole = hull_volume(cloud);
  Real best = whole;
  for (int k = 0; k < 3; ++k) {
    const Vec3 n = eigen.eigenvectors().col(k).normalized();
    if (!n.allFinite()) continue;
    const Real offset = n.dot(mean);
    best = std::min(best, hull_below(cloud, n, offset, cell) + hull_below(cloud, -n, -offset, cell));
  }
  return whole - best;
}

}  // namespace tem
