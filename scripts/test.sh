#!/usr/bin/env bash
# Installs what is missing, builds TEM twice (optimised with warnings as errors, and with
# AddressSanitizer + UndefinedBehaviorSanitizer) and runs every test in both builds, then fuzzes
# the scene parser for a bounded time (FUZZ_SECONDS, default 30).
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
