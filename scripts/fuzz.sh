#!/usr/bin/env bash
# Builds the fuzz targets with clang (fuzz/) and runs each for a bounded time (FUZZ_SECONDS,
# default 30): the scene parser, starting from every scene file in the repository, and the mesh
# reader and checks, starting from every mesh file in scenes/meshes. Any crash, sanitizer report,
# hang or broken round trip fails the script and leaves the input that did it in build/fuzz/
# (crash-*, timeout-*): rerun it with build/fuzz/fuzz_scene_reader FILE (or fuzz_mesh_reader).
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
cd ../..

# The mesh target reads its first byte as the format (0 obj, 1 stl, 2 ply, 3 off).
mesh_corpus=build/fuzz/mesh_corpus
mkdir -p "$mesh_corpus"
for f in scenes/meshes/*; do
  case "${f##*.}" in obj) b='\x00' ;; stl) b='\x01' ;; ply) b='\x02' ;; off) b='\x03' ;; *) continue ;; esac
  { printf "$b"; cat "$f"; } >"$mesh_corpus/seed_${f//\//_}"
done
cd build/fuzz
LSAN_OPTIONS="suppressions=$(pwd)/../../fuzz/lsan.supp" ./fuzz_mesh_reader -max_total_time="$seconds" -dict=../../fuzz/mesh.dict -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 mesh_corpus 2>&1 | tail -n 12
