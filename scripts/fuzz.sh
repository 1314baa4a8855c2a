#!/usr/bin/env bash
# Builds the scene-parser fuzz target with clang (fuzz/) and runs it for a bounded time
# (FUZZ_SECONDS, default 30), starting from every scene file in the repository. Any crash,
# sanitizer report, hang or broken round trip fails the script and leaves the input that did it
# in build/fuzz/ (crash-*, timeout-*): rerun it with build/fuzz/fuzz_scene_reader FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
cmake -S fuzz -B build/fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/fuzz -j "$(nproc)"
corpus=build/fuzz/corpus
mkdir -p "$corpus"
for f in scenes/*.json scenes/*/*.json tests/scenes/*.json tests/scenes/*/*.json; do
  cp "$f" "$corpus/seed_${f//\//_}"   # one name per path: several dirs hold a coin.json
done
cd build/fuzz
./fuzz_scene_reader -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
  -dict=../../fuzz/scene.dict -print_final_stats=1 corpus 2>&1 | tail -n 12
