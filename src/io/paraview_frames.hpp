// The two files of one ParaView frame (docs/figures.md lists their fields):
//
// bodies: every block instance's surface triangles in world coordinates. Points are the block's
//   nodes, once per block instance (blocks of one body do not share points), in the order body,
//   block instance, node. Cell data: body_id (index into the scene's bodies, which is also the
//   order of a frame's rows in bodies.csv) and block_id (global index of the block instance,
//   counting body 0's instances first). Point data: velocity of that material point,
//   v + w x (p - x), and the body's angular velocity w, both in world axes.
// contacts: one VTK_VERTEX per contact patch at the patch point. Point data: normal (unit, from
//   body_a into body_b), depth, fn and ft (magnitudes of the force on body_a, as contacts.csv),
//   force = fn * normal (the normal force body_a exerts on body_b), body_a, body_b (-1 for a
//   wall) and wall (index into the model's walls, or -1).
#pragma once

#include <string>
#include <vector>

#include "simulation/step.hpp"

namespace tem {

// With `only` (one flag per body), the bodies flagged, block_id still counting every body's
// instances: one rank's piece of a frame (src/distributed/).
std::string bodies_vtu(const Model& model, const State& state,
                       const std::vector<char>* only = nullptr);

// `forces` is empty or holds one entry per patch; an empty one writes zero forces.
std::string contacts_vtu(Real time, const std::vector<ContactPatch>& patches,
                         const std::vector<PatchForce>& forces);

// The .pvtu file that makes one frame of `pieces` (file names relative to the .pvtu's folder),
// declaring the arrays bodies_vtu / contacts_vtu write.
std::string bodies_pvtu(const std::vector<std::string>& pieces);
std::string contacts_pvtu(const std::vector<std::string>& pieces);

}  // namespace tem
