// Cutting a mesh part by a plane: surface polygons clipped, caps clipped and closed along the
// plane, the new cap built from both (plane_cut.hpp).
#include "mesh/plane_cut.hpp"

#include <algorithm>
#include <tuple>

namespace tem {
namespace {

Real distance_to(const CutPlane& plane, const Vec3& x) {
  return plane.normal.dot(x) - plane.offset;
}

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

// Where segment a-b crosses the plane, from the ends' signed distances. The ends are taken in
// a fixed order, so the two polygons that share an edge (and a cap's segment on it) get the
// same bits: cut segments then join exactly, and each crossing is one point.
Vec3 crossing(Vec3 a, Real da, Vec3 b, Real db) {
  if (da == 0) return a;
  if (db == 0) return b;
  if (lexicographic_less(b, a)) {
    std::swap(a, b);
    std::swap(da, db);
  }
  const Real t = da / (da - db);
  if (t <= 0.5) return a + t * (b - a);
  return b + (db / (db - da)) * (a - b);  // from the nearer end, for precision
}

// Six times the signed volume of the cones from the origin to a fan of the polygon.
Real fan_volume6(const Vec3* corner, size_t count) {
  Real v = 0;
  for (size_t k = 1; k + 1 < count; ++k) v += corner[0].dot(corner[k].cross(corner[k + 1]));
  return v;
}

// A cap's share of the volume: the signed fan from the plane's point nearest the origin.
Real cap_volume(const MeshPart::Cap& cap) {
  const Vec3 apex = cap.plane.offset * cap.plane.normal;
  Real v = 0;
  for (const auto& edge : cap.edges) v += apex.dot(edge[0].cross(edge[1]));
  return v / 6;
}

void append_polygon(MeshPart& part, const Vec3* corner, size_t count) {
  part.corners.insert(part.corners.end(), corner, corner + count);
  part.polygon_start.push_back(static_cast<int>(part.corners.size()));
}

struct Crossing {
  Real along;  // position on the line where the cap's plane meets the cutting plane
  int step;    // +1 where the cap's boundary leaves the kept side, -1 where it comes back
  Vec3 at;
};

// Clips an old cap to side `plane` and closes it along the cutting plane. Where the line
// (cap plane) x (cutting plane) lies inside the cap, counted by the winding of the cap's
// boundary crossings along it, the cap gets a segment along the line and the new cap the same
// segment reversed; its ends are corners of the part.
void clip_cap(const MeshPart::Cap& cap, const CutPlane& cut, const CutPlane& plane, bool below,
              MeshPart& side, std::vector<std::array<Vec3, 2>>& new_cap,
              std::vector<Vec3>& new_points) {
  MeshPart::Cap kept{cap.plane, {}};
  // With the cap's boundary counter-clockwise about its normal, the cap lies on the left:
  // leaving the kept side, it lies ahead along normal x plane normal.
  const Vec3 along = cap.plane.normal.cross(plane.normal);
  std::vector<Crossing> crossings;
  for (const auto& edge : cap.edges) {
    const Real da = distance_to(cut, edge[0]), db = distance_to(cut, edge[1]);
    const bool in_a = below ? da < 0 : da > 0, in_b = below ? db < 0 : db > 0;
    if (in_a && in_b) {
      kept.edges.push_back(edge);
    } else if (in_a != in_b) {
      const Vec3 x = crossing(edge[0], da, edge[1], db);
      kept.edges.push_back(in_a ? std::array<Vec3, 2>{edge[0], x} : std::array<Vec3, 2>{x, edge[1]});
      crossings.push_back({x.dot(along), in_a ? 1 : -1, x});
    }
  }
  std::stable_sort(crossings.begin(), crossings.end(),
                   [](const Crossing& a, const Crossing& b) { return a.along < b.along; });
  int winding = 0;
  Vec3 start = Vec3::Zero();
  for (size_t k = 0; k < crossings.size();) {
    const int before = winding;
    size_t next = k;
    while (next < crossings.size() && crossings[next].along == crossings[k].along)
      winding += crossings[next++].step;
    if (before <= 0 && winding > 0) {
      start = crossings[k].at;
    } else if (before > 0 && winding <= 0) {
      const Vec3 end = crossings[k].at;
      kept.edges.push_back({start, end});
      new_cap.push_back({end, start});
      new_points.push_back(start);
      new_points.push_back(end);
    }
    k = next;
  }
  if (!kept.edges.empty()) side.caps.push_back(std::move(kept));
}

}  // namespace

MeshPart whole_mesh_part(const TriangleMesh& mesh, const Vec3& origin) {
  MeshPart part;
  part.polygon_start.push_back(0);
  Real volume6 = 0;
  std::vector<bool> used(mesh.vertices.size(), false);
  for (const auto& face : mesh.faces) {
    const Vec3 corner[3] = {mesh.vertices[face[0]] - origin, mesh.vertices[face[1]] - origin,
                            mesh.vertices[face[2]] - origin};
    append_polygon(part, corner, 3);
    volume6 += fan_volume6(corner, 3);
    for (int v : face) used[v] = true;
  }
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    if (used[v]) part.points.push_back(mesh.vertices[v] - origin);
  part.volume = volume6 / 6;
  return part;
}

std::array<MeshPart, 2> cut_part(const MeshPart& part, const CutPlane& plane, bool keep_surface) {
  const std::array<CutPlane, 2> sides{plane, CutPlane{-plane.normal, -plane.offset}};
  std::array<MeshPart, 2> side;
  std::array<std::vector<std::array<Vec3, 2>>, 2> new_cap;
  std::array<std::vector<Vec3>, 2> new_points;
  std::array<Real, 2> volume6{0, 0};
  for (MeshPart& s : side) s.polygon_start.push_back(0);

  // Surface polygons: convex, so each side keeps one convex piece; where the boundary leaves
  // the side at X and comes back at Y, the piece has the edge X -> Y and the cap Y -> X.
  std::vector<Real> d;
  std::vector<Vec3> piece;
  std::vector<bool> exits;
  const size_t polygons = part.polygon_start.size() - 1;
  for (size_t i = 0; i < polygons; ++i) {
    const Vec3* corner = &part.corners[part.polygon_start[i]];
    const size_t count = part.polygon_start[i + 1] - part.polygon_start[i];
    d.resize(count);
    std::array<size_t, 2> inside{0, 0};
    for (size_t k = 0; k < count; ++k) {
      d[k] = distance_to(plane, corner[k]);
      inside[0] += d[k] < 0;
      inside[1] += d[k] > 0;
    }
    for (int s = 0; s < 2; ++s) {
      if (inside[s] == 0) continue;
      if (inside[s] == count) {
        volume6[s] += fan_volume6(corner, count);
        if (keep_surface) append_polygon(side[s], corner, count);
        continue;
      }
      auto in = [&](size_t k) { return s == 0 ? d[k] < 0 : d[k] > 0; };
      piece.clear();
      exits.clear();
      for (size_t k = 0; k < count; ++k) {
        const size_t n = (k + 1) % count;
        if (in(k)) {
          piece.push_back(corner[k]);
          exits.push_back(false);
        }
        if (in(k) != in(n)) {
          piece.push_back(crossing(corner[k], d[k], corner[n], d[n]));
          exits.push_back(in(k));
          new_points[s].push_back(piece.back());
        }
      }
      for (size_t k = 0; k < piece.size(); ++k)
        if (exits[k]) new_cap[s].push_back({piece[(k + 1) % piece.size()], piece[k]});
      volume6[s] += fan_volume6(piece.data(), piece.size());
      if (keep_surface) append_polygon(side[s], piece.data(), piece.size());
    }
  }

  for (const auto& cap : part.caps)
    for (int s = 0; s < 2; ++s)
      clip_cap(cap, plane, sides[s], s == 0, side[s], new_cap[s], new_points[s]);

  for (const Vec3& p : part.points) {
    const Real dp = distance_to(plane, p);
    if (dp < 0) side[0].points.push_back(p);
    if (dp > 0) side[1].points.push_back(p);
  }
  for (int s = 0; s < 2; ++s) {
    if (!new_cap[s].empty()) side[s].caps.push_back({sides[s], std::move(new_cap[s])});
    auto& added = new_points[s];
    std::sort(added.begin(), added.end(), lexicographic_less);
    added.erase(std::unique(added.begin(), added.end()), added.end());
    side[s].points.insert(side[s].points.end(), added.begin(), added.end());
    side[s].volume = volume6[s] / 6;
    for (const auto& cap : side[s].caps) side[s].volume += cap_volume(cap);
  }
  return side;
}

Real part_volume(const MeshPart& part) {
  Real volume6 = 0;
  for (size_t i = 0; i + 1 < part.polygon_start.size(); ++i)
    volume6 += fan_volume6(&part.corners[part.polygon_start[i]],
                           part.polygon_start[i + 1] - part.polygon_start[i]);
  Real volume = volume6 / 6;
  for (const auto& cap : part.caps) volume += cap_volume(cap);
  return volume;
}

std::vector<std::array<Vec3, 3>> part_triangles(const MeshPart& part) {
  std::vector<std::array<Vec3, 3>> triangles;
  for (size_t i = 0; i + 1 < part.polygon_start.size(); ++i)
    for (int k = part.polygon_start[i] + 1; k + 1 < part.polygon_start[i + 1]; ++k)
      triangles.push_back(
          {part.corners[part.polygon_start[i]], part.corners[k], part.corners[k + 1]});
  for (const auto& cap : part.caps) {
    const Vec3 apex = cap.plane.offset * cap.plane.normal;
    for (const auto& edge : cap.edges) triangles.push_back({apex, edge[0], edge[1]});
  }
  return triangles;
}

}  // namespace tem
