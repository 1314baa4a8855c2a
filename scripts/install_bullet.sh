#!/usr/bin/env bash
# Optional: Bullet from Debian's archive, for tem_bullet and tools/side_by_side.py.
# Not part of install_deps.sh: TEM builds and tests without it. Re-run cmake afterwards so that
# bench/bullet/CMakeLists.txt finds it.
set -euo pipefail

if dpkg -s libbullet-dev >/dev/null 2>&1; then
  echo "install_bullet: libbullet-dev is already installed"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends libbullet-dev pkg-config
