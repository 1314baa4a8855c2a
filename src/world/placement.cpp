#include "world/placement.hpp"

namespace tem {

bool sphere_clear_of_body(const Model& model, const Body& body, const BodyState& state,
                          const Vec3& centre, Real radius) {
  for (const BlockInstance& instance : body.blocks) {
    const Block& block = model.blocks[instance.block];
    // The block's pose as collision/block_pose.hpp has it (this floor is below that one).
    const Mat3 rotation = state.g * instance.rotation;
    const Vec3 position = state.x + state.g * instance.offset;
    if ((position - centre).norm() >= radius + block.bounding_radius()) continue;
    const Vec3 local = rotation.inverse() * (centre - position);
    bool separated = false;
    for (const Polygon& face : block.polygons()) {
      if (face.normal.dot(local) - face.offset >= radius) {
        separated = true;
        break;
      }
    }
    if (!separated) return false;
  }
  return true;
}

}  // namespace tem
