#!/usr/bin/env bash
# Runs the paper's two demonstrations (the falling hexagonal coin, the ring falling onto a
# column) in default mode and in paper mode, draws their figures with tools/figures.py and
# prints a verdict computed from the runs' files. Needs a release build
# (cmake --preset release && cmake --build --preset release -j).
#
# usage: bash scripts/demo.sh          results and figures in out/demo/
set -euo pipefail
cd "$(dirname "$0")/.."

tem=build/release/tem
python=/usr/bin/python3  # Debian's, with numpy and matplotlib (not another python3 on PATH)
out=out/demo
if [ ! -x "$tem" ]; then
  echo "demo: $tem not found; build first: cmake --preset release && cmake --build --preset release -j" >&2
  exit 1
fi
mkdir -p "$out"

# name, scene, snapshot times (those of docs/figures/, shown in README's Pictures)
runs=(
  "default_coin        scenes/coin.json              0 0.06 0.11 0.13 0.16 3"
  "paper_coin          scenes/paper/coin.json        0 0.06 0.11 0.16 1 3"
  "default_ring_column scenes/ring_column.json       0 0.06 0.1 0.15 0.3 4"
  "paper_ring_column   scenes/paper/ring_column.json 0 0.06 0.1 0.15 0.27 0.5"
)

names=()
for line in "${runs[@]}"; do
  read -r name scene times <<<"$line"
  names+=("$name")
  # tools/figures.py needs the ParaView files: run a copy of the scene with them switched on
  # when the scene does not set output.paraview itself.
  if ! "$python" -c "import json, sys; sys.exit(0 if json.load(open('$scene')).get('output', {}).get('paraview') else 1)"; then
    "$python" -c "import json; s = json.load(open('$scene')); s.setdefault('output', {})['paraview'] = True; json.dump(s, open('$out/$name.json', 'w'), indent=1)"
    scene=$out/$name.json
  fi
  printf 'demo: %-20s %s -> %s/%s ... ' "$name" "$scene" "$out" "$name"
  start=$(date +%s%N)
  if ! "$tem" run "$scene" --out "$out/$name" >"$out/$name.log" 2>&1; then
    echo "failed:"; cat "$out/$name.log"; exit 1
  fi
  # shellcheck disable=SC2086  # the times are separate arguments
  "$python" tools/figures.py "$out/$name" --times $times >/dev/null
  ms=$((($(date +%s%N) - start) / 1000000))
  printf '%d.%d s\n' $((ms / 1000)) $((ms % 1000 / 100))
done

echo
echo "Figures (compare with README's Pictures, docs/figures/):"
for name in "${names[@]}"; do
  echo "  $out/$name/figure_snapshots.png  $out/$name/figure_energy.png"
done

echo
echo "Verdict (from each run's bodies.csv, energy.csv and ParaView frames):"
"$python" - "$out" "${names[@]}" <<'EOF'
import csv
import json
import os
import sys

import numpy as np

sys.path.insert(0, "tools")
import figures  # noqa: E402
import tem_vtu  # noqa: E402


def rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def percent(x):
    return f"{x:.0f}" if x >= 10 else f"{x:.2g}"


def verdict(run):
    with open(os.path.join(run, "bodies.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(run, "energy.csv"), newline="") as f:
        total = np.array([float(r["total"]) for r in csv.DictReader(f)])
    names = list(dict.fromkeys(r["body"] for r in rows))
    floor = figures.floor_height(run)
    g = float(np.linalg.norm(json.load(open(os.path.join(run, "scene.json")))["gravity"]))
    below = {n: [] for n in names}  # per frame: how far the lowest point is below the floor
    above = {n: [] for n in names}  # per frame: height of the highest point over the floor
    thickness, reach = {}, {}
    for k, (_, bodies_file, _) in enumerate(figures.read_frames(run)):
        _, arrays, _ = tem_vtu.read_vtu(bodies_file)
        points = arrays["Points"].reshape(-1, 3)
        cells = arrays["connectivity"].reshape(-1, 3)
        for b, n in enumerate(names):
            p = points[np.unique(cells[arrays["body_id"] == b])]
            below[n].append(floor - p[:, 2].min())
            above[n].append(p[:, 2].max() - floor)
            if k == 0:  # thickness: the body's smallest extent along its own axes
                r = next(r for r in rows if r["body"] == n)
                centre = np.array([float(r[c]) for c in "xyz"])
                local = (p - centre) @ rotation([float(r[c]) for c in ("qw", "qx", "qy", "qz")])
                thickness[n] = np.ptp(local, axis=0).min()
                reach[n] = np.linalg.norm(p - centre, axis=1).max()
    where, rest_from = [], []
    for n in names:
        depth = max(below[n]) / thickness[n] * 100
        if min(above[n]) < 0:
            where.append(f"the {n} falls through the floor")
        elif depth <= 1:
            where.append(f"the {n}'s lowest point at most {percent(max(depth, 0))} % of its "
                         "thickness below the floor")
        else:
            where.append(f"the {n}'s lowest point sinks {percent(depth)} % of its thickness into "
                         "the floor")
        # at rest: its fastest point slower than 1e-6 of sqrt(g * thickness) from then on
        times, speeds = [], []
        for r in rows:
            if r["body"] == n:
                times.append(float(r["time"]))
                v = np.linalg.norm([float(r[c]) for c in ("vx", "vy", "vz")])
                w = np.linalg.norm([float(r[c]) for c in ("wx", "wy", "wz")])
                speeds.append(v + w * reach[n])
        moving = np.nonzero(np.array(speeds) >= 1e-6 * np.sqrt(g * thickness[n]))[0]
        rest_from.append(times[moving[-1] + 1] if len(moving) and moving[-1] + 1 < len(times)
                         else None if len(moving) else times[0])
    if None in rest_from:
        rest = f"still moving at t = {times[-1]:g} s"
    else:
        rest = f"at rest from t = {max(rest_from):g} s"
    rise = max(np.diff(total).max(), 0) / abs(total[0])
    energy = ("total energy never rises" if rise < 1e-9 else
              f"total energy rises by up to {percent(rise * 100)} % of its start between frames")
    return "; ".join([", ".join(where), rest, energy]) + "."


out = sys.argv[1]
for name in sys.argv[2:]:
    mode, scene = name.split("_", 1)
    print(f"  {mode} mode, {scene.replace('_', ' + ')}: {verdict(os.path.join(out, name))}")
EOF
