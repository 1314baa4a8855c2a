// Building a block: validation of the polyhedron, triangulation of its polygons, the elements
// (eqs. 19-20 matrices), mass moments of the elements (eq. 5-6) and the node and edge normals
// (eqs. 2-3 and the default variants of method.md §1).
#include "geometry/block.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <utility>

namespace tem {
namespace {

// Lengths are compared relative to the block's size; this is far above round-off of any
// construction and far below any intended feature.
constexpr Real kRelativeTolerance = 1e-9;

std::string describe(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Newell's normal of a polygon loop: robust for any planar loop, length = twice the area.
Vec3 newell_normal(const std::vector<Vec3>& pts, const std::vector<int>& loop) {
  // About the loop's first point: the cross products are then of the loop's own size, so a
  // small polygon far from the origin keeps its normal to round-off of its size, not of the
  // coordinates (a block's validity must not depend on where it sits).
  const Vec3& o = pts[loop[0]];
  Vec3 n = Vec3::Zero();
  for (size_t i = 1; i + 1 < loop.size(); ++i) n += (pts[loop[i]] - o).cross(pts[loop[i + 1]] - o);
  return n;
}

void check_points(const PolyhedronDef& def, Real tol) {
  if (def.points.size() < 4)
    throw GeometryError("a block needs at least 4 points, got " +
                        std::to_string(def.points.size()));
  for (size_t i = 0; i < def.points.size(); ++i)
    if (!def.points[i].allFinite())
      throw GeometryError("point " + std::to_string(i) + " is not finite");
  for (size_t i = 0; i < def.points.size(); ++i)
    for (size_t j = i + 1; j < def.points.size(); ++j)
      if ((def.points[i] - def.points[j]).norm() <= tol)
        throw GeometryError("points " + std::to_string(i) + " and " + std::to_string(j) +
                            " coincide at " + describe(def.points[i]));
}

// Every directed edge of the polygon loops must appear once, and its reverse once: the surface
// is then closed, two-manifold at edges, and consistently oriented.
void check_closed(const PolyhedronDef& def) {
  std::map<std::pair<int, int>, int> directed;
  std::vector<bool> used(def.points.size(), false);
  for (size_t f = 0; f < def.polygons.size(); ++f) {
    const auto& loop = def.polygons[f];
    if (loop.size() < 3)
      throw GeometryError("polygon " + std::to_string(f) + " has fewer than 3 nodes");
    for (size_t i = 0; i < loop.size(); ++i) {
      const int a = loop[i], b = loop[(i + 1) % loop.size()];
      if (a < 0 || a >= static_cast<int>(def.points.size()))
        throw GeometryError("polygon " + std::to_string(f) + " names point " + std::to_string(a) +
                            ", which does not exist");
      if (a == b || std::count(loop.begin(), loop.end(), a) != 1)
        throw GeometryError("polygon " + std::to_string(f) + " repeats point " + std::to_string(a));
      used[a] = true;
      if (++directed[{a, b}] > 1)
        throw GeometryError("edge " + std::to_string(a) + "-" + std::to_string(b) +
                            " is used twice in the same direction: the faces are not "
                            "consistently oriented or the surface is not a manifold");
    }
  }
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first}))
      throw GeometryError("edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
                          " has a face on one side only: the surface is not closed");
  for (size_t i = 0; i < used.size(); ++i)
    if (!used[i]) throw GeometryError("point " + std::to_string(i) + " is on no face");
}

}  // namespace

Block::Block(const PolyhedronDef& def) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : def.points) mean += p;
  mean /= static_cast<Real>(std::max<size_t>(def.points.size(), 1));
  Real size = 0;
  for (const Vec3& p : def.points) size = std::max(size, (p - mean).norm());
  const Real tol = kRelativeTolerance * size;

  check_points(def, tol);
  if (size <= 0) throw GeometryError("the block has zero size");
  check_closed(def);

  // Polygons: planar, convex loops; their fan triangles become the block's faces.
  const std::vector<Vec3>& pts = def.points;
  std::vector<Vec3> poly_normal(def.polygons.size());
  for (size_t f = 0; f < def.polygons.size(); ++f) {
    const auto& loop = def.polygons[f];
    const Vec3 n = newell_normal(pts, loop);
    if (n.norm() <= tol * size)
      throw GeometryError("polygon " + std::to_string(f) + " has zero area");
    poly_normal[f] = n.normalized();
    Vec3 c = Vec3::Zero();
    for (int i : loop) c += pts[i];
    c /= static_cast<Real>(loop.size());
    for (int i : loop) {
      const Real off = std::abs(poly_normal[f].dot(pts[i] - c));
      if (off > tol)
        throw GeometryError("polygon " + std::to_string(f) + " is not planar: point " +
                            std::to_string(i) + " lies " + std::to_string(off) + " off its plane");
    }
    for (size_t i = 0; i < loop.size(); ++i) {
      const Vec3& a = pts[loop[i]];
      const Vec3& b = pts[loop[(i + 1) % loop.size()]];
      const Vec3& d = pts[loop[(i + 2) % loop.size()]];
      if ((b - a).cross(d - b).dot(poly_normal[f]) <= tol * size)
        throw GeometryError("polygon " + std::to_string(f) + " is not strictly convex at point " +
                            std::to_string(loop[(i + 1) % loop.size()]));
    }
  }

  // Volume and centroid from tetrahedra on the point mean; signed, so exact for any closed,
  // outward-oriented surface, convex or not.
  Real volume = 0;
  Vec3 moment = Vec3::Zero();
  for (const auto& loop : def.polygons)
    for (size_t i = 1; i + 1 < loop.size(); ++i) {
      const Vec3 a = pts[loop[0]] - mean, b = pts[loop[i]] - mean, c = pts[loop[i + 1]] - mean;
      const Real v = a.dot(b.cross(c)) / 6;
      volume += v;
      moment += v * (a + b + c) / 4;
    }
  if (volume <= tol * size * size)
    throw GeometryError(volume < 0 ? "the block has negative volume: its faces point inward"
                                   : "the block has zero volume (its points are coplanar)");
  centroid_in_input_ = mean + moment / volume;

  nodes_.reserve(pts.size());
  for (const Vec3& p : pts) nodes_.push_back(p - centroid_in_input_);

  // Convexity (§2.2 of the paper): every node on the inner side of every polygon's plane.
  polygons_.resize(def.polygons.size());
  int worst_node = -1, worst_poly = -1;
  for (size_t f = 0; f < def.polygons.size(); ++f) {
    Polygon& poly = polygons_[f];
    poly.nodes = def.polygons[f];
    poly.normal = poly_normal[f];
    poly.offset = 0;
    for (int i : poly.nodes) poly.offset += poly.normal.dot(nodes_[i]);
    poly.offset /= static_cast<Real>(poly.nodes.size());
    for (size_t i = 0; i < nodes_.size(); ++i) {
      const Real out = poly.normal.dot(nodes_[i]) - poly.offset;
      if (out > tol && out > nonconvexity_) {
        nonconvexity_ = out;
        worst_node = static_cast<int>(i);
        worst_poly = static_cast<int>(f);
      }
    }
  }
  if (nonconvexity_ > 0 && !def.allow_nonconvex)
    throw GeometryError("the block is not convex: node " + std::to_string(worst_node) + " lies " +
                        std::to_string(nonconvexity_) + " outside the plane of polygon " +
                        std::to_string(worst_poly));

  // Faces: fan triangles of each convex polygon.
  for (size_t f = 0; f < polygons_.size(); ++f) {
    const auto& loop = polygons_[f].nodes;
    for (size_t i = 1; i + 1 < loop.size(); ++i) {
      polygons_[f].triangles.push_back(static_cast<int>(triangles_.size()));
      triangles_.push_back(
          {{loop[0], loop[i], loop[i + 1]}, static_cast<int>(f), polygons_[f].normal});
    }
  }

  // Elements: tetrahedron (centroid, triangle). E = [a1 a2 a3] and its inverse (eq. 19); the
  // second moment of each element by eq. 5 with unit density, summed by eq. 6.
  elements_.reserve(triangles_.size());
  for (size_t t = 0; t < triangles_.size(); ++t) {
    Mat3 e;
    for (int k = 0; k < 3; ++k) e.col(k) = nodes_[triangles_[t].nodes[k]];
    const Real det = e.determinant();
    if (det <= 0)
      throw GeometryError("face " + std::to_string(t) +
                          " does not face away from the block's centroid: the tetrahedral "
                          "elements would not tile the block");
    const Real v = det / 6;
    const Vec3 sum = e.col(0) + e.col(1) + e.col(2);
    Mat3 s = sum * sum.transpose();
    for (int k = 0; k < 3; ++k) s += e.col(k) * e.col(k).transpose();
    second_moment_ += v / 20 * s;
    volume_ += v;
    elements_.push_back({static_cast<int>(t), e.inverse(), v});
  }

  // Edges: unique triangle edges with their two triangles.
  std::map<std::pair<int, int>, size_t> edge_index;
  for (size_t t = 0; t < triangles_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      int a = triangles_[t].nodes[k], b = triangles_[t].nodes[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      auto [it, fresh] = edge_index.emplace(std::make_pair(a, b), edges_.size());
      if (fresh)
        edges_.push_back({{a, b}, {static_cast<int>(t), -1}, true});
      else
        edges_[it->second].triangles[1] = static_cast<int>(t);
    }
  for (Edge& e : edges_) {
    const int first = triangles_[e.triangles[0]].polygon;
    const int second = triangles_[e.triangles[1]].polygon;
    e.polygon_boundary = first != second;
    if (e.polygon_boundary) polygon_edges_.push_back({e.nodes, {first, second}});
  }

  // Node normals. Paper (eq. 2): the sum of the normals of the triangles at the node, which
  // weights a polygon by how many of its triangles meet there. Default: the angle-weighted
  // pseudo-normal, independent of the triangulation (the angles of a polygon's triangles at a
  // node add up to the polygon's angle there).
  node_normals_.assign(nodes_.size(), Vec3::Zero());
  node_normals_paper_.assign(nodes_.size(), Vec3::Zero());
  for (const Triangle& tri : triangles_)
    for (int k = 0; k < 3; ++k) {
      const int i = tri.nodes[k];
      const Vec3 u = (nodes_[tri.nodes[(k + 1) % 3]] - nodes_[i]).normalized();
      const Vec3 w = (nodes_[tri.nodes[(k + 2) % 3]] - nodes_[i]).normalized();
      const Real angle = std::acos(std::clamp(u.dot(w), Real(-1), Real(1)));
      node_normals_[i] += angle * tri.normal;
      node_normals_paper_[i] += tri.normal;
    }
  for (Vec3& n : node_normals_) n.normalize();
  for (Vec3& n : node_normals_paper_) n.normalize();

  // Edge normals. Paper (eq. 3): mean of the end nodes' (paper) normals. Default: mean of the
  // two adjacent faces' normals, which the paper itself names as the better choice.
  edge_normals_.reserve(edges_.size());
  edge_normals_paper_.reserve(edges_.size());
  for (const Edge& e : edges_) {
    edge_normals_.push_back(
        (triangles_[e.triangles[0]].normal + triangles_[e.triangles[1]].normal).normalized());
    edge_normals_paper_.push_back(
        (node_normals_paper_[e.nodes[0]] + node_normals_paper_[e.nodes[1]]).normalized());
  }

  bounds_min_ = bounds_max_ = nodes_[0];
  for (const Vec3& p : nodes_) {
    bounding_radius_ = std::max(bounding_radius_, p.norm());
    bounds_min_ = bounds_min_.cwiseMin(p);
    bounds_max_ = bounds_max_.cwiseMax(p);
  }
}

}  // namespace tem
