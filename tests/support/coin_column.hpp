// A column of hexagonal coins on the floor of a box: the pure form of what a pile asks of the
// contact solver (the weight of every layer above must reach the floor within the step's sweeps).
#pragma once

#include <numbers>
#include <string>
#include <utility>

#include "tem/scene_def.hpp"

namespace tem::testing_support {

constexpr Real kCoinRadius = 0.15, kCoinThickness = 0.1;

// `layers` hexagonal coins (r 0.15, h 0.1, density 1), each turned 7 degrees about the vertical
// from the one below and 5 um above it, on the floor of a 1 x 1 cm box under earth gravity:
// friction 0.3, tolerance 1e-3 and 20 sweeps as scenes/bench/coins_1000.json (tools/
// tall_stack.py writes the same column).
inline SceneDef coin_column(int layers, Real dt) {
  SceneDef scene;
  scene.gravity = Vec3(0, 0, -981);
  scene.time_step = dt;
  scene.contact.friction = 0.3;
  scene.contact.tolerance = 1e-3;
  scene.contact.max_sweeps = 20;
  const Real top = 0.2 * layers;
  for (const auto& [point, normal] :
       {std::pair{Vec3(0, 0, 0), Vec3(0, 0, 1)}, std::pair{Vec3(1, 1, top), Vec3(0, 0, -1)},
        std::pair{Vec3(0, 0, 0), Vec3(1, 0, 0)}, std::pair{Vec3(1, 1, top), Vec3(-1, 0, 0)},
        std::pair{Vec3(0, 0, 0), Vec3(0, 1, 0)}, std::pair{Vec3(1, 1, top), Vec3(0, -1, 0)}})
    scene.walls.push_back({point, normal});
  for (int k = 0; k < layers; ++k) {
    BodyDef coin;
    coin.name = "c" + std::to_string(k);
    coin.shape.type = ShapeType::prism;
    coin.shape.sides = 6;
    coin.shape.radius = kCoinRadius;
    coin.shape.height = kCoinThickness;
    coin.density = 1;
    coin.position = Vec3(0.5, 0.5, 0.05 + 0.1005 * k);
    coin.rotation = Eigen::AngleAxis<Real>(7 * k * std::numbers::pi / 180, Vec3::UnitZ()).matrix();
    scene.bodies.push_back(coin);
  }
  return scene;
}

// A lattice of `side` x `side` columns of `layers` coins, 0.4 cm apart, on a floor without
// side walls: many islands at once (thread-count checks).
inline SceneDef coin_lattice(int side, int layers, Real dt) {
  const SceneDef column = coin_column(layers, dt);
  SceneDef scene = column;
  scene.walls.assign(1, column.walls[0]);  // the floor
  scene.bodies.clear();
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (BodyDef coin : column.bodies) {
        coin.name += "_" + std::to_string(i) + "_" + std::to_string(j);
        coin.position += Vec3(0.4 * i, 0.4 * j, 0);
        scene.bodies.push_back(coin);
      }
  return scene;
}

}  // namespace tem::testing_support
