// Cutting the solid of a closed mesh by planes, as approximate_decomposition's tree of cells
// does: each part is the solid inside one convex cell, kept as
//   - the mesh's triangles clipped to the cell (convex polygons, counter-clockwise seen from
//     outside), the part's real surface;
//   - one cap per cutting plane it touches: the plane's section of the solid, kept only as its
//     boundary, directed segments that run counter-clockwise about the cap's outward normal.
//     A cap is never triangulated: its share of the volume (divergence theorem) is the signed
//     fan from a point of its plane to these segments, which is right for caps that are not
//     convex or have holes, and a later plane only clips the segments;
//   - its corners, the points whose hull is the part's hull: mesh vertices inside the cell,
//     where the cell's planes cross the mesh's edges and where two planes' common line enters
//     and leaves the solid (a cap's segments on another cap's plane).
// A point exactly on a cutting plane belongs to neither side (as if the plane were moved a
// hair towards each side in turn), so faces lying in the plane drop out and the cap takes their
// place; the sides stay closed surfaces without special cases.
#pragma once

#include <array>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace tem {

// A half-space: the side kept is normal . x < offset.
struct CutPlane {
  Vec3 normal;
  Real offset;
};

struct MeshPart {
  std::vector<Vec3> corners;       // polygon corners, one polygon after another
  std::vector<int> polygon_start;  // polygon i: corners[start[i]] .. corners[start[i + 1] - 1]
  struct Cap {
    CutPlane plane;                          // the cap's outward normal is plane.normal
    std::vector<std::array<Vec3, 2>> edges;  // its boundary, segment from [0] to [1]
  };
  std::vector<Cap> caps;
  std::vector<Vec3> points;  // the corners of the part's solid (no repeats)
  Real volume = 0;
};

// The whole solid of a closed, outward-oriented mesh, shifted by -origin (cutting works near
// the origin, where coordinates carry the most precision).
MeshPart whole_mesh_part(const TriangleMesh& mesh, const Vec3& origin);

// The two sides of `part`: [0] where plane.normal . x < offset, [1] the other side. With
// keep_surface false the sides get no surface polygons: caps, points and volumes only, which
// is all that scoring a candidate plane needs.
std::array<MeshPart, 2> cut_part(const MeshPart& part, const CutPlane& plane, bool keep_surface);

// The part's volume from its surface polygons and caps (the divergence theorem, as cut_part
// finds it); needs the surface polygons.
Real part_volume(const MeshPart& part);

// The part's closed surface as triangles (surface polygons as fans, caps as signed fans), for
// surface integrals such as surface_mass_properties().
std::vector<std::array<Vec3, 3>> part_triangles(const MeshPart& part);

}  // namespace tem
