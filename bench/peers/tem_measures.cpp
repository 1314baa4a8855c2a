#include "tem_measures.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace tem::peers {

Overlap measure_overlap(const Model& model, const State& state, ContactWorkspace& workspace) {
  std::vector<ContactPatch> patches;
  detect_contacts(model, state, patch_variant(model.scene), workspace, patches);
  Overlap o;
  o.patches = static_cast<int>(patches.size());
  for (const ContactPatch& p : patches) {
    o.worst = std::max(o.worst, p.depth);
    if (p.wall < 0) o.worst_bodies = std::max(o.worst_bodies, p.depth);
  }
  return o;
}

int bodies_outside(const Model& model, const State& state) {
  if (!model.scene.container) return 0;
  const ContainerDef& box = *model.scene.container;
  int n = 0;
  for (const BodyState& b : state.bodies)
    if ((b.x.array() < box.min.array()).any() || (b.x.array() > box.max.array()).any()) ++n;
  return n;
}

Real smallest_body_size(const Model& model) {
  Real size = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < static_cast<int>(model.bodies.size()); ++i)
    size = std::min(size, body_size(model, i));
  return size;
}

}  // namespace tem::peers
