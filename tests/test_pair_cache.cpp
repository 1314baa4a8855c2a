// Friction that holds, and the pair cache (contact.pair_cache, contact/pair_cache.hpp).
//
// A column of coins must come to rest at the time step and sweeps the benchmark scenes use: a
// patch keeps the same four corners of a face lying flat from step to step (reduce_points), so
// the warm start carries the impulses and no coin creeps. A block pair that has barely moved
// takes last step's features: the same bits as the whole search where the search would keep
// them, the same rest, resumed runs bit for bit, the cache renumbered when bodies leave.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "collision/block_manifold.hpp"
#include "contact/pair_cache.hpp"
#include "geometry/primitives.hpp"
#include "io/checkpoint.hpp"
#include "support/checkpoint_bytes.hpp"
#include "support/coin_column.hpp"
#include "support/simulate.hpp"
#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_pair_cache {

using testing_support::report;
using testing_support::simulate;
using testing_support::temp_path;

using testing_support::coin_column;
using testing_support::kCoinRadius;
using testing_support::kCoinThickness;

// The fastest point of any coin (|v| + |omega| r) at any step after `after`, and the deepest
// overlap over the run, as a fraction of the coin's thickness.
struct Rest {
  Real creep = 0, deepest = 0;
  Real top = 0;  // the highest centre at the end
};

Rest settle(const SceneDef& scene, Real duration, Real after) {
  const Model model = build_model(scene);
  State state = initial_state(model);
  Rest rest;
  const auto watch = simulate(model, state, duration, [&](const State& s, const Workspace&) {
    if (s.time < after) return;
    for (const BodyState& b : s.bodies)
      rest.creep =
          std::max(rest.creep, b.v.norm() + b.angular_velocity_world().norm() * kCoinRadius);
  });
  rest.deepest = watch.deepest / kCoinThickness;
  for (const BodyState& b : state.bodies) rest.top = std::max(rest.top, b.x.z());
  return rest;
}

// Before the four corners of a flat patch were chosen to stay the same, "the deepest" of
// twelve corners at one depth changed with every tremor, the warm start was lost and these
// columns crept at 0.09 cm/s (three coins) and 0.8 cm/s (ten) for as long as they ran.
TEST(FrictionHolds, ColumnsOfCoinsComeToRestAtTheBenchmarkStep) {
  for (const int layers : {3, 10}) {
    const Rest rest = settle(coin_column(layers, 5e-4), 1.0, 0.5);
    report("column of " + std::to_string(layers) + " coins, dt 5e-4, 20 sweeps: fastest point "
           "over 0.5-1 s (cm/s)", rest.creep);
    EXPECT_LT(rest.creep, 1e-8) << layers << " coins";
    EXPECT_LT(rest.deepest, 0.01) << layers << " coins";
    // Standing: the top coin's centre where the column puts it, to a hundredth of a coin.
    EXPECT_NEAR(rest.top, 0.05 + 0.1 * (layers - 1), 1e-3) << layers << " coins";
  }
}

// The cache takes last step's features only where the search would find them again, so a
// settling column is the same, bit for bit, with and without it; and it answers most of the
// pairs once the column stands.
TEST(PairCache, SameColumnWithAndWithoutItAndMostPairsCached) {
  SceneDef with = coin_column(10, 5e-4), without = with;
  without.contact.pair_cache = false;
  const Model model_with = build_model(with), model_without = build_model(without);
  State a = initial_state(model_with), b = initial_state(model_without);
  long long pairs = 0, cached = 0;
  simulate(model_with, a, 0.5, [&](const State&, const Workspace& w) {
    pairs = w.times.block_pairs;
    cached = w.times.cached_pairs;
  });
  simulate(model_without, b, 0.5);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].x, b.bodies[i].x) << i;
    EXPECT_EQ(a.bodies[i].g, b.bodies[i].g) << i;
    EXPECT_EQ(a.bodies[i].v, b.bodies[i].v) << i;
  }
  ASSERT_GT(pairs, 0);
  report("column of 10 coins over 0.5 s: block pairs from last step's features (%)",
         100.0 * static_cast<Real>(cached) / static_cast<Real>(pairs));
  EXPECT_GT(cached, pairs * 9 / 10);
}

// Limits of the cache: a pair turned by more than 0.02 rad or slid by more than 2 % of the
// smaller radius since its features were searched is searched again; its feature indices must
// exist in the blocks it is applied to.
TEST(PairCache, EntriesHoldOnlyNearTheirSearch) {
  CachedFeatures e;
  e.feature = ManifoldFeature::face_of_a;
  e.feature_a = 1;
  e.rotation = Mat3::Identity();
  e.offset = Vec3(0, 0, 0.1);
  const auto turned = [](Real angle) {
    return Eigen::AngleAxis<Real>(angle, Vec3(1, 2, 3).normalized()).matrix();
  };
  EXPECT_TRUE(near_search(e, turned(0.019), Vec3(0, 0, 0.1), kCoinRadius));
  EXPECT_FALSE(near_search(e, turned(0.021), Vec3(0, 0, 0.1), kCoinRadius));
  EXPECT_TRUE(near_search(e, Mat3::Identity(), Vec3(0.0029, 0, 0.1), kCoinRadius));
  EXPECT_FALSE(near_search(e, Mat3::Identity(), Vec3(0.0031, 0, 0.1), kCoinRadius));
  std::vector<CachedFeatures> cache(3, e);
  cache[0].body_a = 0, cache[0].body_b = 1;
  cache[1].body_a = 0, cache[1].body_b = 2;
  cache[2].body_a = 1, cache[2].body_b = 2;
  for (CachedFeatures& c : cache) c.block_a = c.block_b = 0;
  EXPECT_EQ(cached_features(cache, 0, 0, 2, 0), &cache[1]);
  EXPECT_EQ(cached_features(cache, 0, 0, 2, 1), nullptr);
  EXPECT_EQ(cached_features(cache, 2, 0, 1, 0), nullptr);  // the other order is another pair
  WorldBlock two_faces;
  two_faces.normals.resize(2);
  EXPECT_TRUE(features_fit(e, two_faces, two_faces));
  e.feature_a = 2;
  EXPECT_FALSE(features_fit(e, two_faces, two_faces));
}

// The separating-face cache may skip a search only where the search would find the pair apart
// too: over random coin pairs found beyond the margin by a face, moved a little, wherever the
// cached face still separates them, the whole search says the same (and it does so often
// enough for the check to mean something).
TEST(PairCache, ACachedSeparatingFaceNeverHidesAContact) {
  const Block coin(regular_prism(6, kCoinRadius, kCoinThickness, Axis::z));
  const Real margin = 0.02;
  std::mt19937_64 rng(11);
  std::normal_distribution<Real> normal;
  std::uniform_real_distribution<Real> unit(0, 1);
  auto turn = [&](Real angle) {
    const Vec3 axis = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    return Eigen::AngleAxis<Real>(angle, axis).matrix();
  };
  auto pose = [](const Mat3& r, const Vec3& x) { return BlockPose{r, r.transpose(), x}; };
  ManifoldScratch scratch;
  WorldBlock wa, wb;
  int kept_apart = 0, searched_apart = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const BlockPose a = pose(turn(3.2 * unit(rng)), Vec3::Zero());
    const Vec3 direction = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Vec3 offset = (0.15 + 0.25 * unit(rng)) * direction;
    const BlockPose b = pose(turn(3.2 * unit(rng)), offset);
    place_block(coin, a, wa);
    place_block(coin, b, wb);
    Manifold m;
    SeparatingFace face;
    if (block_manifold(coin, wa, coin, wb, margin, scratch, m, &face)) continue;
    if (face.side == ManifoldFeature::none) continue;
    ++searched_apart;
    // A step's motion later: up to 0.05 rad and 0.01 cm.
    const Vec3 slide = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const BlockPose moved =
        pose(turn(0.05 * unit(rng)) * b.rotation, b.position + 0.01 * unit(rng) * slide);
    place_block(coin, moved, wb);
    if (!still_separated(wa, wb, face, margin)) continue;
    ++kept_apart;
    EXPECT_FALSE(block_manifold(coin, wa, coin, wb, margin, scratch, m)) << "trial " << trial;
  }
  report("coin pairs apart by a face: searched, then still kept apart by that face",
         static_cast<Real>(kept_apart));
  EXPECT_GT(searched_apart, 500);
  EXPECT_GT(kept_apart, searched_apart / 2);
  // A face the blocks do not have separates nothing.
  EXPECT_FALSE(still_separated(wa, wb, {ManifoldFeature::face_of_a, 99}, margin));
  EXPECT_FALSE(still_separated(wa, wb, {ManifoldFeature::edges, 0}, margin));
}

// The cache is part of what a checkpoint keeps: a settling column resumed mid-run is the
// uninterrupted one to the last bit, and the checkpoint holds the column's pairs.
TEST(PairCache, ResumedColumnIsBitIdentical) {
  const std::string scene_file = temp_path("pair_cache_column") + ".json";
  {
    // Written through the scene writer's own JSON: the column as a user would give it.
    std::ofstream out(scene_file);
    out << R"({"gravity": "earth", "time_step": 5e-4, "duration": 0.3,
      "contact": {"friction": 0.3, "tolerance": 1e-3, "max_sweeps": 20},
      "container": {"min": [0, 0, 0], "max": [1, 1, 1]}, "bodies": [)";
    for (int k = 0; k < 5; ++k)
      out << (k ? "," : "") << R"({"name": "c)" << k
          << R"(", "shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1, "axis": "z"},
          "density": 1, "position": [0.5, 0.5, )"
          << 0.05 + 0.1005 * k << R"(], "euler_zxz_deg": [)" << 7 * k << ", 0, 0]}";
    out << "]}";
  }
  Simulation a = Simulation::load(scene_file);
  a.step(200);
  const std::string checkpoint = temp_path("pair_cache_column") + ".bin";
  a.write_checkpoint(checkpoint);
  EXPECT_GE(read_checkpoint(checkpoint).features.size(), 4u);  // one per coin on a coin
  Simulation b = Simulation::resume(scene_file, checkpoint);
  a.step(300);
  b.step(300);
  EXPECT_EQ(a.state_hash_hex(), b.state_hash_hex());
  std::filesystem::remove(checkpoint);
  std::filesystem::remove(scene_file);
}

// The checkpoint keeps each cached feature's node past the rim (version 5); a version 4 file,
// made here by taking those records away (a count and one Real per feature before the checksum,
// the version field set to 4 and the sum taken again), is read with none past the rim.
TEST(PairCache, CheckpointKeepsANodePastTheRim) {
  Checkpoint c;
  CachedFeatures e;
  e.body_a = 0, e.block_a = 0, e.body_b = 1, e.block_b = 0;
  e.feature = ManifoldFeature::face_of_b;
  e.feature_b = 3;
  e.beyond_rim = 0.0123;
  c.features = {e, e};
  c.features[1].body_b = 2;
  c.features[1].beyond_rim = 0;
  const std::string file = temp_path("pair_cache_rim") + ".bin";
  write_checkpoint(file, c);
  const Checkpoint back = read_checkpoint(file);
  ASSERT_EQ(back.features.size(), 2u);
  EXPECT_EQ(back.features[0].beyond_rim, 0.0123);
  EXPECT_EQ(back.features[1].beyond_rim, 0);
  EXPECT_EQ(back.features[0].feature_b, 3);

  std::string bytes = testing_support::checkpoint_bytes(file);
  // Version 4 ends before the records past the rim (and version 6's list of files and version
  // 7's contact memory, two counts of 0).
  const size_t rim_records = 8 + 2 * sizeof(Real), files = 8 + 8;
  ASSERT_GT(bytes.size(), rim_records + files + 8 + 12);
  bytes.resize(bytes.size() - 8 - files - rim_records);
  testing_support::write_checkpoint_bytes(file, bytes, 4);
  const Checkpoint old = read_checkpoint(file);
  ASSERT_EQ(old.features.size(), 2u);
  EXPECT_EQ(old.features[0].beyond_rim, 0);
  EXPECT_EQ(old.features[0].feature_b, 3);
  EXPECT_EQ(old.features[1].body_b, 2);
  std::filesystem::remove(file);
}

}  // namespace test_pair_cache
}  // namespace tem
