// The shapes of the paper and a few more, as polyhedra ready to become blocks (method.md §1).
//
// Each primitive is built about its own centre with its symmetry axis along `axis`. Built along
// z, a prism's first node lies at angle 0, i.e. on +x; a different axis is reached by a cyclic
// permutation of the coordinates (x,y,z) -> (y,z,x) for axis x or (z,x,y) for axis y, so the
// first node then lies on +y (axis x) or +z (axis y). With the paper's scenes (axis y) this puts
// the hexagonal column's lowest point at z = 0.094 as method.md §7 works out.
#pragma once

#include <vector>

#include "geometry/block.hpp"
#include "tem/scene_def.hpp"

namespace tem {

// Rotation taking the canonical symmetry axis z to `axis` by cyclic permutation.
Mat3 axis_rotation(Axis axis);

// Regular `sides`-gon prism: circumradius `radius`, `height` along the axis. One convex block.
PolyhedronDef regular_prism(int sides, Real radius, Real height, Axis axis);

// Box of edge lengths size (x, y, z), centred at the origin. One convex block.
PolyhedronDef box(const Vec3& size);

// Polygonal ring: a `sides`-gon section of circumradius `section_radius` swept around a regular
// `segments`-gon centre line of circumradius `radius`. The section is the regular polygon in the
// plane through the symmetry axis at each centre-line vertex (the mitre plane), its first node
// pointing radially outward. Each of the `blocks` blocks spans segments/blocks segments; a block
// of one segment is a convex prism cut by two mitre planes, a block of several segments is
// slightly non-convex on its inner side (the paper's 8-block ring, method.md §1).
std::vector<PolyhedronDef> polygonal_ring(int segments, int sides, Real radius, Real section_radius,
                                          int blocks, Axis axis, bool allow_nonconvex);

}  // namespace tem
