#include "simulation/substep_count.hpp"

#include <algorithm>
#include <cmath>

namespace tem {

int substeps_for_step(const Model& model, const State& state,
                      const std::vector<ContactPatch>& patches) {
  const ContactDef& contact = model.scene.contact;
  if (contact.max_substeps <= contact.substeps) return contact.substeps;
  // Per patch: how far its two bodies move relative to each other over the step, sliding and
  // turning (|omega| size: a corner's speed about the centre), as a share of the smaller size.
  Real share = 0;
  for (const ContactPatch& p : patches) {
    const BodyState& a = state.bodies[p.body_a];
    const Real size_a = body_size(model, p.body_a);
    Vec3 sliding = a.v;
    Real turning = a.omega.norm() * size_a, size = size_a;
    if (p.body_b >= 0) {
      const BodyState& b = state.bodies[p.body_b];
      const Real size_b = body_size(model, p.body_b);
      sliding -= b.v;
      turning += b.omega.norm() * size_b;
      size = std::min(size_a, size_b);
    }
    share = std::max(share, (sliding.norm() + turning) * model.scene.time_step / size);
  }
  const Real wanted = std::ceil(share / contact.substep_motion);
  if (!(wanted < contact.max_substeps)) return contact.max_substeps;  // also a NaN's answer
  return std::max(contact.substeps, static_cast<int>(wanted));
}

}  // namespace tem
