#!/usr/bin/env bash
# Installs, from Debian's archive, every package TEM needs that is missing on this machine.
# Safe to run again: it does nothing when everything is present.
set -euo pipefail
packages=(
  build-essential cmake
  ninja-build            # CI's builds: keeps both cores busy across libraries (scripts/test.sh)
  libeigen3-dev          # vectors, matrices, small dense solves
  nlohmann-json3-dev     # scene files
  libcli11-dev           # command line
  libqhull-dev           # convex hulls of user points
  zlib1g-dev             # compresses the ParaView files
  libgtest-dev           # tests
  libbenchmark-dev       # benchmarks
  clang libclang-rt-14-dev   # libFuzzer for the scene parser (scripts/fuzz.sh)
  python3-meshio         # tests: reads the ParaView output back
  python3-numpy python3-matplotlib   # tools/figures.py
  pybind11-dev python3-pytest python3-dev   # the Python module (python/) and its tests
  libcgal-dev            # checks meshes and cuts them exactly into convex blocks
  libsuitesparse-dev     # CHOLMOD: SEMM by Newton's factorisation of large islands
  libopenblas0-serial    # its BLAS: without it CHOLMOD gets Debian's reference BLAS, and a
                         # settled 1,000-coin pile's Newton step takes 2.6 times as long
  libopenmpi-dev openmpi-bin   # mpirun -np N tem run (TEM_MPI)
  libtrilinos-zoltan-dev       # recursive coordinate bisection of the bodies among the ranks
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: everything TEM needs is installed"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
