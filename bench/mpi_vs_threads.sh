#!/usr/bin/env bash
# Two ranks against two threads (issue 14) on the 10,000-coin pour with the penalty model
# (scenes/bench/coins_10000_penalty.json: the distributed engine carries penalty contact so
# far): time per step at 1 thread, 2 threads and 2 ranks of one thread each, the exchanges'
# share and message sizes, and the final state's hash (the same in all three runs).
# Usage: bench/mpi_vs_threads.sh [BUILD_DIR (default build/ci, a TEM_MPI build)] [SCENE]
set -euo pipefail
cd "$(dirname "$0")/.."
tem="${1:-build/ci}/tem"
scene="${2:-scenes/bench/coins_10000_penalty.json}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
for threads in 1 2; do
  echo "== $threads thread(s) =="
  "$tem" run "$scene" --out "$out/t$threads" --threads "$threads" --hash 2>&1 |
    grep -E "steps to|per step:|contacts:|hash"
done
echo "== 2 ranks, 1 thread each =="
mpirun -np 2 "$tem" run "$scene" --out "$out/r2" --hash 2>&1 | grep -E "steps to|ranks:|hash"
