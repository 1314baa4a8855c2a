// Sub-steps (contact.substeps, refreshed_patches.hpp): one detection per step, the contact
// features it found rebuilt and solved at every sub-step. The rebuilt manifold is the searched
// one while the features hold, the whole search once they do not; a coin lands when free fall
// says at a step four times the largest that holds without sub-steps' help; processes keep their
// energy accounting, resume and threads their bit-identity.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <tuple>

#include "collision/block_manifold.hpp"
#include "contact/contact_margins.hpp"
#include "geometry/primitives.hpp"
#include "support/belt_energy.hpp"
#include "support/falling_coin.hpp"
#include "support/parallel.hpp"
#include "support/simulate.hpp"
#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_substeps {

using testing_support::report;
using testing_support::run_tem;
using testing_support::simulate;
using testing_support::slurp;
using testing_support::temp_path;

Mat3 about(const Vec3& axis, Real angle) {
  return Eigen::AngleAxis<Real>(angle, axis.normalized()).matrix();
}

BlockPose pose_of(const Mat3& rotation, const Vec3& position) {
  return {rotation, rotation.transpose(), position};
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<Real> normal;
  return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

// Two coins (hexagonal prisms r 0.15, h 0.1) in the contacts a pile has: lying face on face
// (turned about the vertical), crossed rim on rim, and one on its rim on the other's face; each
// found by the whole search, then moved by a small random motion (up to 0.02 rad and 0.002 cm,
// what a sub-step of a pour moves a coin) and rebuilt from the features the search found.
// Where the search at the new pose picks the same features, the rebuilt manifold is its very
// manifold (the same arithmetic); where it picks others, the rebuilt one is never farther apart
// than the search says, beyond the search's own preference for faces (0.5 % of the radius).
TEST(SubStepManifold, RebuiltFromItsFeaturesIsTheSearchedOne) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  const Real margin = 0.02, face_preference = 0.005 * 0.15;
  // Standing on its rim with a corner down (turned 30 degrees about its axis, then stood up
  // about x): its lowest feature a ridge along y, 0.15 below its centre; turned a further 90
  // degrees about the vertical, a ridge along x.
  const Mat3 standing = about(Vec3::UnitX(), 1.5707963267948966) * about(Vec3::UnitZ(), 0.5235987755982988);
  const Mat3 across = about(Vec3::UnitZ(), 1.5707963267948966) * standing;
  struct Start {
    Mat3 rotation_a, rotation_b;
    Vec3 position_b;
  };
  const Start starts[] = {
      {Mat3::Identity(), about(Vec3::UnitZ(), 0.3), Vec3(0.05, -0.03, 0.1 + 0.001)},  // faces
      {Mat3::Identity(), standing, Vec3(0.02, 0, 0.05 + 0.15 + 0.001)},  // ridge on a face
      {standing, across, Vec3(0, 0, 0.15 + 0.15 + 0.001)},               // crossed ridges
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<Real> unit(0, 1);
  int same = 0, other = 0;
  for (const Start& s : starts) {
    const BlockPose pa = pose_of(s.rotation_a, Vec3::Zero());
    const BlockPose pb = pose_of(s.rotation_b, s.position_b);
    ManifoldScratch scratch;
    Manifold detected;
    ASSERT_TRUE(block_manifold(coin, pa, coin, pb, margin, scratch, detected));
    ASSERT_NE(detected.feature, ManifoldFeature::none);
    for (int trial = 0; trial < 200; ++trial) {
      const BlockPose qa = pose_of(about(random_unit(rng), 0.02 * unit(rng)) * s.rotation_a,
                                   0.002 * unit(rng) * random_unit(rng));
      const BlockPose qb = pose_of(about(random_unit(rng), 0.02 * unit(rng)) * s.rotation_b,
                                   s.position_b + 0.002 * unit(rng) * random_unit(rng));
      WorldBlock wa, wb;
      place_block(coin, qa, wa);
      place_block(coin, qb, wb);
      Manifold searched, rebuilt;
      const bool found = block_manifold(coin, wa, coin, wb, margin, scratch, searched);
      bool was_searched = false;
      const bool rebuilt_found =
          rebuild_manifold(coin, wa, coin, wb, margin, detected, scratch, rebuilt, &was_searched);
      // The same on blocks placed without their edges, as a sub-step places them: the same
      // manifold to the bit, or a call for the search exactly where rebuild_manifold searched.
      WorldBlock fa, fb;
      place_faces(coin, qa, fa);
      place_faces(coin, qb, fb);
      Manifold from_faces;
      const Rebuild r =
          rebuild_from_features(coin, fa, coin, fb, margin, detected, scratch, from_faces);
      ASSERT_EQ(r == Rebuild::search, was_searched);
      if (r != Rebuild::search) {
        ASSERT_EQ(r == Rebuild::held, rebuilt_found);
        ASSERT_EQ(from_faces.count, rebuilt.count);
        EXPECT_EQ(from_faces.normal, rebuilt.normal);
        for (int k = 0; k < rebuilt.count; ++k) {
          EXPECT_EQ(from_faces.point[k], rebuilt.point[k]);
          EXPECT_EQ(from_faces.gap[k], rebuilt.gap[k]);
        }
      }
      if (found && searched.feature == detected.feature &&
          searched.feature_a == detected.feature_a && searched.feature_b == detected.feature_b) {
        ++same;
        ASSERT_TRUE(rebuilt_found);
        ASSERT_EQ(rebuilt.count, searched.count);
        EXPECT_LE((rebuilt.normal - searched.normal).norm(), 1e-15);
        for (int k = 0; k < searched.count; ++k) {
          EXPECT_LE((rebuilt.point[k] - searched.point[k]).norm(), 1e-15);
          EXPECT_NEAR(rebuilt.gap[k], searched.gap[k], 1e-15);
        }
        continue;
      }
      ++other;
      if (!found) continue;  // nothing within the margin; the rebuilt one may still see a point
      ASSERT_TRUE(rebuilt_found);
      Real searched_gap = searched.gap[0], rebuilt_gap = rebuilt.gap[0];
      for (int k = 1; k < searched.count; ++k) searched_gap = std::min(searched_gap, searched.gap[k]);
      for (int k = 1; k < rebuilt.count; ++k) rebuilt_gap = std::min(rebuilt_gap, rebuilt.gap[k]);
      EXPECT_LE(rebuilt_gap, searched_gap + face_preference + 1e-12);
    }
  }
  report("small motions rebuilt with the searched features", same);
  report("small motions where the search changed features", other);
  EXPECT_GT(same, 400);
}

// Crossed ridges (edge on edge), then B turned 45 degrees about its own ridge: the next ridge
// of its hexagon is now the lowest, the cached edge pair no longer bounds B along its axis, and
// the rebuild is the whole search's answer (another edge pair).
TEST(SubStepManifold, FeaturesThatNoLongerHoldAreSearchedAgain) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  const Real margin = 0.05;
  const Mat3 standing = about(Vec3::UnitX(), 1.5707963267948966) * about(Vec3::UnitZ(), 0.5235987755982988);
  const Mat3 across = about(Vec3::UnitZ(), 1.5707963267948966) * standing;
  const BlockPose pa = pose_of(standing, Vec3::Zero());
  const BlockPose pb = pose_of(across, Vec3(0, 0, 0.3 + 0.001));
  ManifoldScratch scratch;
  Manifold detected;
  ASSERT_TRUE(block_manifold(coin, pa, coin, pb, margin, scratch, detected));
  ASSERT_EQ(detected.feature, ManifoldFeature::edges);
  // Its next ridge, 15 degrees off the vertical, is 0.15 cos 15 deg below its centre.
  const BlockPose turned = pose_of(about(Vec3::UnitX(), 0.7853981633974483) * across,
                                   Vec3(0, 0, 0.15 + 0.15 * std::cos(0.2617993877991494) + 0.001));
  WorldBlock wa, wb;
  place_block(coin, pa, wa);
  place_block(coin, turned, wb);
  Manifold searched, rebuilt;
  ASSERT_TRUE(block_manifold(coin, wa, coin, wb, margin, scratch, searched));
  ASSERT_TRUE(rebuild_manifold(coin, wa, coin, wb, margin, detected, scratch, rebuilt));
  EXPECT_NE(std::tuple(searched.feature, searched.feature_a, searched.feature_b),
            std::tuple(detected.feature, detected.feature_a, detected.feature_b));
  EXPECT_EQ(std::tuple(rebuilt.feature, rebuilt.feature_a, rebuilt.feature_b),
            std::tuple(searched.feature, searched.feature_a, searched.feature_b));
  ASSERT_EQ(rebuilt.count, searched.count);
  for (int k = 0; k < searched.count; ++k) EXPECT_EQ(rebuilt.gap[k], searched.gap[k]);
  EXPECT_NEAR(searched.gap[0], 0.001, 1e-12);
}

// A coin lying tilted across another's rim: the search takes a face whose clipped corners are
// not the other coin's deepest node below the reference plane (that node is past the rim, beside
// the face). A sub-step's rebuild lets such a node lie as deep again (Manifold::beyond_rim)
// instead of calling the search every time; where the search at the moved pose picks the same
// features, the rebuilt manifold is its very manifold, and a node that sinks further past the
// rim (here: the allowance taken away) still calls the search.
TEST(SubStepManifold, ANodePastTheRimAsDeepAsAtTheSearchKeepsTheFeatures) {
  const Block coin(regular_prism(6, 0.15, 0.1, Axis::z));
  const Real margin = 0.02;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> unit(0, 1);
  int past_rim = 0, held = 0, same = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const BlockPose pa = pose_of(Mat3::Identity(), Vec3::Zero());
    const Mat3 tilt = about(Vec3(unit(rng) - 0.5, unit(rng) - 0.5, 0), 0.4 * unit(rng));
    const BlockPose pb = pose_of(tilt * about(Vec3::UnitZ(), unit(rng)),
                                 Vec3(0.12 + 0.15 * unit(rng), 0.1 * (unit(rng) - 0.5),
                                      0.05 + 0.1 * unit(rng)));
    ManifoldScratch scratch;
    Manifold detected;
    if (!block_manifold(coin, pa, coin, pb, margin, scratch, detected)) continue;
    if (detected.feature != ManifoldFeature::face_of_a &&
        detected.feature != ManifoldFeature::face_of_b)
      continue;
    if (!(detected.beyond_rim > 1e-4)) continue;
    ++past_rim;
    // At the search's own pose with the allowance taken away (as if the node had sunk further
    // past the rim): the search answers.
    WorldBlock wa, wb;
    place_block(coin, pa, wa);
    place_block(coin, pb, wb);
    Manifold stricter = detected, searched, rebuilt;
    stricter.beyond_rim = 0;
    EXPECT_EQ(rebuild_from_features(coin, wa, coin, wb, margin, stricter, scratch, rebuilt),
              Rebuild::search);
    // A sub-step's motion: up to 2e-3 rad and 2e-4 cm.
    const BlockPose qb = pose_of(about(random_unit(rng), 2e-3 * unit(rng)) * pb.rotation,
                                 pb.position + 2e-4 * unit(rng) * random_unit(rng));
    place_block(coin, qb, wb);
    const bool found = block_manifold(coin, wa, coin, wb, margin, scratch, searched);
    if (rebuild_from_features(coin, wa, coin, wb, margin, detected, scratch, rebuilt) !=
        Rebuild::held)
      continue;
    ++held;
    if (!found || searched.feature != detected.feature ||
        searched.feature_a != detected.feature_a || searched.feature_b != detected.feature_b)
      continue;
    ++same;
    ASSERT_EQ(rebuilt.count, searched.count);
    EXPECT_EQ(rebuilt.normal, searched.normal);
    for (int k = 0; k < searched.count; ++k) {
      EXPECT_EQ(rebuilt.point[k], searched.point[k]);
      EXPECT_EQ(rebuilt.gap[k], searched.gap[k]);
    }
  }
  report("past_rim_searched_manifolds", past_rim);
  report("past_rim_rebuilt_without_search", held);
  report("past_rim_rebuilt_same_features_as_search", same);
  // About half the motions raise the node past the rim against the clipped corners (those hold)
  // and half sink it (the search answers).
  EXPECT_GE(past_rim, 20);
  EXPECT_GE(held, 5);
  EXPECT_GE(same, held * 9 / 10);
}

SceneDef falling_coin(Real height, Real dt, int substeps) {
  SceneDef scene = testing_support::falling_coin(height, 0, dt);
  scene.contact.substeps = substeps;
  return scene;
}

// Dropped flat from 1 cm at dt 2e-3 with four sub-steps (it falls 0.088 cm, 56 % of its size,
// in the step it lands): it lands within a sub-step of free fall's landing time, at rest on the
// floor, without overlapping it and without gaining energy. One solve per step at the same dt
// lands it a step late: the braking rule of semm.cpp stops it a step ahead of the floor.
TEST(SubSteps, CoinLandsWithinASubStepAtFourTimesTheStep) {
  const Real dt = 2e-3, h = 1.0, g = testing_support::kCoinGravity;
  const Real free_fall = std::sqrt(2 * h / g);
  auto landing = [&](int substeps, Real* deepest, Real* rise, Real* z) {
    const Model model = build_model(falling_coin(h, dt, substeps));
    State state = initial_state(model);
    Real landed = -1;
    const auto watch = simulate(model, state, 0.2, [&](const State& s, const Workspace&) {
      if (landed < 0 && s.bodies[0].x.z() - 0.05 <= 1e-9) landed = s.time;
    });
    *deepest = watch.deepest;
    *rise = watch.largest_energy_rise / (model.bodies[0].inertia.mass * g);
    *z = state.bodies[0].x.z();
    return landed;
  };
  Real deepest = 0, rise = 0, z = 0;
  const Real landed = landing(4, &deepest, &rise, &z);
  report("coin, dt 2e-3 with 4 sub-steps: landing time (s)", landed);
  report("free fall's landing time (s)", free_fall);
  EXPECT_GE(landed, free_fall);
  EXPECT_LE(landed, free_fall + dt);
  EXPECT_NEAR(z, 0.05, 1e-9);
  EXPECT_LE(deepest, 1e-9);
  EXPECT_LE(rise, 1e-12);
  Real deepest_one = 0, rise_one = 0, z_one = 0;
  const Real landed_one = landing(1, &deepest_one, &rise_one, &z_one);
  report("coin, dt 2e-3, one solve per step: landing time (s)", landed_one);
  EXPECT_GT(landed_one, free_fall + dt);
}

std::string processes_scene(const std::string& name) {
  return std::string(TEM_SOURCE_DIR) + "/tests/scenes/processes/" + name;
}

// A copy of a process scene with `"substeps": n` in its contact block (made if absent), and its
// duration changed if `duration` is given.
std::string with_substeps(const std::string& name, int n, const std::string& duration = "") {
  std::string text = slurp(processes_scene(name));
  if (!duration.empty()) {
    const std::string key = "\"duration\": ";
    const size_t at = text.find(key) + key.size();
    text.replace(at, text.find(',', at) - at, duration);
  }
  const std::string key = "\"contact\": {";
  const size_t at = text.find(key);
  if (at != std::string::npos)
    text.insert(at + key.size(), "\"substeps\": " + std::to_string(n) + ", ");
  else
    text.insert(text.find('{') + 1, "\"contact\": {\"substeps\": " + std::to_string(n) + "},");
  const std::string path = temp_path("substeps_" + name);
  std::ofstream(path) << text;
  return path;
}

// A belt carries a block with sub-steps: what the belt puts in is counted, the rest only falls.
TEST(SubSteps, EnergyLessDrivenWorkNeverRisesOnABelt) {
  const std::string scene = with_substeps("belt.json", 4);
  Simulation sim = Simulation::load(scene);
  testing_support::expect_energy_less_driven_work_never_rises(sim, 300);
  std::filesystem::remove(scene);
}

// Grains on a gate that opens, an outlet that takes them, with three sub-steps: a checkpoint
// taken mid-run resumes bit for bit, and two threads give the bytes of one. The one-thread run
// is the API's own, recorded as `tem run` writes (SimulationApi.RecordingWritesWhatTemRunWrites),
// so that the run of the resume check is also the threads check's reference. Under the
// sanitizers, the test's longest, it took 151 s with a third run and 119 s without (CI's clean
// runs, 2026-11-27).
TEST(SubSteps, ResumeAndThreadsGiveTheSameBitsWhileBodiesComeAndGo) {
  // To 0.2 s: past the gate's opening at 0.15 s, grains falling to the outlet.
  const std::string scene = with_substeps("gate_outlet.json", 3, "0.2");
  const std::string dir = temp_path("substeps_threads");
  const int threads = max_threads();
  set_threads(1);
  Simulation a = Simulation::load(scene);
  a.record(dir + "_1");
  a.step(250);
  const std::string checkpoint = temp_path("substeps_gate") + ".bin";
  a.write_checkpoint(checkpoint);
  Simulation b = Simulation::resume(scene, checkpoint);
  a.step(150);
  b.step(150);
  a.finish_recording();
  set_threads(threads);
  ASSERT_EQ(a.step_count(), a.total_steps());
  EXPECT_EQ(a.state_hash_hex(), b.state_hash_hex());
  const auto two = run_tem("run '" + scene + "' --out '" + dir + "_2' --hash --threads 2");
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_NE(two.out.find("hash: " + a.state_hash_hex()), std::string::npos) << two.out;
  EXPECT_EQ(slurp(dir + "_1/bodies.csv"), slurp(dir + "_2/bodies.csv"));
  for (const std::string& d : {dir + "_1", dir + "_2"}) std::filesystem::remove_all(d);
  std::filesystem::remove(checkpoint);
  std::filesystem::remove(scene);
}

// Sub-steps carry the points of contact before overlap; without them there is nothing to carry,
// and the scene says so where it asks for them.
TEST(SubSteps, RefusedWhereContactIsNotMadeBeforeOverlap) {
  const std::string scene = R"({"time_step": 1e-4, "duration": 0.01,
    "contact": {"model": "penalty", "stiffness": 1e6, "substeps": 2},
    "bodies": [{"name": "b", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 1]}]
  })";
  try {
    Simulation::from_json(scene);
    ADD_FAILURE() << "a penalty scene with sub-steps was accepted";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("contact.substeps"), std::string::npos) << message;
    EXPECT_NE(message.find("before overlap"), std::string::npos) << message;
  }
}

}  // namespace test_substeps
}  // namespace tem
