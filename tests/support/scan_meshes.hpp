// Scan-like closed meshes built in code, for the approximate cutter's tests and benchmark: no
// scanned file is at hand, so these stand in for one. Each is a smooth, non-convex shape with
// low-frequency bumps and a per-vertex "scanner noise" along its surface's radial direction,
// deterministic (no random generator, a hash of the grid position). At the default resolution
// each has 75,000 faces. The torus and the potato are radial graphs (over a circle of the
// torus's centre line, or over the sphere), so no face crosses another whatever the
// displacement; the knot's tube is thinner than its strands are apart (below).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "mesh/triangle_mesh.hpp"
#include "mesh_shapes.hpp"  // this directory's, for the tests and the benchmark

namespace tem::testing_support {

// A value in [-1, 1) from a grid position (splitmix64).
inline Real grid_noise(int i, int j) {
  std::uint64_t x = static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL +
                    static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL + 0x165667B19E3779F9ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  x ^= x >> 31;
  return static_cast<Real>(x >> 11) / static_cast<Real>(1ULL << 52) - 1;
}

// A torus about z (centre-line radius 1) whose tube radius, 0.3 on average, wanders by up to
// about a third with waves around and along the tube, plus noise of +-0.002 (0.05 % of the
// bounding box's diagonal). n x m grid, 2 n m faces.
inline TriangleMesh bumpy_torus_mesh(int n = 500, int m = 75) {
  TriangleMesh mesh;
  mesh.source = "bumpy torus";
  const Real pi = std::numbers::pi;
  for (int i = 0; i < n; ++i) {
    const Real u = 2 * pi * i / n;
    for (int j = 0; j < m; ++j) {
      const Real v = 2 * pi * j / m;
      const Real r = 0.3 * (1 + 0.15 * std::sin(3 * u + 1) * std::cos(2 * v) +
                            0.10 * std::sin(5 * u) * std::sin(3 * v + 0.5) +
                            0.06 * std::cos(2 * u - 4 * v)) +
                     0.002 * grid_noise(i, j);
      mesh.vertices.push_back(Vec3((1 + r * std::cos(v)) * std::cos(u),
                                   (1 + r * std::cos(v)) * std::sin(u), r * std::sin(v)));
    }
  }
  add_tube_faces(mesh, n, m);
  return mesh;
}

// A "potato": a unit sphere with five smooth waves in its radius, a deep dent (0.45 of the
// radius at its bottom) on one side, stretched to 1.4 x 1 x 0.8, plus noise of +-0.002.
// n meridians, m - 1 rings between the poles: 2 n (m - 1) faces.
inline TriangleMesh potato_mesh(int n = 300, int m = 126) {
  TriangleMesh mesh;
  mesh.source = "potato";
  const Real pi = std::numbers::pi;
  struct Wave {
    Vec3 direction;
    Real frequency, amplitude, phase;
  };
  const std::array<Wave, 5> waves{{{Vec3(1, 2, 0.5).normalized(), 1.7, 0.08, 0.3},
                                   {Vec3(-2, 0.5, 1).normalized(), 2.3, 0.06, 1.1},
                                   {Vec3(0.3, -1, 2).normalized(), 3.1, 0.05, 2.0},
                                   {Vec3(1, -1, -1).normalized(), 2.9, 0.04, 0.7},
                                   {Vec3(-0.5, -2, 0.2).normalized(), 1.3, 0.07, 2.6}}};
  const Vec3 dent = Vec3(0.2, 1, 0.3).normalized();
  auto radius = [&](const Vec3& d, int i, int j) {
    Real r = 1 - 0.45 * std::exp(-(d - dent).squaredNorm() / 0.15) + 0.002 * grid_noise(i, j);
    for (const Wave& w : waves) r += w.amplitude * std::sin(w.frequency * w.direction.dot(d) + w.phase);
    return r;
  };
  const Vec3 stretch(1.4, 1.0, 0.8);
  auto place = [&](const Vec3& d, int i, int j) {
    mesh.vertices.push_back(radius(d, i, j) * d.cwiseProduct(stretch));
  };
  place(Vec3::UnitZ(), -1, 0);  // north pole: vertex 0
  for (int j = 1; j < m; ++j) {
    const Real theta = pi * j / m;
    for (int i = 0; i < n; ++i) {
      const Real phi = 2 * pi * i / n;
      place(Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)),
            i, j);
    }
  }
  place(-Vec3::UnitZ(), -1, m);  // south pole: the last vertex
  auto at = [&](int i, int ring) { return 1 + (ring - 1) * n + (i + n) % n; };
  const int south = static_cast<int>(mesh.vertices.size()) - 1;
  for (int i = 0; i < n; ++i) {
    mesh.faces.push_back({0, at(i, 1), at(i + 1, 1)});
    for (int ring = 1; ring + 1 < m; ++ring) {
      mesh.faces.push_back({at(i, ring), at(i, ring + 1), at(i + 1, ring + 1)});
      mesh.faces.push_back({at(i, ring), at(i + 1, ring + 1), at(i + 1, ring)});
    }
    mesh.faces.push_back({south, at(i + 1, m - 1), at(i, m - 1)});
  }
  return mesh;
}

// A trefoil knot: a tube about the curve (sin u + 2 sin 2u, cos u - 2 cos 2u, -sin 3u), whose
// radius, 0.42 on average, wanders by up to a fifth with waves around and along the tube, plus
// noise of +-0.002. The strands' centre lines come no nearer than 1.21 to each other and bend no
// tighter than a radius of 1.29, so the tube (radius at most 0.51) meets itself nowhere. Its
// cross-sections sit in the curve's Frenet frame, which closes on itself as the curve never
// straightens; they turn from normal towards minus binormal so that faces point out. n x m grid,
// 2 n m faces.
inline TriangleMesh knot_mesh(int n = 500, int m = 75) {
  TriangleMesh mesh;
  mesh.source = "trefoil knot";
  const Real pi = std::numbers::pi;
  for (int i = 0; i < n; ++i) {
    const Real u = 2 * pi * i / n;
    const Vec3 centre(std::sin(u) + 2 * std::sin(2 * u), std::cos(u) - 2 * std::cos(2 * u),
                      -std::sin(3 * u));
    const Vec3 velocity(std::cos(u) + 4 * std::cos(2 * u), -std::sin(u) + 4 * std::sin(2 * u),
                        -3 * std::cos(3 * u));
    const Vec3 acceleration(-std::sin(u) - 8 * std::sin(2 * u),
                            -std::cos(u) + 8 * std::cos(2 * u), 9 * std::sin(3 * u));
    const Vec3 tangent = velocity.normalized();
    const Vec3 binormal = velocity.cross(acceleration).normalized();
    const Vec3 normal = binormal.cross(tangent);
    for (int j = 0; j < m; ++j) {
      const Real v = 2 * pi * j / m;
      const Real r = 0.42 * (1 + 0.12 * std::sin(4 * u + 0.3) * std::cos(2 * v) +
                             0.08 * std::sin(7 * u) * std::sin(3 * v + 1)) +
                     0.002 * grid_noise(i, j);
      mesh.vertices.push_back(centre + r * (std::cos(v) * normal - std::sin(v) * binormal));
    }
  }
  add_tube_faces(mesh, n, m);
  return mesh;
}

}  // namespace tem::testing_support
