// Reading mesh files (every format, written here from meshes built in code) and checking meshes:
// what passes, with which volume, and the message of each kind of failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "geometry/primitives.hpp"
#include "mass/surface_integrals.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/mesh_reader.hpp"
#include "support/mesh_shapes.hpp"

namespace tem {
namespace {

using namespace tem::testing_support;
namespace fs = std::filesystem;

// A directory of this test's own, under the test framework's temporary directory.
fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) /
                       ("tem_mesh_" + std::to_string(::getpid()) + "_" + info->test_suite_name() +
                        "_" + info->name());
  fs::create_directories(dir);
  return dir;
}

// Volume from Eberly's surface integrals: a route that shares no code with check_mesh().
Real surface_volume(const TriangleMesh& mesh) {
  std::vector<std::array<Vec3, 3>> triangles;
  for (const auto& f : mesh.faces)
    triangles.push_back({mesh.vertices[f[0]], mesh.vertices[f[1]], mesh.vertices[f[2]]});
  return surface_mass_properties(triangles).volume;
}

// The mesh as a reader of 32-bit floats sees it: Debian's assimp is built without
// ASSIMP_DOUBLE_PRECISION, so every format, ASCII and double-valued ones too, arrives as floats.
// The float goes through a volatile: g++ 12.2's SLP vectorizer at -O2 drops the double -> float
// -> double round trip of this loop altogether (a compiler bug).
TriangleMesh rounded_to_float(TriangleMesh mesh) {
  for (Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      const volatile float rounded = static_cast<float>(v[k]);
      v[k] = rounded;
    }
  return mesh;
}

TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi, const std::string& source = "box") {
  TriangleMesh mesh = extruded_mesh({{{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}}},
                                    {{0, 1, 2}, {0, 2, 3}}, hi.z() - lo.z(), source);
  for (Vec3& v : mesh.vertices) v.z() += lo.z();
  return mesh;
}

// Both meshes' faces in one mesh (b's vertices renumbered after a's).
TriangleMesh combined(TriangleMesh a, const TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto f : b.faces) a.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  return a;
}

TriangleMesh inverted(TriangleMesh mesh) {
  for (auto& f : mesh.faces) std::swap(f[1], f[2]);
  return mesh;
}

// The message of the MeshError that check_mesh() throws (fails the test if none is thrown).
std::string check_error(TriangleMesh mesh) {
  try {
    check_mesh(mesh);
  } catch (const MeshError& e) {
    return e.what();
  }
  ADD_FAILURE() << "check_mesh accepted " << mesh.source;
  return "";
}

template <class Read>
std::string read_error(Read read) {
  try {
    read();
  } catch (const MeshError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the mesh was read without an error";
  return "";
}

std::string edge_name(int a, int b) {
  return "edge " + std::to_string(std::min(a, b)) + "-" + std::to_string(std::max(a, b));
}

struct Format {
  std::string extension;
  void (*write)(const TriangleMesh&, const std::string&);
};

const std::vector<Format> kFormats = {
    {"obj", write_obj},          {"off", write_off},       {"ply", write_ply_ascii},
    {"ply", write_ply_binary},   {"stl", write_stl_ascii}, {"stl", write_stl_binary}};

TriangleMesh paper_ring_expected(Real* volume) {
  *volume = 0;
  for (const PolyhedronDef& def : polygonal_ring(16, 6, 0.3, 0.05, 16, Axis::z, false))
    *volume += Block(def).volume();
  return paper_ring_mesh();
}

// ---------------------------------------------------------------------------------------------
// Reading

// Every format gives back the mesh: the same numbers of vertices (STL's separate corners are
// welded) and faces, and the volume of the mesh rounded to floats (the reader's precision).
TEST(MeshRead, EveryFormatGivesBackTheMesh) {
  const fs::path dir = scratch_dir();
  Real ring_volume;
  const std::vector<TriangleMesh> meshes = {l_mesh(), holed_cube_mesh(), torus_mesh(1, 0.3, 48, 24),
                                            paper_ring_expected(&ring_volume)};
  int file = 0;
  for (const TriangleMesh& original : meshes)
    for (const Format& format : kFormats) {
      const std::string path = (dir / ("mesh" + std::to_string(file++) + "." + format.extension)).string();
      format.write(original, path);
      SCOPED_TRACE(original.source + " as " + path);
      TriangleMesh mesh = read_mesh_file(path);
      EXPECT_EQ(mesh.source, path);
      EXPECT_EQ(mesh.vertices.size(), original.vertices.size());
      EXPECT_EQ(mesh.faces.size(), original.faces.size());
      const MeshCheck check = check_mesh(mesh);
      EXPECT_TRUE(check.closed);
      EXPECT_FALSE(check.turned);
      EXPECT_TRUE(check.warnings.empty());
      const Real expected = surface_volume(rounded_to_float(original));
      EXPECT_NEAR(check.volume, expected, 1e-12 * expected);
    }
}

// L and holed cube have integer coordinates, which floats hold exactly.
TEST(MeshRead, IntegerMeshesKeepTheirExactVolume) {
  const fs::path dir = scratch_dir();
  for (const Format& format : kFormats) {
    const std::string path = (dir / ("holed." + format.extension)).string();
    format.write(holed_cube_mesh(), path);
    TriangleMesh mesh = read_mesh_file(path);
    EXPECT_NEAR(check_mesh(mesh).volume, 24, 1e-12 * 24) << path;
  }
}

TEST(MeshRead, ScaleMultipliesVolumeByItsCube) {
  const fs::path dir = scratch_dir();
  const std::string path = (dir / "l.obj").string();
  write_obj(l_mesh(), path);
  TriangleMesh mesh = read_mesh_file(path, 0.01);
  const Real volume = check_mesh(mesh).volume;
  EXPECT_NEAR(volume, 3e-6, 1e-12 * 3e-6);
  Real largest_x = 0;
  for (const Vec3& v : mesh.vertices) largest_x = std::max(largest_x, v.x());
  EXPECT_EQ(largest_x, 0.02);
}

TEST(MeshRead, ExtensionIsCaseInsensitive) {
  const fs::path dir = scratch_dir();
  const std::string path = (dir / "L.OBJ").string();
  write_obj(l_mesh(), path);
  EXPECT_EQ(read_mesh_file(path).faces.size(), l_mesh().faces.size());
}

TEST(MeshRead, MissingFileIsAnError) {
  const std::string path = (scratch_dir() / "nothing.stl").string();
  const std::string message = read_error([&] { read_mesh_file(path); });
  EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST(MeshRead, UnknownExtensionIsAnError) {
  const std::string path = (scratch_dir() / "points.xyz").string();
  std::ofstream(path) << "0 0 0\n";
  const std::string message = read_error([&] { read_mesh_file(path); });
  EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
  for (const char* extension : {".obj", ".stl", ".ply", ".off"})
    EXPECT_NE(message.find(extension), std::string::npos) << message;
}

TEST(MeshRead, ScaleMustBePositiveAndFinite) {
  const std::string path = (scratch_dir() / "l.obj").string();
  write_obj(l_mesh(), path);
  for (Real scale : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    const std::string message = read_error([&] { read_mesh_file(path, scale); });
    EXPECT_EQ(message.rfind(path + ": scale", 0), 0u) << message;
  }
}

TEST(MeshRead, ParseFailureNamesTheSourceAndAssimpsReason) {
  const std::string text = "v 0 0 0\nf 1 2 3\n";  // vertices 2 and 3 are missing
  EXPECT_EQ(read_error([&] { read_mesh_memory(text.data(), text.size(), "obj", "short.obj"); }),
            "short.obj: cannot be parsed as .obj (OBJ: vertex index out of range)");
}

// What assimp's loaders let through or trip over in damaged files is refused before it matters.
TEST(MeshRead, DamagedHeadersAndFacesAreErrors) {
  auto error = [](const std::string& text, const std::string& extension) {
    return read_error([&] { read_mesh_memory(text.data(), text.size(), extension, "bad"); });
  };
  EXPECT_EQ(error("OFF\n3 1 0\n0 0 0\n1 0 0\n", "off"),
            "bad: the OFF file ends before its 3 vertices and 1 faces");
  // What fuzz_mesh_reader found making assimp read out of bounds: a face past the vertices, a
  // damaged number.
  EXPECT_EQ(error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9999999999\n", "off"),
            "bad: line 6: face 0 has a corner '9999999999' that is not a vertex index below 3");
  EXPECT_EQ(error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0.5-0.5\n3 0 1 2\n", "off"),
            "bad: line 5: vertex 2 needs three numbers x y z");
  EXPECT_EQ(error("OFF\n2000000000 1 0\n0 0 0\n", "off"),
            "bad: the header declares 2000000000 vertices, more than the file's 25 bytes can hold");
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n";
  EXPECT_EQ(error(ply, "ply"), "bad: the PLY header has no end_header line");
  EXPECT_EQ(error(ply + "end_header", "ply"), "bad: the PLY header has no end_header line");
  EXPECT_EQ(error(ply + "property dou le y\nend_header\n", "ply"),
            "bad: line 5 of the PLY header is not a PLY header line: 'property dou le y'");
  // What fuzz_mesh_reader found making assimp allocate 16 GB: a list count in the body far
  // beyond what the file holds, in ASCII and in binary; and a body cut short.
  const std::string triangle =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(error(triangle + "3999999999 0 1 2\n", "ply"),
            "bad: face 0 of the PLY body has a list whose count '3999999999' is more than the "
            "values left in the file");
  EXPECT_EQ(error(triangle, "ply"), "bad: face 0 of the PLY body is missing: the file ends first");
  EXPECT_EQ(error(triangle.substr(0, triangle.size() - 6), "ply"),
            "bad: vertex 2 of the PLY body is missing: the file ends first");
  std::string binary =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list int int vertex_indices\nend_header\n";
  binary += std::string(36, '\0');        // three vertices at the origin
  binary += std::string("\xff\xff\xff\x7f", 4);  // a count of 2^31 - 1
  binary += std::string(12, '\0');
  EXPECT_EQ(error(binary, "ply"),
            "bad: face 0 of the PLY body has a list whose count is more than the bytes left in "
            "the file");
}

TEST(MeshRead, LinesAndPointsAreErrors) {
  const std::string lines = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n";
  EXPECT_EQ(read_error([&] { read_mesh_memory(lines.data(), lines.size(), "obj", "wire.obj"); })
                .rfind("wire.obj: the file has lines", 0),
            0u);
  const std::string only_lines = "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n";
  EXPECT_EQ(read_error([&] { read_mesh_memory(only_lines.data(), only_lines.size(), "obj", "wire.obj"); }),
            "wire.obj: the file has no triangles, only lines");
  // A file of vertices alone becomes an assimp point cloud, which its own validation rejects.
  const std::string points = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string message =
      read_error([&] { read_mesh_memory(points.data(), points.size(), "obj", "cloud.obj"); });
  EXPECT_EQ(message.rfind("cloud.obj: cannot be parsed as .obj (", 0), 0u) << message;
  EXPECT_NE(message.find("no faces"), std::string::npos) << message;
}

TEST(MeshRead, NonFiniteCoordinateIsAnError) {
  const std::string text = "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n";  // 1e39 overflows a float
  const std::string message =
      read_error([&] { read_mesh_memory(text.data(), text.size(), "obj", "huge.obj"); });
  EXPECT_EQ(message.rfind("huge.obj:", 0), 0u) << message;
  EXPECT_NE(message.find("not finite"), std::string::npos) << message;
}

// assimp 5.2's ASCII STL and PLY loaders leak what they had built when they give up on a
// damaged file (TEM holds none of it: the Importer owns the scene). Under AddressSanitizer the
// leak checker is told to ignore allocations made meanwhile, so that it reports TEM's leaks only.
#if defined(__SANITIZE_ADDRESS__)
struct AssimpLeaksIgnored {
  AssimpLeaksIgnored() { __lsan_disable(); }
  ~AssimpLeaksIgnored() { __lsan_enable(); }
  AssimpLeaksIgnored(const AssimpLeaksIgnored&) = delete;
  AssimpLeaksIgnored& operator=(const AssimpLeaksIgnored&) = delete;
};
#else
struct AssimpLeaksIgnored {};
#endif

// Bytes that are no mesh, and damaged copies of good files: a MeshError or a mesh, never a
// crash or a hang (the fuzz target exercises the same entry point far longer).
TEST(MeshRead, GarbageIsAnErrorNotACrash) {
  std::mt19937 random(12);
  std::vector<char> noise(4000);
  for (char& c : noise) c = static_cast<char>(random());
  for (const char* extension : {"obj", "stl", "ply", "off"}) {
    const std::string message =
        read_error([&] { read_mesh_memory(noise.data(), noise.size(), extension, "noise"); });
    EXPECT_EQ(message.rfind("noise:", 0), 0u) << message;
  }
  EXPECT_EQ(read_error([&] { read_mesh_memory("", 0, "stl", "empty.stl"); }),
            "empty.stl: the file is empty");

  const fs::path dir = scratch_dir();
  const TriangleMesh cube = holed_cube_mesh();
  [[maybe_unused]] const AssimpLeaksIgnored ignored;
  int file = 0;
  for (const Format& format : kFormats) {
    const std::string path = (dir / ("good" + std::to_string(file++) + "." + format.extension)).string();
    format.write(cube, path);
    std::ifstream in(path, std::ios::binary);
    const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (int trial = 0; trial < 200; ++trial) {
      std::string bad = good;
      const int changes = 1 + static_cast<int>(random() % 8);
      for (int k = 0; k < changes; ++k) bad[random() % bad.size()] = static_cast<char>(random());
      if (trial % 4 == 0) bad.resize(random() % bad.size());
      try {
        TriangleMesh mesh = read_mesh_memory(bad.data(), bad.size(), format.extension, "damaged");
        try {
          check_mesh(mesh);
        } catch (const MeshError&) {
        }
      } catch (const MeshError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("damaged:", 0), 0u) << e.what();
      }
    }
  }
}

// assimp's logger stays silent: reading prints nothing, good files or bad.
TEST(MeshRead, PrintsNothing) {
  const std::string path = (scratch_dir() / "l.stl").string();
  write_stl_ascii(l_mesh(), path);
  const std::string garbage = "v 0 0 0\nf 1 2 3\n";  // assimp fails (and would log) on it
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  read_mesh_file(path);
  try {
    read_mesh_memory(garbage.data(), garbage.size(), "obj", "garbage.obj");
  } catch (const MeshError&) {
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
}

// ---------------------------------------------------------------------------------------------
// Checking

TEST(MeshCheck, ShapesAreClosedWithTheirVolumes) {
  TriangleMesh l = l_mesh();
  const MeshCheck l_check = check_mesh(l);
  EXPECT_TRUE(l_check.closed);
  EXPECT_NEAR(l_check.volume, 3, 1e-12 * 3);
  EXPECT_EQ(l_check.vertices, 12);
  EXPECT_EQ(l_check.faces, static_cast<int>(l.faces.size()));
  EXPECT_FALSE(l_check.turned);
  EXPECT_TRUE(l_check.warnings.empty());

  TriangleMesh holed = holed_cube_mesh();
  const MeshCheck holed_check = check_mesh(holed);
  EXPECT_TRUE(holed_check.closed);
  EXPECT_NEAR(holed_check.volume, 24, 1e-12 * 24);

  // The ring's blocks' volumes come from TEM's tetrahedral elements, not from a surface.
  Real ring_volume;
  TriangleMesh ring = paper_ring_expected(&ring_volume);
  const MeshCheck ring_check = check_mesh(ring);
  EXPECT_TRUE(ring_check.closed);
  EXPECT_NEAR(ring_check.volume, ring_volume, 1e-12 * ring_volume);
}

// The torus's sections are regular m-gons (area A = (m/2) r^2 sin(2 pi/m), centroid on the
// centre line at R) in planes through the z axis 2 pi/n apart, and its quads are planar (each is
// symmetric about the plane halfway between its sections). Between two sections the solid is
// then swept along straight lines, x(s, rho, z) = p0 + s (p1 - p0), whose Jacobian is
// rho sin(2 pi/n): the volume is n sin(2 pi/n) R A exactly. It is 1.4% less than the smooth
// torus's 2 pi^2 R r^2 for n = 48, m = 24 (the inscribed 24-gon alone loses 1.1%).
TEST(MeshCheck, TorusVolumeIsExact) {
  const Real R = 1, r = 0.3;
  const int n = 48, m = 24;
  TriangleMesh torus = torus_mesh(R, r, n, m);
  const MeshCheck check = check_mesh(torus);
  EXPECT_TRUE(check.closed);
  const Real section = (m / 2.0) * r * r * std::sin(2 * std::numbers::pi / m);
  const Real swept = n * std::sin(2 * std::numbers::pi / n) * R * section;
  EXPECT_NEAR(check.volume, swept, 1e-12 * swept);
  const Real smooth = 2 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_NEAR(check.volume, 0.986 * smooth, 0.001 * smooth);
}

TEST(MeshCheck, OpenMeshIsAnError) {
  TriangleMesh mesh = l_mesh();
  const auto removed = mesh.faces[5];
  mesh.faces.erase(mesh.faces.begin() + 5);
  // All three edges of the removed face are open; the first in vertex order is named first.
  std::pair<int, int> first{INT_MAX, INT_MAX};
  for (int k = 0; k < 3; ++k)
    first = std::min(first, std::pair<int, int>(std::minmax(removed[k], removed[(k + 1) % 3])));
  const std::string message = check_error(mesh);
  EXPECT_EQ(message.rfind("L: refused: 3 open edges\n", 0), 0u) << message;
  EXPECT_NE(message.find("3 open edges (a face on one side only: the mesh is not closed): " +
                         edge_name(first.first, first.second) + " at ("),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(": belongs to face "), std::string::npos) << message;
}

TEST(MeshCheck, NonManifoldEdgeIsAnError) {
  TriangleMesh mesh = l_mesh();
  const int a = mesh.faces[0][0], b = mesh.faces[0][1];
  int neighbour = -1;  // the other face on edge a-b
  for (int f = 1; f < static_cast<int>(mesh.faces.size()); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.faces[f][k] == b && mesh.faces[f][(k + 1) % 3] == a) neighbour = f;
  ASSERT_GT(neighbour, 0);
  // A thin fin on edge a-b: two more faces on it, closed between themselves.
  mesh.vertices.push_back(Vec3(-1, -1, -1));
  const int x = static_cast<int>(mesh.vertices.size()) - 1;
  mesh.faces.push_back({a, b, x});
  mesh.faces.push_back({b, a, x});
  // The fin's two faces are one triangle run both ways: they also coincide.
  const std::string message = check_error(mesh);
  EXPECT_EQ(message.rfind("L: refused: 1 edge of more than two faces, 1 pair of intersecting "
                          "faces\n",
                          0),
            0u)
      << message;
  EXPECT_NE(message.find("(not edge-manifold): " + edge_name(a, b) + " at ("), std::string::npos)
      << message;
  EXPECT_NE(message.find(": shared by 4 faces (0, " + std::to_string(neighbour) + ", 20, 21)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("face 20 (vertices "), std::string::npos) << message;
  EXPECT_NE(message.find(" intersects face 21 (vertices "), std::string::npos) << message;
}

TEST(MeshCheck, InconsistentOrientationIsAnError) {
  TriangleMesh mesh = holed_cube_mesh();
  std::swap(mesh.faces[7][1], mesh.faces[7][2]);
  const std::string message = check_error(mesh);
  // Each of face 7's three edges now runs the same way as its neighbour's.
  EXPECT_TRUE(message.find(": face 7 and face ") != std::string::npos ||
              message.find(" and face 7 both run ") != std::string::npos)
      << message;
  EXPECT_EQ(message.rfind("holed cube: refused: 3 inconsistently oriented edges\n", 0), 0u)
      << message;
}

TEST(MeshCheck, InvertedMeshIsTurned) {
  TriangleMesh mesh = inverted(l_mesh());
  const MeshCheck check = check_mesh(mesh);
  EXPECT_TRUE(check.turned);
  ASSERT_EQ(check.warnings.size(), 1u);
  EXPECT_EQ(check.warnings[0], "L: all 20 faces pointed inwards (negative volume) and were turned");
  EXPECT_NEAR(check.volume, 3, 1e-12 * 3);
  EXPECT_EQ(mesh.faces, l_mesh().faces);
}

TEST(MeshCheck, ZeroVolumeIsAnError) {
  TriangleMesh sheet;
  sheet.source = "sheet";
  sheet.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  sheet.faces = {{0, 1, 2}, {0, 2, 1}};
  const std::string message = check_error(sheet);
  // A closed surface of two faces that coincide: no volume, and the faces intersect.
  EXPECT_EQ(message.rfind(
                "sheet: refused: 1 surface of zero volume, 1 pair of intersecting faces\n", 0),
            0u)
      << message;
  EXPECT_NE(message.find("face 0 (vertices 0, 1, 2) at (0.333333, 0.333333, 0): the closed surface "
                         "of 2 faces it belongs to encloses |V| = 0 <= "),
            std::string::npos)
      << message;
}

TEST(MeshCheck, DegenerateFacesAreErrors) {
  TriangleMesh repeated = l_mesh();
  repeated.faces[3][2] = repeated.faces[3][0];
  // The face has no edges left: the three it had are open on its neighbours' side.
  const std::string r = check_error(repeated);
  EXPECT_EQ(r.rfind("L: refused: 1 face with a repeated vertex, 3 open edges\n", 0), 0u) << r;
  EXPECT_NE(r.find("(a degenerate face): face 3 (vertices "), std::string::npos) << r;
  EXPECT_NE(r.find(" appears twice"), std::string::npos) << r;

  TriangleMesh flat = l_mesh();
  const auto f = flat.faces[0];
  flat.vertices.push_back(0.5 * (flat.vertices[f[0]] + flat.vertices[f[1]]));
  flat.faces.push_back({f[0], f[1], static_cast<int>(flat.vertices.size()) - 1});
  // A flat face on edge f0-f1 gives it a third face, and its other two edges are open.
  const std::string z = check_error(flat);
  EXPECT_EQ(z.rfind("L: refused: 1 face of zero area, 2 open edges, 1 edge of more than two "
                    "faces\n",
                    0),
            0u)
      << z;
  EXPECT_NE(z.find("(a degenerate face: area at most 1e-14 x bounding-box diagonal^2): face 20 "
                   "(vertices "),
            std::string::npos)
      << z;
}

TEST(MeshCheck, NonFiniteCoordinateIsAnError) {
  TriangleMesh mesh = l_mesh();
  mesh.vertices[7].y() = std::nan("");
  const std::string message = check_error(mesh);
  EXPECT_EQ(message.rfind("L: refused: 1 vertex with a non-finite coordinate\n", 0), 0u) << message;
  EXPECT_NE(message.find("(a coordinate is not finite): vertex 7 at ("), std::string::npos)
      << message;
}

// Two boxes touching at one corner only: the corner's faces form two fans.
TEST(MeshCheck, VerticesMustBeManifold) {
  TriangleMesh mesh = combined(box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1)), box_mesh(Vec3(1, 1, 1), Vec3(2, 2, 2)));
  // Weld the shared corner (1, 1, 1): vertex 6 of the first box, vertex 0 of the second (8).
  ASSERT_EQ(mesh.vertices[6], mesh.vertices[8]);
  for (auto& f : mesh.faces)
    for (int& v : f)
      if (v == 8) v = 6;
  const std::string message = check_error(mesh);
  EXPECT_EQ(message.rfind("box: refused: 1 pinched vertex\n", 0), 0u) << message;
  EXPECT_NE(message.find("not vertex-manifold): vertex 6 at (1, 1, 1): its faces form 2 fans"),
            std::string::npos)
      << message;
}

TEST(MeshCheck, UnusedVerticesAreDroppedWithAWarning) {
  TriangleMesh mesh = l_mesh();
  mesh.vertices.insert(mesh.vertices.begin(), Vec3(100, 100, 100));
  for (auto& f : mesh.faces)
    for (int& v : f) ++v;
  const MeshCheck check = check_mesh(mesh);
  ASSERT_EQ(check.warnings.size(), 1u);
  EXPECT_EQ(check.warnings[0], "L: 1 vertex(es) belong to no face and were dropped (0)");
  EXPECT_EQ(check.vertices, 12);
  EXPECT_EQ(mesh.vertices, l_mesh().vertices);
  EXPECT_EQ(mesh.faces, l_mesh().faces);
}

// A hollow box: the cavity's surface points inwards, and its volume is taken away.
TEST(MeshCheck, CavitiesPointInwards) {
  const TriangleMesh outer = box_mesh(Vec3(0, 0, 0), Vec3(4, 4, 4), "hollow");
  const TriangleMesh cavity = inverted(box_mesh(Vec3(1, 1, 1), Vec3(2, 3, 3)));
  TriangleMesh hollow = combined(outer, cavity);
  MeshCheck check = check_mesh(hollow);
  EXPECT_NEAR(check.volume, 64 - 4, 1e-12 * 60);
  EXPECT_FALSE(check.turned);

  // All inside out: turned as a whole.
  TriangleMesh everted = inverted(combined(outer, cavity));
  check = check_mesh(everted);
  EXPECT_TRUE(check.turned);
  EXPECT_NEAR(check.volume, 60, 1e-12 * 60);
  EXPECT_EQ(everted.faces, hollow.faces);

  // A cavity pointing outwards: a solid inside a solid or a cavity the wrong way round?
  TriangleMesh doubled = combined(outer, inverted(cavity));
  const std::string message = check_error(doubled);
  EXPECT_EQ(message.rfind("hollow: refused: 1 nested surface pointing the wrong way\n", 0), 0u)
      << message;
  EXPECT_NE(message.find("inwards): face 12 (vertices "), std::string::npos) << message;
  EXPECT_NE(message.find("lies inside 1 other surface(s) and points outwards"), std::string::npos)
      << message;
}

// Two separate boxes, one inside out: that one is turned, with a warning naming it.
TEST(MeshCheck, SeparateInvertedSurfaceIsTurned) {
  TriangleMesh mesh = combined(box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), "pair"),
                               inverted(box_mesh(Vec3(2, 0, 0), Vec3(4, 1, 1))));
  const MeshCheck check = check_mesh(mesh);
  EXPECT_TRUE(check.turned);
  EXPECT_NEAR(check.volume, 3, 1e-12 * 3);
  ASSERT_EQ(check.warnings.size(), 1u);
  EXPECT_EQ(check.warnings[0].rfind("pair: the 1 surface(s) of 12 faces around face 12 (", 0), 0u)
      << check.warnings[0];
}

// Two closed boxes that overlap: reported by CGAL's self-intersection test.
TEST(MeshCheck, SelfIntersectionIsAnError) {
  TriangleMesh mesh = combined(box_mesh(Vec3(0, 0, 0), Vec3(2, 2, 2), "overlap"),
                               box_mesh(Vec3(1, 1, 1), Vec3(3, 3, 3)));
  const std::string message = check_error(mesh);
  EXPECT_EQ(message.rfind("overlap: refused: ", 0), 0u) << message;
  EXPECT_NE(message.find(" pairs of intersecting faces (self-intersecting): face "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(" intersects face "), std::string::npos) << message;
}

// Reading and checking a 75,000-face torus from OBJ: the times are printed for the record (the
// test asserts no limit: sanitizer and loaded CI machines differ too much).
TEST(MeshCheck, LargeMeshTimes) {
  const std::string path = (scratch_dir() / "torus.obj").string();
  const TriangleMesh torus = torus_mesh(1, 0.3, 500, 75);
  ASSERT_EQ(torus.faces.size(), 75000u);
  write_obj(torus, path);
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  TriangleMesh mesh = read_mesh_file(path);
  const auto read = Clock::now();
  const MeshCheck check = check_mesh(mesh);
  const auto checked = Clock::now();
  EXPECT_EQ(check.faces, 75000);
  EXPECT_EQ(check.vertices, 37500);
  auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
  std::cout << "[ timing   ] 75,000-face torus: read " << ms(read - start) << " ms, check "
            << ms(checked - read) << " ms\n";
}

}  // namespace
}  // namespace tem
