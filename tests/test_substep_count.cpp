// Sub-steps chosen per step (contact.max_substeps, simulation/substep_count.hpp): the fewest, from
// contact.substeps up to contact.max_substeps, in which no contact's relative motion covers more
// than contact.substep_motion of the smaller body's size. A landing takes the sub-steps it needs
// and a body at rest the fewest; the choice is the state's alone, so resume and threads keep
// their bits; and the scene says where the keys are wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "simulation/substep_count.hpp"
#include "support/falling_coin.hpp"
#include "support/parallel.hpp"
#include "support/simulate.hpp"
#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_substep_count {

using testing_support::report;
using testing_support::simulate;

// Two coins and the floor: coin 0 on the floor, coin 1 on coin 0, with a patch for each contact.
struct TwoCoins {
  Model model;
  State state;
  std::vector<ContactPatch> patches;
  Real size = 0;
};

TwoCoins two_coins(int substeps, int max_substeps, Real dt) {
  SceneDef scene = testing_support::falling_coin(0, 0, dt);
  scene.bodies.push_back(scene.bodies[0]);
  scene.bodies[1].name = "top";
  scene.bodies[1].position.z() += 0.1;
  scene.contact.substeps = substeps;
  scene.contact.max_substeps = max_substeps;
  TwoCoins c{build_model(scene), {}, {}, 0};
  c.state = initial_state(c.model);
  ContactPatch on_floor, on_coin;
  on_floor.body_a = 0;
  on_floor.wall = 0;
  on_coin.body_a = 1;
  on_coin.body_b = 0;
  c.patches = {on_floor, on_coin};
  c.size = body_size(c.model, 0);
  return c;
}

// The count from the rule's arithmetic: what moves relative to what, over the step, against the
// smaller size, in sub-steps of contact.substep_motion (0.015) at most.
TEST(SubStepCount, ComesFromEachContactsRelativeMotion) {
  const Real dt = 5e-4;
  TwoCoins c = two_coins(4, 16, dt);
  const Real motion = c.model.scene.contact.substep_motion;
  EXPECT_EQ(motion, 0.015);
  // At rest: the fewest.
  EXPECT_EQ(substeps_for_step(c.model, c.state, c.patches), 4);
  // Both coins falling together at 30 cm/s: the pair moves nothing relative to itself, but the
  // bottom coin closes on the floor by 30 cm/s * dt = 0.015 cm, 0.0949 of its size (0.158):
  // seven sub-steps of 0.0136 each.
  c.state.bodies[0].v = c.state.bodies[1].v = Vec3(0, 0, -30);
  const Real share = 30 * dt / c.size;
  EXPECT_EQ(substeps_for_step(c.model, c.state, c.patches),
            static_cast<int>(std::ceil(share / motion)));
  EXPECT_EQ(substeps_for_step(c.model, c.state, c.patches), 7);
  // Only the pair of coins in contact, both moving: their relative motion alone counts.
  const std::vector<ContactPatch> pair = {c.patches[1]};
  EXPECT_EQ(substeps_for_step(c.model, c.state, pair), 4);
  // The top coin spinning at 200 rad/s on the bottom one: its corners sweep 200 * size * dt,
  // 0.1 of its size over the step, seven sub-steps.
  c.state.bodies[0].v = c.state.bodies[1].v = Vec3::Zero();
  c.state.bodies[1].omega = Vec3(0, 0, 200);
  EXPECT_EQ(substeps_for_step(c.model, c.state, pair), 7);
  // Faster than 16 sub-steps can follow: the most.
  c.state.bodies[1].omega = Vec3(0, 0, 2000);
  EXPECT_EQ(substeps_for_step(c.model, c.state, pair), 16);
  // Without max_substeps the count is the scene's, whatever moves.
  TwoCoins fixed = two_coins(4, 0, dt);
  fixed.state.bodies[1].omega = Vec3(0, 0, 2000);
  EXPECT_EQ(substeps_for_step(fixed.model, fixed.state, fixed.patches), 4);
}

// A coin dropped flat from 1 cm at dt 2e-3 (it arrives at 44 cm/s, 0.088 cm a step), with one
// to sixteen sub-steps: sixteen as it lands, one a step once it rests. It falls freely to the
// last step before free fall's landing time (no early braking: one solve a step stops it a step
// ahead, SubSteps.CoinLandsWithinASubStepAtFourTimesTheStep) and lands within the step after,
// without overlap and without gaining energy.
TEST(SubStepCount, LandingTakesTheSubStepsItNeedsAndRestTheFewest) {
  const Real dt = 2e-3, h = 1.0, g = testing_support::kCoinGravity;
  const Real free_fall = std::sqrt(2 * h / g);
  SceneDef scene = testing_support::falling_coin(h, 0, dt);
  scene.contact.max_substeps = 16;
  const Model model = build_model(scene);
  State state = initial_state(model);
  Real landed = -1, speed_before = 0, time_before = 0;
  int most = 0, at_rest = 0;
  const auto watch = simulate(model, state, 0.2, [&](const State& s, const Workspace& w) {
    if (landed < 0 && s.bodies[0].x.z() - 0.05 <= 1e-9) landed = s.time;
    if (s.time < free_fall) {
      speed_before = -s.bodies[0].v.z();
      time_before = s.time;
    }
    most = std::max(most, w.substeps);
    if (s.time > free_fall + 0.05) at_rest = std::max(at_rest, w.substeps);
  });
  report("coin, dt 2e-3 with 1 to 16 sub-steps: landing time (s)", landed);
  report("free fall's landing time (s)", free_fall);
  report("most sub-steps a step", most);
  EXPECT_NEAR(speed_before, g * time_before, 1e-9 * g * time_before);
  EXPECT_GE(landed, free_fall);
  EXPECT_LE(landed, free_fall + dt);
  EXPECT_EQ(most, 16);
  EXPECT_EQ(at_rest, 1);
  EXPECT_NEAR(state.bodies[0].x.z(), 0.05, 1e-9);
  EXPECT_LE(watch.deepest, 1e-9);
  EXPECT_LE(watch.largest_energy_rise / (model.bodies[0].inertia.mass * g), 1e-12);
}

// Coins tumbling onto a floor and each other, the sub-steps changing from step to step: a
// checkpoint taken mid-fall resumes bit for bit, and two threads give the bits of one.
TEST(SubStepCount, ResumeAndThreadsKeepTheBits) {
  const std::string scene = R"({"gravity": "earth", "time_step": 1e-3, "duration": 0.2,
    "contact": {"substeps": 2, "max_substeps": 12},
    "container": {"min": [0, 0, 0], "max": [1, 1, 3]},
    "fill": [{"name": "coin", "count": 12, "seed": 3,
              "region": {"min": [0, 0, 0.05], "max": [1, 1, 2.5]},
              "body": {"shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1},
                       "density": 7.0}}]})";
  const std::string file = testing_support::temp_path("substep_count") + ".json";
  std::ofstream(file) << scene;
  const int threads = max_threads();
  set_threads(1);
  Simulation a = Simulation::load(file);
  a.step(60);  // mid-crash: the next 60 steps take 6.4 sub-steps on average
  const std::string checkpoint = testing_support::temp_path("substep_count") + ".bin";
  a.write_checkpoint(checkpoint);
  Simulation b = Simulation::resume(file, checkpoint);
  a.step(140);
  b.step(140);
  EXPECT_EQ(a.state_hash_hex(), b.state_hash_hex());
  set_threads(2);
  Simulation c = Simulation::load(file);
  c.step(200);
  set_threads(threads);
  EXPECT_EQ(a.state_hash_hex(), c.state_hash_hex());
  std::filesystem::remove(checkpoint);
  std::filesystem::remove(file);
}

// Grains in a turning drum (tests/scenes/processes/small_drum.json without its inlet, 2 rad/s)
// with two to eight sub-steps a step (7.6 on average): the drum's velocity for a sub-step is its
// chord over time_step / 2 while the step may take shorter ones, yet what the drum puts in is all
// counted: the energy less the drum's work never rises beyond round-off of the energy over
// 0.15 s of falling and tumbling.
TEST(SubStepCount, TurningDrumsWorkIsAllCounted) {
  nlohmann::json scene = nlohmann::json::parse(testing_support::slurp(
      std::string(TEM_SOURCE_DIR) + "/tests/scenes/processes/small_drum.json"));
  scene.erase("inlets");  // grains that arrive bring energy of their own
  scene["contact"]["substeps"] = 2;
  scene["contact"]["max_substeps"] = 8;
  scene["contact"]["substep_motion"] = 0.005;
  Simulation sim = Simulation::from_json(scene.dump());
  SystemEnergies e = sim.energies();
  Real last = e.total() - e.driven_work, largest_rise = 0;
  for (int k = 0; k < 300; ++k) {
    sim.step();
    e = sim.energies();
    const Real now = e.total() - e.driven_work;
    largest_rise =
        std::max(largest_rise, (now - last) / (std::abs(e.kinetic) + std::abs(e.potential)));
    last = now;
  }
  report("drum with 2 to 8 sub-steps: largest rise of energy less driven work", largest_rise);
  EXPECT_LE(largest_rise, 1e-12);
  EXPECT_GT(e.driven_work, 0);
}

// The keys' errors name the key and say why.
TEST(SubStepCount, WrongKeysAreRefusedWithWhereAndWhy) {
  const auto refusal = [](const std::string& contact) -> std::string {
    const std::string scene = R"({"time_step": 1e-4, "duration": 0.01, "contact": {)" + contact +
                              R"(}, "bodies": [{"name": "b", "shape": {"type": "box",
                              "size": [1, 1, 1]}, "position": [0, 0, 1]}]})";
    try {
      Simulation::from_json(scene);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  const std::string fewer = refusal(R"("substeps": 4, "max_substeps": 2)");
  EXPECT_NE(fewer.find("contact.max_substeps"), std::string::npos) << fewer;
  EXPECT_NE(fewer.find("at least substeps (4)"), std::string::npos) << fewer;
  const std::string penalty = refusal(R"("model": "penalty", "stiffness": 1e6, "max_substeps": 4)");
  EXPECT_NE(penalty.find("contact.max_substeps"), std::string::npos) << penalty;
  EXPECT_NE(penalty.find("before overlap"), std::string::npos) << penalty;
  const std::string motion = refusal(R"("max_substeps": 4, "substep_motion": 0)");
  EXPECT_NE(motion.find("contact.substep_motion"), std::string::npos) << motion;
  const std::string alone = refusal(R"("substeps": 4, "substep_motion": 0.01)");
  EXPECT_NE(alone.find("contact.substep_motion"), std::string::npos) << alone;
  EXPECT_NE(alone.find("without max_substeps"), std::string::npos) << alone;
  EXPECT_EQ(refusal(R"("substeps": 4, "max_substeps": 4)"), "");
}

}  // namespace test_substep_count
}  // namespace tem
