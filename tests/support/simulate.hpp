// Helpers for tests that run scenes: step a model and watch what the physics tests measure.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "io/scene_reader.hpp"
#include "simulation/step.hpp"

namespace tem::testing_support {

// Prints a figure the way the validation page collects them, and records it in the XML report.
inline void report(const std::string& key, Real value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  std::cout << "[ measured ] " << key << " = " << text << "\n";
  ::testing::Test::RecordProperty(key, text);
}

// What a run measured over all its steps.
struct Watch {
  Real largest_energy_rise = 0;  // over one step
  Real deepest = 0;              // deepest patch seen at any step
  long long steps = 0;
};

// Steps `model` from `state` for `duration`, calling `each(state, workspace)` after every step.
template <class Each>
Watch simulate(const Model& model, State& state, Real duration, Each each) {
  Workspace w;
  Watch watch;
  const long long n = std::llround(duration / model.scene.time_step);
  Real energy = system_energies(model, state).total();
  for (long long k = 0; k < n; ++k) {
    find_contact_forces(model, state, w);
    for (const ContactPatch& p : w.patches) watch.deepest = std::max(watch.deepest, p.depth);
    advance(model, state, w);
    const Real next = system_energies(model, state).total();
    watch.largest_energy_rise = std::max(watch.largest_energy_rise, next - energy);
    energy = next;
    ++watch.steps;
    each(state, w);
  }
  return watch;
}

inline Watch simulate(const Model& model, State& state, Real duration) {
  return simulate(model, state, duration, [](const State&, const Workspace&) {});
}

// A scene file of the repository, read and built (the test fails if it has problems).
inline Model load_scene(const std::string& relative) {
  const SceneReadResult read = read_scene_file(std::string(TEM_SOURCE_DIR) + "/" + relative);
  EXPECT_TRUE(read.ok()) << relative;
  return build_model(read.scene);
}

// A 0.2 x 0.2 x 0.1 box (density 1) standing on the floor plane z = 0, its bottom face at
// z = lift, under the default settings.
inline SceneDef box_on_floor(Real lift = 0) {
  SceneDef scene;
  scene.walls.push_back({Vec3::Zero(), Vec3::UnitZ()});
  BodyDef box;
  box.name = "box";
  box.shape.type = ShapeType::box;
  box.shape.size = Vec3(0.2, 0.2, 0.1);
  box.position = Vec3(0, 0, 0.05 + lift);
  scene.bodies.push_back(box);
  return scene;
}

// Angle (degrees) between a body's axis (a body-frame unit vector) and the world's z.
inline Real tilt_degrees(const BodyState& s, const Vec3& body_axis) {
  // atan2 of the cross and dot products: exact for small angles, where acos(1 - e) is not.
  const Vec3 axis = s.g * body_axis;
  return std::atan2(axis.cross(Vec3::UnitZ()).norm(), std::abs(axis.z())) * 180 /
         3.14159265358979323846;
}

}  // namespace tem::testing_support
