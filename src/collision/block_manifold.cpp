#include "collision/block_manifold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tem {
namespace {

constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

struct FaceAxis {
  Real separation = -kInfinity;
  int face = -1;
};

// How far the nodes lie outside the plane normal . x = offset: the nearest one's distance.
// Every face test (best_face, still_separated, rebuild_manifold's check) computes it so, in the
// same arithmetic: a cached face and the search agree to the bit.
Real face_separation(const Vec3& normal, Real offset, const std::vector<Vec3>& nodes) {
  Real lowest = kInfinity;
  for (const Vec3& p : nodes) lowest = std::min(lowest, normal.dot(p));
  return lowest - offset;
}

// The face of `self` whose plane the other block's nodes are farthest outside of.
FaceAxis best_face(const std::vector<Vec3>& normals, const std::vector<Real>& offsets,
                   const std::vector<Vec3>& other_nodes, Real margin) {
  FaceAxis best;
  for (size_t f = 0; f < normals.size(); ++f) {
    const Real s = face_separation(normals[f], offsets[f], other_nodes);
    if (s > best.separation) {
      best = {s, static_cast<int>(f)};
      if (s > margin) return best;  // separated beyond the margin: nothing more to learn
    }
  }
  return best;
}

struct EdgeAxis {
  Real separation = -kInfinity;
  Vec3 axis = Vec3::Zero();
  int edge_a = -1, edge_b = -1;
};

// The edge pairs whose cross product is a candidate axis: those whose arcs cross on the Gauss
// map, A's arc against B's negated (Gregorius's Minkowski-face test with c, d = -n1, -n2 of B,
// d x c = B's arc). Only an edge axis L that separates the blocks by more than the best face
// axis, `floor`, matters, and then L.(centre B - centre A) > floor, the centroids being points
// of the blocks. L lies in the arc of its edge of A, a positive combination of the edge's two
// face normals n1, n2 normalised, so L.d <= max(n1.d, n2.d) where that is <= 0: an edge of A
// whose faces give max(n1.d, n2.d) <= min(0, floor) cannot give it, and is skipped (and the
// same for B's edges with d reversed).
EdgeAxis best_edges(const WorldBlock& a, const WorldBlock& b, Real margin, Real floor,
                    std::vector<int>& b_edges) {
  EdgeAxis best;
  const Vec3 towards_b = b.centre - a.centre;
  const size_t na = a.edge_node.size(), nb = b.edge_node.size();
  b_edges.clear();
  const Real skip = std::min<Real>(0, floor);
  for (size_t j = 0; j < nb; ++j)
    if (std::max(-b.edge_n1[j].dot(towards_b), -b.edge_n2[j].dot(towards_b)) > skip)
      b_edges.push_back(static_cast<int>(j));
  for (size_t i = 0; i < na; ++i) {
    const Vec3 &a1 = a.edge_n1[i], &a2 = a.edge_n2[i], &arc_a = a.edge_arc[i];
    if (std::max(a1.dot(towards_b), a2.dot(towards_b)) <= skip) continue;
    const Vec3& pa = a.nodes[a.edge_node[i]];
    const Vec3& da = a.edge_direction[i];
    for (const int j : b_edges) {
      const Real cba = -b.edge_n1[j].dot(arc_a), dba = -b.edge_n2[j].dot(arc_a);
      if (!(cba * dba < 0)) continue;
      const Real adc = a1.dot(b.edge_arc[j]), bdc = a2.dot(b.edge_arc[j]);
      if (!(adc * bdc < 0 && cba * bdc > 0)) continue;
      const Vec3& db = b.edge_direction[j];
      Vec3 axis = da.cross(db);
      const Real length = axis.norm();
      // Parallel edges: their cross product is no axis (a face axis covers that case).
      if (length <= 1e-6 * da.norm() * db.norm()) continue;
      axis /= length;
      if (axis.dot(pa - a.centre) < 0) axis = -axis;  // out of A
      const Real sep = axis.dot(b.nodes[b.edge_node[j]] - pa);
      if (sep > best.separation) {
        best = {sep, axis, static_cast<int>(i), j};
        if (sep > margin) return best;
      }
    }
  }
  return best;
}

// Closest points of the segments p1 + s d1 and p2 + t d2, s and t in [0, 1].
std::pair<Vec3, Vec3> closest_points(const Vec3& p1, const Vec3& d1, const Vec3& p2,
                                     const Vec3& d2) {
  const Vec3 r = p1 - p2;
  const Real a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r), c = d1.dot(r), b = d1.dot(d2);
  const Real denominator = a * e - b * b;
  Real s = denominator > 0 ? std::clamp((b * f - c * e) / denominator, Real(0), Real(1)) : 0;
  Real t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, Real(0), Real(1));
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, Real(0), Real(1));
  }
  return {p1 + s * d1, p2 + t * d2};
}

// Points whose gaps differ by less than this fraction of the smaller block's bounding radius
// count as equally deep (reduce_points).
constexpr Real kEqualDepth = 1e-4;

// The first edge of a placed block's polygon, in the world: a direction that turns with it.
Vec3 face_edge(const Block& block, const WorldBlock& world, int face) {
  const std::vector<int>& nodes = block.polygons()[face].nodes;
  return world.nodes[nodes[1]] - world.nodes[nodes[0]];
}

// Copies the kept candidates into the manifold: `along`, an edge of the face that made them,
// orders points of one depth (reduce_points), `size` the smaller block's bounding radius.
void keep(const std::vector<Vec3>& points, const std::vector<Real>& gaps, const Vec3& along,
          Real size, Manifold& out) {
  std::array<int, kManifoldPoints> kept{};
  out.count = reduce_points(out.normal, along, kEqualDepth * size, points.data(), gaps.data(),
                            static_cast<int>(points.size()), kept);
  for (int k = 0; k < out.count; ++k) {
    out.point[k] = points[kept[k]];
    out.gap[k] = gaps[kept[k]];
  }
}

// Clips the incident polygon by the side planes of the reference polygon and keeps the corners
// within the margin of the reference plane. `ref_nodes`/`inc_nodes` are world nodes.
void clip_faces(const Block& ref, const std::vector<Vec3>& ref_nodes, const Vec3& ref_normal,
                Real ref_offset, int ref_face, const Block& inc, const std::vector<Vec3>& inc_nodes,
                const std::vector<Vec3>& inc_normals, Real margin, ManifoldScratch& s,
                std::vector<Vec3>& points, std::vector<Real>& gaps) {
  int incident = 0;
  Real most_opposed = kInfinity;
  for (size_t f = 0; f < inc_normals.size(); ++f) {
    const Real d = inc_normals[f].dot(ref_normal);
    if (d < most_opposed) {
      most_opposed = d;
      incident = static_cast<int>(f);
    }
  }
  s.clip_in.clear();
  for (int n : inc.polygons()[incident].nodes) s.clip_in.push_back(inc_nodes[n]);
  const std::vector<int>& loop = ref.polygons()[ref_face].nodes;
  for (size_t k = 0; k < loop.size() && !s.clip_in.empty(); ++k) {
    const Vec3& v0 = ref_nodes[loop[k]];
    const Vec3& v1 = ref_nodes[loop[k + 1 < loop.size() ? k + 1 : 0]];
    // The loop runs counter-clockwise seen from outside: (v1 - v0) x n points out of the face.
    const Vec3 side = (v1 - v0).cross(ref_normal);
    const Real side_offset = side.dot(v0);
    // Each point's distance out of the side once (each is the start of one edge and the end
    // of another).
    const size_t count = s.clip_in.size();
    s.clip_distance.resize(count);
    for (size_t i = 0; i < count; ++i) s.clip_distance[i] = side.dot(s.clip_in[i]) - side_offset;
    s.clip_out.clear();
    for (size_t i = 0; i < count; ++i) {
      const size_t j = i + 1 < count ? i + 1 : 0;
      const Vec3& p = s.clip_in[i];
      const Vec3& q = s.clip_in[j];
      const Real dp = s.clip_distance[i], dq = s.clip_distance[j];
      if (dp <= 0) s.clip_out.push_back(p);
      if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) s.clip_out.push_back(p + dp / (dp - dq) * (q - p));
    }
    std::swap(s.clip_in, s.clip_out);
  }
  points.clear();
  gaps.clear();
  for (const Vec3& p : s.clip_in) {
    const Real gap = ref_normal.dot(p) - ref_offset;
    if (gap > margin) continue;
    points.push_back(p - 0.5 * gap * ref_normal);
    gaps.push_back(gap);
  }
}

// The least gap of the manifold's kept points (its deepest), infinite where it keeps none.
Real deepest_kept(const Manifold& m) {
  Real deepest = kInfinity;
  for (int k = 0; k < m.count; ++k) deepest = std::min(deepest, m.gap[k]);
  return deepest;
}

// How much deeper `lowest` (a face's separation: the other block's deepest node) lies than the
// deepest of the manifold's kept corners.
Real node_beyond_rim(const Manifold& m, Real lowest) {
  return std::max(Real(0), deepest_kept(m) - lowest);
}

// The one point of an edge-pair manifold: midway between the closest points of A's edge i (from
// pa along da) and B's edge j, with the gap `separation` along `axis` (out of A).
void edge_manifold(const Vec3& pa, const Vec3& da, const Vec3& pb, const Vec3& db, int i, int j,
                   const Vec3& axis, Real separation, Manifold& out) {
  const auto [ca, cb] = closest_points(pa, da, pb, db);
  out.normal = axis;
  out.count = 1;
  out.point[0] = 0.5 * (ca + cb);
  out.gap[0] = separation;
  out.feature = ManifoldFeature::edges;
  out.feature_a = i;
  out.feature_b = j;
}

// The same for the placed blocks' edges i and j.
void edge_manifold(const WorldBlock& wa, const WorldBlock& wb, int i, int j, const Vec3& axis,
                   Real separation, Manifold& out) {
  edge_manifold(wa.nodes[wa.edge_node[i]], wa.edge_direction[i], wb.nodes[wb.edge_node[j]],
                wb.edge_direction[j], i, j, axis, separation, out);
}

// The face manifold of out.feature (face_of_a or face_of_b, out.feature_a/_b its face): the
// other block's incident face clipped against it, its corners within the margin kept.
bool clip_reference_face(const Block& a, const WorldBlock& wa, const Block& b,
                         const WorldBlock& wb, Real margin, ManifoldScratch& s, Manifold& out) {
  std::vector<Vec3>& candidates = s.candidates;
  std::vector<Real>& gaps = s.candidate_gaps;
  Vec3 along;
  if (out.feature == ManifoldFeature::face_of_b) {
    const int face = out.feature_b;
    clip_faces(b, wb.nodes, wb.normals[face], wb.offsets[face], face, a, wa.nodes, wa.normals,
               margin, s, candidates, gaps);
    out.normal = -wb.normals[face];
    along = face_edge(b, wb, face);
  } else {
    const int face = out.feature_a;
    clip_faces(a, wa.nodes, wa.normals[face], wa.offsets[face], face, b, wb.nodes, wb.normals,
               margin, s, candidates, gaps);
    out.normal = wa.normals[face];
    along = face_edge(a, wa, face);
  }
  if (candidates.empty()) return false;
  keep(candidates, gaps, along, std::min(a.bounding_radius(), b.bounding_radius()), out);
  return true;
}

}  // namespace

void place_faces(const Block& block, const BlockPose& pose, WorldBlock& out) {
  out.centre = pose.position;
  out.nodes.resize(block.nodes().size());
  for (size_t i = 0; i < out.nodes.size(); ++i) out.nodes[i] = pose.to_world(block.nodes()[i]);
  const std::vector<Polygon>& polygons = block.polygons();
  out.normals.resize(polygons.size());
  out.offsets.resize(polygons.size());
  for (size_t f = 0; f < polygons.size(); ++f) {
    out.normals[f] = pose.rotation * polygons[f].normal;
    out.offsets[f] = out.normals[f].dot(out.nodes[polygons[f].nodes[0]]);
  }
  out.edge_node.clear();
}

void place_edges(const Block& block, WorldBlock& out) {
  const std::vector<PolygonEdge>& edges = block.polygon_edges();
  const size_t count = edges.size();
  out.edge_node.resize(count);
  out.edge_direction.resize(count);
  out.edge_n1.resize(count);
  out.edge_n2.resize(count);
  out.edge_arc.resize(count);
  for (size_t k = 0; k < count; ++k) {
    const PolygonEdge& e = edges[k];
    const Vec3& n1 = out.normals[e.polygons[0]];
    const Vec3& n2 = out.normals[e.polygons[1]];
    out.edge_node[k] = e.nodes[0];
    out.edge_direction[k] = out.nodes[e.nodes[1]] - out.nodes[e.nodes[0]];
    out.edge_n1[k] = n1;
    out.edge_n2[k] = n2;
    out.edge_arc[k] = n2.cross(n1);
  }
}

void place_block(const Block& block, const BlockPose& pose, WorldBlock& out) {
  place_faces(block, pose, out);
  place_edges(block, out);
}

int reduce_points(const Vec3& normal, const Vec3& along, Real equal_depth, const Vec3* points,
                  const Real* gaps, int count, std::array<int, kManifoldPoints>& kept) {
  if (count <= kManifoldPoints) {
    for (int i = 0; i < count; ++i) kept[i] = i;
    return count;
  }
  // Why each choice is made so that it stays the same from step to step while the bodies
  // barely move: the warm start carries a point's impulse to the next step only where a point
  // is found again at the same place (warm_start.hpp). A face resting flat on a face has all
  // its corners at one depth to round-off; "the deepest" of them then changes with every
  // tremor, the four kept points jump around the polygon, the warm start is lost, and 20
  // sweeps leave a column of coins rocking and creeping at 0.1-1 cm/s forever (docs/
  // benchmarks.md). So the first point is the deepest only where it is deeper than the others
  // by `equal_depth`; among points of one depth, the farthest along a direction turned with the
  // face (`along`, turned by 0.3 rad about the normal so that it is parallel to no edge of a
  // regular polygon). The other choices take a later point only where it is better by more
  // than round-off, so that exact ties keep the earlier one.
  const Vec3 in_plane = along - normal.dot(along) * normal;
  const Vec3 direction = std::cos(0.3) * in_plane + std::sin(0.3) * normal.cross(in_plane);
  Real least_gap = gaps[0];
  for (int i = 1; i < count; ++i) least_gap = std::min(least_gap, gaps[i]);
  int deepest = -1;
  for (int i = 0; i < count; ++i) {
    if (gaps[i] > least_gap + equal_depth) continue;
    if (deepest < 0 || direction.dot(points[i]) > direction.dot(points[deepest])) deepest = i;
  }
  constexpr Real kBetter = 1 + 1e-9;
  int farthest = deepest == 0 ? 1 : 0;
  Real farthest_distance = (points[farthest] - points[deepest]).squaredNorm();
  for (int i = 0; i < count; ++i) {
    const Real d = (points[i] - points[deepest]).squaredNorm();
    if (d > kBetter * farthest_distance) {
      farthest_distance = d;
      farthest = i;
    }
  }
  const Vec3 chord = points[farthest] - points[deepest];
  auto side = [&](int i) { return normal.dot(chord.cross(points[i] - points[deepest])); };
  int left = -1, right = -1;
  Real most_left = 0, most_right = 0;
  for (int i = 0; i < count; ++i) {
    const Real a = side(i);
    if (a > kBetter * most_left) {
      most_left = a;
      left = i;
    } else if (a < kBetter * most_right) {
      most_right = a;
      right = i;
    }
  }
  int n = 0;
  kept[n++] = deepest;
  kept[n++] = farthest;
  if (left >= 0) kept[n++] = left;
  if (right >= 0) kept[n++] = right;
  return n;
}

bool still_separated(const WorldBlock& wa, const WorldBlock& wb, const SeparatingFace& face,
                     Real margin) {
  const bool of_a = face.side == ManifoldFeature::face_of_a;
  if (!of_a && face.side != ManifoldFeature::face_of_b) return false;
  const WorldBlock& self = of_a ? wa : wb;
  const WorldBlock& other = of_a ? wb : wa;
  if (face.face < 0 || static_cast<size_t>(face.face) >= self.normals.size()) return false;
  return face_separation(self.normals[face.face], self.offsets[face.face], other.nodes) > margin;
}

bool block_manifold(const Block& a, const WorldBlock& wa, const Block& b, const WorldBlock& wb,
                    Real margin, ManifoldScratch& s, Manifold& out, SeparatingFace* separated) {
  out.count = 0;
  out.beyond_rim = 0;
  // Bounding spheres first: the broad phase's boxes of turned blocks pass many pairs whose
  // spheres are apart, and the axes cost a hundred times more.
  const Real reach = a.bounding_radius() + b.bounding_radius() + margin;
  if ((wa.centre - wb.centre).squaredNorm() > reach * reach) return false;
  const FaceAxis face_a = best_face(wa.normals, wa.offsets, wb.nodes, margin);
  if (face_a.separation > margin) {
    if (separated) *separated = {ManifoldFeature::face_of_a, face_a.face};
    return false;
  }
  const FaceAxis face_b = best_face(wb.normals, wb.offsets, wa.nodes, margin);
  if (face_b.separation > margin) {
    if (separated) *separated = {ManifoldFeature::face_of_b, face_b.face};
    return false;
  }
  const EdgeAxis edges =
      best_edges(wa, wb, margin, std::max(face_a.separation, face_b.separation), s.edge_list);
  if (edges.separation > margin) return false;

  // Faces are preferred within a tolerance: they give whole patches, and a choice that flips
  // between nearly equal axes from step to step would shake a resting body.
  const Real tolerance = 0.005 * std::min(a.bounding_radius(), b.bounding_radius());
  const Real face_best = std::max(face_a.separation, face_b.separation);
  if (edges.edge_a >= 0 && edges.separation > face_best + tolerance) {
    edge_manifold(wa, wb, edges.edge_a, edges.edge_b, edges.axis, edges.separation, out);
    return true;
  }
  if (face_b.separation > face_a.separation + tolerance) {
    out.feature = ManifoldFeature::face_of_b;
    out.feature_a = -1;
    out.feature_b = face_b.face;
  } else {
    out.feature = ManifoldFeature::face_of_a;
    out.feature_a = face_a.face;
    out.feature_b = -1;
  }
  if (clip_reference_face(a, wa, b, wb, margin, s, out)) {
    out.beyond_rim = node_beyond_rim(
        out, out.feature == ManifoldFeature::face_of_b ? face_b.separation : face_a.separation);
    return true;
  }
  // The preferred face's clip can be empty: no part of the other block's most opposed face lies
  // over the reference face. Where the blocks meet edge across edge, the best edge pair's point
  // is the contact, with the better of the two lower bounds of the gap (the face's separation
  // where the edge axis separates less: a pair the face keeps apart is never pushed as if it
  // overlapped along the edge axis). Dropped as apart, such pairs within their margin or already
  // overlapping let coins crossing so in a pour sink up to 19 % of their thickness into each
  // other in one step. Without an edge pair the blocks lie beside
  // each other past the face's rim (a box sliding by the end of another, edges parallel): no
  // contact, as a point held to the face's plane there would brake a body that passes by.
  if (edges.edge_a >= 0) {
    edge_manifold(wa, wb, edges.edge_a, edges.edge_b, edges.axis,
                  std::max(edges.separation, face_best), out);
    out.feature = ManifoldFeature::edges_past_rim;
    return true;
  }
  out.count = 0;
  return false;
}

Rebuild rebuild_from_features(const Block& a, const WorldBlock& wa, const Block& b,
                              const WorldBlock& wb, Real margin, const Manifold& detected,
                              ManifoldScratch& s, Manifold& out) {
  out.count = 0;
  out.beyond_rim = 0;
  out.feature = detected.feature;
  out.feature_a = detected.feature_a;
  out.feature_b = detected.feature_b;
  // The cached features hold while they are still the blocks' supports along their axis: the
  // edges the extreme points of both blocks along the edge axis, the incident face's corners
  // the deepest of its block below the reference plane. Once the blocks have turned so that
  // another node lies beyond them (a rim that was edge on edge now lying face on face), the
  // cached gap would be too large, so the pair is searched again in full.
  const Real tolerance = 1e-6 * std::min(a.bounding_radius(), b.bounding_radius());
  if (detected.feature == ManifoldFeature::edges) {
    const int i = detected.feature_a, j = detected.feature_b;
    // The edges from the placed nodes, as place_edges computes them (the same bits).
    const std::array<int, 2>& ends_a = a.polygon_edges()[static_cast<size_t>(i)].nodes;
    const std::array<int, 2>& ends_b = b.polygon_edges()[static_cast<size_t>(j)].nodes;
    const Vec3& pa = wa.nodes[ends_a[0]];
    const Vec3& pb = wb.nodes[ends_b[0]];
    const Vec3 da = wa.nodes[ends_a[1]] - pa, db = wb.nodes[ends_b[1]] - pb;
    Vec3 axis = da.cross(db);
    const Real length = axis.norm();
    if (length > 1e-6 * da.norm() * db.norm()) {
      axis /= length;
      if (axis.dot(pa - wa.centre) < 0) axis = -axis;  // out of A, as best_edges orients it
      const Real separation = axis.dot(pb - pa);
      Real highest_a = -kInfinity, lowest_b = kInfinity;
      for (const Vec3& p : wa.nodes) highest_a = std::max(highest_a, axis.dot(p));
      for (const Vec3& p : wb.nodes) lowest_b = std::min(lowest_b, axis.dot(p));
      if (lowest_b - highest_a >= separation - tolerance) {
        if (separation > margin) return Rebuild::apart;
        edge_manifold(pa, da, pb, db, i, j, axis, separation, out);
        return Rebuild::held;
      }
    }
    return Rebuild::search;  // turned parallel or no longer the supports
  }
  // Its gap floor is the face's, which only the search finds again.
  if (detected.feature == ManifoldFeature::edges_past_rim) return Rebuild::search;
  if (detected.feature != ManifoldFeature::face_of_a &&
      detected.feature != ManifoldFeature::face_of_b)
    return Rebuild::apart;
  const bool of_b = detected.feature == ManifoldFeature::face_of_b;
  const int face = of_b ? detected.feature_b : detected.feature_a;
  const WorldBlock& reference = of_b ? wb : wa;
  const WorldBlock& other = of_b ? wa : wb;
  const Real lowest =
      face_separation(reference.normals[face], reference.offsets[face], other.nodes);
  if (lowest > margin) return Rebuild::apart;
  if (!clip_reference_face(a, wa, b, wb, margin, s, out)) out.count = 0;
  const Real deepest = deepest_kept(out);
  if (out.count > 0 && lowest >= deepest - tolerance - detected.beyond_rim) {
    out.beyond_rim = std::max(Real(0), deepest - lowest);
    return Rebuild::held;
  }
  // A node deeper than the clipped face's corners by more than one past the rim was when the
  // features were searched (or none of them within the margin while a node is): the whole
  // search.
  return Rebuild::search;
}

bool rebuild_manifold(const Block& a, const WorldBlock& wa, const Block& b, const WorldBlock& wb,
                      Real margin, const Manifold& detected, ManifoldScratch& s, Manifold& out,
                      bool* searched) {
  const Rebuild rebuilt = rebuild_from_features(a, wa, b, wb, margin, detected, s, out);
  if (searched) *searched = rebuilt == Rebuild::search;
  if (rebuilt == Rebuild::search) return block_manifold(a, wa, b, wb, margin, s, out);
  return rebuilt == Rebuild::held;
}

bool block_manifold(const Block& a, const BlockPose& pose_a, const Block& b,
                    const BlockPose& pose_b, Real margin, ManifoldScratch& s, Manifold& out) {
  place_block(a, pose_a, s.a);
  place_block(b, pose_b, s.b);
  return block_manifold(a, s.a, b, s.b, margin, s, out);
}

bool wall_manifold(const Block& block, const WorldBlock& world, const Vec3& wall_point,
                   const Vec3& wall_normal, Real margin, ManifoldScratch& s, Manifold& out) {
  out.count = 0;
  const Real offset = wall_normal.dot(wall_point);
  int deepest = 0;
  Real deepest_gap = kInfinity;
  for (size_t i = 0; i < world.nodes.size(); ++i) {
    const Real gap = wall_normal.dot(world.nodes[i]) - offset;
    if (gap < deepest_gap) {
      deepest_gap = gap;
      deepest = static_cast<int>(i);
    }
  }
  if (deepest_gap > margin) return false;
  int incident = 0;
  Real most_opposed = kInfinity;
  for (size_t f = 0; f < world.normals.size(); ++f) {
    const Real d = world.normals[f].dot(wall_normal);
    if (d < most_opposed) {
      most_opposed = d;
      incident = static_cast<int>(f);
    }
  }
  std::vector<Vec3>& candidates = s.candidates;
  std::vector<Real>& gaps = s.candidate_gaps;
  candidates.clear();
  gaps.clear();
  bool has_deepest = false;
  auto add = [&](int node) {
    const Vec3& p = world.nodes[node];
    const Real gap = wall_normal.dot(p) - offset;
    if (gap > margin) return;
    candidates.push_back(p - 0.5 * gap * wall_normal);
    gaps.push_back(gap);
  };
  for (int n : block.polygons()[incident].nodes) {
    has_deepest = has_deepest || n == deepest;
    add(n);
  }
  if (!has_deepest) add(deepest);
  out.normal = -wall_normal;
  out.feature = ManifoldFeature::wall;
  keep(candidates, gaps, face_edge(block, world, incident), block.bounding_radius(), out);
  return out.count > 0;
}

bool wall_manifold(const Block& block, const BlockPose& pose, const Vec3& wall_point,
                   const Vec3& wall_normal, Real margin, ManifoldScratch& s, Manifold& out) {
  place_block(block, pose, s.a);
  return wall_manifold(block, s.a, wall_point, wall_normal, margin, s, out);
}

}  // namespace tem
