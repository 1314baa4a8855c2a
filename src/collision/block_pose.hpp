// Where a block instance is in the world at a given state, and the map back into its frame.
//
// x_world = rotation * x_block + position, with rotation = g B^c and position = x + g t^c
// (eq. 20's r + c). In paper mode g drifts off the rotation group (eq. 16), so the map back is
// the true inverse of `rotation`, not its transpose: the contact tests then see the body as the
// paper's integrator has deformed it, as the paper's own code would.
#pragma once

#include <limits>

#include "dynamics/body_state.hpp"
#include "world/model.hpp"

namespace tem {

struct BlockPose {
  Mat3 rotation;  // block frame -> world
  Mat3 inverse;   // world -> block frame (rotation^-1)
  Vec3 position;  // world position of the block's centroid

  Vec3 to_world(const Vec3& p) const { return rotation * p + position; }
  Vec3 to_block(const Vec3& p) const { return inverse * (p - position); }
};

// The pose for placing a block, which reads only the map into the world: the same rotation
// and position as block_pose, without the 3 x 3 inverse that a sub-step's refreshed patches
// would otherwise compute twice per patch (`inverse` is NaN, so a reader is caught at once).
inline BlockPose block_placement(const BlockInstance& instance, const BodyState& state) {
  BlockPose pose;
  pose.rotation = state.g * instance.rotation;
  pose.inverse = Mat3::Constant(std::numeric_limits<Real>::quiet_NaN());
  pose.position = state.x + state.g * instance.offset;
  return pose;
}

inline BlockPose block_pose(const BlockInstance& instance, const BodyState& state) {
  BlockPose pose = block_placement(instance, state);
  pose.inverse = pose.rotation.inverse();
  return pose;
}

}  // namespace tem
