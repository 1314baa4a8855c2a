// Contact detection benchmarks: the narrow phase and patches of one block pair for the
// paper's shapes, the broad phase and the whole detection on piles of 10^2 to 10^5 coins.
// Run: build/release/bench/tem_bench --benchmark_filter=Contact
#include <benchmark/benchmark.h>

#include "bench_scenes.hpp"
#include "collision/narrow_phase.hpp"
#include "contact/detect_contacts.hpp"
#include "contact/patches.hpp"
#include "geometry/primitives.hpp"

namespace tem::bench {
namespace {

BlockPose pose_of(const Mat3& rotation, const Vec3& position) {
  return {rotation, rotation.inverse(), position};
}

// Narrow phase + patches of one block pair; counts the patches found so the work is not elided.
void run_pair(benchmark::State& st, const Block& a, const BlockPose& pa, const Block& b,
              const BlockPose& pb) {
  NarrowPhaseScratch scratch;
  PatchScratch patch_scratch;
  PairFeatures features;
  std::vector<ContactPatch> patches;
  size_t found = 0;
  for (auto _ : st) {
    patches.clear();
    if (block_pair_features(a, pa, b, pb, scratch, features))
      pair_patches(a, pa, b, pb, features, NormalVariant::default_, patch_scratch, patches);
    found += patches.size();
    benchmark::DoNotOptimize(patches.data());
  }
  st.counters["patches_per_call"] = static_cast<double>(found) / st.iterations();
}

// Two paper coins, one lying on the other tilted 10 degrees, its rim 0.002 into the lower face.
void BM_ContactPairCoinCoin(benchmark::State& st) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  const Real tilt = 10 * std::numbers::pi / 180;
  // Lowest point below the centre: the hexagon reaches r cos(30 deg) across y, the axis turns.
  const Real reach = 0.15 * std::sqrt(3.0) / 2 * std::sin(tilt) + 0.05 * std::cos(tilt);
  run_pair(st, coin, pose_of(Mat3::Identity(), Vec3::Zero()), coin,
           pose_of(rotation_x(tilt), Vec3(0, 0, 0.05 + reach - 0.002)));
}
BENCHMARK(BM_ContactPairCoinCoin);

// The same coins 0.01 apart: the cost of a pair that the separating-plane test rejects.
void BM_ContactPairCoinCoinSeparated(benchmark::State& st) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  run_pair(st, coin, pose_of(Mat3::Identity(), Vec3::Zero()), coin,
           pose_of(rotation_x(0.17), Vec3(0, 0, 0.2)));
}
BENCHMARK(BM_ContactPairCoinCoinSeparated);

// One segment of the paper's ring (hexagonal section, one block of 16) against the hexagonal
// column (r 0.05, h 0.4) pressed 0.002 into its inner side.
void BM_ContactPairRingSegmentColumn(benchmark::State& st) {
  const std::vector<PolyhedronDef> ring = polygonal_ring(16, 6, 0.15, 0.05, 16, Axis::z, false);
  const Block segment(ring[0]);
  const Block column(regular_prism(6, 0.05, 0.4, Axis::z));
  // The segment spans angles 0 to 22.5 degrees; its innermost ridge is the chord at radius
  // R - r_s = 0.1 whose middle lies at 0.1 cos(11.25 deg). The column, turned so that one of its
  // vertical edges points along 11.25 degrees, pushes that edge 0.002 past the ridge: an
  // edge-edge contact.
  const Real half = std::numbers::pi / 16;
  const Vec3 towards(std::cos(half), std::sin(half), 0);
  const BlockPose ps = pose_of(Mat3::Identity(), segment.centroid_in_input());
  const BlockPose pc = pose_of(rotation_z(half), (0.1 * std::cos(half) + 0.002 - 0.05) * towards);
  run_pair(st, segment, ps, column, pc);
}
BENCHMARK(BM_ContactPairRingSegmentColumn);

// The paper's coin on its rim on the floor (tilted 60 degrees, 0.002 deep): a block-wall pair.
void BM_ContactPairCoinWall(benchmark::State& st) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  const Real tilt = std::numbers::pi / 3;
  const Real reach = 0.15 * std::sqrt(3.0) / 2 * std::sin(tilt) + 0.05 * std::cos(tilt);
  const BlockPose pose = pose_of(rotation_x(tilt), Vec3(0.5, 0.5, reach - 0.002));
  WallFeatures features;
  PatchScratch scratch;
  std::vector<ContactPatch> patches;
  for (auto _ : st) {
    patches.clear();
    block_wall_features(coin, pose, Vec3::Zero(), Vec3::UnitZ(), features);
    wall_patches(coin, pose, Vec3::Zero(), Vec3::UnitZ(), features, NormalVariant::default_,
                 scratch, patches);
    benchmark::DoNotOptimize(patches.data());
  }
  st.counters["patches_per_call"] = static_cast<double>(patches.size());
}
BENCHMARK(BM_ContactPairCoinWall);

// Broad phase alone on a pile of N coins: block poses, world bounds, grid, pairs.
void BM_ContactBroadPhase(benchmark::State& st) {
  const Model model = coin_pile(static_cast<int>(st.range(0)));
  const State state = initial_state(model);
  BroadPhase broad;
  for (auto _ : st) {
    broad.update(model, state);
    benchmark::DoNotOptimize(broad.block_pairs().data());
  }
  st.counters["bodies"] = static_cast<double>(model.bodies.size());
  st.counters["pairs"] = static_cast<double>(broad.block_pairs().size());
  st.counters["wall_pairs"] = static_cast<double>(broad.wall_pairs().size());
  st.counters["ns_per_body"] = benchmark::Counter(
      static_cast<double>(model.bodies.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ContactBroadPhase)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);

// The whole detection (broad phase, narrow phase, patches, merging) on a pile of N coins.
void BM_ContactDetectPile(benchmark::State& st) {
  const Model model = coin_pile(static_cast<int>(st.range(0)));
  const State state = initial_state(model);
  ContactWorkspace workspace;
  std::vector<ContactPatch> patches;
  for (auto _ : st) {
    detect_contacts(model, state, NormalVariant::default_, workspace, patches);
    benchmark::DoNotOptimize(patches.data());
  }
  st.counters["bodies"] = static_cast<double>(model.bodies.size());
  st.counters["patches"] = static_cast<double>(patches.size());
  st.counters["ns_per_body"] = benchmark::Counter(
      static_cast<double>(model.bodies.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  st.counters["ns_per_patch"] = benchmark::Counter(
      static_cast<double>(patches.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ContactDetectPile)->RangeMultiplier(10)->Range(100, 10000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace tem::bench
