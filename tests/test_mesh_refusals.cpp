// A refused mesh is refused once for everything wrong with it: meshes built here with defects of
// known kinds and numbers (counted from how they are made, not by the checker) get one message
// that names every kind with its count and first places, and the checks the defects kept from
// being made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "mesh/mesh_check.hpp"
#include "support/mesh_check_error.hpp"
#include "support/mesh_shapes.hpp"

namespace tem {
namespace test_mesh_refusals {

using namespace tem::testing_support;

// A box as 12 outward triangles (two per side) over 8 vertices.
TriangleMesh box(const Vec3& lo, const Vec3& hi) {
  TriangleMesh mesh =
      extruded_mesh({{{lo.x(), lo.y()}, {hi.x(), lo.y()}, {hi.x(), hi.y()}, {lo.x(), hi.y()}}},
                    {{0, 1, 2}, {0, 2, 3}}, hi.z() - lo.z(), "box");
  for (Vec3& v : mesh.vertices) v.z() += lo.z();
  return mesh;
}

// A thin tetrahedron standing on its tip at `tip`, its base 1 above it around the tip's x, y
// (a triangle of size 0.1), outward-oriented.
TriangleMesh tetrahedron_on_tip(const Vec3& tip) {
  TriangleMesh mesh;
  mesh.source = "tetrahedron";
  mesh.vertices = {tip, tip + Vec3(-0.1, -0.1, 1), tip + Vec3(0.1, -0.1, 1), tip + Vec3(0, 0.1, 1)};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
  const Vec3 &a = mesh.vertices[1], &b = mesh.vertices[2], &c = mesh.vertices[3];
  if ((a - tip).dot((b - tip).cross(c - tip)) < 0)
    for (auto& f : mesh.faces) std::swap(f[1], f[2]);
  return mesh;
}

// b's vertices and faces after a's (b's vertices renumbered).
void append(TriangleMesh& a, const TriangleMesh& b) {
  const int offset = static_cast<int>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& f : b.faces) a.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
}

// Vertices at one position become one (the first), as the reader welds them; unused ones stay,
// and so do numbers of vertices that do not exist.
void weld(TriangleMesh& mesh) {
  std::map<std::tuple<Real, Real, Real>, int> first;
  std::vector<int> to(mesh.vertices.size());
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); ++v) {
    const Vec3& p = mesh.vertices[v];
    to[v] = first.emplace(std::make_tuple(p.x(), p.y(), p.z()), v).first->second;
  }
  for (auto& f : mesh.faces)
    for (int& v : f)
      if (v < static_cast<int>(to.size())) v = to[v];
}

std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

// The line of the message that starts (after its indent) with `start`, or "".
std::string line_starting(const std::string& message, const std::string& start) {
  const std::size_t at = message.find("\n  " + start);
  if (at == std::string::npos) return "";
  const std::size_t end = message.find('\n', at + 1);
  return message.substr(at + 3, end == std::string::npos ? std::string::npos : end - at - 3);
}

std::size_t occurrences(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The index of the face of `mesh` (from `first` on) whose vertices all have z = `z` and whose
// triangle holds (x, y) strictly inside.
int face_holding(const TriangleMesh& mesh, int first, Real z, Real x, Real y) {
  for (int f = first; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& t = mesh.faces[f];
    bool flat = true;
    for (int v : t) flat = flat && mesh.vertices[v].z() == z;
    if (!flat) continue;
    auto side = [&](int i, int j) {
      const Vec3 &a = mesh.vertices[t[i]], &b = mesh.vertices[t[j]];
      return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
    };
    const Real s0 = side(0, 1), s1 = side(1, 2), s2 = side(2, 0);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return f;
  }
  return -1;
}

// Eight pieces 10 apart along x, each with defects of one or two kinds that no other piece has:
//   an open box (face 0 removed: its 3 edges open);
//   a box with face 0 turned (its 3 edges run the same way as their neighbours');
//   three boxes in a row touching corner to corner (2 pinched vertices);
//   a thin tetrahedron whose tip pierces a slab's top triangle (3 pairs of intersecting faces:
//     the tetrahedron's three sides against that triangle);
//   a face with a repeated vertex; a face naming a vertex that does not exist;
//   an unused vertex with a non-finite coordinate;
//   two faces on three collinear points, run both ways (2 faces of zero area making a closed
//     surface of zero volume).
TEST(MeshRefusal, EveryDefectIsCountedInOneMessage) {
  TriangleMesh mesh;
  mesh.source = "mixed";

  TriangleMesh open = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  open.faces.erase(open.faces.begin());
  append(mesh, open);

  TriangleMesh turned = box(Vec3(10, 0, 0), Vec3(11, 1, 1));
  std::swap(turned.faces[0][1], turned.faces[0][2]);
  append(mesh, turned);

  const int row_first_vertex = static_cast<int>(mesh.vertices.size());
  append(mesh, box(Vec3(20, 0, 0), Vec3(21, 1, 1)));
  append(mesh, box(Vec3(21, 1, 1), Vec3(22, 2, 2)));
  append(mesh, box(Vec3(22, 2, 2), Vec3(23, 3, 3)));

  const int slab_first_face = static_cast<int>(mesh.faces.size());
  append(mesh, box(Vec3(30, 0, 0), Vec3(34, 4, 1)));
  const int tetrahedron_first_face = static_cast<int>(mesh.faces.size());
  append(mesh, tetrahedron_on_tip(Vec3(32.5, 0.5, 0.5)));  // the top is z = 1

  const int v = static_cast<int>(mesh.vertices.size());
  mesh.vertices.push_back(Vec3(40, 0, 0));
  mesh.vertices.push_back(Vec3(41, 0, 0));
  const int repeated_face = static_cast<int>(mesh.faces.size());
  mesh.faces.push_back({v, v, v + 1});
  const int missing_face = static_cast<int>(mesh.faces.size());
  mesh.faces.push_back({v, v + 1, 1000000});

  const int nan_vertex = static_cast<int>(mesh.vertices.size());
  mesh.vertices.push_back(Vec3(45, std::numeric_limits<Real>::quiet_NaN(), 0));

  const int w = static_cast<int>(mesh.vertices.size());
  mesh.vertices.push_back(Vec3(50, 0, 0));
  mesh.vertices.push_back(Vec3(51, 0, 0));
  mesh.vertices.push_back(Vec3(52, 0, 0));
  mesh.faces.push_back({w, w + 1, w + 2});
  mesh.faces.push_back({w, w + 2, w + 1});

  weld(mesh);
  // The row's welded corners: the first box's (21, 1, 1) and the second's (22, 2, 2).
  ASSERT_EQ(mesh.vertices[row_first_vertex + 6], Vec3(21, 1, 1));
  ASSERT_EQ(mesh.vertices[row_first_vertex + 8 + 6], Vec3(22, 2, 2));

  const std::string message = check_error(mesh);
  EXPECT_EQ(first_line(message),
            "mixed: refused: 1 face naming a missing vertex, 1 vertex with a non-finite "
            "coordinate, 1 face with a repeated vertex, 2 faces of zero area, 3 open edges, 3 "
            "inconsistently oriented edges, 2 pinched vertices, 1 surface of zero volume, 3 "
            "pairs of intersecting faces")
      << message;

  EXPECT_NE(line_starting(message, "1 face naming a missing vertex")
                .find("face " + std::to_string(missing_face) + " (vertices "),
            std::string::npos)
      << message;
  EXPECT_NE(line_starting(message, "1 face naming a missing vertex")
                .find("vertex 1000000 does not exist"),
            std::string::npos)
      << message;
  EXPECT_NE(line_starting(message, "1 vertex with")
                .find("vertex " + std::to_string(nan_vertex) + " at (45, nan, 0)"),
            std::string::npos)
      << message;
  EXPECT_NE(line_starting(message, "1 face with a repeated vertex")
                .find("face " + std::to_string(repeated_face) + " (vertices "),
            std::string::npos)
      << message;
  EXPECT_EQ(occurrences(line_starting(message, "3 open edges"), "belongs to face "), 3u) << message;
  EXPECT_EQ(occurrences(line_starting(message, "3 inconsistently"), "both run from vertex"), 3u)
      << message;
  const std::string pinched = line_starting(message, "2 pinched vertices");
  EXPECT_NE(pinched.find("at (21, 1, 1): its faces form 2 fans"), std::string::npos) << message;
  EXPECT_NE(pinched.find("at (22, 2, 2): its faces form 2 fans"), std::string::npos) << message;
  EXPECT_NE(line_starting(message, "1 surface of zero volume")
                .find(" faces it belongs to encloses |V| = 0 <= "),
            std::string::npos)
      << message;

  // Each pair: the slab's top triangle under the tip against one side of the tetrahedron.
  const int top = face_holding(mesh, slab_first_face, 1, 32.5, 0.5);
  ASSERT_GE(top, slab_first_face);
  ASSERT_LT(top, tetrahedron_first_face);
  const std::string crossing = line_starting(message, "3 pairs of intersecting faces");
  EXPECT_EQ(occurrences(crossing, "face " + std::to_string(top) + " (vertices "), 3u) << message;
  for (int f = tetrahedron_first_face; f < tetrahedron_first_face + 4; ++f) {
    const bool base = mesh.vertices[mesh.faces[f][0]].z() == 1.5 &&
                      mesh.vertices[mesh.faces[f][1]].z() == 1.5 &&
                      mesh.vertices[mesh.faces[f][2]].z() == 1.5;
    EXPECT_EQ(occurrences(crossing, "intersects face " + std::to_string(f) + " ("), base ? 0u : 1u)
        << message;
  }

  // Surfaces: the open box, the turned box, three in the row, slab, tetrahedron, the flat pair;
  // the first two have no volume to judge. Left out of the crossing test: the faces with a
  // missing or repeated vertex and the two flat ones.
  EXPECT_NE(message.find("\n  not checked: the volume of 2 of 8 connected surfaces"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("\n  not checked: whether the 4 face(s) "), std::string::npos) << message;
  EXPECT_NE(message.find("\n  not checked: how the surfaces nest"), std::string::npos) << message;
}

// Three places are named per kind, the first in vertex order, and the rest counted.
TEST(MeshRefusal, ThreePlacesPerKindAndHowManyMore) {
  TriangleMesh mesh = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  mesh.source = "holes";
  // Face 0 is a bottom triangle, face 1 a top one (tests/support/mesh_shapes.hpp): removing
  // both opens six edges.
  std::vector<std::pair<int, int>> opened;
  for (int f : {0, 1})
    for (int k = 0; k < 3; ++k)
      opened.push_back(std::minmax(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3]));
  std::sort(opened.begin(), opened.end());
  ASSERT_EQ(std::unique(opened.begin(), opened.end()), opened.end());
  mesh.faces.erase(mesh.faces.begin(), mesh.faces.begin() + 2);

  const std::string message = check_error(mesh);
  EXPECT_EQ(first_line(message), "holes: refused: 6 open edges") << message;
  const std::string line = line_starting(message, "6 open edges");
  EXPECT_EQ(occurrences(line, "belongs to face "), 3u) << message;
  std::size_t at = 0;
  for (int k = 0; k < 3; ++k) {
    const std::string edge = "edge " + std::to_string(opened[k].first) + "-" +
                             std::to_string(opened[k].second) + " at (";
    const std::size_t found = line.find(edge);
    EXPECT_NE(found, std::string::npos) << edge << "\n" << message;
    EXPECT_GE(found, at) << message;  // in order
    at = found;
  }
  EXPECT_EQ(line.substr(line.size() - 12), "; and 3 more") << message;
}

// The crossing test needs no manifold surface: a tetrahedron piercing a box is found whether the
// box is open or its faces are inconsistently oriented (CGAL 5.5's test takes neither).
TEST(MeshRefusal, CrossingsAreFoundBesideOtherDefects) {
  TriangleMesh open = box(Vec3(0, 0, 0), Vec3(4, 4, 1));
  open.faces.erase(open.faces.begin());  // a bottom face: the tip pierces the top
  TriangleMesh turned = box(Vec3(0, 0, 0), Vec3(4, 4, 1));
  std::swap(turned.faces[0][1], turned.faces[0][2]);
  for (auto [mesh, defect] : {std::pair(open, std::string("3 open edges")),
                              std::pair(turned, std::string("3 inconsistently oriented edges"))}) {
    mesh.source = "pierced";
    append(mesh, tetrahedron_on_tip(Vec3(2.5, 0.5, 0.5)));
    EXPECT_EQ(first_line(check_error(mesh)),
              "pierced: refused: " + defect + ", 3 pairs of intersecting faces");
  }
}

// Faces sharing vertices by number meet there without crossing; they cross where they overlap
// beyond what they share. Each pair here is a loose soup: its edges are open.
TEST(MeshRefusal, SharedVerticesAndEdgesAreNotCrossings) {
  auto soup = [](std::vector<Vec3> points, std::vector<std::array<int, 3>> faces) {
    TriangleMesh mesh;
    mesh.source = "soup";
    mesh.vertices = std::move(points);
    mesh.faces = std::move(faces);
    return first_line(check_error(mesh));
  };
  const Vec3 o(0, 0, 0), a(2, 0, 0), b(0, 2, 0);
  // One shared vertex, in one plane: the second face inside the first, or in the opposite
  // quadrant. The shared vertex is pinched either way (two fans).
  EXPECT_EQ(soup({o, a, b, Vec3(1, 0.5, 0), Vec3(0.5, 1, 0)}, {{0, 1, 2}, {0, 3, 4}}),
            "soup: refused: 6 open edges, 1 pinched vertex, 1 pair of intersecting faces");
  EXPECT_EQ(soup({o, a, b, Vec3(-1, 0, 0), Vec3(0, -1, 0)}, {{0, 1, 2}, {0, 4, 3}}),
            "soup: refused: 6 open edges, 1 pinched vertex");
  // One shared edge a-b, in one plane: the second face folded back over the first, or unfolded.
  EXPECT_EQ(soup({o, a, b, Vec3(0.5, 0.5, 0)}, {{0, 1, 2}, {2, 1, 3}}),
            "soup: refused: 4 open edges, 1 pair of intersecting faces");
  EXPECT_EQ(soup({o, a, b, Vec3(2, 2, 0)}, {{0, 1, 2}, {2, 1, 3}}), "soup: refused: 4 open edges");
}

// 500 copies of one triangle cross each other in 124,750 pairs: the search stops at 100,000
// and says so.
TEST(MeshRefusal, CrossingsStopAtAHundredThousandPairs) {
  TriangleMesh mesh;
  mesh.source = "pile";
  mesh.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.faces.assign(500, {0, 1, 2});
  const std::string message = check_error(mesh);
  EXPECT_EQ(first_line(message),
            "pile: refused: 3 edges of more than two faces, 100000 pairs of intersecting faces")
      << message;
  EXPECT_NE(message.find("\n  not checked: pairs of intersecting faces beyond the first 100000"),
            std::string::npos)
      << message.substr(0, 2000);
}

}  // namespace test_mesh_refusals
}  // namespace tem
