// A block: one convex polyhedron of a body, and its tetrahedral elements (method.md §1).
//
// The block's surface is a set of planar polygons, each split into triangles (the paper's
// faces). Its nodes are the surface vertices, its edges the unique triangle edges, and its
// elements the tetrahedra (centroid, one surface triangle), which tile a convex block exactly.
// Everything is stored in the block's own frame with the centroid (centre of volume) at the
// origin, so an element's matrix E = [a1 a2 a3] of node offsets and its inverse are constants
// computed once here (eqs. 19-20 reuse them at every contact test).
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "tem/types.hpp"

namespace tem {

// Raised for a block that cannot be simulated: degenerate, open, non-convex (unless allowed).
class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Node and edge normals in the paper's variant (eqs. 2-3 as printed) or the default one.
enum class NormalVariant { paper, default_ };

struct Triangle {
  std::array<int, 3> nodes;  // counter-clockwise seen from outside
  int polygon;               // the planar polygon this triangle belongs to
  Vec3 normal;               // outward unit normal
};

struct Polygon {
  std::vector<int> nodes;  // boundary loop, counter-clockwise seen from outside
  Vec3 normal;             // outward unit normal
  Real offset;             // plane: normal . x = offset (block frame)
  std::vector<int> triangles;
};

struct Edge {
  std::array<int, 2> nodes;      // a -> b with a < b
  std::array<int, 2> triangles;  // the two triangles that share it
  bool polygon_boundary;         // false for a diagonal inside a planar polygon
};

// An edge between two polygons (an Edge that is no diagonal inside one polygon): its nodes a < b
// and the polygons of its first and second triangle. What placing a block in the world walks.
struct PolygonEdge {
  std::array<int, 2> nodes;
  std::array<int, 2> polygons;
};

// Tetrahedron (block centroid, the three nodes of triangle `triangle`).
struct Element {
  int triangle;
  Mat3 inverse;  // E^-1 with E = [a1 a2 a3], a_i the node offsets from the centroid
  Real volume;   // det(E) / 6, positive for an element of a convex block
};

// The input of a block: vertices and outward polygons (each a vertex loop, counter-clockwise
// seen from outside), in any frame. Primitives build these directly; convex_hull() builds them
// from a point cloud.
struct PolyhedronDef {
  std::vector<Vec3> points;
  std::vector<std::vector<int>> polygons;
  bool allow_nonconvex = false;
};

class Block {
 public:
  // Validates and builds a block. Throws GeometryError naming the problem: repeated points,
  // open or inconsistently oriented surface, non-planar polygon, zero or negative volume, or a
  // non-convex block (unless def.allow_nonconvex, which records the defect instead).
  explicit Block(const PolyhedronDef& def);

  const std::vector<Vec3>& nodes() const { return nodes_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Polygon>& polygons() const { return polygons_; }
  const std::vector<Edge>& edges() const { return edges_; }
  // The edges with polygon_boundary, in edges() order.
  const std::vector<PolygonEdge>& polygon_edges() const { return polygon_edges_; }
  const std::vector<Element>& elements() const { return elements_; }

  const Vec3& node_normal(int node, NormalVariant v) const {
    return v == NormalVariant::paper ? node_normals_paper_[node] : node_normals_[node];
  }
  const Vec3& edge_normal(int edge, NormalVariant v) const {
    return v == NormalVariant::paper ? edge_normals_paper_[edge] : edge_normals_[edge];
  }

  // Where the centroid lay in the frame of the PolyhedronDef (nodes() are shifted by it).
  const Vec3& centroid_in_input() const { return centroid_in_input_; }
  Real volume() const { return volume_; }
  // Second moment of volume about the centroid, S = integral of x x^T dV (unit density).
  const Mat3& second_moment() const { return second_moment_; }
  Real bounding_radius() const { return bounding_radius_; }
  // Axis-aligned bounds of the nodes in the block's frame (for world bounds in the broad phase).
  const Vec3& bounds_min() const { return bounds_min_; }
  const Vec3& bounds_max() const { return bounds_max_; }
  // Largest distance of a node outside the plane of a polygon: 0 for a convex block.
  Real nonconvexity() const { return nonconvexity_; }
  bool convex() const { return nonconvexity_ == 0; }

 private:
  std::vector<Vec3> nodes_;
  std::vector<Triangle> triangles_;
  std::vector<Polygon> polygons_;
  std::vector<Edge> edges_;
  std::vector<PolygonEdge> polygon_edges_;
  std::vector<Element> elements_;
  std::vector<Vec3> node_normals_, node_normals_paper_;
  std::vector<Vec3> edge_normals_, edge_normals_paper_;
  Vec3 centroid_in_input_ = Vec3::Zero();
  Real volume_ = 0;
  Mat3 second_moment_ = Mat3::Zero();
  Real bounding_radius_ = 0;
  Vec3 bounds_min_ = Vec3::Zero(), bounds_max_ = Vec3::Zero();
  Real nonconvexity_ = 0;
};

// The convex hull of a point cloud (Qhull), its coplanar facets merged into polygons. Throws
// GeometryError for fewer than 4 points, repeated points, all points coplanar, and points that
// lie strictly inside the hull (a non-convex point set: the block would not have them as nodes).
PolyhedronDef convex_hull(const std::vector<Vec3>& points);

}  // namespace tem
