// The penalty model (classic DEM, the paper's ref. 1, Cundall & Strack): a contact is a spring
// and a dashpot. Normal force from the patch's depth and normal approach speed, linear
// (F = k d + c v) or Hertzian (F = k d^(3/2) + c d^(1/4) v), never pulling, shared among the
// patch's corner points in proportion to their depths (at a single point in its centre a face
// would rock freely about it); a tangential spring per patch, at its centre, that
// stretches with the slip and slides at the Coulomb limit mu (sum of the normal forces) (for the
// Hertzian law its stiffness grows like d^(1/2), Mindlin's); mu is the patch's, from the
// materials of its two sides (materials.hpp), as is the rolling resistance: a torque
// -mu_r R F_n along the relative rolling, clipped to stop it at most. No twisting spring. The spring's stretch is the
// contact's memory: it is carried from step to step for the patch of the same two bodies that
// lies within 1% of the body's size of where it was, and forgotten when the contact opens.
//
// Forces are explicit, from the state at the start of the step; the time step must resolve the
// contact's oscillation, period 2 pi sqrt(m / k) for the lightest body. `penalty_time_step_limit`
// gives a tenth of it, and a scene whose time step is above is warned of when it loads.
#pragma once

#include <vector>

#include "contact/contact_patch.hpp"
#include "forces/contact_points.hpp"
#include "world/model.hpp"

namespace tem {

// The memory of one contact.
struct PenaltySpring {
  int body_a = -1, body_b = -1, wall = -1;
  Vec3 point = Vec3::Zero();
  Vec3 stretch = Vec3::Zero();  // tangential spring extension, world
};

// Forces and torques (about `centres`, the centres of mass) on every body from the patches; `springs` is the last step's memory on
// entry and this step's on return. Per patch, the magnitudes of the force on body A.
void penalty_forces(const Model& model, const State& state,
                    const std::vector<ContactPatch>& patches,
                    const std::vector<ContactPoint>& points, const std::vector<Vec3>& centres,
                    std::vector<PenaltySpring>& springs,
                    std::vector<Vec3>& force, std::vector<Vec3>& torque,
                    std::vector<Real>& normal_magnitude, std::vector<Real>& tangential_magnitude);

// A tenth of the contact oscillation period of the lightest moving body, for the linear law; for
// the Hertzian law at a depth of 1% of that body's size. Infinity when nothing moves.
Real penalty_time_step_limit(const Model& model);

}  // namespace tem
