#!/usr/bin/python3
"""Measures a run of scenes/processes/shaker.json (a bed of large and small grains on a plate
that oscillates vertically).

usage: /usr/bin/python3 tools/shaker_check.py [RUN_DIR] [--tem build/release/tem]
           [--python DIR] [--scene scenes/processes/shaker.json] [--run] [--plot PNG]

Running (with --run, or when RUN_DIR has no bodies.csv; RUN_DIR defaults to /tmp/tem_shaker):
  with --python DIR (a directory holding TEM's Python module, tem.*.so), the scene is run
  through the module: sim.record(RUN_DIR) writes the same files as `tem run`, and after every
  step the energies are read, so RUN_DIR/driven_energy.csv gets `step,time,total,driven_work`
  (total: kinetic + potential of the free bodies; driven_work: the work the plate has done on
  them since the start); without --python, `TEM run SCENE --out RUN_DIR --threads 1`
  (energy.csv's driven_work is per output row, not per step, so the step-by-step energy check
  is skipped). --duration shortens the
  Python run (the energy check step by step costs as much as the run).

Reports, from RUN_DIR's scene.json and bodies.csv (and driven_energy.csv when present):
  - the plate's motion: its z against z0 + A sin(2 pi f (t - start)) after `start` (and z0
    before), the largest difference;
  - segregation: the mean height above the plate's rest top of the large and of the small
    grains (fills named large and small) against time, every 0.2 s and over the last 0.4 s,
    and the large grains' mean rank (0 = lowest grain, 1 = highest);
  - energy: the largest rise of (total - driven_work) over one step, against m g x 1 cm of
    all grains (it must never rise: the plate's work is the only energy put in);
--plot writes the mean heights of both sizes against time (docs/processes/shaker.md's figure).
Needs only Debian's python3-numpy (python3-matplotlib for --plot).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np

G = 980.665


def run_python(module_dir, scene, out, duration=None):
    sys.path.insert(0, module_dir)
    import tem  # noqa: E402
    with open(scene) as fh:
        d = json.load(fh)
    if duration:
        d["duration"] = duration
    sim = tem.Simulation.from_dict(d)
    sim.record(out)
    n = sim.total_steps
    with open(os.path.join(out, "driven_energy.csv"), "w") as f:
        f.write("step,time,total,driven_work\n")
        e = sim.energies()
        f.write(f"0,{sim.time!r},{e['total']!r},{e['driven_work']!r}\n")
        for k in range(1, n + 1):
            sim.step()
            e = sim.energies()
            f.write(f"{k},{sim.time!r},{e['total']!r},{e['driven_work']!r}\n")
    sim.finish_recording()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir", nargs="?", default="/tmp/tem_shaker")
    ap.add_argument("--tem", default="build/release/tem", help="the TEM binary")
    ap.add_argument("--python", help="directory of TEM's Python module (energy check)")
    ap.add_argument("--scene", default="scenes/processes/shaker.json")
    ap.add_argument("--run", action="store_true")
    ap.add_argument("--duration", type=float, help="with --python: run only this long (s)")
    ap.add_argument("--plot", help="PNG of mean heights vs time")
    args = ap.parse_args()
    d = args.run_dir
    if args.run or not os.path.exists(os.path.join(d, "bodies.csv")):
        os.makedirs(d, exist_ok=True)
        if args.python:
            run_python(args.python, args.scene, d, args.duration)
        else:
            subprocess.run([args.tem, "run", args.scene, "--out", d, "--threads", "1"],
                           check=True)

    scene = json.load(open(os.path.join(d, "scene.json")))
    plate = next(b for b in scene["bodies"] if "motion" in b)
    mo = plate["motion"]
    A = mo["oscillation"]["amplitude"][2]
    f = mo["oscillation"]["frequency"]
    start = mo.get("start", 0.0)
    z0 = plate["position"][2]
    top0 = z0 + plate["shape"]["size"][2] / 2
    gamma = A * (2 * np.pi * f) ** 2 / G
    print(f"plate: A = {A} cm, f = {f} Hz, Gamma = A (2 pi f)^2 / g = {gamma:.3f}, "
          f"shaking from {start} s")

    t_plate, z_plate = [], []
    heights = {}  # time -> (names, z)
    with open(os.path.join(d, "bodies.csv")) as fh:
        for r in csv.DictReader(fh):
            t = float(r["time"])
            if r["body"] == plate["name"]:
                t_plate.append(t)
                z_plate.append(float(r["z"]))
            else:
                heights.setdefault(t, ([], []))
                heights[t][0].append(r["body"])
                heights[t][1].append(float(r["z"]))
    t_plate, z_plate = np.array(t_plate), np.array(z_plate)
    ph = np.where(t_plate > start, 2 * np.pi * f * (t_plate - start), 0.0)
    expect = z0 + A * np.sin(ph)
    err = np.abs(z_plate - expect)
    print(f"plate z vs z0 + A sin(2 pi f (t - start)) at {len(t_plate)} output rows: largest "
          f"difference {err.max():.2e} cm ({err.max() / A:.1e} of A)")

    times = np.array(sorted(heights))
    large_m, small_m, rank = [], [], []
    for t in times:
        names, z = heights[t]
        z = np.array(z) - top0
        is_large = np.array([n.startswith("large_") for n in names])
        large_m.append(z[is_large].mean())
        small_m.append(z[~is_large].mean())
        order = np.argsort(np.argsort(z))
        rank.append((order[is_large] / (len(z) - 1)).mean())
    large_m, small_m, rank = map(np.array, (large_m, small_m, rank))
    print("time (s)  large mean z  small mean z  large - small  large's mean rank  (cm above "
          "the plate's rest top)")
    for t in np.arange(0, times[-1] + 1e-9, 0.2):
        i = np.argmin(np.abs(times - t))
        print(f"{times[i]:8.3f}  {large_m[i]:12.3f}  {small_m[i]:12.3f}  "
              f"{large_m[i] - small_m[i]:13.3f}  {rank[i]:17.3f}")
    last = times >= times[-1] - 0.4
    first = (times >= start - 0.1) & (times <= start)
    print(f"settled before shaking ({start - 0.1:.1f}-{start:.1f} s): large {large_m[first].mean():.3f}, "
          f"small {small_m[first].mean():.3f}, rank {rank[first].mean():.3f}; last 0.4 s: "
          f"large {large_m[last].mean():.3f}, small {small_m[last].mean():.3f}, "
          f"rank {rank[last].mean():.3f}; cycles of shaking {f * (times[-1] - start):.0f}")

    path = os.path.join(d, "driven_energy.csv")
    if os.path.exists(path):
        e = np.loadtxt(path, delimiter=",", skiprows=1)
        net = e[:, 2] - e[:, 3]
        rise = np.diff(net)
        scale = None
        # all grains' m g x 1 cm: the mass from the fills' shapes (boxes) and densities
        mass = 0.0
        for fl in scene["fill"]:
            s = fl["body"]["shape"]
            if s["type"] == "box":
                mass += fl["count"] * fl["body"].get("density", 1.0) * np.prod(s["size"])
        scale = mass * G
        i = np.argmax(rise)
        print(f"energy: total - driven_work over {len(rise)} steps: largest rise over one step "
              f"{rise.max():.3e} (step {i + 1}, t = {e[i + 1, 1]:.4f} s) = {rise.max() / scale:.1e} "
              f"of m g x 1 cm ({scale:.1f}); steps with a rise {np.sum(rise > 0)}; plate's work "
              f"{e[-1, 3]:.1f}, dissipated {e[-1, 3] - (e[-1, 2] - e[0, 2]):.1f} "
              f"(= {(e[-1, 3] - (e[-1, 2] - e[0, 2])) / (e[-1, 1] - start):.0f} erg/s)")
    else:
        print("energy: no driven_energy.csv (run with --python to check total - driven_work)")

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.6))
        shown = times >= start - 0.1  # from the settled bed on (the pour is off the scale)
        ax.plot(times[shown], large_m[shown], label="large grains (mean)", color="#b5523b")
        ax.plot(times[shown], small_m[shown], label="small grains (mean)", color="#c8a24a")
        ax2 = ax.twinx()
        ax2.plot(times[shown], rank[shown], color="0.4", lw=1, ls="--",
                 label="large grains' mean rank (right)")
        ax2.set_ylim(0, 1)
        ax2.set_ylabel("mean rank of the large (0 lowest, 1 highest)")
        ax2.legend(loc="upper right", fontsize=8)
        ax.axvline(start, color="0.6", ls=":", lw=1)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("height above the plate (cm)")
        ax.set_title(f"A = {A} cm, f = {f} Hz, $\\Gamma$ = {gamma:.2f}")
        ax.set_ylim(0, 1.6)
        ax.legend(loc="upper left", fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    sys.exit(main())
