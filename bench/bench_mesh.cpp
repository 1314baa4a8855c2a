// The approximate cutter on the scan-like 75,000-face meshes (tests/support/scan_meshes.hpp),
// against issue 12's targets: under a minute, at most 64 blocks, over-coverage under 5 % of the
// mesh's volume, Hausdorff distance under 2 % of the bounding-box diagonal. One run each (a
// run takes seconds); the figures come out as counters.
// Run: build/release/bench/tem_bench --benchmark_filter=MeshApproximate
#include <benchmark/benchmark.h>

#include "mesh/mesh_decomposition.hpp"
#include "support/scan_meshes.hpp"

namespace {

using namespace tem;

Real diagonal(const TriangleMesh& mesh) {
  Vec3 lo = mesh.vertices[0], hi = lo;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

void run(benchmark::State& state, const TriangleMesh& mesh) {
  const int max_blocks = static_cast<int>(state.range(0));
  MeshDecomposition d;
  for (auto _ : state) d = approximate_decomposition(mesh, max_blocks);
  state.counters["faces"] = static_cast<double>(mesh.faces.size());
  state.counters["blocks"] = static_cast<double>(d.blocks.size());
  state.counters["over_coverage_percent"] = 100 * d.over_coverage / d.mesh_volume;
  state.counters["hausdorff_percent_of_diagonal"] = 100 * d.hausdorff / diagonal(mesh);
  state.counters["seconds"] = d.seconds;
}

void MeshApproximateBumpyTorus(benchmark::State& state) {
  static const TriangleMesh mesh = testing_support::bumpy_torus_mesh();
  run(state, mesh);
}
BENCHMARK(MeshApproximateBumpyTorus)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void MeshApproximatePotato(benchmark::State& state) {
  static const TriangleMesh mesh = testing_support::potato_mesh();
  run(state, mesh);
}
BENCHMARK(MeshApproximatePotato)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
