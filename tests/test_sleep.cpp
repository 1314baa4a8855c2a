// Sleep of bodies at rest (simulation/sleep.hpp, docs/method.md "Sleep"): boxes of 0.2 x 0.2 x 0.1
// cm on the floor under earth gravity (cm/s^2), at dt 1e-4 s, sleep.speed 0.5 cm/s and
// sleep.time 0.05 s. A box that settles moves at far less than 0.5 cm/s within a few
// hundredths of a second, and a falling one far faster, so the thresholds tell them apart.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "api/simulation_impl.hpp"
#include "simulation/sleep.hpp"
#include "io/checkpoint.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "support/checkpoint_bytes.hpp"
#include "support/parallel.hpp"
#include "support/simulate.hpp"
#include "support/tem_process.hpp"
#include "world/state_hash.hpp"

namespace tem {
namespace test_sleep {

using testing_support::box_on_floor;
using testing_support::temp_path;

constexpr Real kDt = 1e-4;
constexpr Real kSpeed = 0.5;
constexpr Real kRest = 0.05;

BodyDef box_at(const std::string& name, Real bottom) {
  BodyDef box = box_on_floor().bodies[0];
  box.name = name;
  box.position = Vec3(0, 0, bottom + 0.05);
  return box;
}

// Boxes stacked on the floor, box k with its bottom face at bottoms[k].
SceneDef stack(const std::vector<Real>& bottoms, bool sleep) {
  SceneDef scene = box_on_floor();
  scene.bodies.clear();
  for (size_t k = 0; k < bottoms.size(); ++k)
    scene.bodies.push_back(box_at("box" + std::to_string(k), bottoms[k]));
  scene.time_step = kDt;
  if (sleep) scene.sleep = SleepDef{kSpeed, kRest};
  return scene;
}

// Through the scene text, as a run reads it (defaults filled in).
Model model_of(const SceneDef& scene) {
  const SceneReadResult read = read_scene_text(write_scene_text(scene), "<sleep test>");
  EXPECT_TRUE(read.ok());
  return build_model(read.scene);
}

bool same_pose(const BodyState& a, const BodyState& b) {
  return a.x == b.x && a.g == b.g;  // exact: every bit
}

TEST(Sleep, BoxOnFloorFallsAsleepAfterItsRestTimeAndStaysExactlyPut) {
  const Model model = model_of(stack({0.01}, true));
  State state = initial_state(model);
  Workspace w;
  long long asleep_at = -1;
  Real rest_when_asleep = 0;
  for (long long k = 0; k < 5000 && asleep_at < 0; ++k) {
    const Real rest_before = state.bodies[0].rest_time;
    step(model, state, w);
    if (state.bodies[0].asleep) {
      asleep_at = state.step;
      rest_when_asleep = rest_before + kDt;
    }
  }
  ASSERT_GE(asleep_at, 0) << "the box never fell asleep";
  // It fell asleep on the step its rest reached sleep.time, not before.
  EXPECT_GE(rest_when_asleep, kRest);
  EXPECT_LT(rest_when_asleep, kRest + 1.5 * kDt);
  // It rests on the floor: bottom face at z = 0 within a hundredth of its height.
  EXPECT_NEAR(state.bodies[0].x.z(), 0.05, 1e-3);
  EXPECT_TRUE(state.bodies[0].v.isZero(0));
  EXPECT_TRUE(state.bodies[0].omega.isZero(0));
  testing_support::report("sleep_box_asleep_at_s", state.time);

  const BodyState at_sleep = state.bodies[0];
  for (int k = 0; k < 2000; ++k) {
    step(model, state, w);
    EXPECT_TRUE(w.patches.empty()) << "a sleeping box's floor pair was tested";
    if (!w.patches.empty()) break;
  }
  EXPECT_TRUE(state.bodies[0].asleep);
  EXPECT_TRUE(same_pose(state.bodies[0], at_sleep));
  EXPECT_TRUE(state.bodies[0].v.isZero(0));
}

// Three boxes: two stacked on the floor that settle first, a third dropped onto them later.
// The bottom two rest for sleep.time long before the third lands, yet none sleeps until all
// three have rested that long: the island sleeps as a whole.
TEST(Sleep, StackOfThreeSleepsOnlyAsAWhole) {
  const Model model = model_of(stack({0.0, 0.1, 2.0}, true));
  State state = initial_state(model);
  Workspace w;
  bool bottom_rested_alone = false;
  long long asleep_at = -1;
  for (long long k = 0; k < 8000 && asleep_at < 0; ++k) {
    step(model, state, w);
    const auto& b = state.bodies;
    // Before the third box arrives, the bottom two form their own island and may sleep; once
    // it touches them it wakes them: so look only at the steps where the third lies on them
    // (its centre within 2e-3 of its resting height 0.25).
    if (b[0].rest_time >= kRest && b[2].rest_time < kRest && !b[2].asleep &&
        b[2].x.z() < 0.25 + 2e-3)
      bottom_rested_alone = true;
    if (b[2].x.z() < 0.25 + 2e-3) {  // the third lies on the others: one island
      EXPECT_EQ(b[0].asleep, b[2].asleep) << "at step " << state.step;
      EXPECT_EQ(b[1].asleep, b[2].asleep) << "at step " << state.step;
    }
    if (b[0].asleep && b[1].asleep && b[2].asleep) asleep_at = state.step;
  }
  ASSERT_GE(asleep_at, 0) << "the stack never fell asleep";
  EXPECT_TRUE(bottom_rested_alone);
  const auto& b = state.bodies;
  EXPECT_EQ(b[0].island, b[1].island);
  EXPECT_EQ(b[1].island, b[2].island);
  EXPECT_EQ(b[0].island, 0);            // named by its lowest body id
  EXPECT_NEAR(b[2].x.z(), 0.25, 2e-3);  // on top of the other two
}

// Final poses of a box dropped from 5 cm (0.1 s of fall) onto another that rests on the floor, with
// or without sleep.
struct Drop {
  std::vector<BodyState> bodies;
  bool lower_slept = false, lower_woke = false;
};

Drop drop_on_box(bool sleep) {
  const Model model = model_of(stack({0.0, 5.0}, sleep));
  State state = initial_state(model);
  Workspace w;
  Drop d;
  for (long long k = 0; k < 5000; ++k) {
    step(model, state, w);
    if (state.bodies[0].asleep && !state.bodies[1].asleep && state.bodies[1].x.z() > 0.5)
      d.lower_slept = true;
    if (d.lower_slept && !state.bodies[0].asleep && state.bodies[1].x.z() < 0.3)
      d.lower_woke = true;
  }
  d.bodies = state.bodies;
  return d;
}

TEST(Sleep, BoxDroppedOnASleepingOneWakesItAndThePairRestsAsWithoutSleep) {
  const Drop off = drop_on_box(false), on = drop_on_box(true);
  EXPECT_TRUE(on.lower_slept) << "the lower box did not sleep before the other landed";
  EXPECT_TRUE(on.lower_woke) << "the landing did not wake it";
  ASSERT_EQ(on.bodies.size(), 2u);
  EXPECT_TRUE(on.bodies[0].asleep && on.bodies[1].asleep) << "the pair did not sleep again";
  for (int b = 0; b < 2; ++b) {
    const Real dz = std::abs(on.bodies[b].x.z() - off.bodies[b].x.z());
    const Real dxy = (on.bodies[b].x - off.bodies[b].x).head<2>().norm();
    testing_support::report("sleep_drop_dz_box" + std::to_string(b), dz);
    testing_support::report("sleep_drop_dxy_box" + std::to_string(b), dxy);
    // Both runs end at the same equilibrium: boxes face on face, their heights set by the
    // geometry and the contacts' resting overlap, which the solver finds to its tolerance
    // (1e-9 of the largest impulse) from any nearby start. Sleep only changed the start of
    // the last settling (the lower box frozen, not creeping at under 0.5 cm/s): the heights
    // agree to rounding (measured 2e-16 cm), far inside 1e-9 cm.
    EXPECT_LT(dz, 1e-9) << "box " << b;
    EXPECT_LT(dxy, 1e-9) << "box " << b;
  }
}

// Sleep on, but a speed no body ever gets below: no body sleeps, nothing is left out, and the
// run is the very run without sleep, bit for bit.
TEST(Sleep, SleepThatNeverTriggersChangesNoBit) {
  SceneDef never = stack({0.0, 0.1, 0.5}, true);
  never.sleep->speed = 1e-300;
  const Model with = model_of(never), without = model_of(stack({0.0, 0.1, 0.5}, false));
  State a = initial_state(with), b = initial_state(without);
  Workspace wa, wb;
  for (int k = 0; k < 1500; ++k) {
    step(with, a, wa);
    step(without, b, wb);
  }
  EXPECT_EQ(sleeping_bodies(a), 0);
  EXPECT_EQ(state_hash(a), state_hash(b));
}

// A scene file with sleep, for the API's checkpoint and threads.
std::string write_stack_scene(const std::string& name, Real duration) {
  SceneDef scene = stack({0.0, 0.1, 5.0}, true);
  scene.duration = duration;
  const std::string file = temp_path(name) + ".json";
  std::ofstream(file) << write_scene_text(scene);
  return file;
}

TEST(Sleep, ResumeFromACheckpointWhileAsleepIsBitIdentical) {
  const std::string scene = write_stack_scene("sleep_resume", 0.6);
  Simulation straight = Simulation::load(scene);
  straight.step(6000);

  Simulation first = Simulation::load(scene);
  first.step(800);
  // The checkpoint is taken with the lower boxes asleep and the third still falling or
  // bouncing: timers, flags and island names all matter after it.
  const State& at = first.impl().state;
  ASSERT_TRUE(at.bodies[0].asleep && at.bodies[1].asleep);
  ASSERT_FALSE(at.bodies[2].asleep);
  const std::string checkpoint = temp_path("sleep_resume") + ".bin";
  first.write_checkpoint(checkpoint);
  Simulation resumed = Simulation::resume(scene, checkpoint);
  EXPECT_EQ(resumed.impl().state.bodies[0].island, at.bodies[0].island);
  EXPECT_EQ(resumed.impl().state.bodies[2].rest_time, at.bodies[2].rest_time);
  resumed.step(5200);
  first.step(5200);
  EXPECT_EQ(resumed.state_hash(), straight.state_hash());
  EXPECT_EQ(first.state_hash(), straight.state_hash());
  const State& end = resumed.impl().state;
  for (size_t b = 0; b < 3; ++b) {
    EXPECT_EQ(end.bodies[b].asleep, straight.impl().state.bodies[b].asleep);
    EXPECT_EQ(end.bodies[b].rest_time, straight.impl().state.bodies[b].rest_time);
  }
  std::filesystem::remove(scene);
  std::filesystem::remove(checkpoint);
}

// Nine stacks of three boxes, 0.5 cm apart, the top boxes dropped from heights of 0.5 to 4.5 cm:
// islands fall asleep at different times, and some are woken while others sleep.
TEST(Sleep, OneAndTwoThreadsGiveTheSameBits) {
  SceneDef scene = stack({}, true);
  for (int k = 0; k < 9; ++k) {
    const Vec3 at(0.5 * (k % 3), 0.5 * (k / 3), 0);
    for (const Real bottom : {0.0, 0.1, 0.5 + 0.5 * k}) {
      BodyDef box = box_at("box" + std::to_string(scene.bodies.size()), bottom);
      box.position += at;
      scene.bodies.push_back(box);
    }
  }
  const Model model = model_of(scene);
  auto run = [&](int threads) {
    set_threads(threads);
    State state = initial_state(model);
    Workspace w;
    long long most_asleep = 0, fewest_asleep_after = 27;
    for (int k = 0; k < 4000; ++k) {
      step(model, state, w);
      const long long asleep = sleeping_bodies(state);
      most_asleep = std::max(most_asleep, asleep);
      if (most_asleep > 0) fewest_asleep_after = std::min(fewest_asleep_after, asleep);
    }
    // Some stacks slept while others still moved, and all sleep at the end.
    EXPECT_GT(most_asleep, 0);
    EXPECT_LT(fewest_asleep_after, 27);
    EXPECT_EQ(sleeping_bodies(state), 27);
    return state_hash(state);
  };
  const std::uint64_t one = run(1), two = run(2);
  set_threads(1);
  EXPECT_EQ(one, two);
}

TEST(Sleep, CheckpointKeepsTimersFlagsAndIslands) {
  State state;
  state.bodies.resize(2);
  state.tags = {{0, -1, 0, 1}, {1, -1, 0, 1}};
  state.bodies[0].rest_time = 0.125;
  state.bodies[0].asleep = true;
  state.bodies[0].island = 7;
  state.bodies[1].rest_time = 0.03125;
  Checkpoint c;
  c.state = state;
  const std::string file = temp_path("sleep_checkpoint") + ".bin";
  write_checkpoint(file, c);
  const Checkpoint back = read_checkpoint(file);
  ASSERT_EQ(back.state.bodies.size(), 2u);
  EXPECT_EQ(back.state.bodies[0].rest_time, 0.125);
  EXPECT_TRUE(back.state.bodies[0].asleep);
  EXPECT_EQ(back.state.bodies[0].island, 7);
  EXPECT_EQ(back.state.bodies[1].rest_time, 0.03125);
  EXPECT_FALSE(back.state.bodies[1].asleep);
  EXPECT_EQ(back.state.bodies[1].island, -1);
  std::filesystem::remove(file);
}

// A checkpoint of version 2 (before sleep) is still read: made here from a version 3 one by
// taking away its sleep records (the last 8 + 17 n bytes before the checksum), setting the
// version field (after the 8-byte magic) to 2 and summing it again (FNV-1a, as the format says).
TEST(Sleep, CheckpointOfVersionTwoIsStillRead) {
  Checkpoint c;
  c.state.bodies.resize(2);
  c.state.tags = {{0, -1, 0, 1}, {1, -1, 0, 1}};
  c.state.bodies[0].x = Vec3(1, 2, 3);
  c.state.bodies[1].rest_time = 0.5;
  c.state.bodies[1].asleep = true;
  c.state.bodies[1].island = 1;
  const std::string file = temp_path("sleep_checkpoint_v2") + ".bin";
  write_checkpoint(file, c);
  std::string bytes = testing_support::checkpoint_bytes(file);
  // Version 2 ends before the sleep records (and version 4's empty pair cache, version 5's
  // records of it, version 6's list of files and version 7's contact memory, four counts of 0).
  const size_t sleep_records = 8 + 2 * (sizeof(Real) + sizeof(bool) + sizeof(long long));
  const size_t features = 8 + 8 + 8 + 8;
  ASSERT_GT(bytes.size(), sleep_records + features + 8 + 12);
  bytes.resize(bytes.size() - 8 - features - sleep_records);
  testing_support::write_checkpoint_bytes(file, bytes, 2);
  const Checkpoint back = read_checkpoint(file);
  ASSERT_EQ(back.state.bodies.size(), 2u);
  EXPECT_EQ(back.state.bodies[0].x, Vec3(1, 2, 3));
  EXPECT_FALSE(back.state.bodies[1].asleep);
  EXPECT_EQ(back.state.bodies[1].rest_time, 0);
  EXPECT_EQ(back.state.bodies[1].island, -1);
  std::filesystem::remove(file);
}

// Steps a Simulation (the population stage included) for `seconds`.
void run_for(Simulation& sim, Real seconds) { sim.step(std::llround(seconds / kDt)); }

// A box asleep on a gate, under which a floor lies 1 cm lower: the gate taken away at 0.2 s
// (`wall`: a wall with removed_at; otherwise a fixed body with removed_at) must wake it, and
// it falls to the floor (its centre from 0.05 to -0.95) instead of hanging in the air.
void expect_falls_when_gate_goes(bool wall) {
  SceneDef scene = stack({0.0}, true);
  scene.walls.clear();
  scene.walls.push_back({Vec3(0, 0, -1), Vec3::UnitZ()});
  if (wall) {
    scene.walls.push_back({Vec3::Zero(), Vec3::UnitZ()});
    scene.walls.back().removed_at = 0.2;
  } else {
    BodyDef gate = box_at("gate", -0.1);
    gate.shape.size = Vec3(0.6, 0.6, 0.1);
    gate.fixed = true;
    gate.removed_at = 0.2;
    scene.bodies.push_back(gate);
  }
  scene.duration = 1;
  Simulation sim = Simulation::from_scene(scene);
  run_for(sim, 0.15);
  ASSERT_TRUE(sim.impl().state.bodies[0].asleep);
  const Real z_asleep = sim.impl().state.bodies[0].x.z();
  EXPECT_NEAR(z_asleep, 0.05, 1e-3);
  run_for(sim, 0.3);
  EXPECT_NEAR(sim.impl().state.bodies[0].x.z(), -0.95, 1e-3);
}

TEST(Sleep, WallTakenAwayWakesWhatRestedOnIt) { expect_falls_when_gate_goes(true); }
TEST(Sleep, BodyTakenAwayWakesWhatRestedOnIt) { expect_falls_when_gate_goes(false); }

// An external force on a sleeping box wakes it: pushed sideways with 2.5 times what friction
// holds (friction 0.3 of its weight), it slides.
TEST(Sleep, ExternalForceWakesASleepingBody) {
  SceneDef scene = stack({0.0}, true);
  scene.duration = 1;
  Simulation sim = Simulation::from_scene(scene);
  run_for(sim, 0.1);
  ASSERT_TRUE(sim.impl().state.bodies[0].asleep);
  const Vec3 at = sim.impl().state.bodies[0].x;
  const Real weight = 0.2 * 0.2 * 0.1 * 1.0 * earth_gravity_cgs;
  sim.set_external_force(0, Vec3(2.5 * 0.3 * weight, 0, 0));
  run_for(sim, 0.05);
  EXPECT_FALSE(sim.impl().state.bodies[0].asleep);
  // (2.5 - 1) * 0.3 g: 441 cm/s^2 for 0.05 s gives 0.55 cm.
  EXPECT_GT(sim.impl().state.bodies[0].x.x() - at.x(), 0.3);
}

// Every key checked, each problem naming its path.
std::string problems_of(const std::string& sleep) {
  const std::string text =
      R"({"walls": [{"point": [0,0,0], "normal": [0,0,1]}],
          "bodies": [{"name": "b", "shape": {"type": "box", "size": [1,1,1]},
                      "position": [0,0,0.5]}],
          "sleep": )" +
      sleep + "}";
  const SceneReadResult read = read_scene_text(text, "s.json");
  std::string all;
  for (const auto& p : read.problems) all += p.path + ": " + p.message + "\n";
  return all;
}

TEST(Sleep, SceneKeysAreChecked) {
  EXPECT_EQ(problems_of(R"({"speed": 0.05, "time": 0.2})"), "");
  EXPECT_NE(problems_of(R"({"time": 0.2})").find("sleep: missing required key 'speed'"),
            std::string::npos);
  EXPECT_NE(problems_of(R"({"speed": 0.05})").find("sleep: missing required key 'time'"),
            std::string::npos);
  EXPECT_NE(problems_of(R"({"speed": -1, "time": 0.2})").find("sleep.speed"), std::string::npos);
  EXPECT_NE(problems_of(R"({"speed": 0.05, "time": 0})").find("sleep.time"), std::string::npos);
  EXPECT_NE(
      problems_of(R"({"speed": 0.05, "time": 0.2, "tme": 1})").find("sleep: unknown key 'tme'"),
      std::string::npos);
  EXPECT_NE(problems_of(R"(true)").find("sleep"), std::string::npos);
  // Written back as read; absent, not written at all.
  const SceneReadResult read = read_scene_text(
      R"({"bodies": [{"name": "b", "shape": {"type": "box", "size": [1,1,1]},
                      "position": [0,0,0.5]}],
          "sleep": {"speed": 0.05, "time": 0.2}})",
      "s.json");
  ASSERT_TRUE(read.ok());
  ASSERT_TRUE(read.scene.sleep.has_value());
  EXPECT_EQ(read.scene.sleep->speed, 0.05);
  EXPECT_EQ(read.scene.sleep->time, 0.2);
  const SceneReadResult again = read_scene_text(write_scene_text(read.scene), "again.json");
  ASSERT_TRUE(again.scene.sleep.has_value());
  EXPECT_EQ(again.scene.sleep->time, 0.2);
  SceneDef off = read.scene;
  off.sleep.reset();
  EXPECT_EQ(write_scene_text(off).find("sleep"), std::string::npos);
}

}  // namespace test_sleep
}  // namespace tem
