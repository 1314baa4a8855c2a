// Checking a triangle mesh before it becomes a body: each defect is reported with the face, edge
// or vertex it is at, and the only changes made (turning inward surfaces, dropping vertices that
// no face uses) come with a warning.
//
// Tolerances are relative to the diagonal d of the bounding box of the vertices that faces use:
//   a face whose area is <= 1e-14 d^2 is degenerate (zero area: its normal is round-off);
//   a closed surface whose |volume| is <= 1e-12 d^3 encloses zero volume.
// Edges, orientation and fans are exact (integer) tests on the welded vertex numbers.
#include "mesh/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "mesh/cgal_operations.hpp"

namespace tem {
namespace {

constexpr Real kAreaTolerance = 1e-14;
constexpr Real kVolumeTolerance = 1e-12;
constexpr int kMaxIntersectingPairs = 10;

class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void unite(int a, int b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int> parent_;
};

std::string vertex_text(const TriangleMesh& mesh, int v) {
  const Vec3& p = mesh.vertices[v];
  std::ostringstream s;
  s << "vertex " << v << " at (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

std::string face_text(const TriangleMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  return "face " + std::to_string(f) + " (vertices " + std::to_string(t[0]) + ", " +
         std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")";
}

[[noreturn]] void fail(const TriangleMesh& mesh, const std::string& where, const std::string& why) {
  throw MeshError(mesh.source + ": " + where + ": " + why);
}

std::string number(Real x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

// One side of an edge: face `face` runs from `from` to `to` (its corners `corner` and corner+1).
struct HalfEdge {
  int lo, hi;  // the undirected edge, lo < hi
  int from;
  int face, corner;
};

// Every face's three half-edges, sorted so that the sides of one edge are neighbours.
std::vector<HalfEdge> sorted_half_edges(const TriangleMesh& mesh) {
  std::vector<HalfEdge> edges;
  edges.reserve(3 * mesh.faces.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a, f, k});
    }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  return edges;
}

std::string edge_text(const HalfEdge& e) {
  return "edge " + std::to_string(e.lo) + "-" + std::to_string(e.hi);
}

void check_indices_and_coordinates(const TriangleMesh& mesh) {
  if (mesh.faces.empty()) throw MeshError(mesh.source + ": the mesh has no faces");
  const int n = static_cast<int>(mesh.vertices.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= n)
        fail(mesh, face_text(mesh, f),
             "vertex " + std::to_string(v) + " does not exist (the mesh has " + std::to_string(n) +
                 " vertices)");
  for (int v = 0; v < n; ++v)
    if (!mesh.vertices[v].allFinite()) fail(mesh, vertex_text(mesh, v), "a coordinate is not finite");
}

// The bounding box of the vertices that faces use (a stray vertex must not loosen tolerances).
Eigen::AlignedBox<Real, 3> used_bounds(const TriangleMesh& mesh) {
  Eigen::AlignedBox<Real, 3> box;
  for (const auto& t : mesh.faces)
    for (int v : t) box.extend(mesh.vertices[v]);
  return box;
}

void check_degenerate_faces(const TriangleMesh& mesh, Real diagonal) {
  const Real tolerance = kAreaTolerance * diagonal * diagonal;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == t[(k + 1) % 3])
        fail(mesh, face_text(mesh, f),
             "vertex " + std::to_string(t[k]) + " appears twice (a degenerate face)");
    const Vec3& a = mesh.vertices[t[0]];
    const Real area = 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
    if (!(area > tolerance))
      fail(mesh, face_text(mesh, f),
           "zero area (" + number(area) + " <= 1e-14 x bounding-box diagonal^2 = " +
               number(tolerance) + "; a degenerate face)");
  }
}

// Every edge must have exactly two sides; returns them as pairs (first, second) of indices into
// `edges`.
std::vector<std::pair<int, int>> pair_edges(const TriangleMesh& mesh,
                                            const std::vector<HalfEdge>& edges) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(edges.size() / 2);
  const int n = static_cast<int>(edges.size());
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i == 1)
      fail(mesh, edge_text(edges[i]),
           "belongs to face " + std::to_string(edges[i].face) +
               " only (an open edge: the mesh is not closed)");
    if (j - i > 2) {
      std::string faces;
      for (int k = i; k < j; ++k) faces += (k > i ? ", " : "") + std::to_string(edges[k].face);
      fail(mesh, edge_text(edges[i]),
           "shared by " + std::to_string(j - i) + " faces (" + faces + "; not edge-manifold)");
    }
    pairs.emplace_back(i, i + 1);
    i = j;
  }
  return pairs;
}

void check_orientation(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges,
                       const std::vector<std::pair<int, int>>& pairs) {
  for (const auto& [i, j] : pairs)
    if (edges[i].from == edges[j].from)
      fail(mesh, edge_text(edges[i]),
           "face " + std::to_string(edges[i].face) + " and face " + std::to_string(edges[j].face) +
               " are inconsistently oriented (both run along it from vertex " +
               std::to_string(edges[i].from) + ")");
}

// The faces around a vertex must form one fan: corners (face, vertex) joined across shared
// edges must make one set per vertex. Two cones meeting at their tips fail here.
void check_fans(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges,
                const std::vector<std::pair<int, int>>& pairs) {
  DisjointSets corners(3 * static_cast<int>(mesh.faces.size()));
  for (const auto& [i, j] : pairs) {
    const HalfEdge& e = edges[i];
    const HalfEdge& g = edges[j];  // runs the other way: its corner is e's corner + 1
    corners.unite(3 * e.face + e.corner, 3 * g.face + (g.corner + 1) % 3);
    corners.unite(3 * e.face + (e.corner + 1) % 3, 3 * g.face + g.corner);
  }
  std::vector<int> fan(mesh.vertices.size(), -1);
  for (int c = 0; c < 3 * static_cast<int>(mesh.faces.size()); ++c) {
    const int v = mesh.faces[c / 3][c % 3];
    const int root = corners.find(c);
    if (fan[v] == -1) fan[v] = root;
    if (fan[v] == root) continue;
    std::set<int> roots;
    for (int d = 0; d < 3 * static_cast<int>(mesh.faces.size()); ++d)
      if (mesh.faces[d / 3][d % 3] == v) roots.insert(corners.find(d));
    fail(mesh, vertex_text(mesh, v),
         "its faces form " + std::to_string(roots.size()) +
             " fans that meet only at this vertex (not vertex-manifold)");
  }
}

std::vector<int> unused_vertices(const TriangleMesh& mesh) {
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const auto& t : mesh.faces)
    for (int v : t) used[v] = 1;
  std::vector<int> unused;
  for (int v = 0; v < static_cast<int>(used.size()); ++v)
    if (!used[v]) unused.push_back(v);
  return unused;
}

// A connected closed surface: its faces, signed volume and bounds.
struct Surface {
  std::vector<int> faces;
  Real volume = 0;
  Eigen::AlignedBox<Real, 3> box;
};

std::vector<Surface> surfaces(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges,
                              const std::vector<std::pair<int, int>>& pairs, const Vec3& origin) {
  const int n = static_cast<int>(mesh.faces.size());
  DisjointSets sets(n);
  for (const auto& [i, j] : pairs) sets.unite(edges[i].face, edges[j].face);
  std::vector<int> index(n, -1);
  std::vector<Surface> result;
  for (int f = 0; f < n; ++f) {
    int& s = index[sets.find(f)];
    if (s == -1) {
      s = static_cast<int>(result.size());
      result.emplace_back();
    }
    Surface& surface = result[s];
    surface.faces.push_back(f);
    const auto& t = mesh.faces[f];
    // Divergence theorem: the tetrahedra from `origin` (the box centre, to keep round-off small).
    const Vec3 a = mesh.vertices[t[0]] - origin, b = mesh.vertices[t[1]] - origin,
               c = mesh.vertices[t[2]] - origin;
    surface.volume += a.dot(b.cross(c)) / 6;
    for (int v : t) surface.box.extend(mesh.vertices[v]);
  }
  return result;
}

// Solid angle of the surface seen from p over 4 pi (van Oosterom and Strackee's formula per
// triangle): +-1 inside a closed surface, 0 outside, whatever the surface's shape.
Real winding_number(const TriangleMesh& mesh, const Surface& surface, const Vec3& p) {
  Real sum = 0;
  for (int f : surface.faces) {
    const auto& t = mesh.faces[f];
    const Vec3 a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const Real la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2 * std::atan2(a.dot(b.cross(c)),
                          la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return sum / (4 * std::numbers::pi);
}

void turn(TriangleMesh& mesh, Surface& surface) {
  for (int f : surface.faces) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  surface.volume = -surface.volume;
}

// Surfaces nested in others alternate: an outermost surface points outwards (positive volume),
// a cavity in it inwards, a solid in the cavity outwards again, and so on. An outermost surface
// whose nest is inside out as a whole (every surface in it pointing the wrong way, e.g. a mesh
// exported with all normals inwards) is turned with a warning: there is one reading of it. A nest
// that is partly right and partly wrong is an error: whether the wrong surface was meant as a
// cavity or a solid cannot be told. Returns whether anything was turned.
bool orient_surfaces(TriangleMesh& mesh, std::vector<Surface>& surfaces, MeshCheck& check) {
  const int n = static_cast<int>(surfaces.size());
  std::vector<std::vector<int>> containers(n);
  for (int c = 0; c < n; ++c) {
    const Vec3& p = mesh.vertices[mesh.faces[surfaces[c].faces.front()][0]];
    for (int d = 0; d < n; ++d)
      if (d != c && surfaces[d].box.contains(surfaces[c].box) &&
          std::abs(winding_number(mesh, surfaces[d], p)) > 0.5)
        containers[c].push_back(d);
  }
  std::vector<int> outermost(n);
  std::vector<char> wrong(n);
  for (int c = 0; c < n; ++c) {
    outermost[c] = c;
    for (int d : containers[c])
      if (containers[d].empty()) outermost[c] = d;
    const bool cavity = containers[c].size() % 2 == 1;
    wrong[c] = cavity ? surfaces[c].volume > 0 : surfaces[c].volume < 0;
  }
  bool turned = false;
  for (int root = 0; root < n; ++root) {
    if (outermost[root] != root) continue;
    int count = 0, wrong_count = 0, first_wrong = -1, faces = 0;
    for (int c = 0; c < n; ++c)
      if (outermost[c] == root) {
        ++count;
        faces += static_cast<int>(surfaces[c].faces.size());
        if (wrong[c] && (first_wrong == -1 || containers[c].size() < containers[first_wrong].size()))
          first_wrong = c;
        wrong_count += wrong[c];
      }
    if (wrong_count == 0) continue;
    if (wrong_count < count) {
      const Surface& s = surfaces[first_wrong];
      fail(mesh, face_text(mesh, s.faces.front()),
           "the closed surface of " + std::to_string(s.faces.size()) + " faces it belongs to lies "
               "inside " + std::to_string(containers[first_wrong].size()) + " other surface(s) "
               "and points " + (s.volume > 0 ? "outwards" : "inwards") + ", against the "
               "surfaces around it (nested surfaces must alternate: outermost outwards, "
               "cavities inwards)");
    }
    for (int c = 0; c < n; ++c)
      if (outermost[c] == root) turn(mesh, surfaces[c]);
    turned = true;
    check.warnings.push_back(
        mesh.source + ": " +
        (n == count ? "all " + std::to_string(faces) + " faces pointed inwards"
                    : "the " + std::to_string(count) + " surface(s) of " + std::to_string(faces) +
                          " faces around " + face_text(mesh, surfaces[root].faces.front()) +
                          " pointed inwards") +
        " (negative volume) and were turned");
  }
  return turned;
}

// Removes vertices no face uses and renumbers the faces.
void drop_vertices(TriangleMesh& mesh, const std::vector<int>& unused) {
  std::vector<int> renumber(mesh.vertices.size(), 0);
  for (int v : unused) renumber[v] = -1;
  int next = 0;
  for (std::size_t v = 0; v < renumber.size(); ++v)
    if (renumber[v] == 0) {
      mesh.vertices[next] = mesh.vertices[v];
      renumber[v] = next++;
    }
  mesh.vertices.resize(next);
  for (auto& t : mesh.faces)
    for (int& v : t) v = renumber[v];
}

}  // namespace

MeshCheck check_mesh(TriangleMesh& mesh) {
  MeshCheck check;
  check_indices_and_coordinates(mesh);
  const Eigen::AlignedBox<Real, 3> box = used_bounds(mesh);
  const Real diagonal = box.diagonal().norm();
  check_degenerate_faces(mesh, diagonal);

  const std::vector<HalfEdge> edges = sorted_half_edges(mesh);
  const std::vector<std::pair<int, int>> pairs = pair_edges(mesh, edges);
  check.closed = true;
  check_orientation(mesh, edges, pairs);
  check_fans(mesh, edges, pairs);

  // Unused vertices are kept until every message has been written in the input's numbering.
  const std::vector<int> unused = unused_vertices(mesh);

  std::vector<Surface> parts = surfaces(mesh, edges, pairs, box.center());
  const Real zero_volume = kVolumeTolerance * diagonal * diagonal * diagonal;
  for (const Surface& s : parts)
    if (!(std::abs(s.volume) > zero_volume))
      fail(mesh, face_text(mesh, s.faces.front()),
           "the closed surface of " + std::to_string(s.faces.size()) +
               " faces it belongs to encloses zero volume (|V| = " + number(std::abs(s.volume)) +
               " <= 1e-12 x bounding-box diagonal^3 = " + number(zero_volume) + ")");

  // Before nesting is worked out: containment means nothing for surfaces that cross.
  const auto crossing = self_intersecting_faces(mesh, kMaxIntersectingPairs);
  if (!crossing.empty())
    fail(mesh, face_text(mesh, crossing.front().first),
         "intersects " + face_text(mesh, crossing.front().second) + " (self-intersecting; " +
             std::to_string(crossing.size()) + " pair(s) found, the search stops at " +
             std::to_string(kMaxIntersectingPairs) + ")");

  check.turned = orient_surfaces(mesh, parts, check);
  for (const Surface& s : parts) check.volume += s.volume;

  if (!unused.empty()) {
    std::string list;
    for (std::size_t k = 0; k < std::min<std::size_t>(unused.size(), 5); ++k)
      list += (k ? ", " : "") + std::to_string(unused[k]);
    if (unused.size() > 5) list += ", ...";
    check.warnings.push_back(mesh.source + ": " + std::to_string(unused.size()) +
                             " vertex(es) belong to no face and were dropped (" + list + ")");
    drop_vertices(mesh, unused);
  }
  check.vertices = static_cast<int>(mesh.vertices.size());
  check.faces = static_cast<int>(mesh.faces.size());
  return check;
}

}  // namespace tem
