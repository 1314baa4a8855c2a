// The public C++ API (include/tem/simulation.hpp) as a program built on TEM uses it: loading,
// stepping, views that see every step, forces from outside, results, checkpoints, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_simulation_api {

using testing_support::contains;
using testing_support::run_tem;
using testing_support::temp_path;

const std::string kScenes = std::string(TEM_SOURCE_DIR) + "/tests/scenes/";

// A box of 0.2 x 0.2 x 0.1 resting flat on the container's floor, friction 0.3, no gravity
// tricks: the scene every load test below pushes on.
std::string box_on_floor(Real friction) {
  return R"({"time_step": 1e-3, "duration": 1,
    "contact": {"model": "semm", "friction": )" +
         std::to_string(friction) + R"(, "restitution": 0.0},
    "container": {"min": [0, 0, 0], "max": [10, 10, 1]},
    "bodies": [{"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.1]},
                "position": [5, 5, 0.05]}]})";
}

// A coin alone in space (no container, no walls).
const char* kCoinInSpace = R"({"time_step": 1e-3, "duration": 1,
  "bodies": [{"name": "coin", "shape": {"type": "prism", "sides": 6, "radius": 1, "height": 0.3},
              "density": 2.0, "position": [0, 0, 100]}]})";

TEST(SimulationApi, ViewsSeeEveryStepWithoutACopy) {
  Simulation sim = Simulation::from_json(kCoinInSpace);
  const Real* x = sim.position_data();
  const Real* v = sim.velocity_data();
  const Real z0 = x[2];
  sim.step(10);
  EXPECT_EQ(sim.position_data(), x);  // the same memory, now holding the new state
  EXPECT_EQ(sim.step_count(), 10);
  EXPECT_DOUBLE_EQ(sim.time(), 0.01);
  EXPECT_LT(x[2], z0);
  EXPECT_EQ(x[2], sim.position(0).z());
  EXPECT_EQ(v[2], sim.velocity(0).z());
  const Real g = -sim.scene().gravity.z();
  // Free fall is exact under the default integrator: z = z0 - g t^2 / 2, v = -g t.
  EXPECT_NEAR(v[2], -g * 0.01, 1e-12 * g);
  EXPECT_NEAR(x[2], z0 - 0.5 * g * 0.01 * 0.01, 1e-12 * z0);
  // Moving the Simulation keeps its storage.
  Simulation moved = std::move(sim);
  EXPECT_EQ(moved.position_data(), x);
  // The attitude views: a unit quaternion [w, x, y, z].
  const Real* q = moved.quaternion_data();
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1, 1e-15);
}

TEST(SimulationApi, ConstantForceAgainstGravityHoldsABodyStill) {
  Simulation sim = Simulation::from_json(kCoinInSpace);
  const Real m = sim.mass(0);
  sim.set_external_force(0, -m * sim.scene().gravity);
  const Vec3 x0 = sim.position(0);
  sim.step(500);
  EXPECT_LT((sim.position(0) - x0).norm(), 1e-12);
  EXPECT_LT(sim.velocity(0).norm(), 1e-12);
}

TEST(SimulationApi, LinearDragReachesTheTerminalSpeed) {
  Simulation sim = Simulation::from_json(kCoinInSpace);
  const Real m = sim.mass(0), g = -sim.scene().gravity.z();
  const Real c = m / 0.05;  // time constant m / c = 0.05 s: 1 s is 20 of them
  for (int k = 0; k < 1000; ++k) {
    sim.set_external_force(0, -c * sim.velocity(0));
    sim.step();
  }
  const Real terminal = m * g / c;
  // The force held over a step lags the velocity by one step: the discrete fixed point is
  // v = -(g - c v / m) dt + v, i.e. exactly m g / c; e^-20 of the start is left.
  EXPECT_NEAR(-sim.velocity(0).z(), terminal, 1e-6 * terminal);
}

TEST(SimulationApi, ExternalTorqueSpinsAsTheInertiaSays) {
  Simulation sim = Simulation::from_json(kCoinInSpace);
  sim.set_external_force(0, -sim.mass(0) * sim.scene().gravity);
  const Vec3 torque(0, 0, 3.0);
  sim.set_external_torque(0, torque);
  sim.step(200);
  // About the symmetry axis (z, the coin's axis) the spin grows as N t / I_zz.
  const Real izz = sim.inertia_world(0)(2, 2);
  EXPECT_NEAR(sim.angular_velocity(0).z(), torque.z() * 0.2 / izz, 1e-9 * torque.z() * 0.2 / izz);
}

TEST(SimulationApi, FrictionHoldsAPushBelowMuMgAndYieldsAbove) {
  for (const Real share : {0.2, 0.5}) {
    SCOPED_TRACE(share);
    Simulation sim = Simulation::from_json(box_on_floor(0.3));
    const Real m = sim.mass(0), g = -sim.scene().gravity.z();
    sim.step(50);  // settle
    const Vec3 x0 = sim.position(0);
    sim.set_external_force(0, Vec3(share * m * g, 0, 0));
    sim.step(100);
    const Real t = 0.1;
    if (share < 0.3) {
      // Static friction takes the whole push.
      EXPECT_LT((sim.position(0) - x0).norm(), 1e-9);
    } else {
      // Sliding: a = (F - mu m g) / m, from rest at the push.
      const Real a = (share - 0.3) * g;
      EXPECT_NEAR(sim.velocity(0).x(), a * t, 1e-6 * a * t);
      EXPECT_NEAR(sim.position(0).x() - x0.x(), 0.5 * a * t * t, 1e-3 * 0.5 * a * t * t);
    }
    // The floor carries the weight: the patches' normal forces add up to m g.
    Real fn = 0;
    for (const Contact& c : sim.contacts()) fn += c.normal_force;
    EXPECT_NEAR(fn, m * g, 1e-6 * m * g);
  }
}

TEST(SimulationApi, SameHashAsTemRun) {
  const std::string scene = kScenes + "small_pile.json";
  Simulation sim = Simulation::load(scene);
  sim.step(sim.total_steps());
  const std::string dir = temp_path("api_hash");
  const auto run = run_tem("run '" + scene + "' --out '" + dir + "' --hash");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.out, "hash: " + sim.state_hash_hex())) << run.out;
  std::filesystem::remove_all(dir);
}

TEST(SimulationApi, RecordingWritesWhatTemRunWrites) {
  const std::string scene = kScenes + "drop_box.json";
  const std::string mine = temp_path("api_record"), theirs = temp_path("api_record_cli");
  Simulation sim = Simulation::load(scene);
  sim.record(mine, /*contacts=*/true);
  sim.step(sim.total_steps());
  sim.finish_recording();
  const auto run = run_tem("run '" + scene + "' --out '" + theirs + "' --contacts");
  ASSERT_EQ(run.status, 0) << run.err;
  for (const char* file : {"bodies.csv", "energy.csv", "contacts.csv", "scene.json"})
    EXPECT_EQ(testing_support::slurp(mine + "/" + file), testing_support::slurp(theirs + "/" + file))
        << file;
  std::filesystem::remove_all(mine);
  std::filesystem::remove_all(theirs);
}

TEST(SimulationApi, CheckpointResumesBitForBit) {
  const std::string scene = kScenes + "small_pile.json";
  Simulation whole = Simulation::load(scene);
  whole.step(whole.total_steps());
  Simulation first = Simulation::load(scene);
  first.step(137);
  const std::string file = temp_path("api_checkpoint.bin");
  first.write_checkpoint(file);
  Simulation second = Simulation::resume(scene, file);
  EXPECT_EQ(second.step_count(), 137);
  second.step(second.total_steps() - 137);
  EXPECT_EQ(second.state_hash(), whole.state_hash());
  std::filesystem::remove(file);
}

TEST(SimulationApi, BadScenesThrowWithPathAndReason) {
  try {
    Simulation::from_json(R"({"time_step": 1e-3, "bodies": [{"name": "b",
      "shape": {"type": "box", "size": [0.2, -0.2, 0.1]}}]})", "mine.json");
    FAIL() << "a negative size was accepted";
  } catch (const SceneLoadError& e) {
    EXPECT_TRUE(contains(e.what(), "mine.json: bodies[0].shape.size")) << e.what();
  }
  SceneDef scene;
  scene.source = "built in code";
  scene.time_step = std::nan("");
  EXPECT_THROW(Simulation::from_scene(scene), SceneLoadError);
  EXPECT_THROW(Simulation::load(kScenes + "no_such_scene.json"), SceneLoadError);
  Simulation sim = Simulation::from_json(kCoinInSpace);
  EXPECT_THROW(sim.position(1), std::out_of_range);
  EXPECT_THROW(Simulation::resume(kScenes + "small_pile.json", "/nonexistent/checkpoint.bin"),
               std::runtime_error);
}

TEST(SimulationApi, SceneBuiltInCode) {
  SceneDef scene;
  scene.time_step = 1e-3;
  BodyDef body;
  body.name = "cube";
  body.shape.type = ShapeType::box;
  body.shape.size = Vec3(1, 1, 1);
  scene.bodies.push_back(body);
  Simulation sim = Simulation::from_scene(scene);
  ASSERT_EQ(sim.body_count(), 1);
  EXPECT_EQ(sim.body_name(0), "cube");
  EXPECT_EQ(sim.body_index("cube"), 0);
  EXPECT_NEAR(sim.volume(0), 1, 1e-14);
  EXPECT_NEAR(sim.inertia_body(0)(0, 0), sim.mass(0) / 6, 1e-14);
}

}  // namespace test_simulation_api
}  // namespace tem
