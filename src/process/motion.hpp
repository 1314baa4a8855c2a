// Prescribed motion (scene key `motion`, docs/processes.md): bodies that move as they are told,
// push the others and are never pushed (belts, drums, shakers, pistons).
//
// The pose is a closed form of time, not an integration, so a drum turns by exactly omega t
// however long the run: between `start` and `end` the body turns about the axis through
// `center` by R(t) = exp(omega (t - start)) (omega fixed in world axes), moves by
// velocity (t - start), and is displaced by amplitude sin(2 pi f (t - start)); before `start` it
// stands at its initial pose and after `end` at the pose it reached then.
//
// What the contact solver sees: over a step from t to t + dt, the velocity that takes the
// centre of mass from its pose at t to its pose at t + dt, and the mean angular velocity over
// the step. Contact forces then do on a body exactly the work the step's motion implies, and
// the solver's energy rule (relative velocities: work done on the free bodies no larger than
// the driven bodies' own) keeps its meaning.
#pragma once

#include "world/model.hpp"

namespace tem {

struct DrivenPose {
  Vec3 x;  // centre of mass
  Mat3 g;  // body to world
};

// The pose of a body with a motion at time t, from its initial pose.
DrivenPose motion_pose(const Body& body, Real t);

// Puts every body with a motion at its pose at state.time and gives it the velocities of the
// sub-step of length h that starts there (the centre's mean velocity and the mean angular
// velocity). h is the step's own sub-step: with contact.max_substeps a step's count is chosen
// after its detection (find_contact_forces), which gives the driven bodies their velocities for
// it; until then they hold those of the fewest sub-steps (substep_time).
void move_driven_bodies(const Model& model, State& state, Real h);

// Whether the scene has bodies with a prescribed motion.
bool has_motion(const Model& model);

}  // namespace tem
