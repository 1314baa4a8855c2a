// The exact convex decomposition of a closed mesh (CGAL's Nef polyhedra), and the repairs that
// make Block-valid blocks of its pieces. With crossing_faces.cpp, the only translation units that
// include CGAL's headers; this one is by far the heavier to compile (exact kernel, Nef), so it
// holds nothing else.

// With -fsanitize, GCC 12 reports "may be used uninitialized" inside std::pair for the
// default-constructed Plane_3 and Direction_3 that CGAL's Epic_converter returns on failure
// (CGAL/Epic_converter.h). The warning comes after inlining, at the std::pair line, so it cannot
// be fenced around CGAL's includes; it is switched off for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "mesh/mesh_decomposition.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>

#include "mass/surface_integrals.hpp"
#include "mesh/crossing_faces.hpp"
#include "mesh/hull_polyhedron.hpp"
#include "mesh/mesh_check.hpp"

namespace tem {
namespace {

// The mesh as a CGAL surface whose face k is face k of `mesh` (faces are added in order, and a
// Surface_mesh numbers its faces in the order they are added). Throws MeshError where CGAL cannot
// link a face into the surface (an edge with more than two faces, or inconsistent orientation):
// check_mesh() reports those with the rest of what is wrong with a mesh.
template <class Kernel>
CGAL::Surface_mesh<typename Kernel::Point_3> surface_mesh(const TriangleMesh& mesh) {
  using Surface = CGAL::Surface_mesh<typename Kernel::Point_3>;
  Surface surface;
  surface.reserve(static_cast<typename Surface::size_type>(mesh.vertices.size()),
                  static_cast<typename Surface::size_type>(3 * mesh.faces.size() / 2),
                  static_cast<typename Surface::size_type>(mesh.faces.size()));
  std::vector<typename Surface::Vertex_index> vertex;
  vertex.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) vertex.push_back(surface.add_vertex({p.x(), p.y(), p.z()}));
  const int count = static_cast<int>(mesh.vertices.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (int v : t)
      if (v < 0 || v >= count)
        throw MeshError(mesh.source + ": face " + std::to_string(f) + " names vertex " +
                        std::to_string(v) + ", which does not exist");
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      throw MeshError(mesh.source + ": face " + std::to_string(f) + " repeats a vertex");
    if (surface.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == Surface::null_face())
      throw MeshError(mesh.source + ": face " + std::to_string(f) + " (vertices " +
                      std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
                      std::to_string(t[2]) +
                      ") cannot be joined to its neighbours: an edge has more than two faces, a "
                      "vertex's faces do not form one fan, or the faces are not consistently "
                      "oriented");
  }
  return surface;
}

}  // namespace

namespace {

using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = Exact::Point_3;
using Nef = CGAL::Nef_polyhedron_3<Exact>;
using ExactPolyhedron = CGAL::Polyhedron_3<Exact>;

// Pieces smaller than this fraction of the mesh's volume are slivers (CGAL 5.5 leaves some of
// about 1e-9 of the volume next to its cuts), and at most this fraction may be dropped in all.
constexpr Real kSliverFraction = 1e-9;
constexpr Real kDroppedFraction = 1e-10;
// A piece that Block rejects for features below its tolerances is replaced by the convex hull of
// its welded nodes, and two pieces are joined into their hull, only when that changes the volume
// by at most this fraction of the mesh's: what it removes is rounding (nodes 1e-17 apart, faces
// 1e-16 out of one plane), never a feature of the mesh.
constexpr Real kReshapeFraction = 1e-14;
// At most this fraction of the mesh's volume may change in any one piece, or in any one join of
// a thin piece to a neighbour, to make valid blocks of pieces whose corners are bent by the
// mesh's rounding (make_piece, rounded_union). Each change is counted, signed, and the final
// check holds the blocks to the mesh's volume plus those changes, so that it keeps meaning that
// CGAL's pieces fill the mesh however many pieces there are. In all, the changes come to at most
// 3.7e-10 of the volume below 2,000 pieces, 9.9e-10 for 6-digit fandisk's 9,682
// (docs/meshes.md); above this fraction, the cut says so in a warning.
constexpr Real kRoundingFraction = 8e-10;
// Corners are left out of a piece when they come within this factor of breaking one of Block's
// checks: little above 1, so that as few as possible go, but clear of Block's own rounding.
constexpr Real kTightMargin = 1.5;
// Nodes of a piece closer than this (relative to its size) are one node: Block takes them for
// one point (its own tolerance is 1e-9; twice that keeps a welded cloud clear of it).
constexpr Real kWeldFraction = 2e-9;
// The blocks' volumes must add up to the mesh's to this relative tolerance: far above the
// rounding of CGAL's exact vertices to double, far below any missing or doubled piece.
constexpr Real kVolumeTolerance = 1e-9;
static_assert(kRoundingFraction + kDroppedFraction < kVolumeTolerance);

// One convex volume of the decomposition and the block made of it.
struct Piece {
  PolyhedronDef def;                             // a valid block unless `defect` says why not
  Real volume = 0;                               // the exact volume of the piece, rounded
  Vec3 low = Vec3::Zero(), high = Vec3::Zero();  // bounds of def.points
  std::vector<std::pair<Vec3, Real>> planes;     // of def.polygons: unit normal n, n . x
  std::string defect;                            // empty when Block accepts def
  Real reshaped = 0;  // volume trimmed_hull added (negative: took) to make a valid block
};

std::string describe_point(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// Joins the facets that lie in one plane into one polygon and removes the corners where the loop
// runs straight on. CGAL splits a volume's face where the volumes beyond it change, so a block
// face may come as several facets, and the splitting vertices stay on its edges. Returns the
// polygon, empty where the facets have no area, or nullopt where they do not form one loop.
std::optional<std::vector<int>> merge_facets(const std::vector<ExactPoint>& points,
                                             const std::vector<std::vector<int>>& facets,
                                             const std::vector<int>& group) {
  std::map<std::pair<int, int>, int> directed;
  for (int f : group)
    for (size_t i = 0; i < facets[f].size(); ++i)
      ++directed[{facets[f][i], facets[f][(i + 1) % facets[f].size()]}];
  // Edges shared by two facets of the group run both ways and are inside the polygon.
  std::map<int, int> next;
  for (const auto& [edge, count] : directed) {
    if (count != 1) return std::nullopt;
    if (directed.count({edge.second, edge.first})) continue;
    if (!next.emplace(edge.first, edge.second).second) return std::nullopt;
  }
  if (next.empty()) return std::vector<int>{};
  std::vector<int> loop{next.begin()->first};
  for (int at = next.at(loop.front()); at != loop.front(); at = next.at(at)) {
    if (loop.size() > next.size() || !next.count(at)) return std::nullopt;
    loop.push_back(at);
  }
  if (loop.size() != next.size()) return std::nullopt;
  for (bool changed = true; changed && loop.size() >= 3;) {
    changed = false;
    for (size_t i = 0; i < loop.size() && loop.size() >= 3; ++i) {
      const size_t prev = (i + loop.size() - 1) % loop.size(), after = (i + 1) % loop.size();
      if (CGAL::collinear(points[loop[prev]], points[loop[i]], points[loop[after]])) {
        loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
    }
  }
  if (loop.size() < 3) loop.clear();
  return loop;
}

// Bounds and face planes of piece.def, to find its neighbours.
void set_geometry(Piece& piece) {
  piece.planes.clear();
  if (piece.def.points.empty()) return;
  const auto& pts = piece.def.points;
  piece.low = piece.high = pts.front();
  for (const Vec3& p : pts) {
    piece.low = piece.low.cwiseMin(p);
    piece.high = piece.high.cwiseMax(p);
  }
  for (const auto& loop : piece.def.polygons) {
    Vec3 n = Vec3::Zero();  // Newell's normal
    for (size_t i = 0; i < loop.size(); ++i)
      n += pts[loop[i]].cross(pts[loop[(i + 1) % loop.size()]]);
    if (n.norm() == 0) continue;
    n.normalize();
    piece.planes.emplace_back(n, n.dot(pts[loop[0]]));
  }
}

// The convex hull of `points` (Qhull, which merges faces that are coplanar to rounding) with
// points closer than the weld distance taken once, as a block. nullopt when Block rejects it.
std::optional<std::pair<PolyhedronDef, Real>> welded_hull(const std::vector<Vec3>& points) {
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<Real>(std::max<size_t>(points.size(), 1));
  Real size = 0;
  for (const Vec3& p : points) size = std::max(size, (p - mean).norm());
  std::vector<Vec3> kept;
  for (const Vec3& p : points)
    if (std::none_of(kept.begin(), kept.end(),
                     [&](const Vec3& q) { return (p - q).norm() <= kWeldFraction * size; }))
      kept.push_back(p);
  try {
    PolyhedronDef def = convex_hull(kept);
    const Real volume = Block(def).volume();
    return std::make_pair(std::move(def), volume);
  } catch (const GeometryError&) {
    return std::nullopt;
  }
}

// The hull of the points less the fewest corners that keep Block from accepting it: first
// those within 1.5 times Block's tolerance of breaking a check, then, where Block still refuses
// that hull, within 10 times (hull_block's default margin).
std::optional<PolyhedronDef> trimmed_hull(const std::vector<Vec3>& points, Real weld) {
  if (auto tight = hull_block(points, weld, kTightMargin)) return tight;
  return hull_block(points, weld);
}

// How far make_piece may go to make a valid block of a piece: `reshape`, the largest volume
// change for its welded hull (double rounding); `weld`, the distance below which the mesh's own
// coordinates cannot tell points apart; `rounding`, the largest volume change to leave out
// corners bent by the mesh's rounding. Absolute, in the mesh's units.
struct Tolerances {
  Real reshape = 0, weld = 0, rounding = 0;
};

// A piece from a closed, convex shell of exact points and facets (any orientation). Returns
// nullopt for an empty shell (no volume), which CGAL 5.5 sometimes reports as a volume.
std::optional<Piece> make_piece(const std::vector<ExactPoint>& points,
                                std::vector<std::vector<int>> facets, const Tolerances& tol) {
  const Real reshape = tol.reshape;
  if (points.empty()) return std::nullopt;
  Exact::FT volume = 0;
  for (const auto& facet : facets)
    for (size_t i = 1; i + 1 < facet.size(); ++i)
      volume += CGAL::volume(points[0], points[facet[0]], points[facet[i]], points[facet[i + 1]]);
  if (CGAL::is_zero(volume)) return std::nullopt;
  if (CGAL::is_negative(volume)) {
    volume = -volume;
    for (auto& facet : facets) std::reverse(facet.begin(), facet.end());
  }
  Piece piece;
  piece.volume = CGAL::to_double(volume);

  // Facets grouped by their oriented plane (exactly: a convex piece has one face per plane).
  std::vector<Exact::Plane_3> planes;
  std::vector<std::vector<int>> groups;
  for (size_t f = 0; f < facets.size(); ++f) {
    const auto& facet = facets[f];
    std::optional<Exact::Plane_3> plane;
    for (size_t i = 1; i + 1 < facet.size() && !plane; ++i)
      if (!CGAL::collinear(points[facet[0]], points[facet[i]], points[facet[i + 1]]))
        plane = Exact::Plane_3(points[facet[0]], points[facet[i]], points[facet[i + 1]]);
    if (!plane) continue;  // a facet without area bounds nothing
    const auto same = std::find(planes.begin(), planes.end(), *plane);
    if (same == planes.end()) {
      planes.push_back(*plane);
      groups.push_back({static_cast<int>(f)});
    } else {
      groups[static_cast<size_t>(same - planes.begin())].push_back(static_cast<int>(f));
    }
  }
  for (const auto& group : groups) {
    const auto polygon = merge_facets(points, facets, group);
    if (!polygon)
      piece.defect = "the facets in one plane do not form one polygon";
    else if (!polygon->empty())
      piece.def.polygons.push_back(*polygon);
  }

  // Keep the nodes that are corners of some face; the others were splitting vertices.
  std::vector<int> renumber(points.size(), -1);
  for (auto& polygon : piece.def.polygons)
    for (int& node : polygon) {
      if (renumber[node] < 0) {
        renumber[node] = static_cast<int>(piece.def.points.size());
        const ExactPoint& p = points[node];
        piece.def.points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                                      CGAL::to_double(p.z()));
      }
      node = renumber[node];
    }
  set_geometry(piece);
  if (piece.defect.empty()) try {
      static_cast<void>(Block(piece.def));  // for its checks only
      return piece;
    } catch (const GeometryError& e) {
      piece.defect = e.what();
    }

  // Rejected for nodes closer than Block's tolerance or corners straight to it: those come from
  // cuts through edges that the mesh's rounding left a hair off straight (its quads are not
  // quite planar). Their hull, welded, is the piece less that rounding.
  if (auto hull = welded_hull(piece.def.points);
      hull && std::abs(hull->second - piece.volume) <= reshape) {
    piece.def = std::move(hull->first);
    piece.defect.clear();
    set_geometry(piece);
    return piece;
  }
  // Still rejected: corners bent by more than double rounding but less than Block's tolerance.
  // A mesh written as 32-bit floats (binary STL) or with few digits (an OBJ exporter's "%g")
  // has quads planar only to 1e-8 or 1e-6 of its size, and CGAL's exact cuts through their
  // diagonals leave corners bent by that much, or short edges where a cut meets a mesh edge
  // near its vertex. The hull without those corners (trimmed_hull) is the piece less slivers of
  // that thickness; the volume it loses is counted (decompose). Nodes closer than the mesh's
  // resolution are welded first (a cut meets a mesh edge a hair from the mesh's own vertex
  // there). A piece it would change by more than tol.rounding stays defective,
  // to be joined to a neighbour (decompose).
  const Real weld = std::max(tol.weld, kWeldFraction * radius_about_mean(piece.def.points));
  if (auto hull = trimmed_hull(piece.def.points, weld)) {
    try {
      const Real volume = Block(*hull).volume();
      if (std::abs(volume - piece.volume) <= tol.rounding) {
        piece.reshaped = volume - piece.volume;
        piece.volume = volume;
        piece.def = std::move(*hull);
        piece.defect.clear();
        set_geometry(piece);
      }
    } catch (const GeometryError&) {
    }
  }
  return piece;
}

std::optional<Piece> piece_from_polyhedron(const ExactPolyhedron& shell, const Tolerances& tol) {
  std::vector<ExactPoint> points;
  std::unordered_map<const void*, int> index;
  for (auto v = shell.vertices_begin(); v != shell.vertices_end(); ++v) {
    index.emplace(&*v, static_cast<int>(points.size()));
    points.push_back(v->point());
  }
  std::vector<std::vector<int>> facets;
  for (auto f = shell.facets_begin(); f != shell.facets_end(); ++f) {
    std::vector<int> facet;
    auto h = f->facet_begin();
    do facet.push_back(index.at(&*h->vertex()));
    while (++h != f->facet_begin());
    facets.push_back(std::move(facet));
  }
  return make_piece(points, std::move(facets), tol);
}

// The union of two pieces that meet, as one block, when that union is convex: then their convex
// hull has the sum of their volumes (they do not overlap), here to `reshape`.
std::optional<Piece> convex_union(const Piece& a, const Piece& b, Real reshape) {
  std::vector<Vec3> points = a.def.points;
  points.insert(points.end(), b.def.points.begin(), b.def.points.end());
  auto hull = welded_hull(points);
  if (!hull || std::abs(hull->second - (a.volume + b.volume)) > reshape) return std::nullopt;
  Piece joined;
  joined.def = std::move(hull->first);
  joined.volume = a.volume + b.volume;
  set_geometry(joined);
  return joined;
}

// The union of two pieces as the block trimmed_hull makes of their nodes (corners bent by less
// than Block's tolerance left out), when its volume differs from theirs by at most `budget`.
std::optional<Piece> rounded_union(const Piece& a, const Piece& b, Real budget, Real weld) {
  std::vector<Vec3> points = a.def.points;
  points.insert(points.end(), b.def.points.begin(), b.def.points.end());
  auto hull = trimmed_hull(points, std::max(weld, kWeldFraction * radius_about_mean(points)));
  if (!hull) return std::nullopt;
  Piece joined;
  try {
    joined.volume = Block(*hull).volume();
  } catch (const GeometryError&) {
    return std::nullopt;
  }
  joined.reshaped = joined.volume - (a.volume + b.volume);
  if (std::abs(joined.reshaped) > budget) return std::nullopt;
  joined.def = std::move(*hull);
  set_geometry(joined);
  return joined;
}

// A convex piece that no hull makes a valid block, re-cut into tetrahedra from its centroid to
// the triangles of its faces: the paper's elements, exactly filling it. Each face is fanned from
// the corner that makes its thinnest triangle the fattest, so that a corner where the face runs
// nearly straight (what Block refused) is never the tip of a triangle. Tetrahedra Block refuses
// (none but from faces of no area) are left out; `left_out` gets their volume.
std::vector<Piece> tetrahedra(const Piece& piece, Real& left_out) {
  const auto& pts = piece.def.points;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : pts) centroid += p;
  centroid /= static_cast<Real>(pts.size());
  std::vector<Piece> result;
  Real volume = 0;  // of the tetrahedra, kept or not
  for (const auto& loop : piece.def.polygons) {
    const size_t n = loop.size();
    size_t apex = 0;
    Real fattest = -1;
    for (size_t a = 0; a < n; ++a) {
      Real thinnest = std::numeric_limits<Real>::infinity();
      for (size_t i = 1; i + 1 < n; ++i)
        thinnest = std::min(thinnest, (pts[loop[(a + i) % n]] - pts[loop[a]])
                                          .cross(pts[loop[(a + i + 1) % n]] - pts[loop[a]])
                                          .norm());
      if (thinnest > fattest) {
        fattest = thinnest;
        apex = a;
      }
    }
    for (size_t i = 1; i + 1 < n; ++i) {
      const Vec3 &a = pts[loop[apex]], &b = pts[loop[(apex + i) % n]],
                 &c = pts[loop[(apex + i + 1) % n]];
      const Real six_volume = (b - a).cross(c - a).dot(a - centroid);  // a, b, c run outwards
      volume += six_volume / 6;
      Piece tetrahedron;
      tetrahedron.def.points = {centroid, a, b, c};
      tetrahedron.def.polygons = {{1, 2, 3}, {0, 2, 1}, {0, 3, 2}, {0, 1, 3}};
      try {
        tetrahedron.volume = Block(tetrahedron.def).volume();
        set_geometry(tetrahedron);
        result.push_back(std::move(tetrahedron));
      } catch (const GeometryError&) {
        left_out += six_volume / 6;
      }
    }
  }
  // The pieces' volumes are rounded sums; what they differ from the piece's is rounding.
  if (!result.empty()) result.front().reshaped = volume - piece.volume;
  return result;
}

bool boxes_meet(const Piece& a, const Piece& b, Real margin) {
  return (a.low.array() <= b.high.array() + margin).all() &&
         (b.low.array() <= a.high.array() + margin).all();
}

// Whether a face of `a` and one of `b` lie in one plane (roughly: this only saves hulls), facing
// each other: only pieces that meet at a face can have a convex union.
bool faces_meet(const Piece& a, const Piece& b, Real margin) {
  for (const auto& [na, da] : a.planes)
    for (const auto& [nb, db] : b.planes)
      if (na.dot(nb) < -1 + 1e-6 && std::abs(da + db) <= margin) return true;
  return false;
}

// Joins neighbouring blocks whose union is convex, until no two can be joined. CGAL cuts along
// every reflex edge, however slight: a mesh's quads, each split into two triangles a hair off one
// plane by rounding, have one at each diagonal, and many of the blocks cut there join again here
// (the paper's ring: 90 blocks before, 48 after).
void coalesce(std::vector<Piece>& blocks, Real reshape, Real margin) {
  for (bool joined = true; joined;) {
    joined = false;
    for (size_t i = 0; i < blocks.size(); ++i)
      for (size_t j = i + 1; j < blocks.size(); ++j) {
        if (!boxes_meet(blocks[i], blocks[j], margin) || !faces_meet(blocks[i], blocks[j], margin))
          continue;
        if (auto both = convex_union(blocks[i], blocks[j], reshape)) {
          blocks[i] = std::move(*both);
          blocks.erase(blocks.begin() + static_cast<std::ptrdiff_t>(j));
          j = i;  // blocks[i] grew: try the others again
          joined = true;
        }
      }
  }
}

// The checks that keep CGAL from undefined behaviour: it assumes a closed, oriented,
// non-self-intersecting surface and does not check (its preconditions are off in release).
// Returns the mesh's volume.
template <class Surface>
Real check_input(const TriangleMesh& mesh, const Surface& surface, Real diagonal) {
  for (auto h : surface.halfedges())
    if (surface.is_border(h))
      throw MeshError(mesh.source + ": edge " + std::to_string(surface.source(h).idx()) + "-" +
                      std::to_string(surface.target(h).idx()) +
                      " has a face on one side only: the mesh is not closed");
  // The soup test takes faces of non-zero area only (check_mesh() refuses the others first).
  const Real least_area = kFaceAreaTolerance * diagonal * diagonal;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3& a = mesh.vertices[t[0]];
    if (!(0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm() > least_area))
      throw MeshError(mesh.source + ": face " + std::to_string(f) + " has zero area");
  }
  const auto crossing = crossing_faces(mesh, std::vector<char>(mesh.faces.size(), 0), 1);
  if (!crossing.empty())
    throw MeshError(mesh.source + ": faces " + std::to_string(crossing[0].first) + " and " +
                    std::to_string(crossing[0].second) + " intersect");
  const Real volume = surface_mass_properties(corner_triangles(mesh)).volume;
  if (!(volume > 0))
    throw MeshError(mesh.source + ": the mesh encloses no positive volume (" +
                    std::to_string(volume) + "): its faces point inwards or it is flat");
  return volume;
}

// The distance below which the mesh's coordinates cannot tell two points apart: a few units in
// the last place of its largest coordinate, as 32-bit floats when every coordinate is one (a
// binary STL, or a reader that delivers floats) or as doubles.
Real resolution(const TriangleMesh& mesh) {
  Real largest = 0;
  bool floats = true;
  for (const Vec3& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      largest = std::max(largest, std::abs(v[k]));
      // Through a volatile: g++ 12.2 at -O2 may drop a double -> float -> double round trip.
      const volatile float rounded = static_cast<float>(v[k]);
      floats = floats && rounded == v[k];
    }
  const Real unit =
      floats ? std::numeric_limits<float>::epsilon() : std::numeric_limits<Real>::epsilon();
  return 4 * unit * largest;
}

Vec3 to_vec(const ExactPoint& p) {
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

// The midpoints of the closed surface's reflex edges: those where the face beyond the edge
// rises above the plane of the face before it, decided exactly on the input's coordinates. CGAL
// cuts along each of them; a convex mesh has none.
template <class Surface>
std::vector<Vec3> reflex_edge_midpoints(const Surface& surface) {
  std::vector<Vec3> midpoints;
  for (auto e : surface.edges()) {
    const auto h = surface.halfedge(e);
    const auto& a = surface.point(surface.source(h));
    const auto& b = surface.point(surface.target(h));
    const auto& c = surface.point(surface.target(surface.next(h)));
    const auto& d = surface.point(surface.target(surface.next(surface.opposite(h))));
    if (CGAL::orientation(a, b, c, d) == CGAL::POSITIVE)
      midpoints.push_back(0.5 * (to_vec(a) + to_vec(b)));
  }
  return midpoints;
}

// Cuts the mesh, as a Nef polyhedron, into parts with at most `per_part` reflex edges each: a k-d
// tree of planes normal to an axis, each splitting the part's reflex edges most evenly along the
// axis on which they spread most, each cut exact (the intersection with a box). CGAL's
// decomposition of the parts costs far less than of the whole (docs/meshes.md), and the blocks
// cut at a plane join again where their union is convex (coalesce). A plane never passes through
// a vertex of the mesh: it lies halfway between two consecutive vertex coordinates, so it meets
// the surface only across edges and faces.
class PartCutter {
 public:
  // `bounds`: the mesh's bounding box.
  PartCutter(const TriangleMesh& mesh, const Eigen::AlignedBox<Real, 3>& bounds, int per_part)
      : per_part_(static_cast<size_t>(std::max(per_part, 1))) {
    for (const Vec3& p : mesh.vertices)
      for (int k = 0; k < 3; ++k) coordinates_[k].push_back(p[k]);
    for (auto& c : coordinates_) {
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end()), c.end());
    }
    const Vec3 margin = Vec3::Constant(bounds.diagonal().norm());
    low_ = bounds.min() - margin;
    high_ = bounds.max() + margin;
  }

  // Hands each part to `take`, in the tree's order (below before above).
  void cut(Nef part, std::vector<Vec3> reflex, const std::function<void(Nef&)>& take) const {
    if (reflex.size() > per_part_) {
      Vec3 low = reflex.front(), high = low;
      for (const Vec3& p : reflex) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      std::array<int, 3> axes{0, 1, 2};
      const Vec3 extent = high - low;
      std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
      for (int axis : axes) {
        const auto at = even_plane(axis, reflex);
        if (!at) continue;
        const auto first_above = std::partition(reflex.begin(), reflex.end(),
                                                [&](const Vec3& p) { return p[axis] < *at; });
        std::vector<Vec3> above(first_above, reflex.end());
        reflex.erase(first_above, reflex.end());
        Nef lower = part * half_space(axis, *at, true);
        Nef upper = part * half_space(axis, *at, false);
        part = Nef();  // the parts hold all of it now
        cut(std::move(lower), std::move(reflex), take);
        cut(std::move(upper), std::move(above), take);
        return;
      }
    }
    take(part);
  }

 private:
  // The plane x[axis] = at that splits the reflex edges' midpoints most evenly, halfway between
  // two consecutive vertex coordinates (with a double strictly between them: coordinates one
  // unit in the last place apart, as a symmetric mesh's rounding makes them, have none).
  std::optional<Real> even_plane(int axis, const std::vector<Vec3>& reflex) const {
    std::vector<Real> along;
    for (const Vec3& p : reflex) along.push_back(p[axis]);
    std::sort(along.begin(), along.end());
    const auto& c = coordinates_[static_cast<size_t>(axis)];
    std::optional<Real> best;
    size_t least = along.size();  // the larger side's count, to be made least
    if (c.size() < 2) return std::nullopt;
    for (auto i = std::max(std::upper_bound(c.begin(), c.end(), along.front()), c.begin() + 1);
         i != c.end() && *std::prev(i) < along.back(); ++i) {
      const Real below = *std::prev(i), middle = below + 0.5 * (*i - below);
      if (!(below < middle && middle < *i)) continue;
      const auto count = static_cast<size_t>(
          std::lower_bound(along.begin(), along.end(), middle) - along.begin());
      const size_t larger = std::max(count, along.size() - count);
      if (count > 0 && count < along.size() && larger < least) {
        least = larger;
        best = middle;
      }
    }
    return best;
  }

  // The box well around the mesh less what lies above (or below) the plane x[axis] = at.
  Nef half_space(int axis, Real at, bool below) const {
    Vec3 low = low_, high = high_;
    (below ? high : low)[axis] = at;
    CGAL::Surface_mesh<ExactPoint> box;
    std::array<CGAL::Surface_mesh<ExactPoint>::Vertex_index, 8> v;
    for (int i = 0; i < 8; ++i)
      v[static_cast<size_t>(i)] = box.add_vertex(ExactPoint(
          i & 1 ? high.x() : low.x(), i & 2 ? high.y() : low.y(), i & 4 ? high.z() : low.z()));
    // Corner i has bit 0 for x, 1 for y, 2 for z; each face counter-clockwise seen from outside.
    constexpr size_t kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : kFaces) box.add_face(v[f[0]], v[f[1]], v[f[2]], v[f[3]]);
    return Nef(box);
  }

  size_t per_part_;
  std::array<std::vector<Real>, 3> coordinates_;  // the vertices', sorted, each once
  Vec3 low_, high_;                               // a box well around the mesh
};

MeshDecomposition decompose(const TriangleMesh& mesh, int reflex_edges_per_part) {
  MeshDecomposition result;
  if (mesh.faces.empty()) throw MeshError(mesh.source + ": the mesh has no faces");
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      throw MeshError(mesh.source + ": vertex " + std::to_string(i) + " is not finite");
  const auto surface = surface_mesh<Exact>(mesh);
  Eigen::AlignedBox<Real, 3> bounds;
  for (const Vec3& p : mesh.vertices) bounds.extend(p);
  const Real diagonal = bounds.diagonal().norm();
  result.mesh_volume = check_input(mesh, surface, diagonal);

  const Real reshape = kReshapeFraction * result.mesh_volume;
  const Real rounding = kRoundingFraction * result.mesh_volume;  // for any one piece or join
  const Real weld = resolution(mesh);
  std::vector<Piece> pieces;
  const auto decompose_part = [&](Nef& nef) {
    CGAL::convex_decomposition_3(nef);
    // The first volume of a Nef polyhedron is the unbounded one outside; the others that are
    // marked are inside the mesh, each convex after the decomposition, with one shell.
    auto volume = nef.volumes_begin();
    for (++volume; volume != nef.volumes_end(); ++volume) {
      if (!volume->mark()) continue;
      if (std::distance(volume->shells_begin(), volume->shells_end()) != 1)
        throw MeshError(mesh.source + ": CGAL's convex decomposition returned a piece with " +
                        "a cavity (not convex)");
      ExactPolyhedron shell;
      nef.convert_inner_shell_to_polyhedron(volume->shells_begin(), shell);
      if (auto piece = piece_from_polyhedron(shell, {reshape, weld, rounding}))
        pieces.push_back(std::move(*piece));
    }
    ++result.parts;
  };
  std::vector<Vec3> reflex = reflex_edge_midpoints(surface);
  result.reflex_edges = static_cast<int>(reflex.size());
  result.parts = 0;
  PartCutter(mesh, bounds, reflex_edges_per_part)
      .cut(Nef(surface), std::move(reflex), decompose_part);

  result.pieces = static_cast<int>(pieces.size());

  // Slivers, and pieces Block rejects (too thin for its tolerances), join a neighbour when
  // their union is convex; otherwise valid slivers stay blocks and the others are dropped if
  // they are negligible in all.
  const Real sliver = kSliverFraction * result.mesh_volume;
  std::vector<Piece> blocks, slivers;
  for (Piece& p : pieces)
    (p.defect.empty() && p.volume >= sliver ? blocks : slivers).push_back(std::move(p));
  const Real margin = kVolumeTolerance * diagonal;
  // What making valid blocks changed, signed: hulls without corners bent by rounding
  // (make_piece), thin pieces joined to a neighbour into a hull a hair larger or smaller than
  // both, thin pieces dropped.
  Real reshaped = 0;
  for (const Piece& p : blocks) reshaped += p.reshaped;
  Real dropped = 0;
  // Joins may add volume (the hull of two pieces covers the wedge between their bent faces, and
  // overlaps a neighbour by as much): kRoundingFraction of the mesh's in all. Without that
  // bound, 6-digit fandisk's joins added 3.2e-7 of its volume; pieces they would not join are
  // blocks of their own or re-cut below.
  Real joins_changed = 0;
  std::string first_dropped;
  for (Piece& s : slivers) {
    ++result.merged_slivers;
    reshaped += s.reshaped;
    bool joined = false;
    for (Piece& b : blocks) {
      if (!boxes_meet(b, s, margin)) continue;
      if (auto both = convex_union(b, s, reshape)) {
        b = std::move(*both);
        joined = true;
        break;
      }
    }
    // A piece thinner than Block's tolerance next to a face bent by rounding: the hull of the
    // two, less the bent corners, differs from them by slivers of the rounding's thickness.
    const auto join_rounded = [&](Real budget) {
      for (Piece& b : blocks) {
        if (!boxes_meet(b, s, margin) || !faces_meet(b, s, margin)) continue;
        if (auto both = rounded_union(b, s, budget, weld)) {
          reshaped += both->reshaped;
          joins_changed += std::abs(both->reshaped);
          b = std::move(*both);
          return true;
        }
      }
      return false;
    };
    if (joined || join_rounded(rounding - joins_changed)) continue;
    // A valid block however small is kept: dropping it would leave a hole in the mesh's volume.
    if (s.defect.empty()) {
      blocks.push_back(std::move(s));
      continue;
    }
    // Else the piece is re-cut into tetrahedra, each a block (6-digit fandisk: 4 such pieces,
    // 0.1 % of its volume, that no hull made a block of).
    Real left_out = 0;
    std::vector<Piece> parts = tetrahedra(s, left_out);
    if (!parts.empty() && left_out <= reshape) {
      reshaped += parts.front().reshaped - left_out;
      ++result.recut_pieces;
      for (Piece& t : parts) blocks.push_back(std::move(t));
      continue;
    }
    // Else a piece flat to Block's tolerance: joined beyond the joins' budget, since dropping it
    // would leave a gap as thin as the wedge the join adds (6-digit fandisk: 1.6e-9 of its
    // volume in such pieces), or dropped.
    if (join_rounded(rounding)) continue;
    dropped += s.volume;
    if (first_dropped.empty())
      first_dropped =
          "near " + describe_point(s.low) + (s.defect.empty() ? "" : " (" + s.defect + ")");
  }
  result.rounding_change = reshaped - dropped;
  if (std::abs(reshaped) > rounding) {
    std::ostringstream w;
    w << mesh.source << ": leaving out the corners of CGAL's " << result.pieces
      << " pieces that the mesh's rounding bends by less than Block's tolerance changes the "
      << "volume by " << reshaped / result.mesh_volume << " of the mesh's";
    result.warnings.push_back(w.str());
  }
  // Left: pieces that neither Block nor the hulls above accept (thinner than Block's tolerance,
  // or bent by more than the rounding budget) and that join no neighbour; all the others are
  // blocks now.
  if (dropped > kDroppedFraction * result.mesh_volume) {
    std::ostringstream e;
    e << mesh.source << ": CGAL's convex decomposition left pieces of volume " << dropped << " ("
      << dropped / result.mesh_volume
      << " of the mesh) that Block refuses, whose hull less their corners bent by rounding "
         "would change the volume by more than "
      << kRoundingFraction << " of the mesh's, and that join no neighbour into a convex block, "
      << "e.g. " << first_dropped;
    throw MeshError(e.str());
  }
  if (dropped > 0) {
    std::ostringstream w;
    w << mesh.source << ": dropped thin pieces of CGAL's convex decomposition, volume " << dropped
      << " (" << dropped / result.mesh_volume << " of the mesh), " << first_dropped;
    result.warnings.push_back(w.str());
  }
  coalesce(blocks, reshape, margin);
  for (Piece& b : blocks) result.blocks.push_back(std::move(b.def));
  return result;
}

}  // namespace

MeshDecomposition exact_decomposition(const TriangleMesh& mesh, int reflex_edges_per_part) {
  const auto start = std::chrono::steady_clock::now();
  MeshDecomposition result;
  try {
    result = decompose(mesh, reflex_edges_per_part);
  } catch (const MeshError&) {
    throw;
  } catch (const CGAL::Failure_exception& e) {
    throw MeshError(mesh.source + ": CGAL's exact convex decomposition failed: " + e.what());
  } catch (const std::exception& e) {
    throw MeshError(mesh.source + ": the exact convex decomposition failed: " + e.what());
  }
  // Never pass on a wrong cut: the blocks must be convex and fill the mesh's volume.
  for (size_t i = 0; i < result.blocks.size(); ++i) {
    const Block block(result.blocks[i]);
    if (!block.convex())
      throw MeshError(mesh.source + ": exact cutting gave a non-convex block " + std::to_string(i));
    result.blocks_volume += block.volume();
  }
  // What the repairs changed is counted; the rest must be the mesh's own volume.
  const Real error =
      std::abs(result.blocks_volume - (result.mesh_volume + result.rounding_change));
  if (error > kVolumeTolerance * result.mesh_volume)
    throw MeshError(mesh.source + ": the exact cut's blocks have volume " +
                    std::to_string(result.blocks_volume) + ", the mesh " +
                    std::to_string(result.mesh_volume) +
                    ": CGAL's convex decomposition is wrong for this mesh");
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace tem
