// Sub-steps chosen per step (contact.max_substeps, simulation/substep_count.hpp): the fewest, from
// contact.substeps up to contact.max_substeps, in which no contact's relative motion covers more
// than contact.substep_motion of the smaller body's size. A landing takes the sub-steps it needs
// and a body at rest the fewest; the choice is the state's alone, so resume and threads keep
// their bits; and the scene says where the keys are wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "io/scene_reader.hpp"
#include "process/motion.hpp"
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
// with two to eight sub-steps a step (7.6 on average), the drum's velocity in each its chord
// over the step's own sub-step: what the drum puts in is all counted, the energy less the drum's
// work never rising beyond round-off of the energy over 0.15 s of falling and tumbling.
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

// A coin spinning at 400 rad/s on a plate that shakes up and down (0.04 cm at 20 Hz, 632 cm/s^2 at
// its turns, under g), over the half period in which the plate accelerates downward, away from
// the coin, so that the coin rides it. The spin makes each step take 12 to 14 sub-steps of the 1
// to 16 allowed. With the plate's velocity in each sub-step its chord over that sub-step, the coin
// moves exactly as the plate does: no gap opens and none closes, and it leaves every step at the
// plate's own velocity. (Taken over the fewest sub-steps' length, the whole step, that velocity
// was off by the plate's acceleration times half the difference, up to 0.15 cm/s of its 5 cm/s:
// the coin sank 8e-5 cm into the plate within 3 ms and needed the overlap correction every other
// step.)
TEST(SubStepCount, DrivenBodyMovesAtItsChordOverTheStepsOwnSubStep) {
  const Real amplitude = 0.04, omega = 2 * std::numbers::pi * 20;
  const Real peak = amplitude * omega;
  const std::string text = R"({"gravity": "earth", "time_step": 5e-4, "duration": 0.025,
    "contact": {"substeps": 1, "max_substeps": 16},
    "bodies": [
      {"name": "plate", "shape": {"type": "box", "size": [2, 2, 0.2]}, "position": [0, 0, 0],
       "motion": {"oscillation": {"amplitude": [0, 0, 0.04], "frequency": 20}}},
      {"name": "coin", "shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1},
       "density": 7.0, "position": [0, 0, 0.15], "velocity": [0, 0, )" +
                           std::to_string(peak) + R"(], "angular_velocity": [0, 0, 400]}]})";
  const SceneReadResult read = read_scene_text(text, "shaker");
  ASSERT_TRUE(read.ok());
  const Model model = build_model(read.scene);
  State state = initial_state(model);
  // The coin's bottom face over the plate's top face.
  const auto gap = [](const State& s) {
    return s.bodies[1].x.z() - 0.05 - (s.bodies[0].x.z() + 0.1);
  };
  Real worst_speed = 0, worst_gap = 0, largest_rise = 0;
  Real last = system_energies(model, state).total();
  int fewest = 16;
  long long corrected = 0;
  simulate(model, state, 0.025, [&](const State& s, const Workspace& w) {
    fewest = std::min(fewest, w.substeps);
    corrected = w.times.corrected_steps;
    const Real plate_speed = peak * std::cos(omega * s.time);
    worst_speed = std::max(worst_speed, std::abs(s.bodies[1].v.z() - plate_speed));
    worst_gap = std::max(worst_gap, std::abs(gap(s)));
    const Real now = system_energies(model, s).total() - s.driven_work;
    largest_rise = std::max(largest_rise, now - last);
    last = now;
  });
  report("coin on a shaker, 1 to 16 sub-steps: fewest sub-steps a step", fewest);
  report("largest difference of the coin's vertical velocity from the plate's (cm/s)",
         worst_speed);
  report("largest gap or overlap under the coin (cm)", worst_gap);
  EXPECT_GE(fewest, 8);
  EXPECT_EQ(corrected, 0);
  EXPECT_LE(worst_gap, 1e-12);
  EXPECT_LE(worst_speed, 1e-4 * peak);
  EXPECT_LE(largest_rise, 1e-12 * model.bodies[1].inertia.mass * earth_gravity_cgs * 0.2);
  EXPECT_NEAR(state.time, 0.025, 1e-15);
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
