// Whole steps through the public API (include/tem/simulation.hpp), as a program built on TEM
// takes them: the 1,000-coin pour of scenes/bench/coins_1000.json at dt 1.25e-4 (its largest
// right dt, docs/benchmarks.md) once most coins have landed (0.2 s), and the same with an
// external drag on every coin set through the writable array before each step (a coupling's
// cost).
// The stage split lives in bench_step.cpp, which times the stages inside the step.
#include <benchmark/benchmark.h>

#include <string>

#include "tem/simulation.hpp"

namespace tem::bench {
namespace {

// The pour, loaded and run to 0.2 s once for both variants (the second goes on from where the
// first stopped, a few dozen steps later in the same settling pile).
Simulation& landed_pour() {
  static Simulation sim = [] {
    Simulation::set_threads(1);
    SceneDef scene =
        Simulation::load(std::string(TEM_SOURCE_DIR) + "/scenes/bench/coins_1000.json").scene();
    scene.time_step = 1.25e-4;
    Simulation s = Simulation::from_scene(scene);
    s.step(1600);  // 0.2 s: most coins have landed
    return s;
  }();
  return sim;
}

void BM_ApiStepPour(benchmark::State& st) {
  Simulation::set_threads(1);
  Simulation& sim = landed_pour();
  const bool drag = st.range(0) != 0;
  const int n = sim.body_count();
  Real* force = sim.external_force_data();
  const Real* velocity = sim.velocity_data();
  const std::ptrdiff_t stride = sim.state_stride() / static_cast<std::ptrdiff_t>(sizeof(Real));
  for (auto _ : st) {
    if (drag)  // a linear drag, written through the array as a coupled solver would
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) force[3 * i + k] = -0.01 * velocity[i * stride + k];
    sim.step();
  }
  if (drag) sim.clear_external_loads();
  st.counters["bodies"] = n;
  st.counters["patches"] = static_cast<double>(sim.contacts().size());
  st.counters["body_steps_per_s"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ApiStepPour)->Arg(0)->Arg(1)->ArgNames({"drag"})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tem::bench
