// What a step changes about one rigid body (method.md §3). Everything else about the body is in
// the Model and never changes, so a checkpoint is just the State and restarting is exact.
#pragma once

#include <cstdint>
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
  // Sleep (simulation/sleep.hpp; only with the scene's `sleep`): how long the body has moved
  // slower than sleep.speed, whether it sleeps (then v and omega are exactly zero), and the
  // island it fell asleep with, named by the lowest BodyTag::id in it (-1: none).
  Real rest_time = 0;
  bool asleep = false;
  long long island = -1;

  Vec3 angular_velocity_world() const { return g * omega; }
};

// Who a live body is (granular processes, src/process/): a stable id that outlives the
// reordering of the arrays, and for a copy made by an inlet, the inlet, the copy's number and
// its size factor, from which a checkpoint rebuilds it. Bodies of the scene and of its fills
// have ids 0, 1, ... in the order of Model::bodies at the start and inlet -1.
struct BodyTag {
  long long id = 0;
  int inlet = -1;
  int copy = 0;
  Real scale = 1;
};

// How far an inlet has got: copies placed, and random numbers drawn (its generator is counter
// based, so this count is its whole state).
struct InletProgress {
  long long placed = 0;
  std::uint64_t draws = 0;
};

// What a sensor has gathered: a plane's net crossings and their mass since the start; a force
// sensor's summed contact force and torque (about the world origin) over `steps` steps since
// its last output row.
struct SensorTotals {
  long long count = 0;
  Real mass = 0;
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
  long long steps = 0;
};

struct State {
  Real time = 0;
  long long step = 0;
  std::vector<BodyState> bodies;
  // Granular processes: one tag per body (parallel to `bodies`, ids increasing), the next id
  // to give, each inlet's progress, each sensor's totals, and the work the bodies with a
  // prescribed motion have done on the others through contact since the start.
  std::vector<BodyTag> tags;
  long long next_id = 0;
  std::vector<InletProgress> inlets;
  std::vector<SensorTotals> sensors;
  Real driven_work = 0;
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
