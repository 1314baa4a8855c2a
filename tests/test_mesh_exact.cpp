// The exact cut of a mesh into convex blocks (CGAL's Nef-polyhedron convex decomposition): the
// blocks are convex, do not overlap and have the mesh's own volume, centre and second moment
// (from its surface, independently of any block); the paper's ring cut from its mesh has the
// ring primitive's mass properties to round-off; CAD-like solids of revolution (spools),, also with float coordinates as read from a file, are cut; bad meshes give MeshError.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"
#include "mass/mass_properties.hpp"
#include "mass/surface_integrals.hpp"
#include "mesh/mesh_decomposition.hpp"
#include "support/mesh_shapes.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_mesh_exact {

using testing_support::report;

constexpr Real kExact = 1e-9;  // relative: the blocks' vertices are CGAL's exact ones, rounded

Real size_of(const TriangleMesh& mesh) {
  Vec3 low = mesh.vertices.front(), high = low;
  for (const Vec3& p : mesh.vertices) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return (high - low).norm();
}

MassProperties combined(const std::vector<Block>& blocks) {
  std::vector<PlacedMass> parts;
  for (const Block& b : blocks)
    parts.push_back({block_mass_properties(b, 1.0), Mat3::Identity(), b.centroid_in_input()});
  return combine(parts);
}

// The blocks' nodes in the frame of the mesh.
std::vector<Vec3> nodes_in_input(const Block& b) {
  std::vector<Vec3> nodes;
  for (const Vec3& n : b.nodes()) nodes.push_back(n + b.centroid_in_input());
  return nodes;
}

// How deep two convex blocks overlap: the least overlap of their projections over the axes of
// the separating-axis theorem for convex polyhedra (face normals of each, and the cross products
// of their edges). 0 or less when some axis separates them.
Real overlap_depth(const Block& a, const Block& b) {
  const std::vector<Vec3> pa = nodes_in_input(a), pb = nodes_in_input(b);
  std::vector<Vec3> axes;
  for (const Block* block : {&a, &b})
    for (const Polygon& p : block->polygons()) axes.push_back(p.normal);
  for (const Edge& ea : a.edges())
    for (const Edge& eb : b.edges()) {
      const Vec3 da = a.nodes()[ea.nodes[1]] - a.nodes()[ea.nodes[0]];
      const Vec3 db = b.nodes()[eb.nodes[1]] - b.nodes()[eb.nodes[0]];
      const Vec3 n = da.cross(db);
      if (n.norm() > 1e-9 * da.norm() * db.norm()) axes.push_back(n.normalized());
    }
  Real depth = std::numeric_limits<Real>::infinity();
  for (const Vec3& axis : axes) {
    Real lo_a = std::numeric_limits<Real>::infinity(), hi_a = -lo_a, lo_b = lo_a, hi_b = -lo_a;
    for (const Vec3& p : pa) {
      lo_a = std::min(lo_a, axis.dot(p));
      hi_a = std::max(hi_a, axis.dot(p));
    }
    for (const Vec3& p : pb) {
      lo_b = std::min(lo_b, axis.dot(p));
      hi_b = std::max(hi_b, axis.dot(p));
    }
    depth = std::min(depth, std::min(hi_a - lo_b, hi_b - lo_a));
  }
  return depth;
}

struct Cut {
  MeshDecomposition decomposition;
  std::vector<Block> blocks;
};

// Cuts `mesh` exactly and checks the blocks against the mesh's own surface integrals; reports
// the block count, the time and the errors under `name`.
Cut cut_and_check(const TriangleMesh& mesh, const std::string& name,
                  int reflex_edges_per_part = kReflexEdgesPerPart) {
  Cut cut;
  cut.decomposition = exact_decomposition(mesh, reflex_edges_per_part);
  const MeshDecomposition& d = cut.decomposition;
  for (const PolyhedronDef& def : d.blocks) cut.blocks.emplace_back(def);
  for (const Block& b : cut.blocks) EXPECT_TRUE(b.convex()) << name;

  const MassProperties surface = surface_mass_properties(corner_triangles(mesh));
  const MassProperties blocks = combined(cut.blocks);
  const Real size = size_of(mesh);
  const Real volume_error = std::abs(blocks.volume - surface.volume) / surface.volume;
  const Real centre_error = (blocks.center - surface.center).norm() / size;
  const Real moment_error = (blocks.second_moment - surface.second_moment).cwiseAbs().maxCoeff() /
                            surface.second_moment.cwiseAbs().maxCoeff();
  EXPECT_LE(volume_error, kExact) << name;
  EXPECT_LE(centre_error, kExact) << name;
  EXPECT_LE(moment_error, kExact) << name;
  EXPECT_NEAR(d.mesh_volume, surface.volume, kExact * surface.volume) << name;
  EXPECT_NEAR(d.blocks_volume, blocks.volume, kExact * surface.volume) << name;

  Real deepest = 0;
  for (size_t i = 0; i < cut.blocks.size(); ++i)
    for (size_t j = i + 1; j < cut.blocks.size(); ++j) {
      const Block &a = cut.blocks[i], &b = cut.blocks[j];
      const bool apart = ((a.bounds_min() + a.centroid_in_input()).array() >
                          (b.bounds_max() + b.centroid_in_input()).array())
                             .any() ||
                         ((b.bounds_min() + b.centroid_in_input()).array() >
                          (a.bounds_max() + a.centroid_in_input()).array())
                             .any();
      if (!apart) deepest = std::max(deepest, overlap_depth(a, b));
    }
  EXPECT_LE(deepest, kExact * size) << name << ": two blocks overlap";

  for (const std::string& w : d.warnings) std::cout << "[ warning  ] " << w << "\n";
  report("exact." + name + ".faces", static_cast<Real>(mesh.faces.size()));
  report("exact." + name + ".blocks", static_cast<Real>(cut.blocks.size()));
  report("exact." + name + ".merged_slivers", d.merged_slivers);
  report("exact." + name + ".reflex_edges", d.reflex_edges);
  report("exact." + name + ".parts", d.parts);
  report("exact." + name + ".seconds", d.seconds);
  report("exact." + name + ".volume_error", volume_error);
  report("exact." + name + ".centre_error", centre_error);
  report("exact." + name + ".second_moment_error", moment_error);
  report("exact." + name + ".deepest_overlap", deepest / size);
  return cut;
}

TEST(MeshExact, LShapeIsTwoBlocks) {
  const Cut cut = cut_and_check(testing_support::l_mesh(), "L");
  EXPECT_EQ(cut.blocks.size(), 2u);
  EXPECT_TRUE(cut.decomposition.warnings.empty());
  // Its one reflex edge is the inner corner; the diagonals of its flat faces are not reflex.
  EXPECT_EQ(cut.decomposition.reflex_edges, 1);
  EXPECT_EQ(cut.decomposition.parts, 1);
}

TEST(MeshExact, HoledCubeKeepsItsHole) {
  const Cut cut = cut_and_check(testing_support::holed_cube_mesh(), "holed_cube");
  EXPECT_GE(cut.blocks.size(), 4u);
  EXPECT_EQ(cut.decomposition.reflex_edges, 4);  // the hole's four edges along its axis
  EXPECT_NEAR(cut.decomposition.blocks_volume, 24.0, 24.0 * kExact);
}

TEST(MeshExact, TorusBlocksFillIt) {
  cut_and_check(testing_support::torus_mesh(1.0, 0.3, 16, 8), "torus_16x8");
}

// A spur gear ring of `teeth` teeth (outer radius 1, root 0.85, bore 0.5, width 0.3): flat faces
// and many reflex edges, like a part from CAD. 32 faces per tooth.
TriangleMesh gear_mesh(int teeth) {
  const int n = 4 * teeth;
  std::vector<std::array<Real, 2>> outer, bore;
  for (int i = 0; i < n; ++i) {
    const Real angle = 2 * std::numbers::pi * i / n;
    const Real r = (i % 4 == 1 || i % 4 == 2) ? 1.0 : 0.85;
    outer.push_back({r * std::cos(angle), r * std::sin(angle)});
  }
  // The bore runs clockwise: its point k lies at the angle of outer point (n - k) % n.
  for (int k = 0; k < n; ++k) {
    const Real angle = 2 * std::numbers::pi * ((n - k) % n) / n;
    bore.push_back({0.5 * std::cos(angle), 0.5 * std::sin(angle)});
  }
  auto below = [&](int i) { return n + (n - i % n) % n; };  // bore point at outer point i's angle
  std::vector<std::array<int, 3>> cap;
  for (int i = 0; i < n; ++i) {
    cap.push_back({i, (i + 1) % n, below(i + 1)});
    cap.push_back({i, below(i + 1), below(i)});
  }
  return testing_support::extruded_mesh({outer, bore}, cap, 0.3, "gear");
}

// A part as from CAD: flat faces, a bore, and two reflex edges at every tooth.
TEST(MeshExact, GearRingIsCut) {
  const Cut cut = cut_and_check(gear_mesh(8), "gear_8");
  // Two at each of the 8 teeth, and the bore's 32 edges along its axis.
  EXPECT_EQ(cut.decomposition.reflex_edges, 2 * 8 + 32);
  EXPECT_EQ(cut.decomposition.parts, 1);
}

// Large meshes are cut by planes into parts of a few reflex edges each before CGAL decomposes
// them (docs/meshes.md); here the gear ring into parts of at most 8 and of at most 1. The blocks
// must still be convex, not overlap, and have the mesh's volume, centre and second moment
// (cut_and_check), as the whole mesh's decomposition does. (The torus and the paper's ring are
// cut in two parts by default.)
TEST(MeshExact, PartsCutByPlanesFillTheMesh) {
  const Cut whole = cut_and_check(gear_mesh(8), "gear_8");
  for (const int per_part : {8, 1}) {
    const std::string name = "gear_8_in_parts_of_" + std::to_string(per_part);
    const Cut parts = cut_and_check(gear_mesh(8), name, per_part);
    EXPECT_GE(parts.decomposition.parts, (2 * 8 + 32) / per_part) << name;
    EXPECT_EQ(parts.decomposition.reflex_edges, whole.decomposition.reflex_edges) << name;
    EXPECT_NEAR(parts.decomposition.blocks_volume, whole.decomposition.blocks_volume,
                1e-14 * whole.decomposition.blocks_volume)
        << name;
  }
}

// The ring cut from its mesh against the ring primitive's 16 blocks (built from the same nodes):
// the issue asks for the same volume, centre and second moment to 1e-12.
TEST(MeshExact, PaperRingMatchesTheRingPrimitive) {
  const Cut cut = cut_and_check(testing_support::paper_ring_mesh(), "paper_ring");
  std::vector<Block> primitive;
  for (const PolyhedronDef& def : polygonal_ring(16, 6, 0.3, 0.05, 16, Axis::z, false))
    primitive.emplace_back(def);
  const MassProperties ring = combined(primitive), mesh = combined(cut.blocks);
  const Real volume_error = std::abs(mesh.volume - ring.volume) / ring.volume;
  const Real centre_error = (mesh.center - ring.center).norm() / 0.35;  // the ring's outer radius
  const Real moment_error = (mesh.second_moment - ring.second_moment).cwiseAbs().maxCoeff() /
                            ring.second_moment.cwiseAbs().maxCoeff();
  EXPECT_LE(volume_error, 1e-12);
  EXPECT_LE(centre_error, 1e-12);
  EXPECT_LE(moment_error, 1e-12);
  report("exact.paper_ring.vs_primitive.volume_error", volume_error);
  report("exact.paper_ring.vs_primitive.centre_error", centre_error);
  report("exact.paper_ring.vs_primitive.second_moment_error", moment_error);
}

// CAD-like solids of revolution that CGAL cuts into pieces with corners bent by the
// mesh's rounding (its cones' quads are planar only to rounding). Every one must be cut. With
// double vertices the bends are 1e-16 and the blocks keep the mesh's volume to 1e-12.
struct RevolvedPart {
  std::string name;
  TriangleMesh mesh;
};

std::vector<RevolvedPart> revolved_parts() {
  using testing_support::revolved_mesh;
  using testing_support::spool_mesh;
  using Profile = std::vector<std::array<Real, 2>>;  // (r, z), counter-clockwise
  const Profile pulley{{0.2, 0}, {1, 0}, {1, 0.3}, {0.7, 0.5}, {1, 0.7}, {1, 1}, {0.2, 1}};
  const Profile bushing{{0.5, 0}, {1, 0}, {1, 0.15}, {0.7, 0.15}, {0.7, 1.2}, {0.5, 1.2}};
  const Profile shaft{{0, 0},     {0.3, 0},    {0.3, 1},    {0.5, 1},
                      {0.5, 1.5}, {0.25, 1.5}, {0.25, 2.5}, {0, 2.5}};
  const Profile washers{{0.3, 0},   {1, 0},     {1, 0.1},   {0.6, 0.1}, {0.6, 0.2},
                        {0.9, 0.2}, {0.9, 0.3}, {0.5, 0.3}, {0.5, 0.4}, {0.3, 0.4}};
  return {
      {"spool_16", spool_mesh(16, 0, 0, 0)},
      {"spool_16_bore", spool_mesh(16, 0.2, 0, 0)},
      {"spool_16_chamfer", spool_mesh(16, 0, 0.03, 0)},
      {"spool_16_bore_chamfer", spool_mesh(16, 0.2, 0.03, 0)},
      {"spool_16_fillet", spool_mesh(16, 0, 0, 0.1)},
      {"spool_16_fillet_thick_top", spool_mesh(16, 0, 0, 0.1, 0.05, 0.2)},
      {"pulley_16", revolved_mesh(pulley, 16, "pulley")},
      {"flanged_bushing_16", revolved_mesh(bushing, 16, "bushing")},
      {"stepped_shaft_16", revolved_mesh(shaft, 16, "shaft")},
      {"washer_stack_16", revolved_mesh(washers, 16, "washers")},
  };
}

Real volume_error(const Cut& cut, const TriangleMesh& mesh) {
  const Real surface = surface_mass_properties(corner_triangles(mesh)).volume;
  return std::abs(combined(cut.blocks).volume - surface) / surface;
}

TEST(MeshExact, RevolvedPartsAreCut) {
  for (const RevolvedPart& part : revolved_parts()) {
    const Cut cut = cut_and_check(part.mesh, part.name);
    EXPECT_LE(volume_error(cut, part.mesh), 1e-12) << part.name;
  }
}

// The same parts as `tem mesh` reads them from a file: vertices rounded to 32-bit floats, so
// cones' quads bend by about 1e-8 and CGAL's pieces have corners bent by less than Block's
// tolerance (a Block refuses such corners). Their blocks leave out those
// corners; the volume this changes is bounded by the cutter (1e-9 of the mesh's, kExact here).
TEST(MeshExact, RevolvedPartsReadAsFloatsAreCut) {
  for (const RevolvedPart& part : revolved_parts())
    cut_and_check(testing_support::rounded_to_float(part.mesh), part.name + "_float");
}

// The same parts as written with 6 significant digits (an OBJ exporter's "%g"): bends of 1e-6
// are well above Block's tolerance, but cuts meet mesh edges a rounding's width from vertices.
TEST(MeshExact, RevolvedPartsWithSixDigitsAreCut) {
  for (const RevolvedPart& part : revolved_parts())
    cut_and_check(testing_support::rounded_to_digits(part.mesh, 6), part.name + "_6digits");
}

TEST(MeshExact, BadMeshesGiveMeshError) {
  TriangleMesh open = testing_support::l_mesh();
  open.faces.pop_back();
  EXPECT_THROW(exact_decomposition(open), MeshError);

  TriangleMesh inward = testing_support::l_mesh();
  for (auto& f : inward.faces) std::swap(f[1], f[2]);
  EXPECT_THROW(exact_decomposition(inward), MeshError);

  TriangleMesh stray = testing_support::l_mesh();
  stray.faces[3][1] = 1000;
  EXPECT_THROW(exact_decomposition(stray), MeshError);

  TriangleMesh repeated = testing_support::l_mesh();
  repeated.faces[3][1] = repeated.faces[3][0];
  EXPECT_THROW(exact_decomposition(repeated), MeshError);

  TriangleMesh not_finite = testing_support::l_mesh();
  not_finite.vertices[2].x() = std::numeric_limits<Real>::quiet_NaN();
  EXPECT_THROW(exact_decomposition(not_finite), MeshError);

  EXPECT_THROW(exact_decomposition(TriangleMesh{}), MeshError);

  // Two L shapes through each other: closed and oriented, but their faces cross.
  TriangleMesh crossing = testing_support::l_mesh();
  const TriangleMesh second = testing_support::l_mesh();
  const int first = static_cast<int>(crossing.vertices.size());
  for (const Vec3& v : second.vertices) crossing.vertices.push_back(v + Vec3(0.5, 0.25, 0.125));
  for (const auto& f : second.faces)
    crossing.faces.push_back({f[0] + first, f[1] + first, f[2] + first});
  try {
    exact_decomposition(crossing);
    ADD_FAILURE() << "crossing faces were not reported";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("L: faces"), std::string::npos) << e.what();
  }
}

// CAD-sized meshes (about 1,000 faces): the target is an exact cut in seconds. Too slow
// for the unit suite (and its sanitizer build); run with --gtest_also_run_disabled_tests.
TEST(MeshExact, DISABLED_ThousandFaceMeshesTiming) {
  cut_and_check(gear_mesh(32), "gear_32");
  cut_and_check(testing_support::torus_mesh(1.0, 0.3, 32, 16), "torus_32x16");
  const TriangleMesh spool = testing_support::spool_mesh(24, 0.2, 0.02, 0.08, 0.08, 0.15);
  const Cut cut = cut_and_check(spool, "spool_24_bore_chamfer_fillet");
  EXPECT_LE(volume_error(cut, spool), 1e-12);
  cut_and_check(testing_support::rounded_to_float(spool), "spool_24_bore_chamfer_fillet_float");
}

}  // namespace test_mesh_exact
}  // namespace tem
