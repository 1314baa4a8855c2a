// Reading mesh files (every format, written here from meshes built in code) and checking meshes:
// what passes, with which volume, and the message of each kind of failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "geometry/primitives.hpp"
#include "mass/surface_integrals.hpp"
#include "mesh/mesh_check.hpp"
#include "mesh/mesh_reader.hpp"
#include "mesh/polygon_triangulation.hpp"
#include "support/mesh_check_error.hpp"
#include "support/mesh_shapes.hpp"

namespace tem {
namespace test_mesh_reading {

using namespace tem::testing_support;
namespace fs = std::filesystem;

// A directory of this test's own, under the test framework's temporary directory.
fs::path scratch_path(const ::testing::TestInfo& info) {
  return fs::path(::testing::TempDir()) / ("tem_mesh_" + std::to_string(::getpid()) + "_" +
                                           info.test_suite_name() + "_" + info.name());
}

fs::path scratch_dir() {
  const fs::path dir = scratch_path(*::testing::UnitTest::GetInstance()->current_test_info());
  fs::create_directories(dir);
  return dir;
}

// Each test's directory goes when the test ends, passed or failed: the files are written by
// the test itself, and a run of the suite left some 30 folders in /tmp.
class RemoveScratch : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& info) override {
    std::error_code ignored;
    fs::remove_all(scratch_path(info), ignored);
  }
};
[[maybe_unused]] const bool kScratchRemoved = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new RemoveScratch);
  return true;
}();

// Volume from Eberly's surface integrals: a route that shares no code with check_mesh().
Real surface_volume(const TriangleMesh& mesh) {
  return surface_mass_properties(corner_triangles(mesh)).volume;
}

// The mesh as a reader of 32-bit floats sees it (binary STL stores floats; before TEM read the
// formats itself, Debian's single-precision assimp rounded every format so). The float goes
// through a volatile: g++ 12.2's SLP vectorizer at -O2 drops the double -> float
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
  bool floats = false;  // the format stores 32-bit floats
};

const std::vector<Format> kFormats = {
    {"obj", write_obj},          {"off", write_off},       {"ply", write_ply_ascii},
    {"ply", write_ply_binary},   {"stl", write_stl_ascii}, {"stl", write_stl_binary, true}};

TriangleMesh paper_ring_expected(Real* volume) {
  *volume = 0;
  for (const PolyhedronDef& def : polygonal_ring(16, 6, 0.3, 0.05, 16, Axis::z, false))
    *volume += Block(def).volume();
  return paper_ring_mesh();
}

// ---------------------------------------------------------------------------------------------
// Reading

// Every format gives back the mesh: the same numbers of vertices (STL's separate corners are
// welded) and faces, and the volume of the mesh as written (17 digits, read in double precision),
// or of the mesh rounded to floats from binary STL.
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
      const Real expected = surface_volume(format.floats ? rounded_to_float(original) : original);
      EXPECT_NEAR(check.volume, expected, 1e-12 * expected);
    }
}

// A UTF-8 byte order mark before the text (as Windows editors write it, and as CGAL's
// elephant.off has it) is passed over: the same vertices, to the bit, as without. In a binary
// STL the same three bytes are part of the 80-byte header, so the file stays binary.
TEST(MeshRead, ByteOrderMarkIsPassedOver) {
  const fs::path dir = scratch_dir();
  const TriangleMesh original = torus_mesh(1, 0.3, 12, 8);
  const std::string mark = "\xEF\xBB\xBF";
  int file = 0;
  for (const Format& format : kFormats) {
    const std::string path = (dir / ("mesh" + std::to_string(file++) + "." + format.extension)).string();
    format.write(original, path);
    SCOPED_TRACE(path);
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const TriangleMesh plain = read_mesh_memory(bytes.data(), bytes.size(), format.extension, "plain");
    if (format.floats)
      bytes.replace(0, mark.size(), mark);
    else
      bytes.insert(0, mark);
    const TriangleMesh marked = read_mesh_memory(bytes.data(), bytes.size(), format.extension, "marked");
    ASSERT_EQ(marked.vertices.size(), plain.vertices.size());
    EXPECT_EQ(marked.faces, plain.faces);
    for (std::size_t v = 0; v < plain.vertices.size(); ++v)
      EXPECT_EQ(marked.vertices[v], plain.vertices[v]);
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

TEST(MeshRead, ParseFailureNamesTheSourceLineAndReason) {
  const std::string text = "v 0 0 0\nf 1 2 3\n";  // vertices 2 and 3 are missing
  EXPECT_EQ(read_error([&] { read_mesh_memory(text.data(), text.size(), "obj", "short.obj"); }),
            "short.obj: line 2: face corner 2 names a missing vertex (the file has 1)");
}

// Damaged headers, counts and faces are refused with what is wrong (found by fuzz_mesh_reader
// when assimp read these files: it read out of bounds, allocated 16 GB, or looped forever).
TEST(MeshRead, DamagedHeadersAndFacesAreErrors) {
  auto error = [](const std::string& text, const std::string& extension) {
    return read_error([&] { read_mesh_memory(text.data(), text.size(), extension, "bad"); });
  };
  EXPECT_EQ(error("OFF\n3 1 0\n0 0 0\n1 0 0\n", "off"),
            "bad: the OFF file ends before its 3 vertices and 1 faces");
  // A face past the vertices, a damaged number.
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
  // A list count in the body far beyond what the file holds, in ASCII and in binary; and a body
  // cut short.
  const std::string triangle =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(error(triangle + "3999999999 0 1 2\n", "ply"),
            "bad: face 0 of the PLY body has a list whose count '3999999999' is more than the "
            "values left in the file (line 13)");
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
  const std::string points = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(read_error([&] { read_mesh_memory(points.data(), points.size(), "obj", "cloud.obj"); }),
            "cloud.obj: the file has no faces, only 3 vertices");
  const std::string marked = "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n";
  EXPECT_EQ(read_error([&] { read_mesh_memory(marked.data(), marked.size(), "obj", "dots.obj"); }),
            "dots.obj: the file has no triangles, only points");
}

TEST(MeshRead, NonFiniteCoordinateIsAnError) {
  const std::string text = "v 0 0 0\nv 1e309 0 0\nv 0 1 0\nf 1 2 3\n";  // 1e309 overflows a double
  const std::string message =
      read_error([&] { read_mesh_memory(text.data(), text.size(), "obj", "huge.obj"); });
  EXPECT_EQ(message.rfind("huge.obj:", 0), 0u) << message;
  EXPECT_NE(message.find("not finite"), std::string::npos) << message;
  for (const char* word : {"inf", "nan"}) {
    const std::string named = "v 0 0 0\nv 1 " + std::string(word) + " 0\nv 0 1 0\nf 1 2 3\n";
    EXPECT_NE(read_error([&] { read_mesh_memory(named.data(), named.size(), "obj", "named.obj"); })
                  .find("not finite"),
              std::string::npos);
  }
  // 1e39 overflowed assimp's floats; it is an ordinary double.
  const std::string large = "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_EQ(read_mesh_memory(large.data(), large.size(), "obj", "large.obj").vertices[1].x(), 1e39);
  // Scaling can overflow too: checked after scaling.
  const std::string big = "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_NE(read_error([&] { read_mesh_memory(big.data(), big.size(), "obj", "big.obj", 1e10); })
                .find("not finite"),
            std::string::npos);
}

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

// Reading prints nothing, good files or bad (errors are MeshErrors for the caller to report).
TEST(MeshRead, PrintsNothing) {
  const std::string path = (scratch_dir() / "l.stl").string();
  write_stl_ascii(l_mesh(), path);
  const std::string garbage = "v 0 0 0\nf 1 2 3\n";  // a face past the vertices
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
// Precision: text formats and binary PLY give back the file's own doubles

// Mass properties from Eberly's surface integrals (shares no code with the reader).
MassProperties surface_properties(const TriangleMesh& mesh) {
  return surface_mass_properties(corner_triangles(mesh));
}

// A closed, lopsided octahedron whose coordinates carry 17 significant digits: its tips are
// c + r_k e_k tilted off their axes, all numbers irrational-looking so that no coordinate is a
// float (checked in the test).
TriangleMesh seventeen_digit_octahedron() {
  TriangleMesh mesh;
  mesh.source = "17-digit octahedron";
  const Vec3 c(0.12345678901234568, -0.27182818284590451, 0.31415926535897931);
  const Vec3 r(1.4142135623730951, 1.7320508075688772, 2.2360679774997898);
  const Vec3 tilt(1.0 / 7.0, -1.0 / 11.0, 1.0 / 13.0);
  for (int k = 0; k < 3; ++k)
    for (int sign : {1, -1}) {
      Vec3 p = c + tilt * sign * 0.5;
      p[k] = c[k] + sign * r[k] * (1 + 0.01 * std::sqrt(2.0 + k));
      mesh.vertices.push_back(p);  // vertex 2k (+) and 2k + 1 (-)
    }
  for (int sx : {0, 1})
    for (int sy : {0, 1})
      for (int sz : {0, 1}) {
        const int x = sx, y = 2 + sy, z = 4 + sz;
        // Counter-clockwise from outside when an even number of the three tips point down.
        if ((sx + sy + sz) % 2 == 0) mesh.faces.push_back({x, y, z});
        else mesh.faces.push_back({x, z, y});
      }
  return mesh;
}

// Binary PLY in the byte order x86 does not use, with double coordinates.
void write_ply_binary_big_endian(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_big_endian 1.0\nelement vertex " << mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
      << mesh.faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  auto big = [&](const void* value, int size) {
    const char* bytes = static_cast<const char*>(value);
    for (int k = size - 1; k >= 0; --k) out.put(bytes[k]);
  };
  for (const Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) big(&v[k], 8);
  for (const auto& f : mesh.faces) {
    out.put(3);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t index = f[k];
      big(&index, 4);
    }
  }
}

TEST(MeshRead, SeventeenDigitsArriveBitForBit) {
  const TriangleMesh original = seventeen_digit_octahedron();
  TriangleMesh checked = original;
  const MeshCheck check = check_mesh(checked);  // a valid closed body, pointing outwards
  ASSERT_FALSE(check.turned);
  ASSERT_GT(check.volume, 0);
  const TriangleMesh floats = rounded_to_float(original);
  for (size_t i = 0; i < original.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_NE(floats.vertices[i][k], original.vertices[i][k]);
  const MassProperties exact = surface_properties(original);
  const MassProperties rounded = surface_properties(floats);
  const Real size = 2.5;  // about the body's half-diagonal, for the centre's scale
  auto inertia = [](const MassProperties& m) { return inertia_from_second_moment(m.second_moment); };
  // Float rounding changes each property by far more than the 1e-12 the test allows below.
  const Real volume_change = std::abs(rounded.volume - exact.volume) / exact.volume;
  const Real centre_change = (rounded.center - exact.center).norm() / size;
  const Real inertia_change = (inertia(rounded) - inertia(exact)).norm() / inertia(exact).norm();
  std::cout << "[ figures  ] 17-digit octahedron, float vs double coordinates: volume "
            << volume_change << ", centre " << centre_change << ", inertia " << inertia_change
            << " (relative)\n";
  EXPECT_GT(volume_change, 1e-9);
  EXPECT_GT(centre_change, 1e-9);
  EXPECT_GT(inertia_change, 1e-9);

  struct Writer {
    std::string name;
    void (*write)(const TriangleMesh&, const std::string&);
  };
  const std::vector<Writer> writers = {
      {"a.obj", write_obj},       {"a.off", write_off},
      {"a.ply", write_ply_ascii}, {"little.ply", write_ply_binary},
      {"big.ply", write_ply_binary_big_endian}, {"a.stl", write_stl_ascii}};
  const fs::path dir = scratch_dir();
  std::vector<TriangleMesh> read;
  for (const Writer& writer : writers) {
    const std::string path = (dir / writer.name).string();
    writer.write(original, path);
    SCOPED_TRACE(path);
    const TriangleMesh mesh = read_mesh_file(path);
    ASSERT_EQ(mesh.vertices.size(), original.vertices.size());
    ASSERT_EQ(mesh.faces.size(), original.faces.size());
    // Corner by corner, the written doubles bit for bit.
    for (size_t f = 0; f < mesh.faces.size(); ++f)
      for (int k = 0; k < 3; ++k)
        for (int d = 0; d < 3; ++d)
          EXPECT_EQ(mesh.vertices[mesh.faces[f][k]][d], original.vertices[original.faces[f][k]][d]);
    const MassProperties got = surface_properties(mesh);
    EXPECT_NEAR(got.volume, exact.volume, 1e-12 * exact.volume);
    EXPECT_LE((got.center - exact.center).norm(), 1e-12 * size);
    EXPECT_LE((inertia(got) - inertia(exact)).norm(), 1e-12 * inertia(exact).norm());
    read.push_back(mesh);
  }
  // Every format gives the same body: the same vertices in the same order, the same faces.
  for (size_t k = 1; k < read.size(); ++k) {
    EXPECT_EQ(read[k].vertices, read[0].vertices) << writers[k].name;
    EXPECT_EQ(read[k].faces, read[0].faces) << writers[k].name;
  }
}

// Binary PLY's numeric types, in both byte orders: integers and floats convert to double
// exactly; properties TEM does not use (a colour, a list of its own, a face flag) are skipped.
TEST(MeshRead, BinaryPlyTypesAndByteOrders) {
  const TriangleMesh l = l_mesh();  // coordinates 0, 1, 2: integers
  for (bool big : {false, true}) {
    SCOPED_TRACE(big ? "big-endian" : "little-endian");
    std::ostringstream out;
    out << "ply\nformat " << (big ? "binary_big_endian" : "binary_little_endian")
        << " 1.0\ncomment x as int16, y as float32, z as uint8; a colour; a list\nelement vertex "
        << l.vertices.size()
        << "\nproperty short x\nproperty uchar red\nproperty float y\nproperty list uint8 double "
           "extra\nproperty uint8 z\nelement face "
        << l.faces.size() << "\nproperty uchar flags\nproperty list uint8 uint16 vertex_indices\n"
        << "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    auto put = [&](auto value) {
      char bytes[sizeof value];
      std::memcpy(bytes, &value, sizeof value);
      if (big) std::reverse(bytes, bytes + sizeof value);
      out.write(bytes, sizeof value);
    };
    // x shifted to -5 .. -3 and y to 0.1f .. 2.1f: a signed integer and non-integer floats.
    for (const Vec3& v : l.vertices) {
      put(static_cast<std::int16_t>(v.x() - 5));
      put(std::uint8_t{200});
      put(static_cast<float>(v.y() + 0.1));
      put(std::uint8_t{2});
      put(1.5);
      put(-2.5);
      put(static_cast<std::uint8_t>(v.z()));
    }
    for (const auto& f : l.faces) {
      put(std::uint8_t{7});
      put(std::uint8_t{3});
      for (int k = 0; k < 3; ++k) put(static_cast<std::uint16_t>(f[k]));
    }
    put(std::int32_t{0});
    put(std::int32_t{1});
    const std::string bytes = out.str();
    const TriangleMesh mesh = read_mesh_memory(bytes.data(), bytes.size(), "ply", "types.ply");
    ASSERT_EQ(mesh.faces.size(), l.faces.size());
    for (size_t f = 0; f < l.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3& want = l.vertices[l.faces[f][k]];
        const Vec3& got = mesh.vertices[mesh.faces[f][k]];
        EXPECT_EQ(got.x(), want.x() - 5);
        EXPECT_EQ(got.y(), static_cast<double>(static_cast<float>(want.y() + 0.1)));
        EXPECT_EQ(got.z(), want.z());
      }
  }
}

// ---------------------------------------------------------------------------------------------
// Polygons

// Twice the signed area of a 2-D polygon (shoelace).
Real shoelace(const std::vector<Vec3>& corners, const Vec3& u, const Vec3& v) {
  Real twice = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3& a = corners[i];
    const Vec3& b = corners[(i + 1) % corners.size()];
    twice += a.dot(u) * b.dot(v) - b.dot(u) * a.dot(v);
  }
  return twice;
}

TEST(MeshRead, ConvexPolygonsAreFannedAndQuadsFromTheirReflexCorner) {
  std::vector<Vec3> pentagon;
  for (int k = 0; k < 5; ++k)
    pentagon.emplace_back(std::cos(2 * std::numbers::pi * k / 5), std::sin(2 * std::numbers::pi * k / 5), 0);
  EXPECT_EQ(triangulate_polygon(pentagon),
            (std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}));
  // A dart, reflex at corner 3: the only diagonal inside it is 1-3.
  const std::vector<Vec3> dart = {Vec3(0, 0, 0), Vec3(4, 2, 0), Vec3(0, 4, 0), Vec3(1, 2, 0)};
  EXPECT_EQ(triangulate_polygon(dart), (std::vector<std::array<int, 3>>{{3, 0, 1}, {3, 1, 2}}));
  // The same dart the other way round (clockwise seen from +z): the reflex corner is 1.
  const std::vector<Vec3> turned = {Vec3(0, 0, 0), Vec3(1, 2, 0), Vec3(0, 4, 0), Vec3(4, 2, 0)};
  EXPECT_EQ(triangulate_polygon(turned), (std::vector<std::array<int, 3>>{{1, 2, 3}, {1, 3, 0}}));
}

// A comb of 12 teeth in a tilted plane: ear clipping gives n - 2 triangles, each turning the
// polygon's way, whose areas add up to the polygon's: they tile it without folding over.
TEST(MeshRead, NonConvexPolygonsAreClippedIntoEars) {
  std::vector<Vec3> flat;  // counter-clockwise in the x-y plane
  const int teeth = 12;
  flat.emplace_back(0, 0, 0);
  flat.emplace_back(2 * teeth, 0, 0);
  for (int t = teeth - 1; t >= 0; --t) {
    flat.emplace_back(2 * t + 2, 5, 0);
    flat.emplace_back(2 * t + 1.5, 5, 0);
    flat.emplace_back(2 * t + 1, 1 + 0.1 * t, 0);
    flat.emplace_back(2 * t + 0.5, 5, 0);
  }
  flat.pop_back();  // the last tooth's left edge goes straight down to the start
  const Mat3 tilt = (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())).toRotationMatrix();
  std::vector<Vec3> corners;
  for (const Vec3& p : flat) corners.push_back(tilt * p + Vec3(0.3, -0.2, 5));
  const Vec3 normal = tilt * Vec3(0, 0, 1), u = tilt * Vec3(1, 0, 0), v = tilt * Vec3(0, 1, 0);
  const auto triangles = triangulate_polygon(corners);
  ASSERT_EQ(triangles.size(), corners.size() - 2);
  Real sum = 0;
  for (const auto& t : triangles) {
    const Vec3 area = (corners[t[1]] - corners[t[0]]).cross(corners[t[2]] - corners[t[0]]);
    EXPECT_GT(area.dot(normal), 0);
    sum += area.dot(normal);
  }
  const Real polygon = shoelace(corners, u, v);
  EXPECT_NEAR(sum, polygon, 1e-12 * polygon);

  // Polygons that cross themselves (a pentagram, a bow tie with a tail) are no polygons to cut
  // right; they still give n - 2 triangles using every corner, and the mesh checks then report
  // the crossing faces.
  std::vector<Vec3> star;
  for (int k = 0; k < 5; ++k)
    star.emplace_back(std::cos(4 * std::numbers::pi * k / 5), std::sin(4 * std::numbers::pi * k / 5), 0);
  const std::vector<Vec3> bow = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(2, 2, 0), Vec3(1, 3, 0)};
  for (const auto& crossing : {star, bow}) {
    const auto cut = triangulate_polygon(crossing);
    ASSERT_EQ(cut.size(), 3u);
    std::vector<int> used(5, 0);
    for (const auto& t : cut)
      for (int c : t) used[c] = 1;
    EXPECT_EQ(used, std::vector<int>(5, 1));
  }
}

// The L prism with its caps as hexagons and its sides as quads, in every polygon format, with
// OBJ's other syntax around it: exactly the volume of the L (3), closed, faces turned outwards.
TEST(MeshRead, PolygonFacesMakeTheBody) {
  const std::vector<Vec3> bottom = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0),
                                    Vec3(1, 1, 0), Vec3(1, 2, 0), Vec3(0, 2, 0)};
  // Corners 0-5 on the bottom, 6-11 above them; the bottom cap seen from below is clockwise.
  std::vector<std::vector<int>> faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (int k = 0; k < 6; ++k) faces.push_back({k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  std::ostringstream obj, off, ply;
  obj << "# an L prism\nmtllib missing.mtl\no L\ng sides caps\ns off\nusemtl steel\n";
  off << "OFF\n# an L prism\n12 8 18\n";
  ply << "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\n"
         "property float z\nelement face 8\nproperty list uchar int vertex_indices\nend_header\n";
  for (int level = 0; level < 2; ++level)
    for (const Vec3& p : bottom) {
      obj << "v " << p.x() << " " << p.y() << " " << level << "\nvt 0 0\nvn 0 0 1\n";
      off << p.x() << " " << p.y() << " " << level << "\n";
      ply << p.x() << " " << p.y() << " " << level << "\n";
    }
  for (size_t f = 0; f < faces.size(); ++f) {
    obj << "f";
    off << faces[f].size();
    ply << faces[f].size();
    for (size_t k = 0; k < faces[f].size(); ++k) {
      const int i = faces[f][k];
      // Alternately: plain, v/vt/vn, v//vn, and counting back from the last vertex (12 defined).
      const int form = static_cast<int>((f + k) % 4);
      if (form == 0) obj << " " << i + 1;
      if (form == 1) obj << " " << i + 1 << "/" << i + 1 << "/" << i + 1;
      if (form == 2) obj << " " << i + 1 << "//1";
      if (form == 3) obj << " " << i - 12;
      if (k == 2 && f == 0) obj << " \\\n";  // a line continued on the next
      off << " " << i;
      ply << " " << i;
    }
    obj << "\n";
    off << "\n";
    ply << "\n";
  }
  for (const auto& [text, extension] : {std::pair{obj.str(), "obj"}, {off.str(), "off"}, {ply.str(), "ply"}}) {
    SCOPED_TRACE(extension);
    TriangleMesh mesh = read_mesh_memory(text.data(), text.size(), extension, "L prism");
    EXPECT_EQ(mesh.vertices.size(), 12u);
    EXPECT_EQ(mesh.faces.size(), 2u * 4 + 6 * 2);
    const MeshCheck check = check_mesh(mesh);
    EXPECT_TRUE(check.closed);
    EXPECT_FALSE(check.turned);
    EXPECT_NEAR(check.volume, 3, 1e-14);
  }
}

// ---------------------------------------------------------------------------------------------
// Damaged files, format by format: each refused with the reason, before anything is allocated
// for a count the file cannot hold.

std::string memory_error(const std::string& text, const std::string& extension) {
  return read_error([&] { read_mesh_memory(text.data(), text.size(), extension, "bad"); });
}

TEST(MeshRead, DamagedObjIsAnError) {
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "obj"),
            "bad: line 2: a vertex is 'v x y z' (or x y z w, or x y z r g b): this one has 2 numbers");
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0x\nv 0 1 0\nf 1 2 3\n", "obj"),
            "bad: line 2: '0x' is not a number");
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 3\n", "obj"),
            "bad: line 4: face corner '0' is not a vertex number (1, 2, ... or -1, -2, ... "
            "counting back)");
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "obj"),
            "bad: line 4: face corner -4 counts back past the first vertex (3 defined so far)");
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "obj"),
            "bad: line 4: face corner '99999999999999999999' is not a vertex number (1, 2, ... "
            "or -1, -2, ... counting back)");
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf\n", "obj"),
            "bad: line 4: a face with no corners");
  EXPECT_EQ(memory_error("v 0 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "obj"),
            "bad: line 1: a homogeneous vertex with w = 0");
  // Cut off in the middle of the faces: what is there is read; a corner past the vertices is not.
  EXPECT_EQ(memory_error("v 0 0 0\nv 1 0 0\nf 1 2 3", "obj"),
            "bad: line 3: face corner 3 names a missing vertex (the file has 2)");
}

TEST(MeshRead, DamagedOffIsAnError) {
  EXPECT_EQ(memory_error("OFF\n3 -1 0\n", "off"), "bad: line 2: expected the counts: vertices faces edges");
  EXPECT_EQ(memory_error("OFF\nthree 1 0\n", "off"), "bad: line 2: expected the counts: vertices faces edges");
  EXPECT_EQ(memory_error("OFF\n3 99999999999 0\n0 0 0\n", "off"),
            "bad: the header declares 99999999999 faces, more than the file's 26 bytes can hold");
  EXPECT_EQ(memory_error("OFFX\n3 1 0\n", "off"), "bad: line 1: an OFF file begins with OFF");
  EXPECT_EQ(memory_error("nOFF 4\n3 1 0\n", "off"),
            "bad: line 1: nOFF: only 3-dimensional vertices make a body, not 4");
  EXPECT_EQ(memory_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "off"),
            "bad: line 6: face 0 needs a corner count (3 or more) and as many indices");
  EXPECT_EQ(memory_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", "off"),
            "bad: line 6: face 0 needs a corner count (3 or more) and as many indices");
  EXPECT_EQ(memory_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "off"),
            "bad: line 6: face 0 has a corner '-1' that is not a vertex index below 3");
  // 4OFF: x y z w, divided by w.
  const std::string homogeneous = "4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 4 0 2\n3 0 1 2\n";
  const TriangleMesh mesh = read_mesh_memory(homogeneous.data(), homogeneous.size(), "off", "w");
  EXPECT_EQ(mesh.vertices, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0)}));
}

TEST(MeshRead, DamagedPlyIsAnError) {
  const std::string vertex = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                             "property double y\nproperty double z\n";
  const std::string face = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(memory_error(vertex + face + body + "3 0 1 3\n", "ply"),
            "bad: face 0 of the PLY body has a corner 3 that is not a vertex index below 3 (line 13)");
  EXPECT_EQ(memory_error(vertex + face + body + "3 0 1 -1\n", "ply"),
            "bad: face 0 of the PLY body has a corner -1 that is not a vertex index below 3 (line 13)");
  EXPECT_EQ(memory_error(vertex + face + "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", "ply"),
            "bad: vertex 1 of the PLY body has a value 'zero' that is not a number of its type "
            "(line 11)");
  EXPECT_EQ(memory_error(vertex + face + body + "3 0 1 2.5\n", "ply"),
            "bad: face 0 of the PLY body has a value '2.5' that is not a number of its type (line 13)");
  EXPECT_EQ(memory_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                         "property double y\n" + face + body + "3 0 1 2\n", "ply"),
            "bad: the PLY header declares no vertex element with x, y and z");
  EXPECT_EQ(memory_error(vertex + "element face 1\nproperty list uchar int corners\nend_header\n" + body +
                             "3 0 1 2\n", "ply"),
            "bad: the PLY face element has no vertex_indices list");
  EXPECT_EQ(memory_error(vertex + "element face 1\nproperty list float int vertex_indices\nend_header\n",
                         "ply"),
            "bad: line 8 of the PLY header is not a PLY header line: 'property list float int vertex_indices'");
  EXPECT_EQ(memory_error("ply\nelement vertex 3\nproperty double x\nend_header\n", "ply"),
            "bad: the PLY header has no format line");
  // Huge counts: in the header, beyond the file; in the body, beyond what is left of it.
  EXPECT_EQ(memory_error("ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty double x\n"
                         "property double y\nproperty double z\nend_header\n", "ply"),
            "bad: the header declares 4000000000 vertex elements, more than the file's 112 bytes "
            "can hold");
  EXPECT_EQ(memory_error("ply\nformat binary_little_endian 1.0\nelement vertex 40\nproperty double x\n"
                         "property double y\nproperty double z\nend_header\n" + std::string(48, '\0'), "ply"),
            "bad: the header declares 40 vertex elements, more than the body's 48 bytes left can hold");
  EXPECT_EQ(memory_error(vertex + "element face 1\nproperty list uchar float vertex_indices\nend_header\n" +
                             body + "3 0 1 2\n", "ply"),
            "bad: the PLY face element's vertex_indices are not integers");
}

// PLY triangle strips: a tetrahedron as one strip 0 1 2 3 0 1 (every second triangle turned),
// after a restart (-1) and a strip of a repeated corner that makes no triangle.
TEST(MeshRead, PlyTriangleStripsMakeTheBody) {
  const std::vector<Vec3> corners = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
  for (const std::string type : {"int", "uint"}) {
    std::ostringstream ply;
    ply << "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
           "property double z\nelement tristrips 1\nproperty list int " << type << " vertex_indices\n"
           "end_header\n";
    for (const Vec3& p : corners) ply << p.x() << " " << p.y() << " " << p.z() << "\n";
    const std::string restart = type == "int" ? "-1" : "4294967295";
    ply << "11 0 0 1 " << restart << " 0 1 2 3 0 1 " << restart << "\n";
    const std::string text = ply.str();
    SCOPED_TRACE(type);
    TriangleMesh mesh = read_mesh_memory(text.data(), text.size(), "ply", "strip");
    EXPECT_EQ(mesh.faces.size(), 4u);
    const MeshCheck check = check_mesh(mesh);
    EXPECT_TRUE(check.closed);
    EXPECT_FALSE(check.turned);
    EXPECT_NEAR(check.volume, 1.0 / 6, 1e-15);
  }
}

TEST(MeshRead, DamagedStlIsAnError) {
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  EXPECT_EQ(memory_error("solid a\n" + facet.substr(0, 43), "stl"), "bad: the file ends inside a facet");
  EXPECT_EQ(memory_error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", "stl"),
            "bad: line 5: a vertex needs three numbers x y z");
  EXPECT_EQ(memory_error("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n", "stl"),
            "bad: line 7: a facet of 2 vertices, not three");
  EXPECT_EQ(memory_error("solid a\n" + facet + "vertex 1 1 1\nendsolid a\n", "stl"),
            "bad: line 9: 'vertex' was not expected here in an ASCII STL");
  // Binary: the facet count at byte 80 must account for the file's size (84 + 50 per facet).
  std::string binary(84 + 50, '\0');
  binary[80] = 2;
  EXPECT_EQ(memory_error(binary, "stl"),
            "bad: neither an ASCII STL (it does not begin with 'solid') nor a binary one (84 + 50 x "
            "2 facets = 184 bytes, the file has 134)");
  binary[80] = binary[81] = binary[82] = binary[83] = '\xff';
  EXPECT_EQ(memory_error(binary, "stl"),
            "bad: neither an ASCII STL (it does not begin with 'solid') nor a binary one (84 + 50 x "
            "4294967295 facets = 214748364834 bytes, the file has 134)");
  // A binary file whose header begins with "solid" (many exporters write it) is still binary.
  binary.replace(0, 5, "solid");
  binary[80] = 1;
  binary[81] = binary[82] = binary[83] = '\0';
  const TriangleMesh one = read_mesh_memory(binary.data(), binary.size(), "stl", "solid header");
  EXPECT_EQ(one.faces.size(), 1u);
  EXPECT_EQ(memory_error("solid" + binary.substr(5, 60), "stl"),
            "bad: neither an ASCII STL (it holds NUL bytes) nor a binary one (84 bytes at least, the "
            "file has 65)");
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

}  // namespace test_mesh_reading
}  // namespace tem
