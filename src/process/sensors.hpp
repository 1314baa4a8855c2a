// Sensors (scene key `sensors`, sensors.csv): what a user of a process measures while it runs.
//   plane:  net count and mass of free bodies whose centre of mass crossed the plane along its
//           normal since the start (crossing back counts -1);
//   force:  the contact force and torque (about the world origin) on the named bodies, the mean
//           over the steps since the sensor's last output row;
//   region: count and mass of free bodies whose centre of mass is inside, at the row's time.
// Fixed bodies and bodies with a prescribed motion are the apparatus, not its contents: plane
// and region sensors do not count them (a bin's centre of mass lies inside its own hollow).
// What accumulates between rows is part of the State, so a resumed run reads the same.
#pragma once

#include <vector>

#include "forces/contact_forces.hpp"
#include "world/model.hpp"

namespace tem {

struct SensorReading {
  long long count = 0;
  Real mass = 0;
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
};

// After a step from `before` to `state` with contact forces `forces`: plane crossings, and the
// step's forces added to the force sensors' sums.
void accumulate_sensors(const Model& model, const std::vector<BodyState>& before, State& state,
                        const ContactForces& forces);

// The readings of every sensor for an output row at `state`; force sensors give their mean since
// the last row and start a new sum (with no step since, the forces of the step starting now,
// `forces`).
std::vector<SensorReading> take_sensor_readings(const Model& model, State& state,
                                                const ContactForces& forces);

}  // namespace tem
