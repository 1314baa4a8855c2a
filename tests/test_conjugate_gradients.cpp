// Conjugate gradients over the rows solver's sweeps (contact.acceleration, semm_rows.cpp): the
// same convex programme, the same answer to the tolerance, in fewer sweeps where Gauss-Seidel
// carries weight down one layer per sweep; no energy added; the same bits at any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "support/coin_column.hpp"
#include "support/parallel.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_conjugate_gradients {

using testing_support::coin_column;
using testing_support::kCoinThickness;
using testing_support::report;
using testing_support::simulate;

struct Solved {
  Real sweeps_per_step = 0;
  long long unconverged_steps = 0;
  Real energy_rise = 0;
  Real energy_scale = 0;  // |total energy| at the start
  State state;
};

// A column of `layers` coins at dt 5e-4 for `duration`, solved to `tolerance` within `sweeps`.
Solved column(int layers, bool conjugate_gradients, Real tolerance, int sweeps, Real duration) {
  SceneDef scene = coin_column(layers, 5e-4);
  scene.contact.solver = ContactSolver::rows;
  scene.contact.tolerance = tolerance;
  scene.contact.max_sweeps = sweeps;
  scene.contact.conjugate_gradients = conjugate_gradients;
  const Model model = build_model(scene);
  Solved solved;
  solved.state = initial_state(model);
  solved.energy_scale = std::abs(system_energies(model, solved.state).total());
  long long steps = 0, total = 0;
  const auto watch = simulate(model, solved.state, duration, [&](const State&, const Workspace& w) {
    steps = w.times.steps;
    total = w.times.sweeps;
    solved.unconverged_steps = w.times.unconverged_steps;
  });
  solved.sweeps_per_step = static_cast<Real>(total) / static_cast<Real>(steps);
  solved.energy_rise = watch.largest_energy_rise;
  return solved;
}

// Forty coins solved to 1e-6 over their first 0.1 s: Gauss-Seidel needs many sweeps a step to
// carry the column's weight down (128 on average, measured 2026-11-27), conjugate gradients an
// eighth of them (16); the two stand the column in the same place, to 1.3e-5 cm, and conjugate
// gradients add no energy beyond round-off (1.7e-13 erg of 460).
TEST(ConjugateGradients, ColumnOfFortyCoinsInFarFewerSweeps) {
  const Solved plain = column(40, false, 1e-6, 2000, 0.1);
  const Solved cg = column(40, true, 1e-6, 2000, 0.1);
  report("40-coin column to 1e-6, Gauss-Seidel: sweeps per step", plain.sweeps_per_step);
  report("40-coin column to 1e-6, conjugate gradients: sweeps per step", cg.sweeps_per_step);
  EXPECT_LT(cg.sweeps_per_step, plain.sweeps_per_step / 3);
  EXPECT_EQ(cg.unconverged_steps, 0);
  EXPECT_LE(cg.energy_rise, 1e-14 * cg.energy_scale);
  Real apart = 0;
  for (size_t i = 0; i < cg.state.bodies.size(); ++i)
    apart = std::max(apart, (cg.state.bodies[i].x - plain.state.bodies[i].x).norm());
  report("40-coin column: largest distance between the two solvers' coins (cm)", apart);
  EXPECT_LT(apart, 1e-3 * kCoinThickness);
}

// Sweeps by colours with conjugate gradients: the same bits on one thread and on two. A lattice
// of 12 x 12 columns of three coins (432 patches with the floor), so that each colour holds
// more than the 64 patches under which a colour is swept on one thread.
TEST(ConjugateGradients, SameBitsAtAnyThreadCount) {
  SceneDef scene = testing_support::coin_lattice(12, 3, 5e-4);
  scene.contact.solver = ContactSolver::rows;
  scene.contact.conjugate_gradients = true;
  scene.contact.colour_sweeps = true;
  scene.contact.tolerance = 1e-9;  // every step's sweeps run on, with the direction's moves
  const Model model = build_model(scene);
  const int threads = max_threads();
  State one = initial_state(model), two = initial_state(model);
  long long sweeps = 0;
  set_threads(1);
  simulate(model, one, 0.01);
  set_threads(2);
  simulate(model, two, 0.01, [&](const State&, const Workspace& w) { sweeps = w.times.sweeps; });
  set_threads(threads);
  EXPECT_GT(sweeps, 20 * 5);  // more than five sweeps a step on average
  for (size_t i = 0; i < one.bodies.size(); ++i) {
    EXPECT_EQ(one.bodies[i].x, two.bodies[i].x) << i;
    EXPECT_EQ(one.bodies[i].v, two.bodies[i].v) << i;
  }
}

// The key: read, written back, and refused where there are no rows' sweeps to accelerate: with
// the blocks solver, and with the default solver (Newton), where the message names the fix.
TEST(ConjugateGradients, SceneKeyReadWrittenAndRefusedWithoutRows) {
  const std::string body = R"("bodies": [{"name": "b", "position": [0, 0, 0],)"
                           R"( "shape": {"type": "box", "size": [1, 1, 1]}}])";
  const SceneReadResult on = read_scene_text(
      R"({"contact": {"solver": "rows", "acceleration": "conjugate_gradients"}, )" + body + "}",
      "cg.json");
  ASSERT_TRUE(on.ok());
  EXPECT_TRUE(on.scene.contact.conjugate_gradients);
  const SceneReadResult again = read_scene_text(write_scene_text(on.scene), "written.json");
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(again.scene.contact.conjugate_gradients);
  EXPECT_FALSE(read_scene_text(std::string("{") + body + "}", "plain.json")
                   .scene.contact.conjugate_gradients);
  const SceneReadResult blocks = read_scene_text(
      R"({"contact": {"solver": "blocks", "acceleration": "conjugate_gradients"}, )" + body + "}",
      "blocks.json");
  ASSERT_FALSE(blocks.ok());
  EXPECT_EQ(blocks.problems[0].path, "contact.acceleration");
  const SceneReadResult by_default = read_scene_text(
      R"({"contact": {"acceleration": "conjugate_gradients"}, )" + body + "}", "default.json");
  ASSERT_FALSE(by_default.ok());
  EXPECT_EQ(by_default.problems[0].path, "contact.acceleration");
  EXPECT_NE(by_default.problems[0].message.find(R"("solver": "rows")"), std::string::npos)
      << by_default.problems[0].message;
  const SceneReadResult wrong =
      read_scene_text(R"({"contact": {"acceleration": "nesterov"}, )" + body + "}", "wrong.json");
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.problems[0].path, "contact.acceleration");
}

}  // namespace test_conjugate_gradients
}  // namespace tem
