// Closed triangle meshes built in code for the mesh tests: a torus, a cube with a square through
// hole, an L-shaped prism, the paper's ring as one surface, and a mesh writer for each file
// format the reader takes. Every mesh is outward-oriented (counter-clockwise seen from outside).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "geometry/primitives.hpp"
#include "mesh/triangle_mesh.hpp"

namespace tem::testing_support {

// The faces of a closed tube whose vertex i m + j is the j-th of m round the i-th of n rings,
// both ways round (a torus's grid): 2 n m triangles, facing out where the rings run along the
// tube's centre line and each ring's vertices turn as a torus's do about its tube.
inline void add_tube_faces(TriangleMesh& mesh, int n, int m) {
  auto at = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      mesh.faces.push_back({a, b, c});
      mesh.faces.push_back({a, c, d});
    }
}

// Torus about z: centre-line radius R, tube radius r, n segments around z, m around the tube.
// Its volume tends to 2 pi^2 R r^2 as n, m grow; each (non-planar) quad of the grid is split into
// two triangles, so the polyhedron is exactly the triangles given.
inline TriangleMesh torus_mesh(Real R, Real r, int n, int m) {
  TriangleMesh mesh;
  mesh.source = "torus";
  for (int i = 0; i < n; ++i) {
    const Real u = 2 * std::numbers::pi * i / n;
    for (int j = 0; j < m; ++j) {
      const Real v = 2 * std::numbers::pi * j / m;
      mesh.vertices.push_back(Vec3((R + r * std::cos(v)) * std::cos(u),
                                   (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)));
    }
  }
  add_tube_faces(mesh, n, m);
  return mesh;
}

// A prism over a polygon with holes given as loops in the xy plane, from z = 0 to z = height.
// `outer` is counter-clockwise, each hole clockwise; `cap` lists the cap's triangles as indices
// into the concatenated loops (outer first), counter-clockwise seen from +z.
inline TriangleMesh extruded_mesh(const std::vector<std::vector<std::array<Real, 2>>>& loops,
                                  const std::vector<std::array<int, 3>>& cap, Real height,
                                  const std::string& source) {
  TriangleMesh mesh;
  mesh.source = source;
  int count = 0;
  for (const auto& loop : loops) count += static_cast<int>(loop.size());
  for (Real z : {Real(0), height})
    for (const auto& loop : loops)
      for (const auto& p : loop) mesh.vertices.push_back(Vec3(p[0], p[1], z));
  for (const auto& t : cap) {
    mesh.faces.push_back({t[0], t[2], t[1]});                          // bottom, seen from -z
    mesh.faces.push_back({t[0] + count, t[1] + count, t[2] + count});  // top
  }
  int first = 0;
  for (const auto& loop : loops) {
    const int k = static_cast<int>(loop.size());
    for (int i = 0; i < k; ++i) {
      const int a = first + i, b = first + (i + 1) % k;
      mesh.faces.push_back({a, b, b + count});
      mesh.faces.push_back({a, b + count, a + count});
    }
    first += k;
  }
  return mesh;
}

// An L: the square [0, 2]^2 less [1, 2]^2, extruded to height 1. Volume 3.
inline TriangleMesh l_mesh() {
  // Outer loop (ccw): 0 (0,0) 1 (2,0) 2 (2,1) 3 (1,1) 4 (1,2) 5 (0,2). Fan from the reflex corner 3.
  return extruded_mesh({{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}},
                       {{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}}, 1.0, "L");
}

// A cube of edge 3 (from 0 to 3) with a square hole of edge 1 through it along z. Volume 24.
inline TriangleMesh holed_cube_mesh() {
  // Outer 0..3 ccw, inner 4..7 cw; the cap between them as four trapezoids of two triangles.
  return extruded_mesh({{{0, 0}, {3, 0}, {3, 3}, {0, 3}}, {{1, 1}, {1, 2}, {2, 2}, {2, 1}}},
                       {{0, 1, 7}, {0, 7, 4},    // bottom band: outer 0-1, inner 4(1,1)-7(2,1)
                        {1, 2, 6}, {1, 6, 7},    // right band
                        {2, 3, 5}, {2, 5, 6},    // top band
                        {3, 0, 4}, {3, 4, 5}},   // left band
                       3.0, "holed cube");
}

// The union of convex polyhedra that meet face to face (a primitive's blocks), as one surface:
// polygons that appear in two blocks (with the same vertex positions) are inside and dropped,
// the others are fanned into triangles. Vertices are welded by exact position.
inline TriangleMesh union_surface(const std::vector<PolyhedronDef>& parts, const std::string& source) {
  using Key = std::tuple<Real, Real, Real>;
  std::map<Key, int> index;
  TriangleMesh mesh;
  mesh.source = source;
  auto vertex = [&](const Vec3& p) {
    const Key key{p.x(), p.y(), p.z()};
    auto [it, added] = index.emplace(key, static_cast<int>(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(p);
    return it->second;
  };
  std::vector<std::vector<int>> polygons;
  std::map<std::set<int>, int> seen;
  for (const PolyhedronDef& part : parts)
    for (const auto& polygon : part.polygons) {
      std::vector<int> loop;
      for (int node : polygon) loop.push_back(vertex(part.points[node]));
      ++seen[std::set<int>(loop.begin(), loop.end())];
      polygons.push_back(loop);
    }
  for (const auto& loop : polygons) {
    if (seen[std::set<int>(loop.begin(), loop.end())] > 1) continue;
    for (size_t k = 1; k + 1 < loop.size(); ++k) mesh.faces.push_back({loop[0], loop[k], loop[k + 1]});
  }
  return mesh;
}

// The paper's ring (method.md §7: 16 segments, hexagonal section) as one closed surface, built
// from the ring primitive's one-segment blocks so that it has exactly the primitive's nodes.
inline TriangleMesh paper_ring_mesh(Real radius = 0.3, Real section_radius = 0.05,
                                    Axis axis = Axis::z) {
  return union_surface(polygonal_ring(16, 6, radius, section_radius, 16, axis, false), "paper ring");
}

// A solid of revolution about z: the closed profile `profile` of (r, z) points, counter-clockwise
// in the (r, z) plane, swept in `segments` steps. Points with r = 0 are poles (one vertex); the
// others give a ring of vertices each. Each quad of the sweep is two triangles, as CAD exporters
// write it: planar quads (flanges, cylinders) are split along a diagonal, cones only nearly so.
inline TriangleMesh revolved_mesh(const std::vector<std::array<Real, 2>>& profile, int segments,
                                  const std::string& source) {
  TriangleMesh mesh;
  mesh.source = source;
  std::vector<std::vector<int>> ring;  // vertex of profile point i at step k
  for (const auto& [r, z] : profile) {
    std::vector<int> row;
    if (r == 0) {
      row.assign(static_cast<size_t>(segments), static_cast<int>(mesh.vertices.size()));
      mesh.vertices.push_back(Vec3(0, 0, z));
    } else {
      for (int k = 0; k < segments; ++k) {
        const Real t = 2 * std::numbers::pi * k / segments;
        row.push_back(static_cast<int>(mesh.vertices.size()));
        mesh.vertices.push_back(Vec3(r * std::cos(t), r * std::sin(t), z));
      }
    }
    ring.push_back(row);
  }
  const size_t m = profile.size();
  for (size_t i = 0; i < m; ++i)
    for (int k = 0; k < segments; ++k) {
      const size_t j = (i + 1) % m, k0 = static_cast<size_t>(k);
      const size_t k1 = static_cast<size_t>((k + 1) % segments);
      // Seen from outside, the counter-clockwise profile sweeps clockwise.
      const int a = ring[i][k0], b = ring[i][k1], c = ring[j][k1], d = ring[j][k0];
      for (const std::array<int, 3>& t : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}})
        if (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) mesh.faces.push_back(t);
    }
  return mesh;
}

// A spool (a CAD-like solid of revolution): two flanges of radius 1 and thicknesses `bottom` and `top`
// on a hub of radius `hub`, length 1 in all, a bore of radius `bore` (0: none), the flanges'
// outer rims chamfered by `chamfer` (0: none) and the hub joined to each flange by a quarter
// circle of radius `fillet` in `fillet_steps` steps (0: a sharp corner).
inline TriangleMesh spool_mesh(int segments, Real bore, Real chamfer, Real fillet,
                               Real bottom = 0.1, Real top = 0.1, Real hub = 0.4,
                               int fillet_steps = 4) {
  std::vector<std::array<Real, 2>> p{{bore, 0}};
  auto rim = [&](Real z0, Real z1) {  // the flange's outer edge, from z0 to z1
    const Real s = z1 > z0 ? 1 : -1;
    if (chamfer > 0) {
      p.push_back({1 - chamfer, z0});
      p.push_back({1, z0 + s * chamfer});
      p.push_back({1, z1 - s * chamfer});
      p.push_back({1 - chamfer, z1});
    } else {
      p.push_back({1, z0});
      p.push_back({1, z1});
    }
  };
  auto corner = [&](Real z, Real s, bool into_hub) {  // flange face at z meets the hub
    if (fillet <= 0) {
      p.push_back({hub, z});
      return;
    }
    for (int k = 0; k <= fillet_steps; ++k) {
      const Real a = std::numbers::pi / 2 * k / fillet_steps;
      const Real along = into_hub ? a : std::numbers::pi / 2 - a;
      p.push_back(
          {hub + fillet - fillet * std::sin(along), z + s * (fillet - fillet * std::cos(along))});
    }
  };
  rim(0, bottom);
  corner(bottom, 1, true);
  corner(1 - top, -1, false);
  rim(1 - top, 1);
  p.push_back({bore, 1});
  return revolved_mesh(p, segments, "spool");
}

// The mesh with its vertices rounded to 32-bit floats, as the mesh reader delivers a file's
// (Assimp reads coordinates as floats): planar quads then bend by about 1e-8 of the size. The
// float goes through a volatile: g++ 12.2's SLP vectorizer at -O2 drops the round trip of such
// a loop (see test_mesh_reading.cpp).
inline TriangleMesh rounded_to_float(TriangleMesh mesh) {
  for (Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      const volatile float rounded = static_cast<float>(v[k]);
      v[k] = rounded;
    }
  mesh.source += " (float)";
  return mesh;
}

// The mesh with its vertices rounded to `digits` significant decimal digits, as many exporters
// write OBJ files ("%g": 6): planar quads then bend by about 1e-6 of the size.
inline TriangleMesh rounded_to_digits(TriangleMesh mesh, int digits) {
  for (Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      char text[40];
      std::snprintf(text, sizeof text, "%.*g", digits, v[k]);
      v[k] = std::strtod(text, nullptr);
    }
  mesh.source += " (" + std::to_string(digits) + " digits)";
  return mesh;
}

// Writers for the reader's formats, so tests read real files without committing any.
inline void write_obj(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  for (const Vec3& v : mesh.vertices) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : mesh.faces) out << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << "\n";
}

inline void write_off(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << mesh.vertices.size() << " " << mesh.faces.size() << " 0\n";
  for (const Vec3& v : mesh.vertices) out << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : mesh.faces) out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
}

inline void write_ply_ascii(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "ply\nformat ascii 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << mesh.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : mesh.vertices) out << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& f : mesh.faces) out << "3 " << f[0] << " " << f[1] << " " << f[2] << "\n";
}

// Binary PLY (little-endian, as x86 stores it) with double coordinates.
inline void write_ply_binary(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << mesh.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : mesh.vertices) out.write(reinterpret_cast<const char*>(v.data()), 3 * sizeof(Real));
  for (const auto& f : mesh.faces) {
    const std::uint8_t corners = 3;
    const std::int32_t indices[3] = {f[0], f[1], f[2]};
    out.write(reinterpret_cast<const char*>(&corners), 1);
    out.write(reinterpret_cast<const char*>(indices), sizeof indices);
  }
}

inline void write_stl_ascii(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(17);
  out << "solid tem\n";
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    out << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n outer loop\n";
    for (const Vec3* v : {&a, &b, &c}) out << "  vertex " << v->x() << " " << v->y() << " " << v->z() << "\n";
    out << " endloop\nendfacet\n";
  }
  out << "endsolid tem\n";
}

// Binary STL stores 32-bit floats: the mesh read back is the mesh rounded to float.
inline void write_stl_binary(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = {};
  std::strncpy(header, "binary STL written by TEM's tests", sizeof header - 1);
  out.write(header, 80);
  const std::uint32_t count = static_cast<std::uint32_t>(mesh.faces.size());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const auto& f : mesh.faces) {
    const Vec3& a = mesh.vertices[f[0]];
    const Vec3& b = mesh.vertices[f[1]];
    const Vec3& c = mesh.vertices[f[2]];
    const Vec3 n = (b - a).cross(c - a).normalized();
    float values[12];
    for (int k = 0; k < 3; ++k) {
      values[k] = static_cast<float>(n[k]);
      values[3 + k] = static_cast<float>(a[k]);
      values[6 + k] = static_cast<float>(b[k]);
      values[9 + k] = static_cast<float>(c[k]);
    }
    out.write(reinterpret_cast<const char*>(values), sizeof values);
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

}  // namespace tem::testing_support
