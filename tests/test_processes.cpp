// Granular processes (docs/processes.md): prescribed motion, removal at a time, inlets, outlets
// and sensors, checked against physics (a belt's friction ramp, a plate's weight, free fall
// after a gate opens, mass balance) and against the project's own promises (bit-identical
// resume and thread counts with bodies coming and going).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/belt_energy.hpp"
#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_processes {

using testing_support::lines;
using testing_support::run_tem;
using testing_support::slurp;
using testing_support::temp_path;

constexpr Real kG = earth_gravity_cgs;

std::string scene_path(const std::string& name) {
  return std::string(TEM_SOURCE_DIR) + "/tests/scenes/processes/" + name;
}

std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  std::string f;
  while (std::getline(in, f, ',')) out.push_back(f);
  return out;
}

// Steps to `until`, checking that the block's speed along x grows at mu g (each sample within
// 1e-6 of v) until it reaches the belt's v, within one step of v / (mu g).
void speeds_up_to_the_belt(Simulation& sim, int block, Real mu, Real v, Real until) {
  const Real t_stick = v / (mu * kG);
  Real reached = -1;
  while (sim.time() < until - 1e-12) {
    sim.step();
    const Real vx = sim.velocity(block).x();
    if (sim.time() < t_stick - 2 * sim.time_step()) {
      EXPECT_NEAR(vx, mu * kG * sim.time(), 1e-6 * v) << "t = " << sim.time();
    }
    if (reached < 0 && vx > v * (1 - 1e-9)) reached = sim.time();
  }
  EXPECT_NEAR(reached, t_stick, 2 * sim.time_step());
}

// A block on a belt moving at v: friction (the pair's mu = 0.25, not either material's own)
// accelerates it at mu g until it moves with the belt, at t = v / (mu g), and then it sticks.
TEST(Processes, BlockOnABeltReachesTheBeltSpeedAfterVOverMuG) {
  Simulation sim = Simulation::load(scene_path("belt.json"));
  const int block = sim.body_index("block"), belt = sim.body_index("belt");
  const Real mu = 0.25, v = 20;
  speeds_up_to_the_belt(sim, block, mu, v, 0.15);
  EXPECT_NEAR(sim.velocity(block).x(), v, 1e-9 * v);  // sticks: moves with the belt
  // The belt moved as told, pushed by nothing: 20 cm/s for 0.15 s.
  EXPECT_NEAR(sim.position(belt).x(), v * 0.15, 1e-12);
  EXPECT_NEAR((sim.velocity(belt) - Vec3(v, 0, 0)).norm(), 0, 1e-12 * v);
  // The belt's work is the block's kinetic energy plus what sliding friction dissipated:
  // mu m g (v t* - v t*/2) = 1/2 m v^2 twice over (the classic half-lost-to-heat result).
  const Real m = sim.mass(block);
  EXPECT_NEAR(sim.energies().driven_work, m * v * v, 2e-3 * m * v * v);
}

// energy.csv's last column is the driven work, as the API has it: the belt's work on the block
// reaches m v^2 by the end, and total - driven_work never rises from row to row.
TEST(Processes, EnergyCsvCarriesTheDrivenWork) {
  const std::string dir = temp_path("belt_energy");
  const auto run = run_tem("run '" + scene_path("belt.json") + "' --out '" + dir + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> rows = lines(slurp(dir + "/energy.csv"));
  ASSERT_EQ(rows.front(), "time,kinetic,potential,total,contacts,max_depth,driven_work");
  Simulation sim = Simulation::load(scene_path("belt.json"));
  sim.step(sim.total_steps());
  const Real m = sim.mass(sim.body_index("block")), v = 20;
  Real previous = std::numeric_limits<Real>::infinity();
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto f = fields(rows[i]);
    ASSERT_EQ(f.size(), 7u);
    const Real lost = std::stod(f[3]) - std::stod(f[6]);
    EXPECT_LE(lost, previous + 1e-9 * m * v * v) << rows[i];
    previous = lost;
  }
  const auto last = fields(rows.back());
  EXPECT_EQ(std::stod(last[6]), sim.energies().driven_work);  // the same number, printed exactly
  EXPECT_NEAR(std::stod(last[6]), m * v * v, 2e-3 * m * v * v);
  std::filesystem::remove_all(dir);
}

// A block resting on a fixed plate: the plate's force sensor reads the block's weight, and the
// torque about the world origin is that of the weight at the block's place.
TEST(Processes, PlateForceSensorReadsTheWeightOfWhatRestsOnIt) {
  const std::string dir = temp_path("plate_sensor");
  const auto run = run_tem("run '" + scene_path("plate_sensor.json") + "' --out '" + dir + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> rows = lines(slurp(dir + "/sensors.csv"));
  ASSERT_EQ(rows.front(), "time,sensor,count,mass,fx,fy,fz,tx,ty,tz");
  const Real m = 2.0, weight = m * kG;  // a 1 cm cube of density 2
  int checked = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto f = fields(rows[i]);
    ASSERT_EQ(f.size(), 10u);
    EXPECT_EQ(f[1], "plate");
    if (std::stod(f[0]) < 0.2) continue;  // the block dropped 0.05 cm and settled
    EXPECT_NEAR(std::stod(f[4]), 0, 1e-9 * weight);
    EXPECT_NEAR(std::stod(f[5]), 0, 1e-9 * weight);
    EXPECT_NEAR(std::stod(f[6]), -weight, 1e-9 * weight);
    // Torque about the origin of the weight acting at (1, 2, .): (2, -1, 0) x (0, 0, -W).
    EXPECT_NEAR(std::stod(f[7]), -2 * weight, 1e-6 * weight);
    EXPECT_NEAR(std::stod(f[8]), weight, 1e-6 * weight);
    ++checked;
  }
  EXPECT_GE(checked, 6);
  std::filesystem::remove_all(dir);
}

// A force sensor on an inlet's copies by prefix ("feed_*"): each copy counts from the step it
// is placed, and once the three cubes rest on the floor the sensor reads their weight, once.
TEST(Processes, ForceSensorByPrefixReadsTheWeightOfInletCopies) {
  const std::string dir = temp_path("inlet_sensor");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/scene.json") << R"({
    "time_step": 1e-3, "duration": 0.6,
    "container": {"min": [-3, -3, 0], "max": [3, 3, 6]},
    "inlets": [{"name": "feed", "region": {"min": [-2, -2, 0.1], "max": [2, 2, 1.9]},
                "rate": 50, "count": 3, "seed": 4,
                "body": {"shape": {"type": "box", "size": [1, 1, 1]}, "density": 2}}],
    "sensors": [{"name": "copies", "type": "force", "bodies": ["feed_*", "feed_1"]}],
    "output": {"interval": 0.05}
  })";
  const auto run = run_tem("run '" + dir + "/scene.json' --out '" + dir + "/out'");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::vector<std::string> rows = lines(slurp(dir + "/out/sensors.csv"));
  const Real m = 2.0, weight = m * kG;
  int checked = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto f = fields(rows[i]);
    ASSERT_EQ(f.size(), 10u);
    const Real t = std::stod(f[0]);
    if (t < 0.01) {
      EXPECT_LE(std::stoi(f[2]), 1) << rows[i];  // one copy placed per 0.02 s
    }
    if (t < 0.45) continue;                                 // the third lands by t = 0.04 + 0.37
    EXPECT_EQ(f[2], "3") << rows[i];
    EXPECT_NEAR(std::stod(f[3]), 3 * m, 1e-12);
    EXPECT_NEAR(std::stod(f[4]), 0, 1e-6 * weight);
    EXPECT_NEAR(std::stod(f[5]), 0, 1e-6 * weight);
    EXPECT_NEAR(std::stod(f[6]), 3 * weight, 1e-6 * weight);
    ++checked;
  }
  EXPECT_GE(checked, 3);
  std::filesystem::remove_all(dir);
}

// Inlets that would deliver less than they say are told of when the scene is loaded (tem check
// and tem run print the same warnings), and the run reports what each placed of what it owed:
// a region buried in a fixed body, a start after the run's end, a rate too slow for the count,
// a region inside an outlet.
TEST(Processes, InletsThatCannotDeliverAreToldOf) {
  const std::string copy = R"("body": {"shape": {"type": "box", "size": [0.5, 0.5, 0.5]}}})";
  Simulation sim = Simulation::from_json(R"({"time_step": 1e-3, "duration": 0.2,
    "container": {"min": [-5, -5, 0], "max": [5, 5, 10]},
    "bodies": [{"name": "rock", "shape": {"type": "box", "size": [4, 4, 4]},
                "position": [0, 0, 5], "fixed": true}],
    "outlets": [{"name": "bin", "region": {"min": [2.5, -5, 0.5], "max": [5, -2.5, 3]}}],
    "inlets": [
      {"name": "buried", "region": {"min": [-1.5, -1.5, 3.5], "max": [1.5, 1.5, 6.5]},
       "rate": 100, "count": 5, )" + copy + R"(,
      {"name": "late", "region": {"min": [3, 3, 1], "max": [4.5, 4.5, 2]}, "start": 0.5,
       "rate": 100, "count": 5, )" + copy + R"(,
      {"name": "slow", "region": {"min": [-4.5, -4.5, 1], "max": [-3, -3, 2]},
       "rate": 10, "count": 5, )" + copy + R"(,
      {"name": "drain", "region": {"min": [3, -4.5, 1], "max": [4.5, -3, 2]},
       "rate": 100, "count": 5, )" + copy + R"(,
      {"name": "fine", "region": {"min": [-4.5, 3, 1], "max": [-3, 4.5, 2]},
       "rate": 100, "count": 5, )" + copy + "]}");
  const std::vector<std::string>& w = sim.warnings();
  ASSERT_EQ(w.size(), 4u);
  const auto has = [](const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
  };
  EXPECT_TRUE(has(w[0], "inlets[0].region: none of 216 places") && has(w[0], "fixed 'rock'")) << w[0];
  EXPECT_TRUE(has(w[1], "inlets[1].start: 0.5 s is after the run's end")) << w[1];
  EXPECT_TRUE(has(w[2], "inlets[2]: only 3 of its 5 copies fall due")) << w[2];
  EXPECT_TRUE(has(w[3], "inlets[3].region: every copy is inside outlets[0].region")) << w[3];
  sim.step(200);
  const auto d = sim.inlet_deliveries();
  ASSERT_EQ(d.size(), 5u);
  const std::vector<std::array<long long, 3>> expected = {
      {0, 5, 5}, {0, 0, 5}, {3, 3, 5}, {5, 5, 5}, {5, 5, 5}};  // placed, due, count
  for (size_t j = 0; j < d.size(); ++j)
    EXPECT_EQ((std::array<long long, 3>{d[j].placed, d[j].due, d[j].count}), expected[j]) << d[j].name;
  // What drains leaves at once: of the 13 copies placed, the 5 of "drain" are gone.
  EXPECT_EQ(sim.body_count(), 1 + 3 + 5);
}

// Inlets whose bodies do not fit in memory: the load fails with how many bodies, how much memory
// and which keys, not a bare std::bad_alloc. The memory is limited with `ulimit -v`, which
// AddressSanitizer's own reservations of address space do not survive.
TEST(Processes, InletsThatDoNotFitInMemorySaySo) {
#ifdef __SANITIZE_ADDRESS__
  GTEST_SKIP() << "AddressSanitizer needs more address space than the limit leaves";
#endif
  const std::string dir = temp_path("inlet_memory");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/scene.json") << R"({"time_step": 1e-3, "duration": 0.01,
    "inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [4, 4, 4]},
                "rate": 100, "count": 10000000,
                "body": {"shape": {"type": "box", "size": [1, 1, 1]}}}]})";
  const std::string command = "ulimit -v 1000000; '" + std::string(TEM_BINARY) + "' run '" + dir +
                              "/scene.json' --out '" + dir + "/out' 2>'" + dir + "/err'";
  const int status = std::system(command.c_str());
  EXPECT_NE(status, 0);
  const std::string err = slurp(dir + "/err");
  EXPECT_NE(err.find("must hold up to 10000000 bodies at once (0 at the start, inlets[0].count "
                     "10000000)"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("GB for their records alone"), std::string::npos) << err;
  EXPECT_EQ(err.find("bad_alloc"), std::string::npos) << err;
  std::filesystem::remove_all(dir);
}

// A prescribed motion too fast for a double to hold the energy it gives (amplitude 1e200 cm at
// 25 Hz) is refused naming the motion, not run until the grain it hits stops being finite.
TEST(Processes, MotionBeyondTheRangeOfADoubleIsRefused) {
  const auto scene = [](const std::string& amplitude) {
    return R"({"time_step": 1e-3, "duration": 0.01,
      "bodies": [{"name": "plate", "shape": {"type": "box", "size": [4, 4, 1]},
                  "position": [0, 0, 0], "motion": {"oscillation": {"amplitude": [0, 0, )" +
           amplitude + R"(], "frequency": 25}}},
                 {"name": "grain", "shape": {"type": "box", "size": [1, 1, 1]},
                  "position": [0, 0, 1.1]}]})";
  };
  try {
    Simulation::from_json(scene("1e200"));
    ADD_FAILURE() << "accepted";
  } catch (const SceneLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies[0].motion: moves at up to 1.5708e+202"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(Simulation::from_json(scene("0.1")));
}

// A gate removed at a time: the grains resting on it fall freely from that moment.
TEST(Processes, BoxOnAGateFallsFreelyOnceTheGateIsRemoved) {
  const std::string scene = R"({
    "time_step": 1e-3, "duration": 0.3,
    "bodies": [
      {"name": "gate", "shape": {"type": "box", "size": [4, 4, 0.2]}, "position": [0, 0, -0.1],
       "fixed": true, "removed_at": 0.1},
      {"name": "box", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0.5]}
    ],
    "walls": [{"point": [0, 0, -100], "normal": [0, 0, 1], "removed_at": 0.2}]
  })";
  Simulation sim = Simulation::from_json(scene);
  ASSERT_EQ(sim.body_count(), 2);
  sim.step(100);  // to t = 0.1: resting, then the gate goes
  EXPECT_EQ(sim.body_count(), 1);
  EXPECT_EQ(sim.body_index("gate"), -1);
  const int box = sim.body_index("box");
  const Real z0 = sim.position(box).z();
  EXPECT_NEAR(z0, 0.5, 1e-4);
  EXPECT_NEAR(sim.velocity(box).norm(), 0, 1e-6);
  sim.step(100);
  const Real t = 0.1;
  EXPECT_NEAR(sim.position(box).z(), z0 - kG * t * t / 2, 1e-9 * kG * t * t);
  EXPECT_NEAR(sim.velocity(box).z(), -kG * t, 1e-9 * kG * t);
}

// Prescribed motion is a closed form of time: a turning drum is at exactly omega t however
// long it has turned, and a shaker's displacement is A sin(2 pi f t).
TEST(Processes, PrescribedMotionFollowsItsClosedForm) {
  const std::string scene = R"({
    "time_step": 1e-3, "duration": 1, "gravity": [0, 0, 0],
    "bodies": [
      {"name": "drum", "shape": {"type": "box", "size": [1, 2, 3]}, "position": [1, 0, 0],
       "motion": {"angular_velocity": [0, 0, 2], "center": [0, 0, 0], "start": 0.1, "end": 0.6}},
      {"name": "shaker", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [5, 5, 5],
       "motion": {"oscillation": {"amplitude": [0, 0, 0.2], "frequency": 5}}}
    ]
  })";
  Simulation sim = Simulation::from_json(scene);
  const int drum = sim.body_index("drum"), shaker = sim.body_index("shaker");
  for (int k = 1; k <= 1000; ++k) {
    sim.step();
    const Real t = sim.time();
    const Real angle = 2 * (std::clamp(t, 0.1, 0.6) - 0.1);
    EXPECT_NEAR(sim.position(drum).x(), std::cos(angle), 1e-12);
    EXPECT_NEAR(sim.position(drum).y(), std::sin(angle), 1e-12);
    EXPECT_NEAR(sim.position(shaker).z(), 5 + 0.2 * std::sin(2 * std::numbers::pi * 5 * t),
                1e-12);
  }
  // Standing still after `end`, at the angle reached then.
  EXPECT_NEAR(sim.position(drum).x(), std::cos(1.0), 1e-12);
  EXPECT_EQ(sim.velocity(drum), Vec3::Zero());
}

struct RunFiles {
  std::string bodies, energy, removed, sensors, hash;
};

RunFiles run_files(const std::string& args, const std::string& dir) {
  const auto run = run_tem(args + " --out '" + dir + "' --hash");
  EXPECT_EQ(run.status, 0) << run.err;
  const auto out = lines(run.out);
  return {slurp(dir + "/bodies.csv"), slurp(dir + "/energy.csv"), slurp(dir + "/removed.csv"),
          slurp(dir + "/sensors.csv"), out.empty() ? "" : out.back()};
}

// Grains pour in through an inlet onto a gate, the gate opens, they fall through a plane
// sensor into an outlet. At every output time every grain inserted is present or in
// removed.csv, never both, and the plane counted each one that fell through.
TEST(Processes, MassBalanceOfAnInletAGateAndAnOutlet) {
  const std::string dir = temp_path("gate_outlet");
  const RunFiles r = run_files("run '" + scene_path("gate_outlet.json") + "'", dir);
  std::map<std::string, std::set<std::string>> present;  // time -> bodies
  for (const std::string& row : lines(r.bodies)) {
    const auto f = fields(row);
    if (f[0] != "time") present[f[0]].insert(f[1]);
  }
  std::vector<std::pair<Real, std::string>> removed;
  Real removed_mass = 0;
  for (const std::string& row : lines(r.removed)) {
    const auto f = fields(row);
    if (f[0] == "time") continue;
    removed.push_back({std::stod(f[0]), f[1]});
    if (f[1] != "gate") removed_mass += std::stod(f[8]);
  }
  ASSERT_FALSE(present.empty());
  long long inserted_before = 0;
  for (const auto& [time, names] : present) {
    const Real t = std::stod(time);
    std::set<std::string> gone;
    for (const auto& [when, name] : removed)
      if (when <= t + 1e-12) gone.insert(name);
    long long inserted = 0;  // copies are numbered in the order they are placed
    for (const std::set<std::string>* s : {&names, static_cast<const std::set<std::string>*>(&gone)})
      for (const std::string& n : *s)
        if (n.rfind("grain_", 0) == 0) inserted = std::max(inserted, std::stoll(n.substr(6)) + 1);
    EXPECT_GE(inserted, inserted_before);
    inserted_before = inserted;
    long long grains_present = 0, grains_gone = 0;
    for (const std::string& n : names) {
      grains_present += n.rfind("grain_", 0) == 0;
      EXPECT_EQ(gone.count(n), 0u) << n << " both present and removed at " << time;
    }
    for (const std::string& n : gone) grains_gone += n.rfind("grain_", 0) == 0;
    EXPECT_EQ(inserted, grains_present + grains_gone) << "t = " << time;
    EXPECT_EQ(names.count("gate") + gone.count("gate"), 1u);
  }
  // All 60 came in (400 per second from t = 0), all left through the outlet once the gate went.
  EXPECT_EQ(inserted_before, 60);
  EXPECT_EQ(removed.size(), 61u);  // the grains and the gate
  // The plane under the gate counted them all, with their mass; the region above is empty.
  const auto sensor_rows = lines(r.sensors);
  std::map<std::string, std::vector<std::string>> last;
  for (const std::string& row : sensor_rows) last[fields(row)[1]] = fields(row);
  EXPECT_EQ(last["through"][2], "60");
  EXPECT_NEAR(std::stod(last["through"][3]), removed_mass, 1e-9 * removed_mass);
  EXPECT_EQ(last["above"][2], "0");
  // Copies drawn with sizes in [0.8, 1.2]: masses between 0.8^3 and 1.2^3 of 2.5 * 0.125 g.
  for (const std::string& row : lines(r.removed)) {
    const auto f = fields(row);
    if (f[1].rfind("grain_", 0) != 0) continue;
    EXPECT_GE(std::stod(f[8]), 0.8 * 0.8 * 0.8 * 0.3125 * (1 - 1e-12));
    EXPECT_LE(std::stod(f[8]), 1.2 * 1.2 * 1.2 * 0.3125 * (1 + 1e-12));
  }
  // While the gate held them, it carried their weight (sensor "gate", before t = 0.15).
  for (const std::string& row : sensor_rows) {
    const auto f = fields(row);
    if (f[1] == "gate" && std::stod(f[0]) > 0.14 && std::stod(f[0]) < 0.15) {
      Real resting = 0;
      for (const std::string& name : present[f[0]])
        if (name.rfind("grain_", 0) == 0) resting += 1;
      EXPECT_LT(std::stod(f[6]), 0);  // pushed down
      EXPECT_GT(resting, 0);
    }
  }
  std::filesystem::remove_all(dir);
}

// Stopped and resumed (here: run to 0.2 s, then the duration raised to 0.4 s and resumed),
// a run with bodies coming and going gives the same files, byte for byte, as one run; and the
// thread count changes nothing.
TEST(Processes, ResumeAndThreadsGiveTheSameBytesWhileBodiesComeAndGo) {
  const std::string full_dir = temp_path("gate_full"), part_dir = temp_path("gate_part");
  const RunFiles full = run_files("run '" + scene_path("gate_outlet.json") + "'", full_dir);
  // The first half: the same scene to 0.2 s.
  std::string text = slurp(scene_path("gate_outlet.json"));
  const std::string half_scene = temp_path("gate_half") + ".json";
  const std::string from = "\"duration\": 0.4";
  ASSERT_NE(text.find(from), std::string::npos);
  {
    std::ofstream(half_scene) << std::string(text).replace(text.find(from), from.size(),
                                                           "\"duration\": 0.2");
  }
  run_files("run '" + half_scene + "'", part_dir);
  const RunFiles resumed =
      run_files("run '" + scene_path("gate_outlet.json") + "' --resume", part_dir);
  EXPECT_EQ(resumed.hash, full.hash);
  EXPECT_EQ(resumed.bodies, full.bodies);
  EXPECT_EQ(resumed.energy, full.energy);
  EXPECT_EQ(resumed.removed, full.removed);
  EXPECT_EQ(resumed.sensors, full.sensors);
  const std::string threads_dir = temp_path("gate_threads");
  const RunFiles two =
      run_files("run '" + scene_path("gate_outlet.json") + "' --threads 2", threads_dir);
  EXPECT_EQ(two.hash, full.hash);
  EXPECT_EQ(two.bodies, full.bodies);
  for (const std::string& d : {full_dir, part_dir, threads_dir}) std::filesystem::remove_all(d);
  std::filesystem::remove(half_scene);
}

// The same through the API: a checkpoint taken mid-run resumes bit for bit, the views follow
// the live bodies, and energy less the driven work never rises on a belt.
TEST(Processes, ApiCheckpointResumesThePopulation) {
  Simulation a = Simulation::load(scene_path("gate_outlet.json"));
  a.step(250);  // grains on the gate, some inserted late
  const std::string checkpoint = temp_path("gate_api") + ".bin";
  a.write_checkpoint(checkpoint);
  Simulation b = Simulation::resume(scene_path("gate_outlet.json"), checkpoint);
  EXPECT_EQ(b.body_count(), a.body_count());
  for (int i = 0; i < a.body_count(); ++i) EXPECT_EQ(b.body_name(i), a.body_name(i));
  a.step(300);
  b.step(300);
  EXPECT_EQ(a.state_hash_hex(), b.state_hash_hex());
  EXPECT_EQ(a.body_count(), b.body_count());
  std::filesystem::remove(checkpoint);
}

TEST(Processes, EnergyLessDrivenWorkNeverRisesOnABelt) {
  Simulation sim = Simulation::load(scene_path("belt.json"));
  testing_support::expect_energy_less_driven_work_never_rises(sim, 300);
}

// `fill` judges bodies that were there first by their blocks: it fills the inside of a cup
// (a compound of five plates) whose bounding sphere holds the whole region.
TEST(Processes, FillPlacesCopiesInsideAHollowBody) {
  const std::string scene = R"({
    "time_step": 1e-4, "duration": 0.01,
    "bodies": [{"name": "cup", "fixed": true, "position": [0, 0, 0],
      "shape": {"type": "compound", "blocks": [
        {"type": "box", "size": [6, 6, 0.5], "position": [0, 0, -0.25]},
        {"type": "box", "size": [0.5, 6, 6], "position": [-3.25, 0, 3]},
        {"type": "box", "size": [0.5, 6, 6], "position": [3.25, 0, 3]},
        {"type": "box", "size": [7, 0.5, 6], "position": [0, -3.25, 3]},
        {"type": "box", "size": [7, 0.5, 6], "position": [0, 3.25, 3]}]}}],
    "fill": [{"name": "grain", "count": 40, "seed": 2,
              "region": {"min": [-3, -3, 0], "max": [3, 3, 6]},
              "body": {"shape": {"type": "box", "size": [0.6, 0.6, 0.6]}}}]
  })";
  Simulation sim = Simulation::from_json(scene);
  ASSERT_EQ(sim.body_count(), 41);
  for (int i = 1; i < 41; ++i) {
    const Vec3 x = sim.position(i);
    EXPECT_LT(std::abs(x.x()), 3);
    EXPECT_LT(std::abs(x.y()), 3);
    EXPECT_GT(x.z(), 0);
  }
  // Nothing touches at the start: no warning of overlap, no patch deeper than zero.
  EXPECT_TRUE(sim.warnings().empty()) << sim.warnings().front();
  sim.step();
  for (const Contact& c : sim.contacts()) EXPECT_LE(c.depth, 0);
}

// An inlet region that no copy can fit in is refused with its JSON path.
TEST(Processes, InletRegionTooSmallForOneCopyIsRefused) {
  const std::string scene = R"({
    "inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [0.2, 2, 2]}, "rate": 10,
                "count": 5, "body": {"shape": {"type": "box", "size": [0.5, 0.5, 0.5]}}}]
  })";
  try {
    Simulation::from_json(scene, "feed.json");
    FAIL() << "accepted";
  } catch (const SceneLoadError& e) {
    EXPECT_NE(std::string(e.what()).find("feed.json: inlets[0].region: is too small for one copy"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace test_processes
}  // namespace tem

namespace tem {
namespace test_processes {

// Copies placed by an inlet inside a cup (whose bounding sphere holds the whole inlet) never
// start overlapping anything: grains that pop apart at insertion, as DEM users know them, would
// show as patches of positive depth where the copies were placed.
TEST(Processes, InletCopiesInsideACupStartClearOfEverything) {
  const std::string scene = R"({
    "time_step": 5e-4, "duration": 0.3,
    "contact": {"tolerance": 1e-3, "max_sweeps": 20},
    "bodies": [{"name": "cup", "fixed": true, "position": [0, 0, 0],
      "shape": {"type": "compound", "blocks": [
        {"type": "box", "size": [4, 4, 0.5], "position": [0, 0, -0.25]},
        {"type": "box", "size": [0.5, 4, 4], "position": [-2.25, 0, 2]},
        {"type": "box", "size": [0.5, 4, 4], "position": [2.25, 0, 2]},
        {"type": "box", "size": [5, 0.5, 4], "position": [0, -2.25, 2]},
        {"type": "box", "size": [5, 0.5, 4], "position": [0, 2.25, 2]}]}}],
    "inlets": [{"name": "grain", "region": {"min": [-2, -2, 0], "max": [2, 2, 2]}, "rate": 3000,
                "count": 100, "seed": 9,
                "body": {"shape": {"type": "prism", "sides": 6, "radius": 0.25, "height": 0.2},
                         "density": 2.5, "scale": {"min": 0.7, "max": 1.3}}}]
  })";
  Simulation sim = Simulation::from_json(scene);
  int most = 0;
  std::set<std::string> fresh;  // placed at the end of the last step
  int checked = 0;
  for (int k = 0; k < 300; ++k) {
    std::set<std::string> before;
    for (int i = 0; i < sim.body_count(); ++i) before.insert(sim.body_name(i));
    sim.step();
    // The patches of this step were found where the last one left the bodies: the new copies'
    // are their contacts as placed, all still a gap apart (depth < 0) or touching at most.
    for (const Contact& c : sim.contacts()) {
      const bool a = c.body_a >= 0 && fresh.count(sim.body_name(c.body_a));
      const bool b = c.body_b >= 0 && fresh.count(sim.body_name(c.body_b));
      if (!a && !b) continue;
      ++checked;
      EXPECT_LE(c.depth, 0) << "step " << k;
    }
    fresh.clear();
    for (int i = 0; i < sim.body_count(); ++i)
      if (!before.count(sim.body_name(i))) fresh.insert(sim.body_name(i));
    most = std::max(most, sim.body_count() - 1);
    for (int i = 1; i < sim.body_count(); ++i) {
      const Vec3 x = sim.position(i);
      ASSERT_LT(std::abs(x.x()), 2) << sim.body_name(i);
      ASSERT_LT(std::abs(x.y()), 2) << sim.body_name(i);
      ASSERT_GT(x.z(), 0) << sim.body_name(i);
    }
  }
  // Most copies are placed with a gap wider than the contact margin (their bounding sphere is
  // clear, and a prism fills little of it); some land within reach of another at once.
  EXPECT_GT(checked, 0);
  EXPECT_EQ(most, 100);  // every copy found room, late or not
}

// `fill` takes the same size factors: each copy's mass within min^3 and max^3 of the
// template's, and not all alike.
TEST(Processes, FillDrawsASizeFactorPerCopy) {
  const std::string scene = R"({
    "container": {"min": [0, 0, 0], "max": [6, 6, 6]},
    "fill": [{"name": "grain", "count": 50, "region": {"min": [0, 0, 0], "max": [6, 6, 6]},
              "body": {"shape": {"type": "box", "size": [0.5, 0.5, 0.5]}, "density": 2,
                       "scale": {"min": 0.5, "max": 1.5}}}]
  })";
  Simulation sim = Simulation::from_json(scene);
  ASSERT_EQ(sim.body_count(), 50);
  const Real m0 = 2 * 0.125;
  Real lightest = 1e9, heaviest = 0;
  for (int i = 0; i < 50; ++i) {
    const Real m = sim.mass(i);
    lightest = std::min(lightest, m);
    heaviest = std::max(heaviest, m);
    EXPECT_GE(m, 0.125 * m0 * (1 - 1e-12));
    EXPECT_LE(m, 3.375 * m0 * (1 + 1e-12));
    // A scaled cube's inertia is m s^2 / 6 with s its scaled edge: exact for the scaled shape.
    const Real edge = std::cbrt(m / 2);
    EXPECT_NEAR(sim.inertia_body(i)(0, 0), m * edge * edge / 6, 1e-12 * m);
  }
  EXPECT_GT(heaviest / lightest, 3);
}

}  // namespace test_processes
}  // namespace tem

namespace tem {
namespace test_processes {

// A conveyor belt that stays where it is while its surface slides (motion.surface_velocity):
// the block speeds up at mu g to the surface's speed, rides to the belt's end and falls off it.
TEST(Processes, SlidingSurfaceCarriesABlockToTheBeltsEndAndOff) {
  Simulation sim = Simulation::load(scene_path("surface_belt.json"));
  const int block = sim.body_index("block"), belt = sim.body_index("belt");
  const Real mu = 0.25, v = 20;
  const Vec3 belt_at = sim.position(belt);
  speeds_up_to_the_belt(sim, block, mu, v, 0.3);
  EXPECT_NEAR(sim.velocity(block).x(), v, 1e-9 * v);
  EXPECT_NEAR(sim.position(block).z(), 0.5, 1e-3);  // riding on top, not pushed into it
  // The belt's work: the block's kinetic energy and as much again lost to sliding.
  const Real m = sim.mass(block);
  EXPECT_NEAR(sim.energies().driven_work, m * v * v, 2e-3 * m * v * v);
  // Past the end (x = 5) it falls: after 0.8 s it is below the belt's top, beyond its end.
  sim.step(1000);
  EXPECT_GT(sim.position(block).x(), 5);
  EXPECT_LT(sim.position(block).z(), 0);
  EXPECT_EQ(sim.position(belt), belt_at);  // the belt itself never moved
}

}  // namespace test_processes
}  // namespace tem

namespace tem {
namespace test_processes {

// A turning drum (12 staves and both end caps in one body, 2 rad/s) with 64 grains: the force
// sensor's torque on the drum about its axis equals the bed's weight acting at its centre of
// mass, sum m g x. The bed's angular momentum about the axis changes little over the window
// (it only rises as the bed climbs the wall), so the two must agree to a small fraction: 0.47 %
// measured over 0.5-1 s, asked to 2 %.
TEST(Processes, DrumDriveTorqueBalancesTheBedsWeight) {
  const std::string dir = temp_path("small_drum");
  const auto run = run_tem("run '" + scene_path("small_drum.json") + "' --out '" + dir + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const Real m = 2.5 * 0.3 * 0.3 * 0.3;
  std::map<std::string, Real> weight_torque;  // time -> sum m g x of the grains
  std::map<std::string, int> grains;
  for (const std::string& row : lines(slurp(dir + "/bodies.csv"))) {
    const auto f = fields(row);
    if (f[0] == "time" || f[1] == "drum") continue;
    weight_torque[f[0]] += m * kG * std::stod(f[2]);
    ++grains[f[0]];
    // Every grain stays inside the drum (inner apothem 2, half length 0.6).
    EXPECT_LT(std::hypot(std::stod(f[2]), std::stod(f[4])), 2.0) << row;
    EXPECT_LT(std::abs(std::stod(f[3])), 0.6) << row;
  }
  Real sensor = 0, weight = 0;
  int rows = 0;
  for (const std::string& row : lines(slurp(dir + "/sensors.csv"))) {
    const auto f = fields(row);
    if (f[0] == "time" || std::stod(f[0]) < 0.5) continue;
    sensor += std::stod(f[8]);  // ty: the torque about the world origin, on the axis
    weight += weight_torque[f[0]];
    EXPECT_EQ(grains[f[0]], 64) << f[0];
    ++rows;
  }
  ASSERT_EQ(rows, 26);
  sensor /= rows;
  weight /= rows;
  EXPECT_LT(weight, 0);  // turning about +y, the bed rides up the -x side
  EXPECT_NEAR(sensor, weight, 0.02 * std::abs(weight));
  std::filesystem::remove_all(dir);
}

}  // namespace test_processes
}  // namespace tem
