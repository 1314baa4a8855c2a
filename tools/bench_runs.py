#!/usr/bin/env python3
"""The `tem run` profile: runs scenes as a user would and prints, per scene and thread
count, microseconds per step, body-steps per second, the split among the stages of the step,
contact patches per step, time per patch, solver sweeps and peak memory (the process's maximum
resident set, from wait4).

  /usr/bin/python3 tools/bench_runs.py [SCENES...] [--duration S] [--threads 1 2] [--tem PATH]

Default scenes: the paper's two, the two default-mode ones, and the piles in scenes/bench/.
`--duration` shortens every scene (piles of thousands of coins take minutes per simulated
second). Each run writes its output into a temporary directory (output every 10 ms), so writing
files costs little next to the steps.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SCENES = ["scenes/paper/coin.json", "scenes/paper/ring_column.json", "scenes/coin.json",
                  "scenes/ring_column.json", "scenes/bench/coins_100.json",
                  "scenes/bench/coins_1000.json", "scenes/bench/coins_4000.json",
                  "scenes/bench/coins_10000.json"]

SUMMARY = re.compile(r"tem run: (\d+) steps to t = (\S+) s in (\S+) s \((\S+) steps/s, (\S+) us/step\)")
STAGES = re.compile(r"broad phase (\S+) us, narrow phase \+ patches (\S+) us, forces (\S+) us, "
                    r"integration (\S+) us")
SOLVER = re.compile(r"contact solver: (\S+) sweeps per step on average, (\d+) at most, (\d+) steps")
CONTACTS = re.compile(r"contacts: (\S+) patches and (\S+) points per step on average, (\S+) us per patch")


def body_count(scene):
    return len(scene.get("bodies", [])) + sum(f["count"] for f in scene.get("fill", []))


def run(tem, scene_path, duration, threads):
    with open(scene_path) as f:
        scene = json.load(f)
    if duration:
        scene["duration"] = duration
    scene.setdefault("output", {})["interval"] = max(0.01, scene["time_step"])
    scene["output"]["paraview"] = False  # the step is measured, not the file writing
    scene["output"]["checkpoint_interval"] = 0
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "scene.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        proc = subprocess.Popen([tem, "run", path, "--out", os.path.join(tmp, "out"),
                                 "--threads", str(threads)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        err = proc.stderr.read()
        _, status, usage = os.wait4(proc.pid, 0)
    if status != 0:
        sys.exit(f"{scene_path}: tem run failed:\n{err}")
    steps, t, wall, _, us = SUMMARY.search(err).groups()
    broad, narrow, forces, integrate = STAGES.search(err).groups()
    sweeps = SOLVER.search(err).group(1)
    patches, points, us_patch = CONTACTS.search(err).groups()
    bodies = body_count(scene)
    return {"scene": os.path.relpath(scene_path, ROOT), "bodies": bodies, "dt": scene["time_step"],
            "threads": threads, "steps": int(steps), "t": float(t), "wall": float(wall),
            "us_step": float(us), "body_steps_s": bodies * int(steps) / float(wall),
            "broad": float(broad), "narrow": float(narrow), "forces": float(forces),
            "integrate": float(integrate), "patches": float(patches), "us_patch": float(us_patch),
            "sweeps": float(sweeps), "rss_mb": usage.ru_maxrss / 1024}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="*")
    parser.add_argument("--duration", type=float, help="simulated seconds per scene")
    parser.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--tem", default=os.path.join(ROOT, "build/release/tem"))
    args = parser.parse_args()
    scenes = [os.path.join(ROOT, s) if not os.path.isabs(s) and not os.path.exists(s) else s
              for s in (args.scenes or DEFAULT_SCENES)]
    header = ("scene", "bodies", "dt", "thr", "steps", "t [s]", "wall [s]", "us/step",
              "body-steps/s", "broad", "narrow", "forces", "integr.", "patches", "us/patch",
              "sweeps", "peak MB")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for scene in scenes:
        for threads in args.threads:
            r = run(args.tem, scene, args.duration, threads)
            print(f"| {r['scene']} | {r['bodies']} | {r['dt']:g} | {threads} | {r['steps']} | "
                  f"{r['t']:g} | {r['wall']:.1f} | {r['us_step']:.1f} | {r['body_steps_s']:.3g} | "
                  f"{r['broad']:.1f} | {r['narrow']:.1f} | {r['forces']:.1f} | "
                  f"{r['integrate']:.1f} | {r['patches']:.1f} | {r['us_patch']:.2f} | "
                  f"{r['sweeps']:.1f} | {r['rss_mb']:.0f} |", flush=True)


if __name__ == "__main__":
    main()
