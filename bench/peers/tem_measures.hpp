// TEM's own yardsticks, applied to any engine's state: how deep the worst overlap is (TEM's
// contact detection) and how many bodies left the container. Used on Bullet's and ODE's states
// so that every engine of the side-by-side is judged by the same code.
#pragma once

#include "contact/detect_contacts.hpp"
#include "world/model.hpp"

namespace tem::peers {

struct Overlap {
  Real worst = 0;          // deepest patch, walls included (TEM's energy.csv max_depth)
  Real worst_bodies = 0;   // deepest patch between two bodies
  int patches = 0;
};

// Contact patches of `state` by TEM's detection with the scene's normal rule.
Overlap measure_overlap(const Model& model, const State& state, ContactWorkspace& workspace);

// Bodies whose centre of mass lies outside the container box; 0 without a container.
int bodies_outside(const Model& model, const State& state);

// The smallest body_size() of the model: overlaps are reported as fractions of it.
Real smallest_body_size(const Model& model);

}  // namespace tem::peers
