#!/usr/bin/python3
"""TEM and Bullet on the same scenes, alternately, in one run.

For every scene: R rounds of `tem run` then `tem_bullet`, on one temporary copy of the scene (so
both read the same dt and duration), the same number of steps. Prints one table row per scene:
median µs/step of each engine, the ratio Bullet/TEM, how many bodies ended with their centre
outside the container box, and the worst overlap as a percentage of the smallest body size,
measured by TEM's own contact detection for both engines (tem_bullet applies it to Bullet's
states). Standard library only.

  /usr/bin/python3 tools/side_by_side.py [SCENE.json ...] [--steps N] [--dt DT] [--rounds R]
"""
import argparse
import csv
import glob
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def default_scenes():
    # The 100,000-coin pour is a one-off measurement of its own (docs/benchmarks.md): minutes for
    # TEM alone, so it is named on the command line when wanted, never run by default.
    bench = [p for p in sorted(glob.glob(os.path.join(ROOT, "scenes/bench/*.json")))
             if not p.endswith("coins_100000.json")]
    if bench:
        return bench
    return [os.path.join(ROOT, p) for p in ("scenes/paper/coin.json", "scenes/paper/ring_column.json",
                                            "scenes/coin.json", "scenes/ring_column.json")]


def find_bullet_program(given):
    if given:
        return given
    # The release preset's build first, then any other build directory that has it.
    candidates = [os.path.join(ROOT, "build/release/bench/bullet/tem_bullet")]
    candidates += sorted(glob.glob(os.path.join(ROOT, "build/*/bench/bullet/tem_bullet")))
    for c in candidates:
        if os.access(c, os.X_OK):
            return c
    sys.exit("side_by_side: tem_bullet not found; install Bullet (bash scripts/install_bullet.sh), "
             "re-run cmake and build the target tem_bullet, or pass --bullet PATH")


def prepare_scene(scene_path, steps, dt, workdir):
    """The scene as both engines will run it: dt and duration overridden, and TEM's output
    thinned to about ten rows so that writing files hardly counts in its time (Bullet writes
    nothing). Returns (path of the copy, scene dict, steps, output stride in steps)."""
    with open(scene_path) as f:
        scene = json.load(f)
    if dt is not None:
        scene["time_step"] = dt
    dt = scene.get("time_step", 1e-5)
    if steps is None:
        steps = round(scene.get("duration", 1.0) / dt)
    scene["duration"] = steps * dt
    stride = max(1, steps // 10)
    scene.setdefault("output", {})["interval"] = stride * dt
    scene["output"]["paraview"] = False
    scene["output"]["checkpoint_interval"] = 0
    path = os.path.join(workdir, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path, scene, steps, stride


def outside(row, box):
    if box is None:
        return False
    p = [float(row["x"]), float(row["y"]), float(row["z"])]
    return any(p[i] < box["min"][i] or p[i] > box["max"][i] for i in range(3))


def run_tem(tem, scene_file, out_dir, box):
    r = subprocess.run([tem, "run", scene_file, "--out", out_dir], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("side_by_side: tem run failed:\n" + r.stderr)
    m = re.search(r"\(([0-9.e+]+) steps/s, ([0-9.e+]+) us/step\)", r.stderr)
    if not m:
        sys.exit("side_by_side: no speed in tem's output:\n" + r.stderr)
    with open(os.path.join(out_dir, "energy.csv")) as f:
        energy = list(csv.DictReader(f))
    with open(os.path.join(out_dir, "bodies.csv")) as f:
        bodies = list(csv.DictReader(f))
    last_time = bodies[-1]["time"]
    final = [b for b in bodies if b["time"] == last_time]
    return {"us": float(m.group(2)),
            "bodies": len(final),
            "outside": sum(outside(b, box) for b in final),
            "overlap": float(energy[-1]["max_depth"]),
            "overlap_run": max(float(e["max_depth"]) for e in energy)}


def run_bullet(program, scene_file, steps, stride, extra):
    cmd = [program, scene_file, "--steps", str(steps), "--report-every", str(stride)] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("side_by_side: tem_bullet failed:\n" + r.stderr)
    line = [l for l in r.stdout.splitlines() if l.startswith("engine=bullet")][-1]
    v = dict(kv.split("=", 1) for kv in line.split())
    return {"us": float(v["us_per_step"]),
            "bodies": int(v["bodies"]),
            "outside": int(v["outside"]),
            "overlap": float(v["worst_overlap"]),
            "overlap_run": float(v["worst_overlap_run"]),
            "size": float(v["min_body_size"]),
            "sleeping": int(v["sleeping"])}


def dt_text(dt):
    # 1/240 reads better than 0.00416667; 1e-05 stays as it is.
    inverse = 1 / dt
    if float("%g" % dt) != dt and abs(inverse - round(inverse)) < 1e-9 * inverse:
        return "1/%d" % round(inverse)
    return "%g" % dt


def sig(v):
    """Three significant digits, without exponents: 0.48, 47, 40,900."""
    r = float("%.3g" % v)
    return "{:,.0f}".format(r) if r >= 100 else "%.3g" % r


def spread(values):
    return "%s (%s-%s)" % (sig(statistics.median(values)), sig(min(values)), sig(max(values)))


def shown(path):
    rel = os.path.relpath(os.path.abspath(path), ROOT)
    return path if rel.startswith("..") else rel


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", nargs="*", help="default: scenes/bench/*.json, else the paper's two "
                    "scenes in paper and default mode")
    ap.add_argument("--steps", type=int, help="steps per run (default: the scene's duration)")
    ap.add_argument("--dt", type=float, help="time step for both engines (default: the scene's)")
    ap.add_argument("--rounds", type=int, default=3, help="runs of each engine, alternating")
    ap.add_argument("--tem", default=os.path.join(ROOT, "build/release/tem"))
    ap.add_argument("--bullet", help="tem_bullet program (default: found under build/)")
    ap.add_argument("--bullet-args", default="",
                    help="extra tem_bullet options, e.g. '--margin-rel 0.04 --no-sleep'")
    a = ap.parse_args()
    bullet = find_bullet_program(a.bullet)
    scenes = a.scenes or default_scenes()

    print("| scene | bodies | dt | steps | TEM µs/step | Bullet µs/step | Bullet/TEM "
          "| outside TEM/Bullet | overlap % final TEM/Bullet | overlap % max TEM/Bullet |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for scene_path in scenes:
        with tempfile.TemporaryDirectory(prefix="tem_sbs_") as work:
            copy, scene, steps, stride = prepare_scene(scene_path, a.steps, a.dt, work)
            box = scene.get("container")
            tem, bul = [], []
            for r in range(a.rounds):
                tem.append(run_tem(a.tem, copy, os.path.join(work, "out%d" % r), box))
                bul.append(run_bullet(bullet, copy, steps, stride, a.bullet_args.split()))
                print("  %s round %d: TEM %.4g us/step, Bullet %.4g us/step"
                      % (shown(scene_path), r + 1, tem[-1]["us"], bul[-1]["us"]),
                      file=sys.stderr)
            t, b = tem[-1], bul[-1]  # both engines are deterministic: any round's state will do
            tu = [x["us"] for x in tem]
            bu = [x["us"] for x in bul]
            def pct(depth):
                return sig(100 * depth / b["size"])
            print("| %s | %d | %s | %d | %s | %s | %.2f | %d/%d | %s/%s | %s/%s |" % (
                shown(scene_path), t["bodies"], dt_text(scene["time_step"]), steps,
                spread(tu), spread(bu), statistics.median(bu) / statistics.median(tu),
                t["outside"], b["outside"], pct(t["overlap"]), pct(b["overlap"]),
                pct(t["overlap_run"]), pct(b["overlap_run"])), flush=True)


if __name__ == "__main__":
    main()
