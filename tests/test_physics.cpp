// Physics of the default mode against closed forms: a box at rest, sliding and sticking on an
// incline, bouncing with a restitution; the energy of every contact scene never rises. Every
// number comes from the run; the expectations are textbook formulas. Each test runs with both
// SEMM solvers (contact.solver "rows" and "newton"): the same closed forms hold for either.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/simulate.hpp"

namespace tem {
namespace test_physics {

using testing_support::report;
using testing_support::simulate;

constexpr Real kG = earth_gravity_cgs;

// A 0.2 x 0.2 x 0.1 box (density 1) on the floor plane z = 0, bottom face at z = lift.
SceneDef box_on_floor(Real lift, Real friction, Real restitution, Real dt, ContactSolver solver) {
  SceneDef scene = testing_support::box_on_floor(lift);
  scene.contact.solver = solver;
  scene.time_step = dt;
  scene.contact.friction = friction;
  scene.contact.restitution = restitution;
  return scene;
}

// Energy scale of a box scene for "round-off": M g times 1 cm.
Real energy_scale(const Model& model) { return model.bodies[0].inertia.mass * kG * 1.0; }

Real rotation_angle(const Mat3& g) {
  return Eigen::AngleAxis<Real>(Mat3(g)).angle();
}

class Physics : public ::testing::TestWithParam<ContactSolver> {};

// A box set down on the floor stays: it sinks by what one step of free fall takes before its
// contact is found (half g dt^2 in that step, as much in the next while the contact stops it:
// g dt^2 in all, to round-off), and neither drifts nor turns, for 2 s.
TEST_P(Physics, BoxRestsOnTheFloor) {
  const Real dt = 1e-4;
  const Model model = build_model(box_on_floor(0, 0.3, 0, dt, GetParam()));
  State state = initial_state(model);
  const Vec3 x0 = state.bodies[0].x;
  Real sink = 0, drift = 0, turn = 0;
  const auto watch = simulate(model, state, 2.0, [&](const State& s, const Workspace&) {
    sink = std::max(sink, x0.z() - s.bodies[0].x.z());
    drift = std::max(drift, (s.bodies[0].x - x0).head<2>().norm());
    turn = std::max(turn, rotation_angle(s.bodies[0].g));
  });
  report("box at rest: deepest sink (cm)", sink);
  report("box at rest: drift (cm)", drift);
  report("box at rest: rotation (rad)", turn);
  report("box at rest: largest energy rise / (M g 1cm)", watch.largest_energy_rise / energy_scale(model));
  EXPECT_LE(sink, kG * dt * dt * (1 + 1e-9));
  EXPECT_LE(drift, 1e-12);
  EXPECT_LE(turn, 1e-12);
  EXPECT_LE(watch.largest_energy_rise, 1e-12 * energy_scale(model));
}

// An incline of atan(0.5), made by turning gravity (the floor stays z = 0, gravity gets the
// component g sin(theta) along +x). With friction mu < tan(theta) the box slides with
// a = g (sin - mu cos); with mu = tan(theta) = 0.5 static friction holds it exactly; without
// friction a = g sin(theta).
struct InclineResult {
  Real acceleration = 0;
  Real travel = 0;
  Real energy_rise = 0;
  Real scale = 0;
};

InclineResult incline(Real friction, ContactSolver solver) {
  const Real theta = std::atan(0.5);
  SceneDef scene = box_on_floor(0, friction, 0, 1e-4, solver);
  scene.gravity = kG * Vec3(std::sin(theta), 0, -std::cos(theta));
  const Model model = build_model(scene);
  State state = initial_state(model);
  const Real x0 = state.bodies[0].x.x();
  Real v_quarter = 0;
  const auto watch = simulate(model, state, 0.5, [&](const State& s, const Workspace&) {
    if (s.step == 2500) v_quarter = s.bodies[0].v.x();
  });
  InclineResult r;
  r.acceleration = (state.bodies[0].v.x() - v_quarter) / 0.25;
  r.travel = state.bodies[0].x.x() - x0;
  r.energy_rise = watch.largest_energy_rise;
  r.scale = energy_scale(model);
  return r;
}

TEST_P(Physics, InclineSlidesWithCoulombFriction) {
  const Real theta = std::atan(0.5);
  const InclineResult r = incline(0.49, GetParam());
  const Real expected = kG * (std::sin(theta) - 0.49 * std::cos(theta));
  report("incline mu 0.49: acceleration / g (sin - mu cos)", r.acceleration / expected);
  EXPECT_NEAR(r.acceleration / expected, 1, 0.02);
  EXPECT_LE(r.energy_rise, 1e-12 * r.scale);
}

// At the friction angle the box moves only in the first step, before its contact exists, and
// the step after, while friction stops it: g sin(theta) dt^2 (as the box at rest sinks g dt^2);
// then it holds, but for round-off creep (the friction it needs is exactly its limit), asked to
// stay below 1e-10 cm, a billionth of the box, over the 5000 steps.
TEST_P(Physics, InclineHoldsAtTheFrictionAngle) {
  const Real theta = std::atan(0.5), dt = 1e-4;
  const InclineResult r = incline(0.5, GetParam());
  report("incline mu 0.5: travel in 0.5 s (cm)", r.travel);
  report("incline mu 0.5: travel beyond g sin dt^2 (cm)", r.travel - kG * std::sin(theta) * dt * dt);
  EXPECT_LE(std::abs(r.travel), kG * std::sin(theta) * dt * dt + 1e-10);
  EXPECT_LE(r.energy_rise, 1e-12 * r.scale);
}

TEST_P(Physics, InclineWithoutFrictionSlidesFreely) {
  const Real theta = std::atan(0.5);
  const InclineResult r = incline(0, GetParam());
  report("incline frictionless: acceleration / (g sin)", r.acceleration / (kG * std::sin(theta)));
  EXPECT_NEAR(r.acceleration / (kG * std::sin(theta)), 1, 0.01);
  EXPECT_LE(r.energy_rise, 1e-12 * r.scale);
}

// A box sent sliding at 10 cm/s along the floor (mu 0.5, dt 5e-4) slows at mu g and stops
// after v^2 / (2 mu g) = 0.102 cm, and does not rise off the floor while it slides: a convex
// relaxation of Coulomb friction (Anitescu's; SAP's cone) would lift it by mu |slip| dt a step
// (2.5e-3 cm at the start). It may rise at most 1e-4 of its size (0.2 cm).
TEST_P(Physics, SlidingBoxSlowsAtMuGAndStaysOnTheFloor) {
  const Real mu = 0.5, v0 = 10, dt = 5e-4;
  SceneDef scene = box_on_floor(0, mu, 0, dt, GetParam());
  scene.bodies[0].velocity = Vec3(v0, 0, 0);
  const Model model = build_model(scene);
  State state = initial_state(model);
  const Vec3 x0 = state.bodies[0].x;
  Real rise = 0, sink = 0;
  const auto watch = simulate(model, state, 0.05, [&](const State& s, const Workspace&) {
    rise = std::max(rise, s.bodies[0].x.z() - x0.z());
    sink = std::max(sink, x0.z() - s.bodies[0].x.z());
  });
  const Real travel = state.bodies[0].x.x() - x0.x(), expected = v0 * v0 / (2 * mu * kG);
  report("sliding box: travel / (v^2 / 2 mu g)", travel / expected);
  report("sliding box: largest rise (cm)", rise);
  report("sliding box: deepest sink (cm)", sink);
  // Once friction stopped it, it is at rest: 0 to round-off.
  report("sliding box: speed at 0.05 s (cm/s)", state.bodies[0].v.norm());
  // The travel's error: the box's speed is a step's worth of mu g dt off at most.
  EXPECT_NEAR(travel, expected, v0 * dt);
  EXPECT_LE(rise, 1e-4 * 0.2);
  EXPECT_LE(sink, kG * dt * dt * (1 + 1e-9));
  EXPECT_LE(state.bodies[0].v.norm(), 1e-12);
  EXPECT_LE(watch.largest_energy_rise, 1e-12 * energy_scale(model));
}

// Dropped flat from 0.1 cm, with restitution 0.5 the box leaves the floor at half the speed
// it hit it with.
TEST_P(Physics, BoxReboundsWithItsRestitution) {
  const Real drop = 0.1;
  const Model model = build_model(box_on_floor(drop, 0.3, 0.5, 1e-5, GetParam()));
  State state = initial_state(model);
  Real impact = 0, rebound = 0;
  bool touched = false;
  simulate(model, state, 0.25, [&](const State& s, const Workspace& w) {
    const Real vz = s.bodies[0].v.z();
    if (!touched) impact = std::min(impact, vz);
    touched = touched || !w.patches.empty();
    if (touched) rebound = std::max(rebound, vz);
  });
  report("rebound: impact speed (cm/s)", -impact);
  report("rebound: speed ratio", rebound / -impact);
  EXPECT_NEAR(-impact, std::sqrt(2 * kG * drop), 0.01 * std::sqrt(2 * kG * drop));
  EXPECT_NEAR(rebound / -impact, 0.5, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Solvers, Physics,
                         ::testing::Values(ContactSolver::rows, ContactSolver::newton),
                         [](const ::testing::TestParamInfo<ContactSolver>& info) {
                           return info.param == ContactSolver::rows ? "rows" : "newton";
                         });

}  // namespace test_physics
}  // namespace tem
