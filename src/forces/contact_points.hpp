// From contact patches to the points where contact impulses act (method.md §5-6).
//
// The paper reduces every patch to one point. A face resting on a face is then held at a single
// point, about which it can rock and creep, a likely cause of the paper's coin coming to rest
// tilted. The default keeps up to eight points per patch: the overlap corners that reach
// furthest along eight directions of the patch's tangent plane (so a square face keeps its four
// corners, a hexagonal face its outline), each moved onto the plane through the patch point.
// Every point carries the patch's normal; the solver shares the patch's load among them.
#pragma once

#include <vector>

#include "contact/contact_patch.hpp"

namespace tem {

struct ContactPoint {
  int patch;     // index into the step's patches
  int body_a;    // the force on A acts along -normal
  int body_b;    // -1 for a wall
  int wall;      // index into Model::walls, or -1
  Vec3 point;    // world
  Vec3 normal;   // unit, from A into B
  Vec3 tangent1, tangent2;  // with normal, a right-handed orthonormal frame
  Real depth;    // the overlap's depth at this point: the patch's for a single point; for a
                 // corner, how far it lies along the normal beyond the shallowest corner; for a
                 // point of contact before overlap, minus its gap (< 0 while still apart)
};

// Appends the points of patch `index`: a patch of contact before overlap its own (at most four);
// else one (the patch point) when `one_per_patch`, else the extreme corners described above (at
// least one).
void patch_points(const ContactPatch& patch, int index, bool one_per_patch,
                  std::vector<ContactPoint>& out);

// A unit vector orthogonal to n, chosen continuously and deterministically.
Vec3 any_orthogonal(const Vec3& n);

}  // namespace tem
