// What a step changes about one rigid body (method.md §3). Everything else about the body is in
// the Model and never changes, so a checkpoint is just the State and restarting is exact.
#pragma once

#include <vector>

#include "tem/types.hpp"

namespace tem {

struct BodyState {
  Vec3 x = Vec3::Zero();            // centre of mass, world
  Vec3 v = Vec3::Zero();            // velocity of the centre of mass, world
  Mat3 g = Mat3::Identity();        // attitude, body to world (a rotation except under eq. 16)
  Vec3 omega = Vec3::Zero();        // angular velocity Omega in BODY axes; L = g A Omega
  Vec3 prev_torque = Vec3::Zero();  // N^{n-1}, world, for the paper's dN of eq. 18
  bool has_prev_torque = false;     // false before the first step: dN is taken as zero then

  Vec3 angular_velocity_world() const { return g * omega; }
};

struct State {
  Real time = 0;
  long long step = 0;
  std::vector<BodyState> bodies;
};

// Forces and torques from outside TEM (a fluid, a field, a user's law), per body, world axes,
// torque about the centre of mass, held through every step until changed. Not part of the
// State: a step does not change them, whoever applies them does. `active` false (all zero): the
// step takes the same path, and gives the same bits, as with no loads at all.
// The bodies one process of a domain decomposition holds (src/distributed/): `owned` ones it
// moves, `resident` ones (owned, or ghosts: copies of bodies owned elsewhere that come within
// contact reach) it tests for contact. One flag per body of the whole scene. Empty: one
// process holds and moves every body.
//
// `solved_once`: every contact is evaluated by one rank only, the owner of its body A (SEMM,
// whose contacts are solved together); otherwise also by the owner of body B (penalty, whose
// forces are local: no force need travel back).
struct BodySubset {
  std::vector<char> resident, owned;
  bool solved_once = false;
  bool empty() const { return owned.empty(); }
};

struct ExternalLoads {
  std::vector<Vec3> force, torque;  // one per body when active
  bool active = false;
  bool empty() const { return !active; }
  // active = some force or torque is not zero.
  void update_active() {
    active = false;
    for (size_t b = 0; b < force.size() && !active; ++b)
      active = !force[b].isZero(0) || !torque[b].isZero(0);
  }
};

// The constant inertial data an integrator needs, in body axes about the centre of mass.
struct RigidInertia {
  Real mass = 1;
  Mat3 inertia = Mat3::Identity();      // A of eq. 4-7
  Mat3 inertia_inv = Mat3::Identity();  // A^-1, the paper's A-tilde
};

}  // namespace tem
