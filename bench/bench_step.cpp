// Whole simulation steps on piles of N coins (bench_scenes.hpp: every coin touching its
// neighbours, as in a settled pile), each the step every driver takes (take_step: the stages
// `tem run` runs, population and sleep included), one and two threads, sweeps in patch order or by colours
// (contact.sweep_order): time per step, body-steps per second,
// time per contact patch, and the split among the stages of the step. The solver stops as in
// scenes/bench (tolerance 1e-3, at most 20 sweeps), dt 1e-4.
#include <benchmark/benchmark.h>

#include "bench_scenes.hpp"
#include "support/parallel.hpp"
#include "simulation/step_loop.hpp"

namespace tem::bench {
namespace {

void BM_StepPile(benchmark::State& st) {
  Model model = coin_pile(static_cast<int>(st.range(0)));
  model.scene.time_step = 1e-4;
  model.scene.contact.friction = 0.3;
  model.scene.contact.tolerance = 1e-3;
  model.scene.contact.max_sweeps = 20;
  model.scene.contact.colour_sweeps = st.range(2) != 0;
  set_threads(static_cast<int>(st.range(1)));
  State state = initial_state(model);
  Workspace workspace;
  std::vector<RemovedBody> removed;
  StepHooks no_driver;  // no files, checkpoints or ranks: the step itself
  // Warm start and scratch in place, as in a running simulation.
  take_step(model, state, workspace, removed, no_driver);
  workspace.times = StageTimes{};
  for (auto _ : st) take_step(model, state, workspace, removed, no_driver);
  set_threads(1);

  const StageTimes& t = workspace.times;
  const double steps = static_cast<double>(t.steps);
  const double bodies = static_cast<double>(model.bodies.size());
  st.counters["bodies"] = bodies;
  st.counters["patches"] = static_cast<double>(t.patches) / steps;
  st.counters["sweeps"] = static_cast<double>(t.sweeps) / steps;
  st.counters["broad_us"] = 1e6 * t.broad_phase / steps;
  st.counters["narrow_us"] = 1e6 * t.narrow_phase / steps;
  st.counters["forces_us"] = 1e6 * t.forces / steps;
  st.counters["integrate_us"] = 1e6 * t.integrate / steps;
  st.counters["body_steps_per_s"] =
      benchmark::Counter(bodies, benchmark::Counter::kIsIterationInvariantRate);
  st.counters["us_per_patch"] =
      1e6 * (t.broad_phase + t.narrow_phase + t.forces + t.integrate) /
      std::max<double>(1, static_cast<double>(t.patches));
}
BENCHMARK(BM_StepPile)
    ->ArgsProduct({{100, 1000, 4000, 10000}, {1, 2}, {0, 1}})
    ->ArgNames({"coins", "threads", "colours"})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace
}  // namespace tem::bench
