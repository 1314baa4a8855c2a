// How many sub-steps a step takes (contact.substeps, contact.max_substeps).
//
// A pour's crash and its settled pile ask opposite things of the sub-step. A crash wants it short:
// what a sub-step rebuilds is the step's detected features at new poses, and a coin that turns or
// closes a gap by more than a few hundredths of its size within one sub-step meets its neighbour
// at corners the features do not hold, so the crash overlaps (docs/benchmarks.md, "How often the
// crash overlaps": 10-17 overlaps over 1 % in 0.2 s at four sub-steps of dt 5e-4, none at eight).
// A settled pile wants few solves, each held. So the count is chosen per step, from the state
// the step starts at: the fewest sub-steps, at least contact.substeps and at most
// contact.max_substeps, in which no contact's relative motion covers more than
// contact.substep_motion of the smaller body's size. A function of the state alone, so resumed
// runs and every thread count choose the same.
#pragma once

#include <vector>

#include "contact/contact_patch.hpp"
#include "world/model.hpp"

namespace tem {

// The sub-steps of the step that starts at `state` with the detected `patches`: the scene's
// contact.substeps where it fixes them (no max_substeps).
int substeps_for_step(const Model& model, const State& state,
                      const std::vector<ContactPatch>& patches);

}  // namespace tem
