#!/usr/bin/python3
"""Does a column of coins stand? The tall-pile check (docs/benchmarks.md).

Writes a column of LAYERS hexagonal coins (r 0.15, h 0.1, density 1, friction 0.3), each turned
7 degrees about the vertical from the one below and dropped from 5 um above it, under earth
gravity in a 1 x 1 cm box; runs it for --duration s with the given time step, sub-steps, sweeps,
solver and acceleration; and prints one markdown row: the deepest overlap over the run (% of a
coin's size), the column's height at the end (2 x mean centre height; standing: LAYERS x 0.1 cm),
the fastest coin at the end, the solver's sweeps per step and tem's wall time. Standard library
only.

  /usr/bin/python3 tools/tall_stack.py --layers 10 40 --dt 5e-4 1.25e-4 --sweeps 20 80
  /usr/bin/python3 tools/tall_stack.py --layers 40 --dt 5e-4 --substeps 4 --solver rows
  /usr/bin/python3 tools/tall_stack.py --layers 40 --sweeps 20 160 --duration 1 \
      --acceleration none conjugate_gradients
"""
import argparse
import itertools
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import pile_check  # noqa: E402


def column(layers, dt, substeps, sweeps, solver, duration, acceleration="none"):
    bodies = [{"name": f"c{k}",
               "shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1, "axis": "z"},
               "density": 1.0, "position": [0.5, 0.5, 0.05 + 0.1005 * k],
               "euler_zxz_deg": [7 * k, 0, 0]} for k in range(layers)]
    return {"gravity": "earth", "time_step": dt, "duration": duration,
            "contact": {"model": "semm", "friction": 0.3, "restitution": 0.0, "tolerance": 1e-3,
                        "max_sweeps": sweeps, "substeps": substeps, "solver": solver,
                        "acceleration": acceleration},
            "container": {"min": [0, 0, 0], "max": [1, 1, 0.2 * layers]},
            "bodies": bodies, "output": {"interval": 0.01}}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--layers", type=int, nargs="+", default=[10, 40])
    ap.add_argument("--dt", type=float, nargs="+", default=[5e-4])
    ap.add_argument("--substeps", type=int, nargs="+", default=[1])
    ap.add_argument("--sweeps", type=int, nargs="+", default=[20])
    ap.add_argument("--solver", nargs="+", default=["rows"])
    ap.add_argument("--acceleration", nargs="+", default=["none"],
                    help="contact.acceleration: none, conjugate_gradients")
    ap.add_argument("--duration", type=float, default=0.5)
    ap.add_argument("--tem", default=os.path.join(ROOT, "build/release/tem"))
    args = ap.parse_args()
    print("| layers | dt | sub-steps | sweeps | solver | acceleration | deepest overlap % "
          "| height cm (standing) | fastest at the end cm/s | sweeps per step | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for layers, dt, n, sweeps, solver, acceleration in itertools.product(
                args.layers, args.dt, args.substeps, args.sweeps, args.solver, args.acceleration):
            scene = os.path.join(work, "column.json")
            with open(scene, "w") as f:
                json.dump(column(layers, dt, n, sweeps, solver, args.duration, acceleration), f)
            out = os.path.join(work, "out")
            run = subprocess.run([args.tem, "run", scene, "--out", out],
                                 capture_output=True, text=True)
            if run.returncode != 0:
                sys.exit(run.stderr)
            wall = re.search(r"in ([0-9.]+) s", run.stderr)
            per_step = re.search(r"([0-9.]+) sweeps per step", run.stderr)
            r = pile_check.check(out, 0.1, None)
            print(f"| {layers} | {dt:g} | {n} | {sweeps} | {solver} | {acceleration} "
                  f"| {r['overlap_pct']:.3g} | {r['height']:.4g} ({0.1 * layers:g}) "
                  f"| {r['fastest']:.3g} | {per_step.group(1) if per_step else '?'} "
                  f"| {wall.group(1) if wall else '?'} |")


if __name__ == "__main__":
    main()
