#!/usr/bin/env bash
# Installs what is missing, builds TEM twice and runs the tests in both builds, then fuzzes the
# scene parser and the mesh reader for a bounded time (FUZZ_SECONDS, default 30):
# - ci: optimised, warnings as errors, with MPI (its tests run `mpirun -np 1, 2, 3 tem run`);
# - sanitize: AddressSanitizer + UndefinedBehaviorSanitizer, without MPI (the serial build,
#   TEM_MPI=OFF, that stays the default).
#
# What the sanitize preset leaves out (CMakePresets.json), and why: the scene runs of
# PhysicsScene.*, the drum's torque balance (Processes.DrumDrive*, a second of a turning drum)
# and the twelve heaviest mesh-cutting tests (revolved parts, torus, approximate cutting of the
# bunny-size meshes). Under ASan at -O1 CGAL's exact arithmetic runs 25-40 times slower than
# optimised, and these alone would take most of CI's time. They all run in the ci build; TEM's
# own code in them (drive, sensors, the plane cutter, the approximate decomposition, the exact
# cut, the mesh reader) stays under the sanitizers through the lighter tests (Processes.*, the
# L-shape, convex hull, gear ring and paper ring meshes, MeshApproxCut.PiecesOfACutPart) and the
# mesh fuzzer.
#
# How the builds are kept fast: Ninja, which starts a library's files while the libraries it
# links still compile (the release preset, which users build, keeps CMake's default generator);
# precompiled headers (Eigen and the standard headers in each library, gtest in the tests;
# CMakeLists.txt); unity builds (eight library files to a unit, six test files, CGAL's two files
# alone: TEM_UNITY_BUILD). The sanitize build has line tables only (-g1, enough for the
# sanitizers' stack traces), no benchmark programs (the ci build compiles them with warnings as
# errors), UBSan off in the tests' own files and in CGAL's exact decomposition (ASan kept), and
# the API compiled once for the static and the shared library. ctest starts the longest tests
# first (tests/test_costs.cmake), and the two fuzzers run side by side. Each phase prints its
# wall time; from a clean clone the whole takes 15-30 minutes on the 2-core machine, whose speed
# drifts over a day.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs=$(nproc)
# Each phase's wall time is printed, so that a run's log says where CI's minutes went.
for preset in ci sanitize; do
  echo "== $preset =="
  start=$SECONDS
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  built=$SECONDS
  ctest --preset "$preset" -j "$jobs"
  echo "== $preset: built in $((built - start)) s, tested in $((SECONDS - built)) s =="
done
echo "== fuzz =="
start=$SECONDS
bash scripts/fuzz.sh
echo "== fuzz: built and run in $((SECONDS - start)) s; all of scripts/test.sh: $SECONDS s =="
