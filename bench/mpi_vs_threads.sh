#!/usr/bin/env bash
# Two ranks against two threads on the 10,000-coin pour (coins_10000) as its cloud
# lands: SEMM at dt 5e-4 (scenes/bench/coins_10000_landing.json, 200 steps) and the penalty
# model at dt 2e-4 (scenes/bench/coins_10000_penalty.json, 500 steps). Time per step at 1
# thread, 2 threads and 2 ranks of one thread each, the exchanges' share and message sizes,
# and the final state's hash (penalty: the same in all three runs; SEMM: the same at 1 and 2
# threads, another at 2 ranks, whose shared solve stops at another point within tolerance).
# Usage: bench/mpi_vs_threads.sh [BUILD_DIR (default build/ci, a TEM_MPI build)] [SCENE...]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/ci}"
shift || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/bench/coins_10000_landing.json scenes/bench/coins_10000_penalty.json)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
tem="$build/tem"
for scene in "${scenes[@]}"; do
  for threads in 1 2; do
    echo "== $scene: $threads thread(s) =="
    "$tem" run "$scene" --out "$out/t$threads" --threads "$threads" --hash 2>&1 |
      grep -E "steps to|per step:|contacts:|sweeps|final|hash"
  done
  echo "== $scene: 2 ranks, 1 thread each =="
  mpirun -np 2 "$tem" run "$scene" --out "$out/r2" --hash 2>&1 |
    grep -E "steps to|ranks:|shared|sweeps|final|hash"
done
