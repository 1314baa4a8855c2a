// The broad phase against brute force: on a random pile of bodies of mixed sizes, with a large
// fixed slab that the grid must put on its large list, it reports exactly the pairs whose world
// bounds overlap (blocks of different bodies, not both fixed), each once, sorted.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "collision/broad_phase.hpp"

namespace tem {
namespace test_broad_phase {

SceneDef random_pile(int bodies, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> unit(0, 1), size(0.02, 0.08), angle(-3.14, 3.14);
  SceneDef scene;
  scene.container = ContainerDef{};
  BodyDef slab;
  slab.name = "slab";
  slab.shape.type = ShapeType::box;
  slab.shape.size = Vec3(1, 1, 0.05);
  slab.position = Vec3(0.5, 0.5, 0.3);
  slab.fixed = true;
  scene.bodies.push_back(slab);
  BodyDef post = slab;  // a second fixed body: never paired with the slab
  post.name = "post";
  post.shape.size = Vec3(0.2, 0.2, 1);
  scene.bodies.push_back(post);
  for (int i = 0; i < bodies; ++i) {
    BodyDef b;
    b.name = "b" + std::to_string(i);
    if (i % 3 == 0) {
      b.shape.type = ShapeType::prism;
      b.shape.sides = 6;
      b.shape.radius = size(rng);
      b.shape.height = size(rng);
    } else if (i % 3 == 1) {
      b.shape.type = ShapeType::box;
      b.shape.size = Vec3(size(rng), size(rng), size(rng));
    } else {  // two blocks: a compound of two boxes
      b.shape.type = ShapeType::compound;
      ShapeDef part;
      part.type = ShapeType::box;
      part.size = Vec3(size(rng), size(rng), size(rng));
      part.position = Vec3(0.03, 0, 0);
      b.shape.parts = {part, part};
      b.shape.parts[1].position = Vec3(-0.03, 0, 0);
    }
    b.position = Vec3(unit(rng), unit(rng), unit(rng) * 1.05 - 0.025);
    b.rotation = euler_zxz(angle(rng), angle(rng), angle(rng));
    scene.bodies.push_back(b);
  }
  return scene;
}

TEST(BroadPhase, SamePairsAsBruteForce) {
  const Model model = build_model(random_pile(600, 7));
  const State state = initial_state(model);
  BroadPhase broad;
  broad.update(model, state);
  const auto& proxies = broad.proxies();
  const auto& bounds = broad.bounds();
  const int n = static_cast<int>(proxies.size());
  EXPECT_GE(broad.large_blocks(), 2);  // the slab and the post

  std::vector<std::pair<int, int>> expected, found;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const int bi = proxies[i].body, bj = proxies[j].body;
      if (bi == bj || (model.bodies[bi].fixed && model.bodies[bj].fixed)) continue;
      if (bounds[i].overlaps(bounds[j])) expected.emplace_back(i, j);
    }
  for (const BlockPair& p : broad.block_pairs()) found.emplace_back(p.a, p.b);
  EXPECT_TRUE(std::is_sorted(found.begin(), found.end()));
  EXPECT_EQ(found, expected);
  EXPECT_GT(expected.size(), 100u);  // a real test: the pile is crowded

  // Bounds are the nodes' exact extremes.
  for (int i = 0; i < n; ++i) {
    const BlockInstance& inst = model.bodies[proxies[i].body].blocks[proxies[i].instance];
    const Block& block = model.blocks[inst.block];
    Vec3 lo = Vec3::Constant(1e300), hi = -lo;
    for (const Vec3& node : block.nodes()) {
      const Vec3 p = state.bodies[proxies[i].body].g * (inst.rotation * node + inst.offset) +
                     state.bodies[proxies[i].body].x;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    EXPECT_LT((lo - bounds[i].min).norm() + (hi - bounds[i].max).norm(), 1e-12);
  }

  // Walls: every non-fixed block whose bounds reach behind a wall plane, and no other.
  std::set<std::pair<int, int>> walls_expected, walls_found;
  for (int i = 0; i < n; ++i) {
    if (model.bodies[proxies[i].body].fixed) continue;
    for (int w = 0; w < static_cast<int>(model.walls.size()); ++w) {
      const Wall& wall = model.walls[w];
      Real lowest = 1e300;
      for (int c = 0; c < 8; ++c) {
        const Vec3 corner((c & 1 ? bounds[i].max : bounds[i].min).x(),
                          (c & 2 ? bounds[i].max : bounds[i].min).y(),
                          (c & 4 ? bounds[i].max : bounds[i].min).z());
        lowest = std::min(lowest, wall.normal.dot(corner - wall.point));
      }
      if (lowest < 0) walls_expected.emplace(i, w);
    }
  }
  for (const WallPair& p : broad.wall_pairs()) walls_found.emplace(p.proxy, p.wall);
  EXPECT_EQ(walls_found, walls_expected);
  EXPECT_FALSE(walls_expected.empty());
}

// Far apart bodies give no pair whatever the cell size; one body gives none.
TEST(BroadPhase, SparseAndSingle) {
  SceneDef scene = random_pile(0, 1);
  scene.bodies.resize(1);
  scene.bodies[0].fixed = false;
  const Model one = build_model(scene);
  BroadPhase broad;
  broad.update(one, initial_state(one));
  EXPECT_TRUE(broad.block_pairs().empty());
}

}  // namespace test_broad_phase
}  // namespace tem
