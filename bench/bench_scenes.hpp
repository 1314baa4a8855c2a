// Scenes the benchmarks share: the paper's shapes in touching poses, and piles of coins.
#pragma once

#include <random>

#include "world/model.hpp"

namespace tem::bench {

inline ShapeDef coin_shape() {  // the paper's hexagonal coin, r 0.15, h 0.1
  ShapeDef s;
  s.type = ShapeType::prism;
  s.sides = 6;
  s.radius = 0.15;
  s.height = 0.1;
  return s;
}

// A pile of `count` coins on a jittered lattice in a container, neighbours overlapping a little
// (spacing 2% under the coin's size) so that every coin has contacts, as in a settled pile.
// All coins share one block, as bodies built from one template do.
inline Model coin_pile(int count, unsigned seed = 1) {
  const int side = static_cast<int>(std::ceil(std::cbrt(count / 4.0)));  // layers are 4x thinner
  const Real dx = 0.26 * 0.98, dz = 0.1 * 0.98;
  SceneDef scene;
  scene.container = ContainerDef{Vec3::Zero(), Vec3(2 * side * dx + 0.3, 2 * side * dx + 0.3, 1)};
  BodyDef first;
  first.name = "coin0";
  first.shape = coin_shape();
  scene.bodies.push_back(first);
  Model model = build_model(scene);
  model.scene.container->max.z() = 4 * side * dz + 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-0.01, 0.01), tilt(-0.02, 0.02), turn(-3.14, 3.14);
  const Body coin = model.bodies[0];
  model.bodies.clear();
  model.scene.bodies.clear();
  for (int i = 0; i < count; ++i) {
    const int ix = i % (2 * side), iy = (i / (2 * side)) % (2 * side), iz = i / (4 * side * side);
    BodyDef def = first;
    def.name = "coin" + std::to_string(i);
    def.position = Vec3(0.15 + (ix + 0.5) * dx + jitter(rng), 0.15 + (iy + 0.5) * dx + jitter(rng),
                        (iz + 0.5) * dz - 0.001);
    def.rotation = euler_zxz(turn(rng), tilt(rng), 0);
    model.scene.bodies.push_back(def);
    Body body = coin;
    body.name = def.name;
    body.start_position = def.position;
    body.start_rotation = def.rotation;
    model.bodies.push_back(body);
  }
  return model;
}

}  // namespace tem::bench
