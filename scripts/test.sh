#!/usr/bin/env bash
# Installs what is missing, builds TEM twice (optimised with warnings as errors and with MPI,
# whose tests run `mpirun -np 1, 2, 3 tem run`; and with AddressSanitizer +
# UndefinedBehaviorSanitizer, without MPI: the serial build TEM_MPI=OFF that stays the default)
# and runs every test in both builds, then fuzzes the scene parser and the mesh reader for a
# bounded time (FUZZ_SECONDS, default 30).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs=$(nproc)
for preset in ci sanitize; do
  echo "== $preset =="
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j "$jobs"
  ctest --preset "$preset" -j "$jobs"
done
echo "== fuzz =="
bash scripts/fuzz.sh
