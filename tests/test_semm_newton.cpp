// SEMM by Newton (contact.solver "newton", src/forces/semm_newton/): the weight of a whole column
// reaches the floor within one solve, in as many Newton iterations at forty coins as at ten;
// the same bits at any thread count; a stopped box at rest in every step; a pyramid of cubes,
// a pile's island, on CHOLMOD's supernodal factorisation; a poured pile that rests and sleeps;
// the scene key read and written. The closed forms of the box on the floor and on the incline
// are in test_physics.cpp, run with both solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "simulation/step.hpp"
#include "support/coin_column.hpp"
#include "support/parallel.hpp"
#include "support/simulate.hpp"

namespace tem {
namespace test_semm_newton {

using testing_support::coin_column;
using testing_support::kCoinThickness;
using testing_support::report;
using testing_support::simulate;

struct Column {
  int most_iterations = 0;
  Real median_iterations = 0;
  Real deepest = 0;         // deepest patch over the run
  Real fastest_end = 0;     // fastest coin at the end (cm/s)
  Real floor_load = 0;      // the floor's push at the end over the column's weight
  Real energy_rise = 0;     // largest rise over one step, over |total energy| at the start
  long long fallbacks = 0;  // islands left to the row solver
};

// A column of `layers` coins at dt 5e-4 for `duration`, solved by Newton to 1e-9.
Column newton_column(int layers, Real duration) {
  SceneDef scene = coin_column(layers, 5e-4);
  scene.contact.solver = ContactSolver::newton;
  scene.contact.tolerance = 1e-9;
  const Model model = build_model(scene);
  State state = initial_state(model);
  const Real energy = std::abs(system_energies(model, state).total());
  std::vector<int> iterations;
  Real floor = 0;
  Column c;
  const auto watch = simulate(model, state, duration, [&](const State&, const Workspace& w) {
    iterations.push_back(w.forces.solver.sweeps);
    c.fallbacks += w.forces.solver.fallback_islands;
    floor = 0;
    for (size_t i = 0; i < w.forces.points.size(); ++i)
      if (w.forces.points[i].wall == 0) floor += w.forces.impulses[i].normal;
  });
  std::sort(iterations.begin(), iterations.end());
  c.most_iterations = iterations.back();
  c.median_iterations = iterations[iterations.size() / 2];
  c.deepest = watch.deepest;
  for (const BodyState& b : state.bodies) c.fastest_end = std::max(c.fastest_end, b.v.norm());
  Real weight = 0;
  for (const Body& b : model.bodies) weight += b.inertia.mass * -scene.gravity.z();
  c.floor_load = floor / (weight * scene.time_step);
  c.energy_rise = watch.largest_energy_rise / energy;
  return c;
}

// Ten and forty coins: both stand (overlap under 1 % of a coin, every coin at rest), the floor
// carries the whole column's weight in the last step to 1e-6, and Newton's median iteration count
// is no larger for forty coins than for ten, give or take two. Newton solves every step of the
// ten-coin column; of the forty-coin column's 400 steps it may leave an island (the landing's) to
// the row solver after kMaxNewtonIterations, asked here to stay under 1 % of the steps.
// A column at rest takes one Newton iteration a step (the median): its last step's impulses are
// its answer, and the energy rule asks no second pass of an island that takes energy out (with
// the rule row by row, four: a row pushing along the creep that the regularised friction left
// in the last step was mirrored, and the island solved again).
TEST(SemmNewton, ColumnStandsInIterationsThatDoNotGrowWithItsHeight) {
  const Column ten = newton_column(10, 0.2), forty = newton_column(40, 0.2);
  for (const auto& [name, c] : {std::pair{"10", ten}, std::pair{"40", forty}}) {
    const std::string k = std::string(name) + "-coin column, Newton: ";
    report(k + "median iterations", c.median_iterations);
    report(k + "most iterations", c.most_iterations);
    report(k + "deepest overlap / coin", c.deepest / kCoinThickness);
    report(k + "fastest coin at the end (cm/s)", c.fastest_end);
    report(k + "floor load / weight", c.floor_load);
    report(k + "largest energy rise / |energy|", c.energy_rise);
    report(k + "islands left to the row solver", static_cast<Real>(c.fallbacks));
    EXPECT_LT(c.deepest, 0.01 * kCoinThickness);
    EXPECT_LT(c.fastest_end, 1e-3);
    EXPECT_NEAR(c.floor_load, 1, 1e-6);
    EXPECT_EQ(c.median_iterations, 1);
    EXPECT_LE(c.energy_rise, 1e-12);
  }
  EXPECT_EQ(ten.fallbacks, 0);
  EXPECT_LT(ten.most_iterations, kMaxNewtonIterations);
  EXPECT_LT(forty.fallbacks, 4);  // 1 % of 400 steps
  EXPECT_LE(forty.median_iterations, ten.median_iterations + 2);
}

// A box sliding at 10 cm/s on the floor (mu 0.5) stops after v / (mu g) = 0.020 s; from 0.03 s
// on it is at rest to round-off in every step, not only at the end: the polish takes one Newton
// step at least, so the impulses are not those of a start within the tolerance (which can leave
// the box moving at up to 3e-10 cm/s in some steps).
TEST(SemmNewton, StoppedBoxIsAtRestInEveryStep) {
  SceneDef scene = testing_support::box_on_floor();
  scene.contact.solver = ContactSolver::newton;
  scene.contact.friction = 0.5;
  scene.time_step = 5e-4;
  scene.bodies[0].velocity = Vec3(10, 0, 0);
  const Model model = build_model(scene);
  State state = initial_state(model);
  Real fastest = 0;
  int steps = 0;
  simulate(model, state, 0.1, [&](const State& s, const Workspace&) {
    if (s.time < 0.03) return;
    fastest = std::max(fastest, s.bodies[0].v.norm());
    ++steps;
  });
  report("stopped box: fastest after 0.03 s (cm/s)", fastest);
  EXPECT_GE(steps, 100);
  EXPECT_LE(fastest, 1e-12);
}

// Islands are solved on their own, each on one thread: a lattice of 12 x 12 columns of three
// coins steps to the same bits on one thread and on two.
TEST(SemmNewton, SameBitsAtAnyThreadCount) {
  SceneDef scene = testing_support::coin_lattice(12, 3, 5e-4);
  scene.contact.solver = ContactSolver::newton;
  scene.contact.tolerance = 1e-9;
  const Model model = build_model(scene);
  const int threads = max_threads();
  State one = initial_state(model), two = initial_state(model);
  set_threads(1);
  simulate(model, one, 0.01);
  set_threads(2);
  simulate(model, two, 0.01);
  set_threads(threads);
  for (size_t i = 0; i < one.bodies.size(); ++i) {
    EXPECT_EQ(one.bodies[i].x, two.bodies[i].x) << i;
    EXPECT_EQ(one.bodies[i].v, two.bodies[i].v) << i;
  }
}

// A pyramid of 0.2 cm cubes, 6 x 6 at the base, each layer shifted half a cube so that every
// cube above the floor stands on four: one island of 91 bodies whose factor fills in as a
// pile's, and so takes CHOLMOD's supernodal factorisation (island_factor.hpp). It stands, the
// floor carries its whole weight in every step once it has landed, and it steps to the same
// bits on one thread and on two (the BLAS held to one thread).
TEST(SemmNewton, PyramidOfCubesStandsOnASupernodalFactorisation) {
  constexpr Real kSide = 0.2;
  SceneDef scene;
  scene.gravity = Vec3(0, 0, -981);
  scene.time_step = 5e-4;
  scene.contact.friction = 0.3;
  scene.contact.solver = ContactSolver::newton;
  scene.contact.tolerance = 1e-9;
  scene.walls.push_back({Vec3::Zero(), Vec3::UnitZ()});
  for (int layer = 0; layer < 6; ++layer)
    for (int i = 0; i < 6 - layer; ++i)
      for (int j = 0; j < 6 - layer; ++j) {
        BodyDef cube;
        cube.name = "c" + std::to_string(scene.bodies.size());
        cube.shape.type = ShapeType::box;
        cube.shape.size = Vec3::Constant(kSide);
        cube.density = 1;
        cube.position = Vec3((i + 0.5 * layer) * kSide, (j + 0.5 * layer) * kSide,
                             (layer + 0.5) * kSide + 1e-4 * (layer + 1));  // 1 um gaps
        scene.bodies.push_back(cube);
      }
  const Model model = build_model(scene);
  Real weight = 0;
  for (const Body& b : model.bodies) weight += b.inertia.mass * -scene.gravity.z();
  const int threads = max_threads();
  std::vector<State> ends;
  for (int count : {1, 2}) {
    set_threads(count);
    State state = initial_state(model);
    int supernodal_steps = 0, loaded_steps = 0;
    Real worst_load = 0;
    const auto watch = simulate(model, state, 0.03, [&](const State& s, const Workspace& w) {
      if (s.time < 0.01) return;  // landing: the top cube's 6 um fall takes 1.1 ms
      supernodal_steps += w.forces.solver.supernodal_islands;
      Real floor = 0;
      for (size_t i = 0; i < w.forces.points.size(); ++i)
        if (w.forces.points[i].wall == 0) floor += w.forces.impulses[i].normal;
      worst_load = std::max(worst_load, std::abs(floor / (weight * scene.time_step) - 1));
      ++loaded_steps;
    });
    Real fastest = 0;
    for (const BodyState& b : state.bodies) fastest = std::max(fastest, b.v.norm());
    if (count == 1) {
      report("cube pyramid: steps factorised supernodally", supernodal_steps);
      report("cube pyramid: worst floor load / weight - 1", worst_load);
      report("cube pyramid: fastest cube at the end (cm/s)", fastest);
      report("cube pyramid: deepest overlap / side", watch.deepest / kSide);
    }
    EXPECT_EQ(supernodal_steps, loaded_steps);  // one island, supernodal in every step
    EXPECT_LT(worst_load, 1e-6);
    EXPECT_LT(fastest, 1e-3);
    EXPECT_LT(watch.deepest, 0.01 * kSide);
    ends.push_back(state);
  }
  set_threads(threads);
  for (size_t i = 0; i < ends[0].bodies.size(); ++i) {
    EXPECT_EQ(ends[0].bodies[i].x, ends[1].bodies[i].x) << i;
    EXPECT_EQ(ends[0].bodies[i].v, ends[1].bodies[i].v) << i;
  }
}

// A hundred hexagonal coins poured 2.5 cm into a 2 x 2 cm box at dt 5e-4 with README's advice
// for pours (4 to 16 sub-steps, sleep): the pile lands and every coin is asleep by 0.3 s, none
// sinks into another by 1 % of its thickness, and the energy never rises. Fill seed 1: when
// friction that slipped in the polish had R 1e-6 w, this pile never rested: the polish failed
// on its island in every step, and the regularised answer left it creeping at 1 s
// (newton_rows.hpp, kSlipRegularisation). Fill seed 8: while every moving island was polished,
// one coin balanced on a line tipped in every sub-step, its island's polish failed in each, and
// the pile crept on past 0.6 s (semm_newton.hpp, kMovingPolishBodies). Seconds of run time
// each: PhysicsScene, not sanitized.
static void newton_pour_of_a_hundred_coins_sleeps(int seed) {
  const SceneReadResult read = read_scene_text(R"({
    "gravity": "earth", "time_step": 0.0005, "duration": 0.3,
    "contact": {"model": "semm", "friction": 0.3, "solver": "newton", "substeps": 4,
                "max_substeps": 16},
    "container": {"min": [0, 0, 0], "max": [2.0, 2.0, 3.5]},
    "fill": [{"name": "coin", "count": 100, "seed": )" + std::to_string(seed) + R"(,
              "region": {"min": [0, 0, 0.05], "max": [2.0, 2.0, 2.5]},
              "body": {"shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1},
                       "density": 7.0}}],
    "sleep": {"speed": 0.05, "time": 0.05}})",
                                               "<newton pour>");
  ASSERT_TRUE(read.ok());
  const Model model = build_model(read.scene);
  State state = initial_state(model);
  Workspace w;
  Real energy = system_energies(model, state).total(), rise = 0, deepest = 0;
  const long long steps = std::llround(model.scene.duration / model.scene.time_step);
  for (long long k = 0; k < steps; ++k) {
    step(model, state, w);
    for (const ContactPatch& p : w.patches) deepest = std::max(deepest, p.depth);
    const Real next = system_energies(model, state).total();
    rise = std::max(rise, next - energy);
    energy = next;
  }
  int asleep = 0;
  for (const BodyState& b : state.bodies) asleep += b.asleep ? 1 : 0;
  Real mass = 0;
  for (const Body& b : model.bodies) mass += b.inertia.mass;
  const std::string name = "newton pour, fill seed " + std::to_string(seed);
  report(name + ": coins asleep at 0.3 s", asleep);
  report(name + ": deepest overlap / thickness", deepest / 0.1);
  const Real weight = mass * model.scene.gravity.norm();
  report(name + ": largest energy rise / (M g 1cm)", rise / weight);
  EXPECT_EQ(asleep, 100);
  EXPECT_LT(deepest, 0.01 * 0.1);
  EXPECT_LE(rise, 1e-12 * weight);
}

TEST(PhysicsScene, NewtonPourOfAHundredCoinsSleeps) { newton_pour_of_a_hundred_coins_sleeps(1); }

TEST(PhysicsScene, NewtonPourWithACoinBalancedOnALineSleeps) {
  newton_pour_of_a_hundred_coins_sleeps(8);
}

TEST(SemmNewton, SceneKeyReadAndWritten) {
  const std::string body = R"("bodies": [{"name": "b", "position": [0, 0, 0],)"
                           R"( "shape": {"type": "box", "size": [1, 1, 1]}}])";
  const SceneReadResult on =
      read_scene_text(R"({"contact": {"solver": "newton"}, )" + body + "}", "newton.json");
  ASSERT_TRUE(on.ok());
  EXPECT_EQ(on.scene.contact.solver, ContactSolver::newton);
  const SceneReadResult again = read_scene_text(write_scene_text(on.scene), "written.json");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again.scene.contact.solver, ContactSolver::newton);
}

}  // namespace test_semm_newton
}  // namespace tem
