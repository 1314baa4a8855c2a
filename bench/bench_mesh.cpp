// The approximate cutter on the scan-like 75,000-face meshes (tests/support/scan_meshes.hpp),
// against the cutter's targets: under a minute, at most 64 blocks, over-coverage under 5 % of the
// mesh's volume, Hausdorff distance under 2 % of the bounding-box diagonal. One run each (a
// run takes seconds); the figures come out as counters.
// With TEM_PUBLIC_MESHES set to a directory, also each closed mesh file there (such as the
// public test meshes of docs/meshes.md, not shipped with TEM) at 32 and 64 blocks; files that
// are open or fail the checks are skipped with a note.
// Run: build/release/bench/tem_bench --benchmark_filter=MeshApproximate
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "mesh/mesh_check.hpp"
#include "mesh/mesh_decomposition.hpp"
#include "mesh/mesh_reader.hpp"
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

void MeshApproximateKnot(benchmark::State& state) {
  static const TriangleMesh mesh = testing_support::knot_mesh();
  run(state, mesh);
}
BENCHMARK(MeshApproximateKnot)->Arg(32)->Arg(64)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// One benchmark per closed mesh file in $TEM_PUBLIC_MESHES, registered before main runs.
bool register_public_meshes() {
  const char* dir = std::getenv("TEM_PUBLIC_MESHES");
  if (!dir) return false;
  std::vector<std::filesystem::path> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext == ".obj" || ext == ".stl" || ext == ".ply" || ext == ".off")
      files.push_back(entry.path());
  }
  if (error)
    std::cerr << dir << ": TEM_PUBLIC_MESHES is not a readable directory: " << error.message()
              << "\n";
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    auto mesh = std::make_shared<TriangleMesh>();
    try {
      *mesh = read_mesh_file(file.string());
      if (!check_mesh(*mesh).closed) throw MeshError(file.string() + ": not closed");
    } catch (const std::exception& e) {
      std::cerr << "MeshApproximatePublic skips " << e.what() << "\n";
      continue;
    }
    benchmark::RegisterBenchmark(("MeshApproximatePublic/" + file.stem().string()).c_str(),
                                 [mesh](benchmark::State& state) { run(state, *mesh); })
        ->Arg(32)
        ->Arg(64)
        ->Iterations(1)
        ->Unit(benchmark::kSecond)
        ->UseRealTime();
  }
  return true;
}
[[maybe_unused]] const bool public_meshes_registered = register_public_meshes();

}  // namespace
