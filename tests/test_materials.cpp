// Materials (docs/method.md "Materials"): each contact's friction, restitution and rolling
// resistance come from the materials of its two sides, by a contact.pairs entry or by the rule
// for pairs without one (smaller friction, smaller restitution, larger rolling resistance).
// Measured against closed forms: sliding decelerates at mu g, a drop rebounds at e times its
// impact speed, a rolling prism slows at the constant-torque rate, under SEMM (rows and blocks)
// and the penalty model; the energy never rises.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "forces/penalty/penalty.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_materials {

using testing_support::report;
using testing_support::simulate;

constexpr Real kG = earth_gravity_cgs;

MaterialDef material(const std::string& name, Real friction, Real restitution = 0,
                     Real rolling = 0) {
  MaterialDef m;
  m.name = name;
  m.path = "materials." + name;
  m.friction = friction;
  m.restitution = restitution;
  m.rolling_resistance = rolling;
  return m;
}

MaterialPairDef pair(const std::string& a, const std::string& b) {
  MaterialPairDef p;
  p.path = "contact.pairs[0]";
  p.first = a;
  p.second = b;
  return p;
}

// A 0.2 x 0.2 x 0.1 box (material "box") with its bottom face at z = lift.
BodyDef box(Real x, Real lift, const Vec3& velocity) {
  BodyDef b;
  b.name = "box";
  b.path = "bodies[0]";
  b.shape.type = ShapeType::box;
  b.shape.size = Vec3(0.2, 0.2, 0.1);
  b.position = Vec3(x, 0, 0.05 + lift);
  b.velocity = velocity;
  b.material = "box";
  return b;
}

// A fixed 60 x 4 x 0.1 plate (material "plate"), its top face at z = 0.
BodyDef plate() {
  BodyDef b;
  b.name = "plate";
  b.path = "bodies[1]";
  b.shape.type = ShapeType::box;
  b.shape.size = Vec3(60, 4, 0.1);
  b.position = Vec3(0, 0, -0.05);
  b.fixed = true;
  b.material = "plate";
  return b;
}

enum class Ground { plate, floor };

// The box launched at 100 cm/s along x on the plate (or the container's floor, material
// "plate"); its deceleration from its velocity at 0.05 s and 0.15 s (it stops after
// 100 / (mu g) > 0.2 s for mu <= 0.5). The scene's own contact.friction (0.9) is never the
// pair's.
struct Sliding {
  Real deceleration = 0;
  Real energy_rise = 0;
};

Sliding slide(SceneDef scene, Ground ground) {
  scene.contact.friction = 0.9;
  scene.bodies.insert(scene.bodies.begin(), box(-20, 0, Vec3(100, 0, 0)));
  if (ground == Ground::plate) {
    scene.bodies.push_back(plate());
  } else {
    ContainerDef c;
    c.min = Vec3(-40, -2, 0);
    c.max = Vec3(40, 2, 10);
    c.material = "plate";
    scene.container = c;
  }
  const Model model = build_model(scene);
  State state = initial_state(model);
  const Real dt = scene.time_step;
  const long long first = std::llround(0.05 / dt), last = std::llround(0.15 / dt);
  Real v_first = 0, v_last = 0;
  const auto watch = simulate(model, state, 0.15, [&](const State& s, const Workspace&) {
    if (s.step == first) v_first = s.bodies[0].v.x();
    if (s.step == last) v_last = s.bodies[0].v.x();
  });
  return {(v_first - v_last) / (static_cast<Real>(last - first) * dt), watch.largest_energy_rise};
}

SceneDef semm_scene() {
  SceneDef scene;
  scene.time_step = 1e-4;
  return scene;
}

// Energy scale of the box for "round-off": M g times 1 cm (M = 0.004 g).
constexpr Real kBoxEnergy = 0.004 * kG;

void expect_mu_g(const Sliding& s, Real mu, const std::string& label) {
  report(label + ": deceleration / (mu g)", s.deceleration / (mu * kG));
  EXPECT_NEAR(s.deceleration / (mu * kG), 1, 0.02) << label;
  EXPECT_LE(s.energy_rise, 1e-12 * kBoxEnergy) << label;
}

TEST(MaterialsFriction, PairEntryGivesTheSlidingDeceleration) {
  for (ContactSolver solver : {ContactSolver::rows, ContactSolver::blocks}) {
    for (Real mu : {0.2, 0.5}) {
      SceneDef scene = semm_scene();
      scene.contact.solver = solver;
      scene.materials = {material("box", 0.8), material("plate", 0.7)};
      MaterialPairDef p = pair("plate", "box");
      p.friction = mu;
      scene.contact.pairs = {p};
      const std::string label = std::string(solver == ContactSolver::rows ? "rows" : "blocks") +
                                " pair mu " + std::to_string(mu).substr(0, 3);
      expect_mu_g(slide(scene, Ground::plate), mu, label);
    }
  }
}

TEST(MaterialsFriction, SmallerFrictionRulesAPairWithoutEntry) {
  for (Real mu : {0.2, 0.5}) {
    SceneDef scene = semm_scene();
    scene.materials = {material("box", mu), material("plate", 0.8)};
    expect_mu_g(slide(scene, Ground::plate), mu, "min rule mu " + std::to_string(mu).substr(0, 3));
    // The same on the container's floor, whose material is the plate's.
    expect_mu_g(slide(scene, Ground::floor), mu,
                "floor min rule mu " + std::to_string(mu).substr(0, 3));
  }
  // The floor's own material the smaller one; and a pair entry for the floor.
  SceneDef scene = semm_scene();
  scene.materials = {material("box", 0.8), material("plate", 0.35)};
  expect_mu_g(slide(scene, Ground::floor), 0.35, "floor material mu 0.35");
  MaterialPairDef p = pair("box", "plate");
  p.friction = 0.15;
  scene.contact.pairs = {p};
  expect_mu_g(slide(scene, Ground::floor), 0.15, "floor pair mu 0.15");
}

// Dropped flat from 0.1 cm onto the plate, the box leaves it at e times the speed it hit it
// with, e the pair's (as Physics.BoxReboundsWithItsRestitution with the scene's).
Real rebound_ratio(const SceneDef& materials_scene) {
  SceneDef scene = materials_scene;
  scene.time_step = 1e-5;
  scene.bodies = {box(0, 0.1, Vec3::Zero()), plate()};
  const Model model = build_model(scene);
  State state = initial_state(model);
  // The impact speed is the fastest fall, the rebound the fastest rise after it. (Not from the
  // first patch: the plate's size gives a margin of contact before overlap that sees the box
  // from the start.)
  Real impact = 0, rebound = 0;
  simulate(model, state, 0.04, [&](const State& s, const Workspace&) {
    const Real vz = s.bodies[0].v.z();
    if (vz < impact) {
      impact = vz;
      rebound = vz;
    }
    rebound = std::max(rebound, vz);
  });
  EXPECT_NEAR(-impact, std::sqrt(2 * kG * 0.1), 0.01 * std::sqrt(2 * kG * 0.1));
  return rebound / -impact;
}

TEST(MaterialsRestitution, ReboundFollowsThePair) {
  {
    SceneDef scene;
    scene.contact.restitution = 0;  // the scene's, never the pair's
    scene.materials = {material("box", 0.3, 0.9), material("plate", 0.3, 0.9)};
    MaterialPairDef p = pair("box", "plate");
    p.restitution = 0.5;
    scene.contact.pairs = {p};
    const Real ratio = rebound_ratio(scene);
    report("pair e 0.5: speed ratio", ratio);
    EXPECT_NEAR(ratio, 0.5, 0.03);
  }
  {
    SceneDef scene;
    scene.contact.restitution = 0.2;
    scene.materials = {material("box", 0.3, 0.8), material("plate", 0.3, 0.9)};
    const Real ratio = rebound_ratio(scene);
    report("min rule e 0.8: speed ratio", ratio);
    EXPECT_NEAR(ratio, 0.8, 0.03);
  }
}

// A 64-sided prism (circumradius 1 cm, 1 cm long, axis y) rolling along x on the floor at
// 10 cm/s, spin v / r. With rolling resistance mu_r the torque mu_r R M g against the rolling
// (R the distance from the centre to the contact, the prism's radius to within 0.1%) slows it
// at a = mu_r g M R^2 / (I + M R^2) (I about its axis; rolling without slipping), 2/3 mu_r g
// for a cylinder. Without it the prism rolls on, slowed only by its edges' small landings.
struct Rolling {
  Real deceleration = 0;     // mean over [0.05 s, 0.15 s]
  Real travel = 0;           // in 1 s
  Real end_speed = 0;
  Real energy_rise = 0;      // largest over one step
  Real expected = 0;         // the constant-torque deceleration
  Real energy_scale = 0;     // M g 1 cm
};

Rolling roll(Real mu_r, ContactSolver solver, bool penalty = false) {
  const Real r = 1, v0 = 10;
  SceneDef scene;
  scene.time_step = 1e-4;
  scene.contact.solver = solver;
  if (penalty) {  // stiff (depth 3e-3 cm), critically damped
    scene.contact.model = ContactModel::penalty;
    scene.contact.stiffness = 1e6;
    scene.contact.tangential_stiffness = 2.0 / 7.0 * 1e6;
    scene.contact.damping = 2 * std::sqrt(3.1 * 1e6);
  }
  scene.materials = {material("prism", 0.8, 0, mu_r), material("floor", 0.8)};
  scene.walls.push_back({Vec3::Zero(), Vec3::UnitZ()});
  scene.walls.back().material = "floor";
  BodyDef prism;
  prism.name = "prism";
  prism.path = "bodies[0]";
  prism.shape.type = ShapeType::prism;
  prism.shape.sides = 64;
  prism.shape.radius = r;
  prism.shape.height = 1;
  prism.shape.axis = Axis::y;
  prism.material = "prism";
  const Real apothem = r * std::cos(3.14159265358979323846 / 64);
  prism.position = Vec3(0, 0, apothem);
  prism.velocity = Vec3(v0, 0, 0);
  prism.angular_velocity = Vec3(0, v0 / apothem, 0);
  scene.bodies.push_back(prism);
  // Stepped directly: Simulation::from_scene goes through the scene file's text, which does not
  // carry materials until the scene reader knows them.
  if (penalty) scene.time_step = penalty_time_step_limit(build_model(scene)) / 4;
  const Model model = build_model(scene);
  State state = initial_state(model);
  const Real mass = model.bodies[0].inertia.mass;
  const Real inertia = model.bodies[0].inertia.inertia(1, 1);
  Rolling out;
  out.expected = mu_r * kG * mass * r * r / (inertia + mass * r * r);
  out.energy_scale = mass * kG;
  const Real x0 = state.bodies[0].x.x();
  Real v_first = 0;
  const long long first = std::llround(0.05 / scene.time_step);
  const long long last = std::llround(0.15 / scene.time_step);
  const auto watch = simulate(model, state, 1.0, [&](const State& s, const Workspace&) {
    if (s.step == first) v_first = s.bodies[0].v.x();
    if (s.step == last)
      out.deceleration =
          (v_first - s.bodies[0].v.x()) / (static_cast<Real>(last - first) * scene.time_step);
  });
  out.energy_rise = watch.largest_energy_rise;
  out.travel = state.bodies[0].x.x() - x0;
  out.end_speed = state.bodies[0].v.norm();
  return out;
}

TEST(MaterialsRolling, ConstantTorqueSlowsAndStopsTheRoll) {
  for (ContactSolver solver : {ContactSolver::rows, ContactSolver::blocks}) {
    const std::string name = solver == ContactSolver::rows ? "rows" : "blocks";
    const Rolling free = roll(0, solver);
    const Rolling resisted = roll(0.05, solver);
    report(name + " rolling mu_r 0: deceleration (cm/s^2)", free.deceleration);
    report(name + " rolling mu_r 0: travel in 1 s (cm)", free.travel);
    report(name + " rolling mu_r 0.05: deceleration / constant-torque rate",
           resisted.deceleration / resisted.expected);
    report(name + " rolling mu_r 0.05: (deceleration - free one) / constant-torque rate",
           (resisted.deceleration - free.deceleration) / resisted.expected);
    report(name + " rolling mu_r 0.05: travel in 1 s (cm)", resisted.travel);
    report(name + " rolling mu_r 0.05: end speed (cm/s)", resisted.end_speed);
    report(name + " rolling mu_r 0.05: travel / v0^2 / (2 a)",
           resisted.travel / (100 / (2 * resisted.expected)));
    report(name + " rolling: largest energy rise / (M g 1cm)",
           std::max(free.energy_rise / free.energy_scale,
                    resisted.energy_rise / resisted.energy_scale));
    // Free: rolls on (most of its 10 cm in the second), barely slowed.
    EXPECT_GT(free.travel, 8) << name;
    EXPECT_LT(free.deceleration, 0.2 * resisted.expected) << name;
    // Resisted: the constant-torque deceleration a, plus at most the free roll's (the edges'
    // landings, which slow it less as it slows: about as v^2); at rest within v0^2 / (2 a) and
    // beyond v0^2 / (2 (a + the free roll's)).
    const Real a = resisted.expected, a_free = free.deceleration;
    EXPECT_GE(resisted.deceleration, 0.99 * a) << name;
    EXPECT_LE(resisted.deceleration, 1.01 * (a + a_free)) << name;
    EXPECT_LT(resisted.end_speed, 1e-6) << name;
    EXPECT_LE(resisted.travel, 100 / (2 * a)) << name;
    EXPECT_GE(resisted.travel, 100 / (2 * (a + a_free))) << name;
    EXPECT_LE(free.energy_rise, 1e-12 * free.energy_scale) << name;
    EXPECT_LE(resisted.energy_rise, 1e-12 * resisted.energy_scale) << name;
  }
}

// The penalty model: the box on the plate decelerates at the pair's mu g.
TEST(MaterialsPenalty, PairFrictionGivesTheSlidingDeceleration) {
  for (Real mu : {0.2, 0.5}) {
    SceneDef scene;
    scene.contact.model = ContactModel::penalty;
    scene.contact.stiffness = 4e3;
    scene.contact.tangential_stiffness = 2.0 / 7.0 * 4e3;
    scene.contact.damping = 2 * std::sqrt(0.004 * 4e3);
    scene.materials = {material("box", 0.8), material("plate", 0.7)};
    MaterialPairDef p = pair("box", "plate");
    p.friction = mu;
    scene.contact.pairs = {p};
    scene.bodies = {box(0, 0, Vec3::Zero())};
    scene.time_step = penalty_time_step_limit(build_model(scene)) / 2;
    scene.bodies.clear();
    const Sliding s = slide(scene, Ground::plate);
    report("penalty pair mu " + std::to_string(mu).substr(0, 3) + ": deceleration / (mu g)",
           s.deceleration / (mu * kG));
    EXPECT_NEAR(s.deceleration / (mu * kG), 1, 0.02);
    // And by the rule, on the floor.
    scene.contact.pairs.clear();
    scene.materials = {material("box", mu), material("plate", 0.8)};
    const Sliding f = slide(scene, Ground::floor);
    report("penalty floor min rule mu " + std::to_string(mu).substr(0, 3) +
               ": deceleration / (mu g)",
           f.deceleration / (mu * kG));
    EXPECT_NEAR(f.deceleration / (mu * kG), 1, 0.02);
  }
}

// The penalty model's rolling torque: the same prism, the same bounds (its energy is not
// checked: the springs' own energy is not part of the system's).
TEST(MaterialsPenalty, RollingTorqueSlowsAndStopsTheRoll) {
  const Rolling free = roll(0, ContactSolver::rows, true);
  const Rolling resisted = roll(0.05, ContactSolver::rows, true);
  report("penalty rolling mu_r 0: deceleration (cm/s^2)", free.deceleration);
  report("penalty rolling mu_r 0: travel in 1 s (cm)", free.travel);
  report("penalty rolling mu_r 0.05: deceleration / constant-torque rate",
         resisted.deceleration / resisted.expected);
  report("penalty rolling mu_r 0.05: travel / v0^2 / (2 a)",
         resisted.travel / (100 / (2 * resisted.expected)));
  report("penalty rolling mu_r 0.05: end speed (cm/s)", resisted.end_speed);
  const Real a = resisted.expected, a_free = free.deceleration;
  EXPECT_GT(free.travel, 8);
  EXPECT_GE(resisted.deceleration, 0.98 * a);
  EXPECT_LE(resisted.deceleration, 1.02 * (a + a_free));
  EXPECT_LE(resisted.travel, 1.02 * 100 / (2 * a));
  EXPECT_GE(resisted.travel, 0.98 * 100 / (2 * (a + a_free)));
  // At rest but for the springs' small rocking on the face it stopped on: under 1% of v0.
  EXPECT_LT(resisted.end_speed, 0.1);
}

}  // namespace test_materials
}  // namespace tem
