// The penalty (DEM) model against closed forms: a box resting on its springs, held and sliding
// on an incline, and the time step limit it warns about.
#include <gtest/gtest.h>

#include <cmath>

#include "forces/penalty/penalty.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_penalty {

using testing_support::report;
using testing_support::simulate;

constexpr Real kG = earth_gravity_cgs;

// A 0.2 x 0.2 x 0.1 box (density 1, mass 0.004 g) on the floor plane, penalty contact.
SceneDef penalty_box(PenaltyLaw law, Real stiffness, Real friction) {
  SceneDef scene = testing_support::box_on_floor();
  scene.contact.model = ContactModel::penalty;
  scene.contact.law = law;
  scene.contact.stiffness = stiffness;
  scene.contact.tangential_stiffness = 2.0 / 7.0 * stiffness;
  scene.contact.friction = friction;
  return scene;
}

// Damped to rest, the box sinks until its spring carries its weight: d = M g / k (linear),
// d = (M g / k)^(2/3) (Hertz).
TEST(Penalty, BoxRestsWhereItsSpringCarriesItsWeight) {
  for (PenaltyLaw law : {PenaltyLaw::linear, PenaltyLaw::hertz}) {
    SceneDef scene = penalty_box(law, law == PenaltyLaw::linear ? 4e3 : 4e5, 0.3);
    Model model = build_model(scene);
    const Real mass = model.bodies[0].inertia.mass;
    // Critical damping of the contact oscillation, at the expected depth for Hertz.
    const Real weight = mass * kG;
    const Real depth = law == PenaltyLaw::linear ? weight / scene.contact.stiffness
                                                 : std::cbrt(std::pow(weight / scene.contact.stiffness, 2));
    const Real k_eff = law == PenaltyLaw::linear ? scene.contact.stiffness
                                                 : 1.5 * scene.contact.stiffness * std::sqrt(depth);
    const Real c = 2 * std::sqrt(mass * k_eff);
    scene.contact.damping = law == PenaltyLaw::linear ? c : c / std::pow(depth, 0.25);
    scene.time_step = penalty_time_step_limit(build_model(scene)) / 2;
    model = build_model(scene);
    State state = initial_state(model);
    simulate(model, state, 0.5);
    const Real sunk = 0.05 - state.bodies[0].x.z();
    report(law == PenaltyLaw::linear ? "penalty linear: rest depth / (M g / k)"
                                     : "penalty hertz: rest depth / (M g / k)^(2/3)",
           sunk / depth);
    EXPECT_NEAR(sunk / depth, 1, 1e-3);
    EXPECT_LT(state.bodies[0].v.norm(), 1e-6);
  }
}

// On an incline of atan(0.5): with mu = 0.6 the tangential spring holds the box, stretched by
// M g sin / k_t; with mu = 0.3 it slides with a = g (sin - mu cos).
TEST(Penalty, InclineHoldsOnTheSpringAndSlidesAtTheLimit) {
  const Real theta = std::atan(0.5);
  for (Real mu : {0.6, 0.3}) {
    SceneDef scene = penalty_box(PenaltyLaw::linear, 4e3, mu);
    scene.gravity = kG * Vec3(std::sin(theta), 0, -std::cos(theta));
    Model model = build_model(scene);
    const Real mass = model.bodies[0].inertia.mass;
    scene.contact.damping = 2 * std::sqrt(mass * scene.contact.stiffness);
    scene.time_step = penalty_time_step_limit(model) / 2;
    model = build_model(scene);
    State state = initial_state(model);
    Real v_half = 0, stretch = 0;
    const long long half = std::llround(0.25 / scene.time_step);
    simulate(model, state, 0.5, [&](const State& s, const Workspace& w) {
      if (s.step == half) v_half = s.bodies[0].v.x();
      stretch = w.forces.springs.empty() ? 0 : w.forces.springs[0].stretch.norm();
    });
    if (mu > 0.5) {
      // Held: at rest, the spring stretched by the load, the box moved by that stretch and the
      // small tilt the friction's moment gives it, nothing more.
      const Real expected = mass * kG * std::sin(theta) / scene.contact.tangential_stiffness;
      report("penalty incline mu 0.6: spring stretch / (M g sin / k_t)", stretch / expected);
      report("penalty incline mu 0.6: travel / (M g sin / k_t)", state.bodies[0].x.x() / expected);
      EXPECT_NEAR(stretch / expected, 1, 0.01);
      EXPECT_LT(state.bodies[0].x.x(), 1.5 * expected);
      EXPECT_LT(state.bodies[0].v.norm(), 1e-6);
    } else {
      const Real a = (state.bodies[0].v.x() - v_half) / (0.5 - half * scene.time_step);
      const Real expected = kG * (std::sin(theta) - mu * std::cos(theta));
      report("penalty incline mu 0.3: acceleration / g (sin - mu cos)", a / expected);
      EXPECT_NEAR(a / expected, 1, 0.02);
    }
  }
}

// A tenth of 2 pi sqrt(m / k).
TEST(Penalty, TimeStepLimitIsATenthOfTheContactPeriod) {
  const Model model = build_model(penalty_box(PenaltyLaw::linear, 4e3, 0.3));
  const Real m = model.bodies[0].inertia.mass;
  EXPECT_NEAR(penalty_time_step_limit(model), 0.2 * 3.14159265358979323846 * std::sqrt(m / 4e3),
              1e-15);
}

}  // namespace test_penalty
}  // namespace tem
