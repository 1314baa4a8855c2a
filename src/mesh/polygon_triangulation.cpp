// Triangulating one polygon: the fan where it is convex, ear clipping where not
// (polygon_triangulation.hpp).
#include "mesh/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tem {
namespace {

using Point = Eigen::Matrix<Real, 2, 1>;

// Twice the signed area of triangle a b c: > 0 when it turns counter-clockwise.
Real turn(const Point& a, const Point& b, const Point& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

std::vector<std::array<int, 3>> fan(int n, int from) {
  std::vector<std::array<int, 3>> triangles;
  for (int k = 1; k + 1 < n; ++k) triangles.push_back({from, (from + k) % n, (from + k + 1) % n});
  return triangles;
}

// The corners in the polygon's own plane, seen from the side its Newell normal points to: the
// polygon then turns counter-clockwise. False if it has no area to define a plane.
bool project(const std::vector<Vec3>& corners, std::vector<Point>& points) {
  const int n = static_cast<int>(corners.size());
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : corners) centre += p;
  centre /= n;
  Vec3 normal = Vec3::Zero();
  for (int i = 0; i < n; ++i) normal += (corners[i] - centre).cross(corners[(i + 1) % n] - centre);
  const Real length = normal.norm();
  if (!(length > 0) || !std::isfinite(length)) return false;
  normal /= length;
  // u: perpendicular to the normal, away from its largest component; v = normal x u.
  int largest = 0;
  normal.cwiseAbs().maxCoeff(&largest);
  Vec3 axis = Vec3::Zero();
  axis[(largest + 1) % 3] = 1;
  const Vec3 u = normal.cross(axis).normalized();
  const Vec3 v = normal.cross(u);
  points.clear();
  for (const Vec3& p : corners) points.emplace_back((p - centre).dot(u), (p - centre).dot(v));
  return true;
}

// A quad has at most one reflex corner, and the diagonal from it is the one inside. Corner i is
// reflex when its angles to the opposite corner, from its two edges, add up to more than pi (on
// a planar quad: its interior angle). This is assimp's test, in double precision, so that
// non-planar quads are split as before. 0 when there is none.
int reflex_quad_corner(const std::vector<Vec3>& c) {
  auto angle = [](const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(a.normalized().dot(b.normalized()), Real(-1), Real(1)));
  };
  for (int i = 0; i < 4; ++i) {
    const Vec3 diagonal = c[(i + 2) % 4] - c[i];
    if (angle(c[(i + 3) % 4] - c[i], diagonal) + angle(c[(i + 1) % 4] - c[i], diagonal) >
        std::numbers::pi)
      return i;
  }
  return 0;
}

std::vector<std::array<int, 3>> clip_ears(const std::vector<Point>& q) {
  const int n = static_cast<int>(q.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
  auto corner_turn = [&](int i) { return turn(q[prev[i]], q[i], q[next[i]]); };
  // Only a corner that does not turn the polygon's way can lie in an ear's triangle.
  std::vector<char> reflex(n);
  for (int i = 0; i < n; ++i) reflex[i] = corner_turn(i) <= 0;
  long long budget = 50'000'000;  // point tests; a fan for the rest once spent
  auto is_ear = [&](int i) {
    const int a = prev[i], c = next[i];
    if (!(turn(q[a], q[i], q[c]) > 0)) return false;
    for (int j = next[c]; j != a; j = next[j]) {
      --budget;
      if (!reflex[j] || q[j] == q[a] || q[j] == q[i] || q[j] == q[c]) continue;
      if (turn(q[a], q[i], q[j]) >= 0 && turn(q[i], q[c], q[j]) >= 0 && turn(q[c], q[a], q[j]) >= 0)
        return false;
    }
    return true;
  };
  std::vector<std::array<int, 3>> triangles;
  int remaining = n, i = 0, misses = 0;
  while (remaining > 3 && budget > 0) {
    if (!is_ear(i)) {
      i = next[i];
      if (++misses <= remaining) continue;
      // No ear all round: the polygon crosses itself. Cut the corner that turns most.
      int best = i;
      for (int j = next[i]; j != i; j = next[j])
        if (corner_turn(j) > corner_turn(best)) best = j;
      i = best;
    }
    triangles.push_back({prev[i], i, next[i]});
    const int a = prev[i], c = next[i];
    next[a] = c;
    prev[c] = a;
    reflex[a] = corner_turn(a) <= 0;
    reflex[c] = corner_turn(c) <= 0;
    --remaining;
    i = c;
    misses = 0;
  }
  // The rest: the last triangle, or a fan once the budget is spent.
  for (int j = next[i]; next[j] != i; j = next[j]) triangles.push_back({i, j, next[j]});
  return triangles;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Vec3>& corners) {
  const int n = static_cast<int>(corners.size());
  if (n < 3) return {};
  if (n == 3) return {{0, 1, 2}};
  if (n == 4) return fan(n, reflex_quad_corner(corners));
  std::vector<Point> q;
  if (!project(corners, q)) return fan(n, 0);
  for (int i = 0; i < n; ++i)
    if (!(turn(q[(i + n - 1) % n], q[i], q[(i + 1) % n]) > 0)) return clip_ears(q);
  return fan(n, 0);
}

}  // namespace tem
