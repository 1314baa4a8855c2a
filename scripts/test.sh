#!/usr/bin/env bash
# Installs what is missing, builds TEM twice (optimised with warnings as errors and with MPI,
# whose tests run `mpirun -np 1, 2, 3 tem run`; and with AddressSanitizer +
# UndefinedBehaviorSanitizer, without MPI: the serial build TEM_MPI=OFF that stays the default)
# and runs the tests in both builds, then fuzzes the scene parser and the mesh reader for a
# bounded time (FUZZ_SECONDS, default 30).
#
# The sanitize preset leaves out (CMakePresets.json) the scene runs of PhysicsScene.*, the
# drum's torque balance (Processes.DrumDrive*: a second of a turning drum, 97 s under ASan,
# whose drive, sensor and process code the lighter Processes.* tests keep under the sanitizers;
# 2026-11-27) and the twelve heaviest mesh-cutting tests (revolved parts, torus, approximate cutting of the bunny-size
# meshes): under ASan at -O1 CGAL's exact arithmetic runs 25-40 times slower than optimised, and
# those twelve alone took 30 of the sanitize half's 44 test-minutes (2026-11-26), which put CI
# at 57 minutes. They all run in the ci build; the same code of TEM's own (the plane cutter, the
# approximate decomposition, the exact cut, the mesh reader) stays under the sanitizers through
# the lighter mesh tests (L-shape, convex hull, gear ring, paper ring) and the mesh fuzzer. The
# approximate cutter's pieces (2026-11-27) stay there through MeshApproxCut.PiecesOfACutPart;
# MeshApprox.PiecesThatACutLeavesBecomeBlocks, 1.3 s in ci, took 29 s there and runs in ci only.
#
# The sanitize build is also lighter to compile (2026-11-26: 29 CPU-minutes against 42): line
# tables only (-g1, enough for the sanitizers' stack traces), no benchmark programs (no test
# runs them; the ci build still compiles them with warnings as errors), UBSan off in the tests'
# own files (the engine they call keeps both sanitizers), the API compiled once for the static
# and the shared library, and CGAL's exact decomposition in a file of its own, apart from the
# light self-intersection test that the mesh checks and the mesh fuzz target need.
#
# Both builds use precompiled headers (Eigen and the standard headers in each library, gtest too
# in the tests; CMakeLists.txt). The ci build, 2026-11-27 on the 2-core machine: 535 s wall and
# 928 CPU-seconds with them, 635 s and 1,170 without (-DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON).
#
# Both builds also compile the libraries' files eight to a unit and the tests' six (CMake's unity
# build, TEM_UNITY_BUILD; CGAL's two files alone; each test file's helpers in a namespace named
# after it). Under the sanitizers CGAL's exact decomposition keeps ASan but not UBSan (its
# compile 180 -> 101 s). ctest starts the longest tests first (tests/test_costs.cmake), and the
# two fuzzers run side by side. Clean-clone `.ci/run` on the 2-core machine, 2026-11-27:
#
#   | phase            | before | after |
#   |------------------|--------|-------|
#   | ci build         | 535 s  | 449 s |
#   | ci tests         | 191 s  | 185 s |
#   | sanitize build   | ~900 s | 532 s |
#   | sanitize tests   | 424 s  | 293 s |
#   | fuzz (build+run) | ~175 s | 117 s |
#   | all              | 2,267 s | 1,576 s |
#
# ("~": the run before printed no per-phase times; its total less the phases it did print, and
# the fuzz build timed alone.)
#
# Both presets build with Ninja (ninja-build, scripts/install_deps.sh), which starts a library's
# files while the libraries it links are still compiling; Make finishes each target before the
# next, so one core idled at every library's last file (CGAL's exact decomposition alone is
# 96 s). The ci build from scratch, same tree, one after the other on the 2-core machine
# (2026-11-27): 504 s with Make, 426 s with Ninja. The release preset, which users build, keeps
# CMake's default generator. Clean-clone `.ci/run`, the session before Ninja and after it (with
# the drum's torque balance out of the sanitize tests and the sub-steps resume test lighter):
#
#   | phase            | before  | after   |
#   |------------------|---------|---------|
#   | ci build         | 516 s   | 435 s   |
#   | ci tests         | 210 s   | 206 s   |
#   | sanitize build   | 682 s   | 642 s   |
#   | sanitize tests   | 392 s   | 298 s   |
#   | fuzz (build+run) | 152 s   | 150 s   |
#   | all              | 1,952 s | 1,731 s | The machine's speed drifts over a day: the ci tests, which no
# change here touched, summed 320 and 311 test-seconds in the two runs. A step between them (the
# tests' unity build, the costs, CGAL without UBSan, the fuzzers side by side) took 1,871 s.
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
