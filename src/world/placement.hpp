// Room for a new body (fill, inlets): is a sphere clear of a body that is already there?
//
// Why blocks and not bounding spheres: a drum, a hopper or a silo holds its contents inside its
// bounding sphere, so a test against that sphere would find no room anywhere inside. The test
// here takes the body's blocks one by one: a sphere is clear of a convex block when one of the
// block's face planes has the sphere's centre farther than its radius on the outer side. It
// never accepts an overlap (every point of the block is behind every face plane), and it may
// refuse a sphere that only passes near a block's edge or corner: such a candidate is simply
// drawn again.
#pragma once

#include "world/model.hpp"

namespace tem {

// Whether the sphere (centre, radius) stays clear of every block of `body` at `state`.
bool sphere_clear_of_body(const Model& model, const Body& body, const BodyState& state,
                          const Vec3& centre, Real radius);

}  // namespace tem
