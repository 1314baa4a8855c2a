// Contact before overlap at large time steps (contact_margins.hpp, block_manifold.hpp, the
// speculative targets of semm.cpp): bodies stop at contact instead of sinking in, land when free
// fall says they do, bounce with their restitution, and gain no energy.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/contact_margins.hpp"
#include "support/falling_coin.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_contact_before_overlap {

using testing_support::report;
using testing_support::simulate;

constexpr Real kG = testing_support::kCoinGravity;

using testing_support::falling_coin;

// The landing and the rebound run with both SEMM solvers (contact.solver "rows" and "newton"):
// either makes contact before overlap exact to its tolerance.
class LandingBeforeOverlap : public ::testing::TestWithParam<ContactSolver> {};

SceneDef coin_for(Real height, Real speed, Real dt, ContactSolver solver) {
  SceneDef scene = falling_coin(height, speed, dt);
  scene.contact.solver = solver;
  return scene;
}

// Dropped from rest 1 cm above the floor at dt = 5e-4 (the coin falls 0.022 cm in its last
// step, a fifth of its thickness and 14% of its size): it lands within a step of free fall's
// landing time, at rest exactly on the floor, never overlaps it and never gains energy.
TEST_P(LandingBeforeOverlap, CoinLandsWhenFreeFallSaysAndRestsOnTheFloor) {
  const Real dt = 5e-4, h = 1.0;
  const Model model = build_model(coin_for(h, 0, dt, GetParam()));
  ASSERT_TRUE(contact_before_overlap(model.scene));
  State state = initial_state(model);
  Real landed = -1;
  const auto watch = simulate(model, state, 0.2, [&](const State& s, const Workspace&) {
    if (landed < 0 && s.bodies[0].x.z() - 0.05 <= 1e-12) landed = s.time;
  });
  const Real free_fall = std::sqrt(2 * h / kG);
  report("coin at dt 5e-4: landing time (s)", landed);
  report("coin at dt 5e-4: free fall's landing time (s)", free_fall);
  report("coin at dt 5e-4: deepest overlap (cm)", watch.deepest);
  EXPECT_NEAR(landed, free_fall, dt);
  // To the solver's tolerance (1e-9 of the impulses): 1e-9 of the coin's thickness.
  EXPECT_NEAR(state.bodies[0].x.z(), 0.05, 1e-10);
  EXPECT_LT(std::abs(state.bodies[0].v.z()), 1e-9);
  EXPECT_LE(watch.deepest, 1e-10);
  EXPECT_LE(watch.largest_energy_rise, 1e-12 * model.bodies[0].inertia.mass * kG);
}

// The same coin thrown down at 300 cm/s (0.3 cm a step at dt 1e-3, three thicknesses): with
// restitution 0.5 it leaves at half its arrival speed, from where it stopped, not from inside
// the floor. The arrival speed is the one at the start of the step it stops in.
TEST_P(LandingBeforeOverlap, FastCoinReboundsWithItsRestitution) {
  const Real dt = 1e-3;
  SceneDef scene = coin_for(1.0, 300, dt, GetParam());
  scene.contact.restitution = 0.5;
  const Model model = build_model(scene);
  State state = initial_state(model);
  Real arrival = 0, rebound = 0;
  Real lowest = 1;
  const auto watch = simulate(model, state, 0.02, [&](const State& s, const Workspace&) {
    const Real v = s.bodies[0].v.z();
    if (rebound == 0 && v < 0) arrival = v;
    if (rebound == 0 && v > 0) rebound = v;
    lowest = std::min(lowest, s.bodies[0].x.z() - 0.05);
  });
  report("fast coin: arrival speed (cm/s)", -arrival);
  report("fast coin: rebound speed (cm/s)", rebound);
  report("fast coin: lowest bottom height (cm)", lowest);
  EXPECT_NEAR(rebound, -0.5 * arrival, 1e-9 * std::abs(arrival));
  EXPECT_GE(lowest, -1e-12);
  EXPECT_LE(watch.largest_energy_rise, 1e-12 * model.bodies[0].inertia.mass * kG);
}

INSTANTIATE_TEST_SUITE_P(Solvers, LandingBeforeOverlap,
                         ::testing::Values(ContactSolver::rows, ContactSolver::newton),
                         [](const ::testing::TestParamInfo<ContactSolver>& info) {
                           return info.param == ContactSolver::rows ? "rows" : "newton";
                         });

// Without contact before overlap (margin 0) the same thrown coin ends the step it arrives in
// well inside the floor: what the margin prevents.
TEST(ContactBeforeOverlap, WithoutAMarginTheFastCoinSinksIn) {
  SceneDef scene = falling_coin(1.0, 300, 1e-3);
  scene.contact.margin = 0.0;
  const Model model = build_model(scene);
  ASSERT_FALSE(contact_before_overlap(model.scene));
  State state = initial_state(model);
  Real lowest = 1;
  simulate(model, state, 0.02, [&](const State& s, const Workspace&) {
    lowest = std::min(lowest, s.bodies[0].x.z() - 0.05);
  });
  report("fast coin without margin: lowest bottom height (cm)", lowest);
  EXPECT_LT(lowest, -0.01);
}

// A box sliding past the side of a fixed box, 0.001 away (inside the margin): a contact point
// that never closes pushes nothing, so the slide goes on untouched (no ghost contact).
TEST(ContactBeforeOverlap, PassingInsideTheMarginPushesNothing) {
  SceneDef scene;
  scene.gravity = Vec3::Zero();
  scene.time_step = 1e-3;
  scene.contact.friction = 0.5;
  BodyDef wall_box, slider;
  wall_box.name = "fixed";
  wall_box.shape.size = Vec3(1, 0.2, 0.2);
  wall_box.fixed = true;
  slider.name = "slider";
  slider.shape.size = Vec3(0.2, 0.2, 0.2);
  slider.position = Vec3(-0.8, 0.201, 0);
  slider.velocity = Vec3(50, 0, 0);
  scene.bodies = {wall_box, slider};
  const Model model = build_model(scene);
  State state = initial_state(model);
  int steps_with_patches = 0;
  simulate(model, state, 0.03,
           [&](const State&, const Workspace& w) { steps_with_patches += !w.patches.empty(); });
  report("slider: steps with a patch", steps_with_patches);
  EXPECT_GT(steps_with_patches, 0);              // the pair was a contact within the margin...
  EXPECT_EQ(state.bodies[1].v, Vec3(50, 0, 0));  // ...that never pushed
  EXPECT_EQ(state.bodies[1].omega, Vec3::Zero());
}

}  // namespace test_contact_before_overlap
}  // namespace tem
