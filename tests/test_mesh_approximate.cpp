// The approximate cutter (approximate_decomposition): convex meshes stay one block,
// boxes are cut exactly, holes stay open, blocks never overlap and cover the mesh, the result
// is the same every run; and the plane cut underneath keeps volumes and corners.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mesh/cut_tree.hpp"
#include "mesh/mesh_decomposition.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/hull_polyhedron.hpp"
#include "mesh/mesh_distance.hpp"
#include "mesh/part_components.hpp"
#include "mesh/plane_cut.hpp"
#include "geometry/primitives.hpp"
#include "support/mesh_shapes.hpp"
#include "support/parallel.hpp"
#include "support/scan_meshes.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_mesh_approximate {

using testing_support::report;

// A latitude-longitude sphere: its quads are planar, so it is convex and its own hull.
TriangleMesh sphere_mesh(int n, int m) {
  TriangleMesh mesh;
  mesh.source = "sphere";
  const Real pi = std::numbers::pi;
  mesh.vertices.push_back(Vec3::UnitZ());
  for (int j = 1; j < m; ++j)
    for (int i = 0; i < n; ++i)
      mesh.vertices.push_back(Vec3(std::sin(pi * j / m) * std::cos(2 * pi * i / n),
                                   std::sin(pi * j / m) * std::sin(2 * pi * i / n),
                                   std::cos(pi * j / m)));
  mesh.vertices.push_back(-Vec3::UnitZ());
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

TriangleMesh box_mesh() {
  return testing_support::extruded_mesh({{{0, 0}, {2, 0}, {2, 1}, {0, 1}}}, {{0, 1, 2}, {0, 2, 3}},
                                        1.5, "box");
}

struct Plane {
  Vec3 normal;  // outward, unit
  Real offset;
};

// The block's face planes as Block computes them (Newell normal, through the loop's centre).
std::vector<Plane> face_planes(const PolyhedronDef& def) {
  std::vector<Plane> planes;
  for (const auto& loop : def.polygons) {
    Vec3 n = Vec3::Zero(), centre = Vec3::Zero();
    for (size_t i = 0; i < loop.size(); ++i) {
      n += def.points[loop[i]].cross(def.points[loop[(i + 1) % loop.size()]]);
      centre += def.points[loop[i]];
    }
    n.normalize();
    planes.push_back({n, n.dot(centre) / static_cast<Real>(loop.size())});
  }
  return planes;
}

bool inside_or_on(const PolyhedronDef& def, const Vec3& p, Real tolerance) {
  for (const Plane& plane : face_planes(def))
    if (plane.normal.dot(p) - plane.offset > tolerance) return false;
  return true;
}

// A face plane of one block with every node of the other outside or on it (within tolerance).
bool separated_by_a_face(const PolyhedronDef& a, const PolyhedronDef& b, Real tolerance) {
  for (const auto& [one, other] : {std::pair{&a, &b}, std::pair{&b, &a}})
    for (const Plane& plane : face_planes(*one)) {
      bool all_outside = true;
      for (const Vec3& p : other->points)
        if (plane.normal.dot(p) - plane.offset < -tolerance) all_outside = false;
      if (all_outside) return true;
    }
  return false;
}

Real mesh_size(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices[0], hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

// Every block is a valid, convex Block; no two overlap.
void expect_valid_and_disjoint(const MeshDecomposition& d, Real size) {
  for (const PolyhedronDef& def : d.blocks) {
    Block block(def);  // throws if Block refuses it
    EXPECT_TRUE(block.convex());
  }
  for (size_t i = 0; i < d.blocks.size(); ++i)
    for (size_t j = i + 1; j < d.blocks.size(); ++j)
      EXPECT_TRUE(separated_by_a_face(d.blocks[i], d.blocks[j], 1e-9 * size))
          << "blocks " << i << " and " << j << " overlap";
}

TEST(MeshApprox, ConvexMeshIsItsHull) {
  for (const TriangleMesh& mesh : {box_mesh(), sphere_mesh(24, 12)}) {
    const MeshDecomposition d = approximate_decomposition(mesh, 32);
    ASSERT_EQ(d.blocks.size(), 1u) << mesh.source;
    EXPECT_NEAR(d.over_coverage, 0, 1e-12 * d.mesh_volume) << mesh.source;
    EXPECT_LT(d.hausdorff, 1e-9) << mesh.source;
    EXPECT_EQ(d.blocks[0].points.size(), mesh.vertices.size()) << mesh.source;
    EXPECT_TRUE(d.warnings.empty()) << mesh.source;
  }
  const MeshDecomposition box = approximate_decomposition(box_mesh(), 32);
  EXPECT_EQ(box.blocks[0].polygons.size(), 6u);  // the triangles of each side merged
  EXPECT_DOUBLE_EQ(box.mesh_volume, 3.0);
}

TEST(MeshApprox, LIsTwoBoxes) {
  const MeshDecomposition d = approximate_decomposition(testing_support::l_mesh(), 32);
  ASSERT_EQ(d.blocks.size(), 2u);
  EXPECT_NEAR(d.mesh_volume, 3.0, 1e-12);
  EXPECT_GE(d.over_coverage, -1e-12);
  EXPECT_LE(d.over_coverage, 1e-12);
  EXPECT_LT(d.hausdorff, 1e-9);
  expect_valid_and_disjoint(d, 3);
  report("l_over_coverage", d.over_coverage);
}

TEST(MeshApprox, HoledCubeKeepsItsHole) {
  const MeshDecomposition d = approximate_decomposition(testing_support::holed_cube_mesh(), 8);
  EXPECT_LE(d.blocks.size(), 8u);
  EXPECT_NEAR(d.mesh_volume, 24.0, 1e-12);
  EXPECT_NEAR(d.over_coverage, 0, 1e-12);
  EXPECT_LT(d.hausdorff, 1e-9);
  expect_valid_and_disjoint(d, 3 * std::sqrt(3.0));
  for (const PolyhedronDef& block : d.blocks)  // the hole's centre, 0.5 from its walls
    EXPECT_FALSE(inside_or_on(block, Vec3(1.5, 1.5, 1.5), 0.4));
  report("holed_cube_blocks", static_cast<Real>(d.blocks.size()));
}

// Bounds on the torus's over-coverage and Hausdorff distance. Measured: 1.71 %, and 0.64 % of
// the diagonal; for scale, 16 equal sectors would exceed the mesh by 1.45 %. The cutter is
// deterministic, so the volume bound is the measured figure rounded up to a whole per cent: a
// change that cuts worse fails here. The distance bound is the cutter's target, 2 %: the
// figure is found to 0.25 % of the diagonal (0.64 + 0.25 < 2), so it cannot fail by
// imprecision alone.
constexpr Real kTorusOverCoverage = 0.02;
constexpr Real kTorusHausdorff = 0.02;

TEST(MeshApprox, TorusBlocksAreDisjointAndKeepTheHole) {
  const TriangleMesh mesh = testing_support::torus_mesh(1, 0.3, 48, 24);
  const MeshDecomposition d = approximate_decomposition(mesh, 16);
  EXPECT_LE(d.blocks.size(), 16u);
  expect_valid_and_disjoint(d, mesh_size(mesh));
  // The hole (radius 0.7) stays open: no block reaches into a cylinder of radius 0.4 about z.
  for (Real rho : {0.0, 0.2, 0.4})
    for (int k = 0; k < 16; ++k)
      for (Real z : {-0.3, 0.0, 0.3}) {
        const Real phi = 2 * std::numbers::pi * k / 16;
        const Vec3 p(rho * std::cos(phi), rho * std::sin(phi), z);
        for (const PolyhedronDef& block : d.blocks) EXPECT_FALSE(inside_or_on(block, p, 1e-9));
      }
  report("torus_blocks", static_cast<Real>(d.blocks.size()));
  report("torus_over_coverage_percent", 100 * d.over_coverage / d.mesh_volume);
  report("torus_hausdorff_percent_of_diagonal", 100 * d.hausdorff / mesh_size(mesh));
  report("torus_seconds", d.seconds);
  // Every part of a torus has a cut into two valid blocks: a block merged from two neighbours is
  // not cut again, but that is no part without a cut.
  for (const std::string& warning : d.warnings)
    EXPECT_EQ(warning.find("no cut into two valid blocks"), std::string::npos) << warning;
  EXPECT_GE(d.over_coverage, -1e-6 * d.mesh_volume);
  EXPECT_LT(d.over_coverage, kTorusOverCoverage * d.mesh_volume);
  EXPECT_LT(d.hausdorff, kTorusHausdorff * mesh_size(mesh));
}

TEST(MeshApprox, BlocksCoverTheMesh) {
  const TriangleMesh mesh = testing_support::potato_mesh(40, 20);
  const MeshDecomposition d = approximate_decomposition(mesh, 12);
  const MeshDistance distance(mesh);
  const Real size = mesh_size(mesh);
  int inside = 0, uncovered = 0;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)
      for (int k = 0; k < 16; ++k) {
        const Vec3 p(-1.6 + 3.2 * (i + 0.5) / 16, -1.2 + 2.4 * (j + 0.5) / 16,
                     -1.0 + 2.0 * (k + 0.5) / 16);
        if (distance.signed_distance(p) > 0) continue;
        ++inside;
        if (std::none_of(d.blocks.begin(), d.blocks.end(), [&](const PolyhedronDef& b) {
              return inside_or_on(b, p, 1e-4 * size);
            }))
          ++uncovered;
      }
  EXPECT_GT(inside, 500);
  EXPECT_EQ(uncovered, 0);
  expect_valid_and_disjoint(d, size);
  report("potato_small_over_coverage_percent", 100 * d.over_coverage / d.mesh_volume);
}

// The search that stops at the first triangle within a bar gives the signed distance wherever
// that is above the bar, and the bar or the distance elsewhere; so a block's sampled distance, which keeps the
// largest so far as its bar, is the largest of the plain distances at the same points.
TEST(MeshDistance, StoppingAtABarKeepsTheLargestDistance) {
  const TriangleMesh mesh = testing_support::potato_mesh(40, 20);
  const MeshDistance distance(mesh);
  const Real size = mesh_size(mesh);
  int above = 0, below = 0;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) {
        const Vec3 p(-2.0 + 4.0 * (i + 0.5) / 10, -1.6 + 3.2 * (j + 0.5) / 10,
                     -1.4 + 2.8 * (k + 0.5) / 10);
        const Real exact = distance.signed_distance(p);
        for (const Real bar : {Real(0), 0.02 * size, 0.1 * size}) {
          const Real stopped = distance.signed_distance_above(p, bar);
          if (exact > bar) {
            EXPECT_EQ(stopped, exact) << p.transpose() << " bar " << bar;
            ++above;
          } else {
            EXPECT_TRUE(stopped == bar || stopped == exact) << p.transpose() << " bar " << bar;
            ++below;
          }
        }
      }
  EXPECT_GT(above, 500);
  EXPECT_GT(below, 500);

  // The potato's hull strays outside it over its hollows.
  const auto hull = hull_polyhedron(mesh.vertices);
  ASSERT_TRUE(hull);
  Real largest = 0;
  for (const Vec3& p : hull->points) largest = std::max(largest, distance.signed_distance(p));
  for (const auto& loop : hull->polygons)
    for (size_t k = 1; k + 1 < loop.size(); ++k) {
      const Vec3 &a = hull->points[loop[0]], &b = hull->points[loop[k]],
                 &c = hull->points[loop[k + 1]];
      for (const Vec3& p :
           {Vec3((a + b + c) / 3), Vec3((a + b) / 2), Vec3((b + c) / 2), Vec3((c + a) / 2)})
        largest = std::max(largest, distance.signed_distance(p));
    }
  EXPECT_GT(largest, 1e-3 * size);
  EXPECT_EQ(sampled_outside_distance(distance, *hull), largest);
}

TEST(MeshApprox, MaxBlocksIsRespected) {
  const TriangleMesh mesh = testing_support::torus_mesh(1, 0.3, 48, 24);
  for (int max_blocks : {1, 2, 5}) {
    const MeshDecomposition d = approximate_decomposition(mesh, max_blocks);
    EXPECT_EQ(static_cast<int>(d.blocks.size()), max_blocks);
    EXPECT_FALSE(d.warnings.empty());  // the torus is still concave
  }
  EXPECT_THROW(approximate_decomposition(mesh, 0), MeshError);
}

TEST(MeshApprox, SameBlocksEveryRunAndThreadCount) {
  const TriangleMesh mesh = testing_support::potato_mesh(24, 12);
  const int threads = max_threads();
  set_threads(1);
  const MeshDecomposition one = approximate_decomposition(mesh, 6);
  set_threads(std::max(threads, 2));
  const MeshDecomposition two = approximate_decomposition(mesh, 6);
  const MeshDecomposition again = approximate_decomposition(mesh, 6);
  set_threads(threads);
  for (const MeshDecomposition* other : {&two, &again}) {
    ASSERT_EQ(one.blocks.size(), other->blocks.size());
    for (size_t b = 0; b < one.blocks.size(); ++b) {
      EXPECT_EQ(one.blocks[b].polygons, other->blocks[b].polygons);
      ASSERT_EQ(one.blocks[b].points.size(), other->blocks[b].points.size());
      for (size_t p = 0; p < one.blocks[b].points.size(); ++p)
        EXPECT_EQ(one.blocks[b].points[p], other->blocks[b].points[p]);  // to the bit
    }
    EXPECT_EQ(one.over_coverage, other->over_coverage);
    EXPECT_EQ(one.hausdorff, other->hausdorff);
  }
}

// The benchmark's stand-ins for scanned meshes are meshes a user could load: closed, outward,
// free of self-intersections (checked here at a low resolution of the same shapes).
TEST(MeshApprox, ScanLikeMeshesPassTheChecks) {
  for (TriangleMesh mesh : {testing_support::bumpy_torus_mesh(60, 16),
                            testing_support::potato_mesh(40, 20),
                            testing_support::knot_mesh(120, 16)}) {
    const MeshCheck check = check_mesh(mesh);
    EXPECT_TRUE(check.closed) << mesh.source;
    EXPECT_FALSE(check.turned) << mesh.source;
    EXPECT_GT(check.volume, 0) << mesh.source;
  }
  EXPECT_EQ(testing_support::bumpy_torus_mesh().faces.size(), 75000u);
  EXPECT_EQ(testing_support::potato_mesh().faces.size(), 75000u);
  EXPECT_EQ(testing_support::knot_mesh().faces.size(), 75000u);
}

// Three planes through a cube's centre: the corner at the centre is inside the solid and on no
// edge of the mesh, found only where the caps' common lines meet; volumes add up exactly.
TEST(MeshApproxCut, CornersInsideTheSolidAndVolumes) {
  const TriangleMesh cube = testing_support::extruded_mesh(
      {{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}}, {{0, 1, 2}, {0, 2, 3}}, 2.0, "cube");
  const MeshPart whole = whole_mesh_part(cube, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(whole.volume, 8.0);
  auto halves = cut_part(whole, {Vec3::UnitX(), 0}, true);
  auto quarters = cut_part(halves[0], {Vec3::UnitY(), 0}, true);
  auto eighths = cut_part(quarters[0], {Vec3::UnitZ(), 0}, true);
  for (const MeshPart& eighth : eighths) {
    EXPECT_DOUBLE_EQ(eighth.volume, 1.0);
    EXPECT_NE(std::find(eighth.points.begin(), eighth.points.end(), Vec3::Zero()),
              eighth.points.end());
    EXPECT_EQ(eighth.points.size(), 8u);  // a unit cube's corners
  }
  EXPECT_DOUBLE_EQ(halves[1].volume + quarters[1].volume, 6.0);

  // A torus cut by planes in general position: the sides' volumes add up to the whole.
  const MeshPart torus = whole_mesh_part(testing_support::torus_mesh(1, 0.3, 48, 24), Vec3::Zero());
  auto a = cut_part(torus, {Vec3(1, 2, 0.5).normalized(), 0.1}, true);
  auto b = cut_part(a[0], {Vec3(-0.3, 1, 1).normalized(), -0.05}, true);
  auto c = cut_part(b[1], {Vec3(0.7, -0.2, 1).normalized(), 0.02}, true);
  EXPECT_NEAR(a[1].volume + b[0].volume + c[0].volume + c[1].volume, torus.volume,
              1e-12 * torus.volume);
}

// Unit cubes [x, x+1] x [y, y+1] x [0, 1] joined face to face into one surface.
TriangleMesh cubes_mesh(const std::vector<std::array<int, 2>>& cells, const std::string& name) {
  std::vector<PolyhedronDef> cubes;
  for (const auto& [x, y] : cells) {
    PolyhedronDef cube = box(Vec3::Ones());
    for (Vec3& p : cube.points) p += Vec3(x + 0.5, y + 0.5, 0.5);
    cubes.push_back(std::move(cube));
  }
  return testing_support::union_surface(cubes, name);
}

TEST(MeshApproxCut, PiecesOfACutPart) {
  // A slab across the torus holds two arcs of its tube, apart.
  const MeshPart torus = whole_mesh_part(testing_support::torus_mesh(1, 0.3, 48, 24), Vec3::Zero());
  const MeshPart slab =
      cut_part(cut_part(torus, {Vec3::UnitX(), 0.5}, true)[0], {-Vec3::UnitX(), 0.5}, true)[0];
  const auto arcs = connected_components(slab);
  ASSERT_EQ(arcs.size(), 2u);
  EXPECT_NEAR(arcs[0].volume + arcs[1].volume, slab.volume, 1e-14);
  EXPECT_NEAR(arcs[0].volume, arcs[1].volume, 1e-12);  // the torus is symmetric in y
  EXPECT_NEAR(arcs[0].volume, part_volume(arcs[0]), 1e-15);
  EXPECT_TRUE(hulls_apart(arcs[0].points, arcs[1].points, 1e-6));
  EXPECT_EQ(separate_groups(slab, 1e-3 * slab.volume, 1e-6).size(), 2u);
  // Each arc's corners are its own: together they are the slab's.
  EXPECT_EQ(arcs[0].points.size() + arcs[1].points.size(), slab.points.size());

  // A slab across the holed cube's hole falls into two bars of 0.6 x 1 x 3 ...
  const MeshPart cube = whole_mesh_part(testing_support::holed_cube_mesh(), Vec3::Zero());
  const MeshPart across =
      cut_part(cut_part(cube, {Vec3::UnitX(), 1.8}, true)[0], {-Vec3::UnitX(), -1.2}, true)[0];
  const auto bars = connected_components(across);
  ASSERT_EQ(bars.size(), 2u);
  for (const MeshPart& bar : bars) EXPECT_NEAR(bar.volume, 1.8, 1e-14);
  // ... while a slab along it is one ring: its inner and outer walls meet only across the caps,
  // where the hole's loop lies inside the outer one.
  const MeshPart ring =
      cut_part(cut_part(cube, {Vec3::UnitZ(), 2}, true)[0], {-Vec3::UnitZ(), -1}, true)[0];
  EXPECT_NEAR(ring.volume, 8, 1e-14);
  ASSERT_EQ(connected_components(ring).size(), 1u);

  // Hulls that pass through each other are not apart, nor are hulls that touch.
  const std::vector<Vec3> a{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  std::vector<Vec3> b = a;
  for (Vec3& p : b) p += Vec3(0.5, 0.5, 0.5);
  EXPECT_FALSE(hulls_apart(a, b, 1e-9));
  for (Vec3& p : b) p += Vec3(-0.5, -0.5, 1.5);  // b's base on a's apex
  EXPECT_FALSE(hulls_apart(a, b, 1e-9));
  for (Vec3& p : b) p += Vec3(0, 0, 1e-3);
  EXPECT_TRUE(hulls_apart(a, b, 1e-9));
}

TEST(MeshApprox, PiecesThatACutLeavesBecomeBlocks) {
  // A U with legs two cubes long: cut at the top of its base, the upper side falls into the two
  // legs, three boxes with nothing over.
  const TriangleMesh u = cubes_mesh({{0, 0}, {1, 0}, {2, 0}, {0, 1}, {2, 1}, {0, 2}, {2, 2}}, "U");
  const MeshDecomposition d = approximate_decomposition(u, 3);
  EXPECT_EQ(d.blocks.size(), 3u);
  EXPECT_NEAR(d.mesh_volume, 7, 1e-12);
  EXPECT_NEAR(d.over_coverage, 0, 1e-12);
  expect_valid_and_disjoint(d, mesh_size(u));

  // Shells apart start as a block each; with one block allowed, one hull covers both.
  const TriangleMesh shells = cubes_mesh({{0, 0}, {2, 0}, {1, 3}}, "three cubes");
  const MeshDecomposition apart = approximate_decomposition(shells, 3);
  EXPECT_EQ(apart.blocks.size(), 3u);
  EXPECT_NEAR(apart.over_coverage, 0, 1e-12);
  expect_valid_and_disjoint(apart, mesh_size(shells));
  const MeshDecomposition one = approximate_decomposition(shells, 1);
  ASSERT_EQ(one.blocks.size(), 1u);
  EXPECT_GT(one.over_coverage, 1.0);  // the hull of the three spans the gaps between them
}

}  // namespace test_mesh_approximate
}  // namespace tem

namespace tem::test_mesh_approximate {

// The tree of a torus grown greedily to `leaves` cells, its planes moved or not.
std::vector<approximate::Leaf> torus_leaves(const TriangleMesh& mesh, const MeshDistance& distance,
                                            int leaves, bool move_planes) {
  using namespace approximate;
  const Real size = mesh_size(mesh);
  Leaf root;
  root.part = whole_mesh_part(mesh, Vec3::Zero());
  root.block = *hull_block(root.part.points, kWeld * radius_about_mean(root.part.points));
  root.hull_volume = hull_volume(root.part.points);
  const Real volume = root.part.volume;
  const Context context{&distance, 2, kDistancePrecision * size, 1e-9 * volume, false};
  root.distance = largest_outside_distance(distance, {root.block}, context.precision);
  CutTree tree(std::move(root), context, leaves, kConcavityFraction * volume,
               kDistanceGoal * size, 1e-9 * size, kSmallestMoveGain * volume);
  tree.grow();
  if (move_planes) {
    EXPECT_TRUE(tree.refine_planes());
  }
  return tree.take_leaves();
}

// Moving the planes of a grown tree (CutTree::refine_planes) lowers the sum of its blocks'
// volumes, and its parts still make up the solid exactly: no piece of the mesh is lost or
// doubled, and the blocks are valid and apart.
TEST(MeshApproxTree, MovingPlanesLowersTheHullsAndKeepsTheSolid) {
  TriangleMesh mesh = testing_support::torus_mesh(1, 0.3, 48, 24);
  const MeshDistance distance(mesh);
  const Real size = mesh_size(mesh);
  const Real volume = check_mesh(mesh).volume;
  const auto grown = torus_leaves(mesh, distance, 8, false);
  const auto moved = torus_leaves(mesh, distance, 8, true);
  ASSERT_EQ(grown.size(), 8u);
  ASSERT_EQ(moved.size(), 8u);
  Real grown_hulls = 0, moved_hulls = 0, moved_parts = 0;
  MeshDecomposition d;
  for (const auto& leaf : grown) grown_hulls += leaf.hull_volume;
  for (const auto& leaf : moved) {
    moved_hulls += leaf.hull_volume;
    moved_parts += leaf.part.volume;
    d.blocks.push_back(leaf.block);
  }
  report("torus_8_over_coverage_grown_percent", 100 * (grown_hulls / volume - 1));
  report("torus_8_over_coverage_moved_percent", 100 * (moved_hulls / volume - 1));
  EXPECT_NEAR(moved_parts, volume, 1e-9 * volume);
  EXPECT_LT(moved_hulls, grown_hulls - approximate::kSmallestMoveGain * volume);
  expect_valid_and_disjoint(d, size);
}

}  // namespace tem::test_mesh_approximate
