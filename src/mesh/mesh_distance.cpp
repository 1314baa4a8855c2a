// Nearest points on a triangle mesh through a tree of bounding boxes (median splits), and the
// side of the surface from the pseudo-normal of the nearest feature: the angle-weighted vertex
// normal at a vertex, the sum of the two face normals on an edge, the face normal inside. These
// give the right side for every point, even near sharp edges and concave corners.
#include "mesh/mesh_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "support/parallel.hpp"

namespace tem {
namespace {

constexpr int kLeafSize = 4;

// The nearest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5) and
// the feature it lies on: 0-2 the corners, 3-5 the edges a-b, b-c, c-a, 6 the inside.
std::pair<Vec3, int> nearest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                         const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Real d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, 0};
  const Vec3 bp = p - b;
  const Real d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, 1};
  const Real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + d1 / (d1 - d3) * ab, 3};
  const Vec3 cp = p - c;
  const Real d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, 2};
  const Real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + d2 / (d2 - d6) * ac, 5};
  const Real va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return {b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b), 4};
  const Real denom = 1 / (va + vb + vc);
  return {a + ab * (vb * denom) + ac * (vc * denom), 6};
}

// The largest signed distance found on triangle abc (corner values sa, sb, sc, and 0). No
// point of it is farther than longest / sqrt(3) from the nearest corner, and the distance
// changes no faster than the point moves: the triangle is halved only while that bound could
// beat `bar` and is coarser than `precision`.
Real refined_largest(const MeshDistance& distance, const Vec3& a, const Vec3& b, const Vec3& c,
                     Real sa, Real sb, Real sc, Real bar, Real precision) {
  const Real corners = std::max({sa, sb, sc});
  const Real reach = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()}) / std::sqrt(Real(3));
  if (corners + reach <= bar || reach <= precision) return std::max(corners, Real(0));
  const Vec3 ab = (a + b) / 2, bc = (b + c) / 2, ca = (c + a) / 2;
  const Real sab = distance.signed_distance(ab), sbc = distance.signed_distance(bc),
             sca = distance.signed_distance(ca);
  return std::max({refined_largest(distance, a, ab, ca, sa, sab, sca, bar, precision),
                   refined_largest(distance, ab, b, bc, sab, sb, sbc, bar, precision),
                   refined_largest(distance, ca, bc, c, sca, sbc, sc, bar, precision),
                   refined_largest(distance, ab, bc, ca, sab, sbc, sca, bar, precision)});
}

Real box_distance2(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0).squaredNorm();
}

}  // namespace

MeshDistance::MeshDistance(const TriangleMesh& mesh) {
  const size_t faces = mesh.faces.size();
  corners_.resize(faces);
  face_normal_.resize(faces);
  std::vector<Vec3> vertex_sum(mesh.vertices.size(), Vec3::Zero());
  std::map<std::pair<int, int>, Vec3> edge_sum;
  for (size_t f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) corners_[f][k] = mesh.vertices[mesh.faces[f][k]];
    const auto& c = corners_[f];
    face_normal_[f] = (c[1] - c[0]).cross(c[2] - c[0]).normalized();
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = (c[(k + 1) % 3] - c[k]).normalized(), w = (c[(k + 2) % 3] - c[k]).normalized();
      vertex_sum[mesh.faces[f][k]] += std::acos(std::clamp(u.dot(w), Real(-1), Real(1))) * face_normal_[f];
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      auto [it, added] = edge_sum.try_emplace({std::min(a, b), std::max(a, b)}, Vec3::Zero());
      it->second += face_normal_[f];
    }
  }
  vertex_normal_.resize(faces);
  edge_normal_.resize(faces);
  for (size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      vertex_normal_[f][k] = vertex_sum[a];
      edge_normal_[f][k] = edge_sum.at({std::min(a, b), std::max(a, b)});
    }
  order_.resize(faces);
  for (size_t f = 0; f < faces; ++f) order_[f] = static_cast<int>(f);
  nodes_.reserve(2 * faces / kLeafSize + 1);
  if (faces > 0) build(0, static_cast<int>(faces));
}

int MeshDistance::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({Vec3::Zero(), Vec3::Zero(), first, count, -1});
  Vec3 lo = Vec3::Constant(std::numeric_limits<Real>::infinity()), hi = -lo;
  Vec3 centre_lo = lo, centre_hi = hi;
  for (int i = first; i < first + count; ++i) {
    Vec3 centre = Vec3::Zero();
    for (const Vec3& c : corners_[order_[i]]) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
      centre += c / 3;
    }
    centre_lo = centre_lo.cwiseMin(centre);
    centre_hi = centre_hi.cwiseMax(centre);
  }
  nodes_[index] = {lo, hi, first, count, -1};
  if (count <= kLeafSize) return index;
  int axis = 0;
  (centre_hi - centre_lo).maxCoeff(&axis);
  const int half = count / 2;
  auto key = [&](int f) {
    const auto& c = corners_[f];
    return std::make_pair(c[0][axis] + c[1][axis] + c[2][axis], f);
  };
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int a, int b) { return key(a) < key(b); });
  nodes_[index].count = 0;
  build(first, half);
  const int right = build(first + half, count - half);
  nodes_[index].right = right;
  return index;
}

bool MeshDistance::nearest(const Vec3& p, Real stop2, Real& best2, Vec3& best_point,
                           int& best_face, int& best_feature) const {
  best2 = std::numeric_limits<Real>::infinity();
  best_point = p;
  best_face = -1;
  best_feature = 6;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(p, node.lo, node.hi) >= best2) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int f = order_[i];
        const auto& c = corners_[f];
        const auto [q, feature] = nearest_on_triangle(p, c[0], c[1], c[2]);
        const Real d2 = (p - q).squaredNorm();
        if (d2 < best2) {
          best2 = d2;
          best_point = q;
          best_face = f;
          best_feature = feature;
          if (best2 <= stop2) return false;
        }
      }
      continue;
    }
    const int left = static_cast<int>(&node - nodes_.data()) + 1;
    const Real dl = box_distance2(p, nodes_[left].lo, nodes_[left].hi);
    const Real dr = box_distance2(p, nodes_[node.right].lo, nodes_[node.right].hi);
    // Nearer child on top of the stack: it tightens best2 before the other is looked at.
    if (dl < dr) {
      stack[top++] = node.right;
      stack[top++] = left;
    } else {
      stack[top++] = left;
      stack[top++] = node.right;
    }
  }
  return true;
}

Real MeshDistance::signed_from(const Vec3& p, Real best2, const Vec3& best_point, int best_face,
                               int best_feature) const {
  const Vec3& normal = best_feature < 3   ? vertex_normal_[best_face][best_feature]
                       : best_feature < 6 ? edge_normal_[best_face][best_feature - 3]
                                          : face_normal_[best_face];
  return (p - best_point).dot(normal) > 0 ? std::sqrt(best2) : -std::sqrt(best2);
}

Real MeshDistance::signed_distance(const Vec3& p) const {
  if (nodes_.empty()) return std::numeric_limits<Real>::infinity();
  Real best2;
  Vec3 best_point;
  int best_face, best_feature;
  nearest(p, -1, best2, best_point, best_face, best_feature);
  return signed_from(p, best2, best_point, best_face, best_feature);
}

Real MeshDistance::signed_distance_above(const Vec3& p, Real bar) const {
  if (nodes_.empty()) return std::numeric_limits<Real>::infinity();
  Real best2;
  Vec3 best_point;
  int best_face, best_feature;
  if (!nearest(p, bar * bar, best2, best_point, best_face, best_feature)) return bar;
  return signed_from(p, best2, best_point, best_face, best_feature);
}

Real largest_outside_distance(const MeshDistance& distance, const std::vector<PolyhedronDef>& blocks,
                              Real precision) {
  std::vector<std::array<Vec3, 3>> triangles;
  for (const PolyhedronDef& block : blocks)
    for (const auto& loop : block.polygons)
      for (size_t k = 1; k + 1 < loop.size(); ++k)
        triangles.push_back({block.points[loop[0]], block.points[loop[k]], block.points[loop[k + 1]]});
  // The bar to beat, from the faces' corners, centres and edge midpoints, is fixed before
  // the faces are refined in parallel, so which triangles are refined (and the result) does
  // not depend on the threads.
  std::vector<Real> coarse(triangles.size(), 0);
  parallel_for(
      static_cast<long long>(triangles.size()), 8,
      [&](long long t) {
        const auto& [a, b, c] = triangles[t];
        for (const Vec3& p : {a, b, c, Vec3((a + b + c) / 3), Vec3((a + b) / 2), Vec3((b + c) / 2),
                              Vec3((c + a) / 2)})
          coarse[t] = std::max(coarse[t], distance.signed_distance_above(p, coarse[t]));
      },
      true);
  Real result = 0;
  for (Real value : coarse) result = std::max(result, value);
  const Real bar = result + precision;
  std::vector<Real> largest(triangles.size(), 0);
  parallel_for(
      static_cast<long long>(triangles.size()), 8,
      [&](long long t) {
        const auto& [a, b, c] = triangles[t];
        largest[t] = refined_largest(distance, a, b, c, distance.signed_distance(a),
                                     distance.signed_distance(b), distance.signed_distance(c), bar,
                                     precision);
      },
      true);
  for (Real value : largest) result = std::max(result, value);
  return result;
}

Real sampled_outside_distance(const MeshDistance& distance, const PolyhedronDef& block) {
  // The faces' centres and edge midpoints first: where a hull spans a hollow they stand
  // farthest out, and a large distance found early lets the other points stop their search
  // sooner (signed_distance_above). The result does not depend on the order.
  Real result = 0;
  for (const auto& loop : block.polygons)
    for (size_t k = 1; k + 1 < loop.size(); ++k) {
      const Vec3 &a = block.points[loop[0]], &b = block.points[loop[k]],
                 &c = block.points[loop[k + 1]];
      for (const Vec3& p :
           {Vec3((a + b + c) / 3), Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2)})
        result = std::max(result, distance.signed_distance_above(p, result));
    }
  for (const Vec3& p : block.points)
    result = std::max(result, distance.signed_distance_above(p, result));
  return result;
}

}  // namespace tem
