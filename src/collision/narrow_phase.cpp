#include "collision/narrow_phase.hpp"

#include <limits>

namespace tem {
namespace {

// Element of `b` holding point q (block frame): s, t, u >= 0 from E^-1 (eq. 19). For a convex
// block, q is known to be inside, so the element is the one whose cone from the centroid holds
// q; with `strict`, also s + t + u < 1 (the paper's full test, for non-convex blocks).
int element_holding(const Block& b, const Vec3& q, bool strict) {
  for (const Element& e : b.elements()) {
    const Vec3 stu = e.inverse * q;
    if (stu.minCoeff() < 0) continue;
    if (strict && !(stu.minCoeff() > 0 && stu.sum() < 1)) continue;
    return e.triangle;  // one element per triangle, same index
  }
  return -1;
}

// The same for a convex block, without scanning every element: the ray from the centroid through
// q leaves the block through the face whose plane it reaches first, the largest
// (n.q) / offset = 1 + distance / offset, so only that polygon's elements can hold q. The full
// scan remains for round-off on the rim between two polygons.
int element_holding_convex(const Block& b, const Vec3& q, const Real* distance) {
  const int n_polys = static_cast<int>(b.polygons().size());
  int first = 0;
  Real reach = -std::numeric_limits<Real>::infinity();
  for (int f = 0; f < n_polys; ++f) {
    const Real r = distance[f] / b.polygons()[f].offset;
    if (r > reach) {
      reach = r;
      first = f;
    }
  }
  for (int t : b.polygons()[first].triangles)
    if ((b.elements()[t].inverse * q).minCoeff() >= 0) return t;
  return element_holding(b, q, false);
}

// Triangle of polygon `f` of `b` containing the in-plane point x, by eq. 21's s, t >= 0,
// s + t <= 1; -1 when x lies outside the polygon.
int triangle_holding(const Block& b, int f, const Vec3& x) {
  for (int t : b.polygons()[f].triangles) {
    const auto& n = b.triangles()[t].nodes;
    const Vec3& v1 = b.nodes()[n[0]];
    const Vec3 e1 = b.nodes()[n[1]] - v1, e2 = b.nodes()[n[2]] - v1, r = x - v1;
    // Solve r = s e1 + t e2 in the plane (normal equations of the 3x2 system).
    const Real a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2);
    const Real b1 = r.dot(e1), b2 = r.dot(e2);
    const Real det = a11 * a22 - a12 * a12;
    const Real s = (b1 * a22 - b2 * a12) / det;
    const Real u = (a11 * b2 - a12 * b1) / det;
    if (s >= 0 && u >= 0 && s + u <= 1) return t;
  }
  return -1;
}

// One direction of §4.3: nodes of `a` inside `b` (step 2) and edges of `a` through `b`'s
// surface (step 4). Returns false when a face plane of convex `b` has every node of `a` strictly
// outside it (a separating plane).
bool one_side(const Block& a, const BlockPose& pose_a, const Block& b, const BlockPose& pose_b,
              NarrowPhaseScratch& scratch, SideFeatures& out) {
  const int n_nodes = static_cast<int>(a.nodes().size());
  const int n_polys = static_cast<int>(b.polygons().size());
  const Mat3 a_to_b = pose_b.inverse * pose_a.rotation;
  const Vec3 shift = pose_b.inverse * (pose_a.position - pose_b.position);
  scratch.nodes_in_other.resize(n_nodes);
  for (int i = 0; i < n_nodes; ++i) scratch.nodes_in_other[i] = a_to_b * a.nodes()[i] + shift;
  const std::vector<Vec3>& q = scratch.nodes_in_other;

  // Signed distances of every node of `a` to every face plane of `b` (> 0: outside).
  std::vector<Real>& d = scratch.distance;
  d.resize(static_cast<size_t>(n_nodes) * n_polys);
  for (int f = 0; f < n_polys; ++f) {
    const Polygon& poly = b.polygons()[f];
    bool all_outside = true;
    for (int i = 0; i < n_nodes; ++i) {
      const Real dist = poly.normal.dot(q[i]) - poly.offset;
      d[i * n_polys + f] = dist;
      all_outside = all_outside && dist > 0;
    }
    if (all_outside && b.convex()) return false;
  }

  // Step 2: nodes inside. Convex: inside every plane; the nearest plane is the face it entered.
  for (int i = 0; i < n_nodes; ++i) {
    int nearest = -1;
    Real largest = -std::numeric_limits<Real>::infinity();
    for (int f = 0; f < n_polys; ++f)
      if (d[i * n_polys + f] > largest) {
        largest = d[i * n_polys + f];
        nearest = f;
      }
    int element;
    if (b.convex()) {
      if (!(largest < 0)) continue;
      element = element_holding_convex(b, q[i], &d[i * n_polys]);
    } else {
      element = element_holding(b, q[i], true);
      if (element < 0) continue;
      nearest = b.triangles()[element].polygon;  // the face of the element that holds it
      largest = d[i * n_polys + nearest];
    }
    out.nodes.push_back({i, element, nearest, -largest, pose_a.to_world(a.nodes()[i]),
                         pose_b.rotation * b.polygons()[nearest].normal});
  }

  // Step 4: edges through faces: a sign change of the plane distance, then eq. 21. Distances
  // are affine along an edge, so those of the crossing point to every other face plane come
  // from the end nodes' for free: an edge lying wholly outside one face plane misses the block,
  // and a crossing point outside another face plane misses the polygon, before any triangle
  // test. The slack lets eq. 21 decide the points on a polygon's rim, as it would alone.
  const Real slack = 1e-9 * b.bounding_radius();
  for (int k = 0; k < static_cast<int>(a.edges().size()); ++k) {
    const Edge& e = a.edges()[k];
    const int i = e.nodes[0], j = e.nodes[1];
    const Real* di_all = &d[i * n_polys];
    const Real* dj_all = &d[j * n_polys];
    bool outside_one_plane = false;
    for (int g = 0; g < n_polys && !outside_one_plane; ++g)
      outside_one_plane = di_all[g] > 0 && dj_all[g] > 0;
    if (outside_one_plane && b.convex()) continue;
    for (int f = 0; f < n_polys; ++f) {
      const Real di = di_all[f], dj = dj_all[f];
      if ((di > 0 && dj > 0) || (di < 0 && dj < 0) || di == dj) continue;
      const Real t = di / (di - dj);
      if (b.convex()) {
        bool inside_others = true;
        for (int g = 0; g < n_polys && inside_others; ++g)
          inside_others = g == f || di_all[g] + t * (dj_all[g] - di_all[g]) <= slack;
        if (!inside_others) continue;
      }
      const Vec3 x = q[i] + t * (q[j] - q[i]);
      const int tri = triangle_holding(b, f, x);
      if (tri < 0) continue;
      out.edges.push_back(
          {k, tri, pose_b.to_world(x), pose_b.rotation * b.triangles()[tri].normal});
    }
  }
  return true;
}

}  // namespace

bool block_pair_features(const Block& a, const BlockPose& pose_a, const Block& b,
                         const BlockPose& pose_b, NarrowPhaseScratch& scratch,
                         PairFeatures& out) {
  out.a.clear();
  out.b.clear();
  if (!one_side(a, pose_a, b, pose_b, scratch, out.a) ||
      !one_side(b, pose_b, a, pose_a, scratch, out.b)) {
    out.a.clear();
    out.b.clear();
    return false;
  }
  return true;
}

void block_wall_features(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                         const Vec3& wall_normal, WallFeatures& out) {
  out.nodes.clear();
  out.edges.clear();
  const auto& nodes = block.nodes();
  auto distance = [&](int i) { return wall_normal.dot(pose.to_world(nodes[i]) - wall_point); };
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
    const Real d = distance(i);
    if (d < 0) out.nodes.push_back({i, -1, -1, -d, pose.to_world(nodes[i]), wall_normal});
  }
  if (out.nodes.empty()) return;
  for (int k = 0; k < static_cast<int>(block.edges().size()); ++k) {
    const Edge& e = block.edges()[k];
    const Real di = distance(e.nodes[0]), dj = distance(e.nodes[1]);
    if ((di < 0) == (dj < 0)) continue;
    const Vec3 pi = pose.to_world(nodes[e.nodes[0]]), pj = pose.to_world(nodes[e.nodes[1]]);
    out.edges.push_back({k, -1, pi + di / (di - dj) * (pj - pi), wall_normal});
  }
}

}  // namespace tem
