#include "process/sensors.hpp"

namespace tem {
namespace {

// The force and torque about the world origin that body b's contact forces make.
void add_body_load(const State& state, const ContactForces& forces, size_t b, Vec3& force,
                   Vec3& torque) {
  if (b >= forces.force.size()) return;
  force += forces.force[b];
  torque += forces.torque[b] + state.bodies[b].x.cross(forces.force[b]);
}

}  // namespace

void accumulate_sensors(const Model& model, const std::vector<BodyState>& before, State& state,
                        const ContactForces& forces) {
  const std::vector<SensorDef>& sensors = model.scene.sensors;
  state.sensors.resize(sensors.size());
  for (size_t k = 0; k < sensors.size(); ++k) {
    const SensorDef& s = sensors[k];
    SensorTotals& t = state.sensors[k];
    if (s.type == SensorType::plane) {
      for (size_t b = 0; b < model.bodies.size() && b < before.size(); ++b) {
        if (model.bodies[b].driven()) continue;  // the flow is of free bodies
        const bool was = s.normal.dot(before[b].x - s.point) >= 0;
        const bool is = s.normal.dot(state.bodies[b].x - s.point) >= 0;
        if (was == is) continue;
        const int sign = is ? 1 : -1;
        t.count += sign;
        t.mass += sign * model.bodies[b].inertia.mass;
      }
    } else if (s.type == SensorType::force) {
      ++t.steps;
    }
  }
  // Force sensors: each body adds its step's force to the sensors that watch it. The forces act
  // through the step at the positions it started from (the centres the torques were taken
  // about), so the torque about the origin uses those.
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    for (int k : model.bodies[b].force_sensors) {
      SensorTotals& t = state.sensors[k];
      if (b >= forces.force.size() || b >= before.size()) continue;
      t.force += forces.force[b];
      t.torque += forces.torque[b] + before[b].x.cross(forces.force[b]);
    }
  }
}

std::vector<SensorReading> take_sensor_readings(const Model& model, State& state,
                                                const ContactForces& forces) {
  const std::vector<SensorDef>& sensors = model.scene.sensors;
  state.sensors.resize(sensors.size());
  std::vector<SensorReading> readings(sensors.size());
  for (size_t k = 0; k < sensors.size(); ++k) {
    const SensorDef& s = sensors[k];
    SensorTotals& t = state.sensors[k];
    SensorReading& r = readings[k];
    switch (s.type) {
      case SensorType::plane:
        r.count = t.count;
        r.mass = t.mass;
        break;
      case SensorType::region:
        for (size_t b = 0; b < model.bodies.size(); ++b) {
          // The contents are free bodies: a bin's own centre lies inside its hollow.
          if (model.bodies[b].driven() || !s.region.contains(state.bodies[b].x)) continue;
          ++r.count;
          r.mass += model.bodies[b].inertia.mass;
        }
        break;
      case SensorType::force: {
        const bool averaged = t.steps > 0;
        if (averaged) {
          r.force = t.force / static_cast<Real>(t.steps);
          r.torque = t.torque / static_cast<Real>(t.steps);
        }
        for (size_t b = 0; b < model.bodies.size(); ++b) {
          for (int watched : model.bodies[b].force_sensors) {
            if (watched != static_cast<int>(k)) continue;
            ++r.count;
            r.mass += model.bodies[b].inertia.mass;
            if (!averaged) add_body_load(state, forces, b, r.force, r.torque);
          }
        }
        t.force = t.torque = Vec3::Zero();
        t.steps = 0;
        break;
      }
    }
  }
  return readings;
}

}  // namespace tem
