#include "contact/contact_margins.hpp"

#include <algorithm>
#include <cmath>

namespace tem {
namespace {

constexpr Real kRestingReach = 0.005;  // of the body's size
constexpr Real kMotionRoom = 2;        // twice a step's motion: room to brake (semm.cpp)

}  // namespace

void contact_reaches(const Model& model, const State& state, std::vector<Real>& reach,
                     const ExternalLoads* loads, const BodySubset* subset) {
  const SceneDef& scene = model.scene;
  if (!contact_before_overlap(scene)) {
    reach.clear();
    return;
  }
  const size_t n = model.bodies.size();
  reach.resize(n);
  const Real dt = scene.time_step;
  const Real fall = scene.gravity.norm() * dt * dt;
  const bool all = !subset || subset->empty();
  for (size_t b = 0; b < n; ++b) {
    if (!all && !subset->resident[b]) continue;  // far from this process: never looked at
    if (scene.contact.margin) {
      reach[b] = *scene.contact.margin / 2;
      continue;
    }
    const Real size = body_size(model, static_cast<int>(b));
    Real r = kRestingReach * size;
    if (!model.bodies[b].fixed) {
      const BodyState& s = state.bodies[b];
      r += kMotionRoom * (s.v.norm() + s.omega.norm() * size) * dt + fall;
      if (loads && !loads->empty()) {
        // What the external force and torque add within the step.
        const RigidInertia& inertia = model.bodies[b].inertia;
        r += (loads->force[b].norm() / inertia.mass +
              (inertia.inertia_inv * (s.g.transpose() * loads->torque[b])).norm() * size) *
             dt * dt;
      }
    }
    reach[b] = r;
  }
}

int bodies_outrunning_reach(const Model& model, const std::vector<Real>& reach,
                            const std::vector<BodyState>& before,
                            const std::vector<BodyState>& after) {
  if (reach.empty()) return 0;
  int count = 0;
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    if (model.bodies[b].fixed) continue;
    const BodyState &s0 = before[b], &s1 = after[b];
    // The rotation angle between the two attitudes, from the trace of g1 g0^T.
    const Real cosine = std::clamp<Real>(((s1.g * s0.g.transpose()).trace() - 1) / 2, -1, 1);
    const Real moved = (s1.x - s0.x).norm() + std::acos(cosine) * body_size(model, static_cast<int>(b));
    if (moved > reach[b]) ++count;
  }
  return count;
}

}  // namespace tem
