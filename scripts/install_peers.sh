#!/usr/bin/env bash
# Optional: the peer engines of the pour benchmark (tools/pour_bench.py) from Debian's
# archive: ODE (libode-dev, for tem_ode) and Bullet (libbullet-dev, for tem_bullet).
# Not part of install_deps.sh: TEM builds and tests without them. Re-run cmake afterwards so
# that bench/ode/ and bench/bullet/ find them.
set -euo pipefail

wanted=()
for package in libode-dev libbullet-dev pkg-config; do
  if dpkg -s "$package" >/dev/null 2>&1; then
    echo "install_peers: $package is already installed"
  else
    wanted+=("$package")
  fi
done
if [ "${#wanted[@]}" -eq 0 ]; then exit 0; fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${wanted[@]}"
