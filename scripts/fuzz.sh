#!/usr/bin/env bash
# Builds the fuzz targets with clang (fuzz/) and runs each for a bounded time (FUZZ_SECONDS,
# default 30): the scene parser, starting from every scene file in the repository, and the mesh
# reader and checks, starting from every mesh file in scenes/meshes. Any crash, sanitizer report,
# hang or broken round trip fails the script and leaves the input that did it in build/fuzz/
# (crash-*, timeout-*): rerun it with build/fuzz/fuzz_scene_reader FILE (or fuzz_mesh_reader).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-30}"
cmake -S fuzz -B build/fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/fuzz -j "$(nproc)"
corpus=build/fuzz/corpus
mkdir -p "$corpus"
for f in scenes/*.json scenes/*/*.json tests/scenes/*.json tests/scenes/*/*.json; do
  cp "$f" "$corpus/seed_${f//\//_}"   # one name per path: several dirs hold a coin.json
done
# The mesh target reads its first byte as the format (0 obj, 1 stl, 2 ply, 3 off).
mesh_corpus=build/fuzz/mesh_corpus
mkdir -p "$mesh_corpus"
for f in scenes/meshes/*; do
  case "${f##*.}" in obj) b='\x00' ;; stl) b='\x01' ;; ply) b='\x02' ;; off) b='\x03' ;; *) continue ;; esac
  { printf "$b"; cat "$f"; } >"$mesh_corpus/seed_${f//\//_}"
done
# The two targets run side by side, one core each (libFuzzer uses one), each into a log of its
# own; the script waits for both and fails if either found something.
cd build/fuzz
./fuzz_scene_reader -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
  -dict=../../fuzz/scene.dict -print_final_stats=1 corpus >scene_fuzz.log 2>&1 &
scene_pid=$!
LSAN_OPTIONS="suppressions=$(pwd)/../../fuzz/lsan.supp" ./fuzz_mesh_reader \
  -max_total_time="$seconds" -dict=../../fuzz/mesh.dict -max_len=16384 -timeout=10 \
  -rss_limit_mb=2048 -print_final_stats=1 mesh_corpus >mesh_fuzz.log 2>&1 &
mesh_pid=$!
scene_status=0
mesh_status=0
wait "$scene_pid" || scene_status=$?
wait "$mesh_pid" || mesh_status=$?
# A clean run's last lines hold its statistics; a finding's whole report is shown.
show() {
  echo "-- $1 (build/fuzz/$2) --"
  if [ "$3" -eq 0 ]; then tail -n 12 "$2"; else cat "$2"; fi
}
show "scene reader" scene_fuzz.log "$scene_status"
show "mesh reader" mesh_fuzz.log "$mesh_status"
[ "$scene_status" -eq 0 ] && [ "$mesh_status" -eq 0 ]
