#include "geometry/primitives.hpp"

#include <cmath>
#include <numbers>

namespace tem {

Mat3 axis_rotation(Axis axis) {
  Mat3 r = Mat3::Zero();
  switch (axis) {
    case Axis::z:
      return Mat3::Identity();
    case Axis::x:  // canonical x, y, z -> body y, z, x
      r.col(0) = Vec3::UnitY();
      r.col(1) = Vec3::UnitZ();
      r.col(2) = Vec3::UnitX();
      return r;
    case Axis::y:  // canonical x, y, z -> body z, x, y
      r.col(0) = Vec3::UnitZ();
      r.col(1) = Vec3::UnitX();
      r.col(2) = Vec3::UnitY();
      return r;
  }
  return Mat3::Identity();
}

PolyhedronDef regular_prism(int sides, Real radius, Real height, Axis axis) {
  const Mat3 r = axis_rotation(axis);
  PolyhedronDef def;
  // Nodes 0..n-1 on the bottom (-h/2), n..2n-1 on the top (+h/2).
  for (int level = 0; level < 2; ++level)
    for (int k = 0; k < sides; ++k) {
      const Real phi = 2 * std::numbers::pi * k / sides;
      def.points.push_back(
          r * Vec3(radius * std::cos(phi), radius * std::sin(phi), (level - 0.5) * height));
    }
  std::vector<int> top, bottom;
  for (int k = 0; k < sides; ++k) {
    top.push_back(sides + k);
    bottom.push_back(sides - 1 - k);
    const int next = (k + 1) % sides;
    def.polygons.push_back({k, next, sides + next, sides + k});
  }
  def.polygons.push_back(top);
  def.polygons.push_back(bottom);
  return def;
}

PolyhedronDef box(const Vec3& size) {
  PolyhedronDef def;
  // Node i has coordinate sign (-,+) from bits 0, 1, 2 of i for x, y, z.
  for (int i = 0; i < 8; ++i)
    def.points.push_back(Vec3((i & 1 ? 0.5 : -0.5) * size.x(), (i & 2 ? 0.5 : -0.5) * size.y(),
                              (i & 4 ? 0.5 : -0.5) * size.z()));
  def.polygons = {{0, 2, 3, 1}, {4, 5, 7, 6},   // -z, +z
                  {0, 1, 5, 4}, {2, 6, 7, 3},   // -y, +y
                  {0, 4, 6, 2}, {1, 3, 7, 5}};  // -x, +x
  return def;
}

std::vector<PolyhedronDef> polygonal_ring(int segments, int sides, Real radius, Real section_radius,
                                          int blocks, Axis axis, bool allow_nonconvex) {
  const Mat3 r = axis_rotation(axis);
  const int per_block = segments / blocks;
  // Node j of the section at centre-line vertex k (canonical frame, axis z).
  auto section_node = [&](int k, int j) {
    const Real theta = 2 * std::numbers::pi * k / segments;
    const Real phi = 2 * std::numbers::pi * j / sides;
    const Vec3 radial(std::cos(theta), std::sin(theta), 0);
    return Vec3(r * ((radius + section_radius * std::cos(phi)) * radial +
                     section_radius * std::sin(phi) * Vec3::UnitZ()));
  };
  std::vector<PolyhedronDef> result;
  for (int b = 0; b < blocks; ++b) {
    PolyhedronDef def;
    def.allow_nonconvex = allow_nonconvex;
    const int first = b * per_block;
    for (int s = 0; s <= per_block; ++s)
      for (int j = 0; j < sides; ++j) def.points.push_back(section_node(first + s, j));
    auto node = [&](int s, int j) { return s * sides + (j % sides); };
    // Start cap faces back along the centre line, end cap forward: in the section plane the
    // node order (radial toward the axis) turns about -e_theta.
    std::vector<int> start, end;
    for (int j = 0; j < sides; ++j) {
      start.push_back(node(0, j));
      end.push_back(node(per_block, sides - 1 - j));
    }
    def.polygons.push_back(start);
    def.polygons.push_back(end);
    for (int s = 0; s < per_block; ++s)
      for (int j = 0; j < sides; ++j)
        def.polygons.push_back({node(s, j), node(s + 1, j), node(s + 1, j + 1), node(s, j + 1)});
    result.push_back(std::move(def));
  }
  return result;
}

}  // namespace tem
