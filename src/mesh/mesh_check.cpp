// Checking a triangle mesh before it becomes a body. A mesh that is refused is refused once, for
// everything found wrong with it: one MeshError that gives, for each kind of defect, how many
// there are and the first few (face, edge or vertex number and where it is), and which checks
// could not be made because of them. The only changes made (turning inward surfaces, dropping
// vertices that no face uses) come with a warning.
//
// Tolerances are relative to the diagonal d of the bounding box of the vertices that faces use:
//   a face whose area is <= 1e-14 d^2 is degenerate (zero area: its normal is round-off);
//   a closed surface whose |volume| is <= 1e-12 d^3 encloses zero volume.
// Edges, orientation and fans are exact (integer) tests on the welded vertex numbers; crossings
// are CGAL's exact predicates.
//
// What a defect keeps from the later checks: a face naming a missing vertex or repeating one has
// no edges (it is left out of the edge, fan, surface and crossing checks); a face of zero area or
// with a non-finite coordinate keeps its edges but is left out of the crossing check; a surface's
// volume is judged only where all its edges have two consistently oriented faces and its
// coordinates are finite; nesting only for a mesh with no other defect.
#include "mesh/mesh_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "mesh/crossing_faces.hpp"

namespace tem {
namespace {

constexpr Real kZeroVolume = 1e-12;  // of the bounding box diagonal cubed
constexpr int kExamples = 3;  // places named per kind of defect
// Enough to say how badly a mesh crosses itself, few enough to keep in memory.
constexpr std::size_t kMaxCrossings = 100'000;

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

std::string number(Real x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string point_text(const Vec3& p) {
  return "(" + number(p.x()) + ", " + number(p.y()) + ", " + number(p.z()) + ")";
}

std::string vertex_text(const TriangleMesh& mesh, int v) {
  return "vertex " + std::to_string(v) + " at " + point_text(mesh.vertices[v]);
}

std::string face_text(const TriangleMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  return "face " + std::to_string(f) + " (vertices " + std::to_string(t[0]) + ", " +
         std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")";
}

// A face whose vertices exist, with its centre: where to look in a viewer.
std::string face_at(const TriangleMesh& mesh, int f) {
  const auto& t = mesh.faces[f];
  return face_text(mesh, f) + " at " +
         point_text((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3);
}

// The kinds of defect, in the order of the checks (and of the message).
enum class Defect {
  missing_vertex,
  non_finite,
  repeated_vertex,
  zero_area,
  open_edge,
  crowded_edge,
  flipped_edge,
  pinched_vertex,
  zero_volume,
  crossing,
  bad_nesting,
};
constexpr int kDefectKinds = static_cast<int>(Defect::bad_nesting) + 1;

struct DefectName {
  const char* one;
  const char* several;
  const char* why;
};
constexpr DefectName kDefectNames[kDefectKinds] = {
    {"face naming a missing vertex", "faces naming missing vertices", "an index out of range"},
    {"vertex with a non-finite coordinate", "vertices with a non-finite coordinate",
     "a coordinate is not finite"},
    {"face with a repeated vertex", "faces with a repeated vertex", "a degenerate face"},
    {"face of zero area", "faces of zero area",
     "a degenerate face: area at most 1e-14 x bounding-box diagonal^2"},
    {"open edge", "open edges", "a face on one side only: the mesh is not closed"},
    {"edge of more than two faces", "edges of more than two faces", "not edge-manifold"},
    {"inconsistently oriented edge", "inconsistently oriented edges",
     "its two faces run along it the same way"},
    {"pinched vertex", "pinched vertices",
     "its faces form fans that meet only at it: not vertex-manifold"},
    {"surface of zero volume", "surfaces of zero volume",
     "a closed surface enclosing at most 1e-12 x bounding-box diagonal^3"},
    {"pair of intersecting faces", "pairs of intersecting faces", "self-intersecting"},
    {"nested surface pointing the wrong way", "nested surfaces pointing the wrong way",
     "nested surfaces must alternate: outermost outwards, cavities inwards"},
};

// Everything wrong with a mesh: per kind, how many and the first kExamples places; and the
// checks that could not be made because of it.
class Defects {
 public:
  void add(Defect kind, std::string example) {
    Found& found = found_[static_cast<int>(kind)];
    if (++found.count <= kExamples) found.examples.push_back(std::move(example));
  }
  void not_checked(std::string what_and_why) { not_checked_.push_back(std::move(what_and_why)); }
  bool empty() const {
    return std::all_of(std::begin(found_), std::end(found_),
                       [](const Found& f) { return f.count == 0; });
  }

  // "SOURCE: refused: 2 pinched vertices, 14 open edges", then a line per kind with its
  // examples, then a line per check not made.
  std::string message(const std::string& source) const {
    auto counted = [this](int k) {
      const int n = found_[k].count;
      return std::to_string(n) + " " + (n == 1 ? kDefectNames[k].one : kDefectNames[k].several);
    };
    std::string text = source + ": refused:", lines;
    const char* separator = " ";
    for (int k = 0; k < kDefectKinds; ++k) {
      if (found_[k].count == 0) continue;
      text += separator + counted(k);
      separator = ", ";
      lines += "\n  " + counted(k) + " (" + kDefectNames[k].why + "): ";
      for (std::size_t i = 0; i < found_[k].examples.size(); ++i)
        lines += (i ? "; " : "") + found_[k].examples[i];
      if (found_[k].count > kExamples)
        lines += "; and " + std::to_string(found_[k].count - kExamples) + " more";
    }
    text += lines;
    for (const std::string& n : not_checked_) text += "\n  not checked: " + n;
    return text;
  }

 private:
  struct Found {
    int count = 0;
    std::vector<std::string> examples;
  };
  Found found_[kDefectKinds];
  std::vector<std::string> not_checked_;
};

// One side of an edge: face `face` runs from `from` to `to` (its corners `corner` and corner+1).
struct HalfEdge {
  int lo, hi;  // the undirected edge, lo < hi
  int from;
  int face, corner;
};

// The half-edges of the faces not left out, sorted so that the sides of one edge are neighbours.
std::vector<HalfEdge> sorted_half_edges(const TriangleMesh& mesh,
                                        const std::vector<char>& left_out) {
  std::vector<HalfEdge> edges;
  edges.reserve(3 * mesh.faces.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    if (!left_out[f])
      for (int k = 0; k < 3; ++k) {
        const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
        edges.push_back({std::min(a, b), std::max(a, b), a, f, k});
      }
  std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.lo, x.hi, x.face) < std::tie(y.lo, y.hi, y.face);
  });
  return edges;
}

std::string edge_at(const TriangleMesh& mesh, const HalfEdge& e) {
  return "edge " + std::to_string(e.lo) + "-" + std::to_string(e.hi) + " at " +
         point_text(0.5 * (mesh.vertices[e.lo] + mesh.vertices[e.hi]));
}

// What the per-face checks found: faces without edges (a missing or repeated vertex) and faces
// the crossing test cannot take (those, zero area, a non-finite coordinate).
struct FaceScreen {
  std::vector<char> no_edges;
  std::vector<char> no_crossing;
  std::vector<char> finite;  // per vertex
};

FaceScreen screen_faces(const TriangleMesh& mesh, Defects& defects) {
  const int faces = static_cast<int>(mesh.faces.size());
  const int n = static_cast<int>(mesh.vertices.size());
  FaceScreen screen{std::vector<char>(faces, 0), std::vector<char>(faces, 0),
                    std::vector<char>(n, 1)};
  for (int f = 0; f < faces; ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= n) {
        defects.add(Defect::missing_vertex, face_text(mesh, f) + ": vertex " + std::to_string(v) +
                                                " does not exist (the mesh has " +
                                                std::to_string(n) + " vertices)");
        screen.no_edges[f] = screen.no_crossing[f] = 1;
        break;
      }
  for (int v = 0; v < n; ++v)
    if (!mesh.vertices[v].allFinite()) {
      screen.finite[v] = 0;
      defects.add(Defect::non_finite, vertex_text(mesh, v));
    }
  for (int f = 0; f < faces; ++f)
    if (!screen.no_edges[f])
      for (int v : mesh.faces[f])
        if (!screen.finite[v]) screen.no_crossing[f] = 1;
  return screen;
}

// The bounding box of the vertices that faces use (a stray vertex must not loosen tolerances).
Eigen::AlignedBox<Real, 3> used_bounds(const TriangleMesh& mesh, const FaceScreen& screen) {
  Eigen::AlignedBox<Real, 3> box;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    if (!screen.no_crossing[f])
      for (int v : mesh.faces[f]) box.extend(mesh.vertices[v]);
  return box;
}

void check_degenerate_faces(const TriangleMesh& mesh, Real diagonal, FaceScreen& screen,
                            Defects& defects) {
  const Real tolerance = kFaceAreaTolerance * diagonal * diagonal;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    if (screen.no_edges[f]) continue;
    const auto& t = mesh.faces[f];
    bool repeated = false;
    for (int k = 0; k < 3 && !repeated; ++k)
      if (t[k] == t[(k + 1) % 3]) {
        repeated = true;
        defects.add(Defect::repeated_vertex,
                    face_text(mesh, f) + ": vertex " + std::to_string(t[k]) + " appears twice");
      }
    if (repeated) {
      screen.no_edges[f] = screen.no_crossing[f] = 1;
      continue;
    }
    if (screen.no_crossing[f]) continue;  // a non-finite coordinate: no area to judge
    const Vec3& a = mesh.vertices[t[0]];
    const Real area = 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
    if (!(area > tolerance)) {
      defects.add(Defect::zero_area,
                  face_at(mesh, f) + ": area " + number(area) + " <= " + number(tolerance));
      screen.no_crossing[f] = 1;
    }
  }
}

// The edges: sides paired two by two where an edge has exactly two (indices into `edges`);
// open edges, edges of more than two faces and inconsistently oriented pairs are defects.
struct EdgeScan {
  std::vector<std::pair<int, int>> pairs;
  std::vector<char> face_unsound;    // has an edge that is open, crowded or flipped
  std::vector<char> vertex_crowded;  // on an edge of more than two faces
};

EdgeScan scan_edges(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges,
                    Defects& defects) {
  EdgeScan scan{
      {}, std::vector<char>(mesh.faces.size(), 0), std::vector<char>(mesh.vertices.size(), 0)};
  scan.pairs.reserve(edges.size() / 2);
  const int n = static_cast<int>(edges.size());
  for (int i = 0; i < n;) {
    int j = i + 1;
    while (j < n && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    const HalfEdge& e = edges[i];
    if (j - i == 2) {
      scan.pairs.emplace_back(i, i + 1);
      if (e.from == edges[i + 1].from) {
        defects.add(Defect::flipped_edge, edge_at(mesh, e) + ": face " + std::to_string(e.face) +
                                              " and face " + std::to_string(edges[i + 1].face) +
                                              " both run from vertex " + std::to_string(e.from));
        scan.face_unsound[e.face] = scan.face_unsound[edges[i + 1].face] = 1;
      }
    } else if (j - i == 1) {
      defects.add(Defect::open_edge,
                  edge_at(mesh, e) + ": belongs to face " + std::to_string(e.face) + " only");
      scan.face_unsound[e.face] = 1;
    } else {
      std::string faces;
      for (int k = i; k < j; ++k) {
        faces += (k > i ? ", " : "") + std::to_string(edges[k].face);
        scan.face_unsound[edges[k].face] = 1;
      }
      defects.add(Defect::crowded_edge, edge_at(mesh, e) + ": shared by " + std::to_string(j - i) +
                                            " faces (" + faces + ")");
      scan.vertex_crowded[e.lo] = scan.vertex_crowded[e.hi] = 1;
    }
    i = j;
  }
  return scan;
}

// The faces around a vertex must form one fan: corners (face, vertex) joined across edges of two
// faces must make one set per vertex. Two cones meeting at their tips fail here. Corners are
// joined by vertex number, so this holds whatever the orientation; a vertex on an edge of more
// than two faces or on a face without edges has no fans to count and is skipped.
void check_fans(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges, const EdgeScan& scan,
                const FaceScreen& screen, Defects& defects) {
  const int faces = static_cast<int>(mesh.faces.size());
  auto corner_of = [&](int f, int v) {
    const auto& t = mesh.faces[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  DisjointSets corners(3 * faces);
  for (const auto& [i, j] : scan.pairs)
    for (int v : {edges[i].lo, edges[i].hi})
      corners.unite(corner_of(edges[i].face, v), corner_of(edges[j].face, v));
  std::vector<char> skip = scan.vertex_crowded;
  for (int f = 0; f < faces; ++f)
    if (screen.no_edges[f])
      for (int v : mesh.faces[f])
        if (v >= 0 && v < static_cast<int>(skip.size())) skip[v] = 1;
  std::vector<std::pair<int, int>> fans;  // (vertex, the set of one of its corners)
  fans.reserve(3 * faces);
  for (int c = 0; c < 3 * faces; ++c)
    if (!screen.no_edges[c / 3]) fans.emplace_back(mesh.faces[c / 3][c % 3], corners.find(c));
  std::sort(fans.begin(), fans.end());
  fans.erase(std::unique(fans.begin(), fans.end()), fans.end());
  for (std::size_t i = 0; i < fans.size();) {
    std::size_t j = i + 1;
    while (j < fans.size() && fans[j].first == fans[i].first) ++j;
    const int v = fans[i].first;
    if (j - i > 1 && !skip[v])
      defects.add(Defect::pinched_vertex,
                  vertex_text(mesh, v) + ": its faces form " + std::to_string(j - i) + " fans");
    i = j;
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

// A connected surface (faces joined across edges of two faces): its faces, signed volume and
// bounds, and whether it is sound: closed, consistently oriented, with finite coordinates, so
// that its volume means something.
struct Surface {
  std::vector<int> faces;
  Real volume = 0;
  Eigen::AlignedBox<Real, 3> box;
  bool sound = true;
};

std::vector<Surface> surfaces(const TriangleMesh& mesh, const std::vector<HalfEdge>& edges,
                              const EdgeScan& scan, const FaceScreen& screen, const Vec3& origin) {
  const int n = static_cast<int>(mesh.faces.size());
  DisjointSets sets(n);
  for (const auto& [i, j] : scan.pairs) sets.unite(edges[i].face, edges[j].face);
  std::vector<int> index(n, -1);
  std::vector<Surface> result;
  for (int f = 0; f < n; ++f) {
    if (screen.no_edges[f]) continue;
    int& s = index[sets.find(f)];
    if (s == -1) {
      s = static_cast<int>(result.size());
      result.emplace_back();
    }
    Surface& surface = result[s];
    surface.faces.push_back(f);
    const auto& t = mesh.faces[f];
    if (scan.face_unsound[f] ||
        !(screen.finite[t[0]] && screen.finite[t[1]] && screen.finite[t[2]]))
      surface.sound = false;
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
    const Vec3 a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p,
               c = mesh.vertices[t[2]] - p;
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
bool orient_surfaces(TriangleMesh& mesh, std::vector<Surface>& surfaces, MeshCheck& check,
                     Defects& defects) {
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
        if (wrong[c] &&
            (first_wrong == -1 || containers[c].size() < containers[first_wrong].size()))
          first_wrong = c;
        wrong_count += wrong[c];
      }
    if (wrong_count == 0) continue;
    if (wrong_count < count) {
      const Surface& w = surfaces[first_wrong];
      defects.add(Defect::bad_nesting,
                  face_at(mesh, w.faces.front()) + ": the closed surface of " +
                      std::to_string(w.faces.size()) + " faces it belongs to lies inside " +
                      std::to_string(containers[first_wrong].size()) +
                      " other surface(s) and points " + (w.volume > 0 ? "outwards" : "inwards") +
                      ", against the surfaces around it");
      continue;
    }
    for (int c = 0; c < n; ++c)
      if (outermost[c] == root) turn(mesh, surfaces[c]);
    turned = true;
    check.warnings.push_back(mesh.source + ": " +
                             (n == count ? "all " + std::to_string(faces) + " faces pointed inwards"
                                         : "the " + std::to_string(count) + " surface(s) of " +
                                               std::to_string(faces) + " faces around " +
                                               face_text(mesh, surfaces[root].faces.front()) +
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
  if (mesh.faces.empty()) throw MeshError(mesh.source + ": the mesh has no faces");
  MeshCheck check;
  Defects defects;
  FaceScreen screen = screen_faces(mesh, defects);
  const Eigen::AlignedBox<Real, 3> box = used_bounds(mesh, screen);
  const Real diagonal = box.isEmpty() ? 0 : box.diagonal().norm();
  check_degenerate_faces(mesh, diagonal, screen, defects);

  const std::vector<HalfEdge> edges = sorted_half_edges(mesh, screen.no_edges);
  const EdgeScan scan = scan_edges(mesh, edges, defects);
  check_fans(mesh, edges, scan, screen, defects);

  std::vector<Surface> parts =
      surfaces(mesh, edges, scan, screen, box.isEmpty() ? Vec3(Vec3::Zero()) : Vec3(box.center()));
  const Real zero_volume = kZeroVolume * diagonal * diagonal * diagonal;
  int unsound = 0;
  for (const Surface& s : parts) {
    if (!s.sound) {
      ++unsound;
      continue;
    }
    if (!(std::abs(s.volume) > zero_volume))
      defects.add(Defect::zero_volume,
                  face_at(mesh, s.faces.front()) + ": the closed surface of " +
                      std::to_string(s.faces.size()) + " faces it belongs to encloses |V| = " +
                      number(std::abs(s.volume)) + " <= " + number(zero_volume));
  }
  if (unsound > 0)
    defects.not_checked("the volume of " + std::to_string(unsound) + " of " +
                        std::to_string(parts.size()) +
                        " connected surfaces (open, with edges of more than two faces, "
                        "inconsistently oriented or with non-finite coordinates)");

  // A soup test: it needs no sound surface, only faces with an area.
  const auto crossing = crossing_faces(mesh, screen.no_crossing, kMaxCrossings);
  for (const auto& [f, g] : crossing)
    defects.add(Defect::crossing, face_at(mesh, f) + " intersects " + face_text(mesh, g));
  if (crossing.size() >= kMaxCrossings)
    defects.not_checked("pairs of intersecting faces beyond the first " +
                        std::to_string(kMaxCrossings) + " (the search stops there)");
  const auto left_out = std::count(screen.no_crossing.begin(), screen.no_crossing.end(), 1);
  if (left_out > 0)
    defects.not_checked("whether the " + std::to_string(left_out) +
                        " face(s) with missing, repeated or non-finite vertices or zero area "
                        "intersect others");

  // Nesting needs closed surfaces that do not cross: containment means nothing otherwise.
  if (defects.empty())
    check.turned = orient_surfaces(mesh, parts, check, defects);
  else
    defects.not_checked(
        "how the surfaces nest and which way they point (needs a mesh with none "
        "of the defects above)");
  if (!defects.empty()) throw MeshError(defects.message(mesh.source));
  check.closed = true;

  // Unused vertices are kept until every message has been written in the input's numbering.
  const std::vector<int> unused = unused_vertices(mesh);
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
