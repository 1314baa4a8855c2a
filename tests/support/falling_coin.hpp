// A hexagonal coin (r 0.15, h 0.1, density 7, axis z: lying flat) over a floor wall, its bottom
// `height` above it, falling at `speed`, at time step dt, under g = 981 cm/s^2: the scene of the
// contact-before-overlap and sub-step tests.
#pragma once

#include "tem/scene_def.hpp"

namespace tem::testing_support {

inline constexpr Real kCoinGravity = 981.0;

inline SceneDef falling_coin(Real height, Real speed, Real dt) {
  SceneDef scene;
  scene.gravity = Vec3(0, 0, -kCoinGravity);
  scene.time_step = dt;
  scene.walls.push_back({Vec3::Zero(), Vec3::UnitZ()});
  BodyDef coin;
  coin.name = "coin";
  coin.shape.type = ShapeType::prism;
  coin.shape.sides = 6;
  coin.shape.radius = 0.15;
  coin.shape.height = 0.1;
  coin.density = 7;
  coin.position = Vec3(0, 0, 0.05 + height);
  coin.velocity = Vec3(0, 0, -speed);
  scene.bodies.push_back(coin);
  return scene;
}

}  // namespace tem::testing_support
