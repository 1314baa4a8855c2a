// Warm start of the contact solver: a contact that persists from one step to the next (a body
// resting, sliding or rolling) needs nearly the same impulse again, so the solver starts from
// the last step's. A point is the same contact when it joins the same two bodies (or body and
// wall) and lies within `radius` of where it was; its old impulses are the guess.
#pragma once

#include <vector>

#include "forces/contact_points.hpp"
#include "forces/semm.hpp"

namespace tem {

// `previous` and `points` are in patch order, hence grouped by body pair; `radius` per body
// (a fraction of its size). Unmatched points start at zero.
void warm_start(const std::vector<ContactPoint>& previous,
                const std::vector<PointImpulse>& previous_impulses,
                const std::vector<ContactPoint>& points, const std::vector<Real>& radius,
                std::vector<PointImpulse>& impulses);

// The same for the friction of patches: a patch of the same pair whose centre is within
// `radius` of the old one's takes its tangential impulse (re-expressed in the new frame) and
// its twist, and its rolling impulse likewise.
void warm_start_friction(const std::vector<PatchFriction>& previous,
                         const std::vector<Real>& radius, std::vector<PatchFriction>& patches);

}  // namespace tem
