#!/usr/bin/python3
"""Largest time step at which a scene stays right.

For each candidate dt (largest first) the scene is copied into a temporary directory with
`time_step` = dt (and `duration` = --duration if given, and `output.interval` as below), run with
`tem run`, and judged from bodies.csv, energy.csv and tem's summary line on stderr:

  inside   every body's centre of mass (bodies.csv x, y, z, every row) lies in the scene's
           `container` box, min <= x <= max on each axis (skipped if the scene has no container);
  overlap  the largest `max_depth` of energy.csv over all rows is < 1 % of the smallest body size;
  energy   `total` of energy.csv never rises from one row to the next by more than
           1e-9 * (|total at the first row| + |potential at the first row|) (round-off allowance).

Body size (what TEM calls body_size: the distance from the centre of mass to the farthest node),
from the shape keys, without building the model, for every body and every fill template
(`fill[i].body.shape`):
  prism   radius r (circumradius), height h:  sqrt(r^2 + (h/2)^2)        (exact)
  box     size [a, b, c]:                     sqrt(a^2 + b^2 + c^2) / 2   (exact)
  ring    radius R (centre line), section_radius rs:  R + rs
          (exact for the node distance: TEM's section node j = 0 lies at R + rs on the radial
          line; TEM's own body_size for a ring, block offset + block bounding radius, is a
          little larger, so 1 % of R + rs is the stricter limit)
  other shapes (convex, compound): not computed; give --size.
The smallest of these is the scene's smallest body size.

Output interval: energy.csv/bodies.csv get a row every max(dt, 1 ms) of simulated time by
default (--interval S to choose another, --every-step for every step); max_depth and the
centres are therefore sampled at those rows only.

Also recorded: tem's `tem run: N steps to t = T s in W s (S steps/s, U us/step)` (U and W).

The largest dt reported is the largest candidate that passes and for which every smaller
candidate tested passes too.

Usage:
  /usr/bin/python3 tools/largest_dt.py SCENE [SCENE ...] [--tem build/release/tem]
      [--dt 1/240,1e-3,...] [--duration S] [--interval S | --every-step] [--size L]
      [--keep DIR] [--markdown]
"""

import argparse
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

DEFAULT_DTS = ["1/240", "1e-3", "5e-4", "2e-4", "1e-4", "5e-5", "2e-5", "1e-5"]
ROUND_OFF = 1e-9
OVERLAP_FRACTION = 0.01
SUMMARY = re.compile(
    r"tem run: (\d+) steps to t = (\S+) s in (\S+) s \((\S+) steps/s, (\S+) us/step\)")


def parse_dt(text):
    text = text.strip()
    if "/" in text:
        num, den = text.split("/")
        return float(num) / float(den)
    return float(text)


def shape_size(shape):
    kind = shape.get("type")
    if kind == "prism":
        return math.hypot(shape["radius"], shape["height"] / 2)
    if kind == "box":
        a, b, c = shape["size"]
        return math.sqrt(a * a + b * b + c * c) / 2
    if kind == "ring":
        return shape["radius"] + shape["section_radius"]
    return None


def smallest_size(scene):
    shapes = [b["shape"] for b in scene.get("bodies", [])]
    shapes += [f["body"]["shape"] for f in scene.get("fill", [])]
    sizes = [shape_size(s) for s in shapes]
    if not sizes or any(s is None for s in sizes):
        return None
    return min(sizes)


def judge(out_dir, container, size):
    result = {}
    # Inside: every centre at every row.
    outside = set()
    with open(os.path.join(out_dir, "bodies.csv"), newline="") as f:
        for row in csv.DictReader(f):
            if container is None:
                continue
            p = (float(row["x"]), float(row["y"]), float(row["z"]))
            lo, hi = container["min"], container["max"]
            if not all(lo[i] <= p[i] <= hi[i] for i in range(3)) or not all(map(math.isfinite, p)):
                outside.add(row["body"])
    result["outside"] = len(outside)
    # Overlap and energy.
    depth = 0.0
    rise = 0.0
    prev = None
    scale = None
    rows = 0
    with open(os.path.join(out_dir, "energy.csv"), newline="") as f:
        for row in csv.DictReader(f):
            rows += 1
            total = float(row["total"])
            d = float(row["max_depth"])
            if not math.isfinite(total) or not math.isfinite(d):
                depth = rise = math.inf
            depth = max(depth, d)
            if scale is None:
                scale = abs(total) + abs(float(row["potential"]))
            if prev is not None:
                rise = max(rise, total - prev)
            prev = total
    result["rows"] = rows
    result["depth"] = depth
    result["depth_pct"] = 100.0 * depth / size
    result["rise"] = rise
    result["rise_rel"] = rise / scale if scale else math.inf
    failed = []
    if result["outside"] > 0:
        failed.append("inside")
    if not depth < OVERLAP_FRACTION * size:
        failed.append("overlap")
    if not rise <= ROUND_OFF * (scale or 0.0):
        failed.append("energy")
    result["failed"] = failed
    return result


def run_one(tem, scene, scene_path, dt, args, work):
    s = json.loads(json.dumps(scene))
    s["time_step"] = dt
    if args.duration is not None:
        s["duration"] = args.duration
    out = s.setdefault("output", {})
    out["paraview"] = False  # only the CSV files are judged
    if args.every_step:
        out["interval"] = dt
    elif args.interval is not None:
        out["interval"] = args.interval
    else:
        out["interval"] = max(dt, 1e-3)
    out["paraview"] = False
    out["checkpoint_interval"] = 0
    tag = "dt_%.6g" % dt
    path = os.path.join(work, tag + ".json")
    with open(path, "w") as f:
        json.dump(s, f, indent=1)
    out_dir = os.path.join(work, tag)
    proc = subprocess.run([tem, "run", path, "--out", out_dir], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    m = SUMMARY.search(proc.stderr)
    # tem writes a row every round(interval / dt) steps (at least 1).
    res = {"dt": dt, "rc": proc.returncode, "every": max(1, round(out["interval"] / dt))}
    if m:
        res["steps"] = int(m.group(1))
        res["t_end"] = float(m.group(2))
        res["wall"] = float(m.group(3))
        res["us_step"] = float(m.group(5))
    else:
        res["steps"] = res["t_end"] = res["wall"] = res["us_step"] = float("nan")
    if proc.returncode != 0 or not os.path.exists(os.path.join(out_dir, "energy.csv")):
        res.update({"failed": ["run (rc %d)" % proc.returncode], "outside": -1, "depth_pct": math.nan,
                    "rise": math.nan, "rise_rel": math.nan, "rows": 0})
        sys.stderr.write(proc.stderr[-2000:])
        return res
    res.update(judge(out_dir, s.get("container"), args.size_value))
    return res


def fmt_dt(dt):
    if abs(dt - 1 / 240) < 1e-15:
        return "1/240"
    return "%g" % dt


def table(name, size, results, largest, markdown):
    head = ["dt", "ok", "failed", "max overlap % of size", "bodies outside",
            "largest energy rise (× scale)", "µs/step", "wall s"]
    lines = []
    for r in results:
        lines.append([
            fmt_dt(r["dt"]),
            "yes" if not r["failed"] else "no",
            ", ".join(r["failed"]) or "-",
            "%.3g" % r["depth_pct"],
            "%d" % r["outside"],
            "%.2g" % r["rise_rel"] if r["rise"] > 0 else "0",
            "%.3g" % r["us_step"],
            "%.3g" % r["wall"],
        ])
    out = []
    out.append("%s  (smallest body size %.6g, overlap limit %.4g)" % (name, size, OVERLAP_FRACTION * size))
    if markdown:
        out.append("| " + " | ".join(head) + " |")
        out.append("|" + "---|" * len(head))
        for l in lines:
            out.append("| " + " | ".join(l) + " |")
    else:
        widths = [max(len(h), *(len(l[i]) for l in lines)) for i, h in enumerate(head)]
        out.append("  ".join(h.ljust(w) for h, w in zip(head, widths)))
        for l in lines:
            out.append("  ".join(c.ljust(w) for c, w in zip(l, widths)))
    coarse = [fmt_dt(r["dt"]) for r in results if r.get("every", 1) > 1]
    if coarse:
        out.append("note: sampled, not every step, at dt %s: the overlap of a landing step can be "
                   "missed (--every-step checks every step)" % ", ".join(coarse))
    if largest is None:
        out.append("largest dt that stays right: none of the candidates")
    else:
        r = largest
        out.append("largest dt that stays right: %s (%d steps to t = %g s in %.3g s, %.3g µs/step)"
                   % (fmt_dt(r["dt"]), r["steps"], r["t_end"], r["wall"], r["us_step"]))
    return "\n".join(out)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scenes", nargs="+")
    p.add_argument("--tem", default="build/release/tem", help="the tem binary")
    p.add_argument("--dt", default=",".join(DEFAULT_DTS),
                   help="comma-separated candidates, largest first (a/b allowed)")
    p.add_argument("--duration", type=float, help="simulated seconds (default: the scene's)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--interval", type=float, help="output interval, s (default max(dt, 1e-3))")
    g.add_argument("--every-step", action="store_true", help="an output row every step")
    p.add_argument("--size", type=float, help="smallest body size (default: from the shapes)")
    p.add_argument("--keep", help="keep the runs' outputs under this directory")
    p.add_argument("--markdown", action="store_true", help="tables in Markdown")
    args = p.parse_args()
    dts = sorted((parse_dt(t) for t in args.dt.split(",")), reverse=True)
    status = 0
    for scene_path in args.scenes:
        with open(scene_path) as f:
            scene = json.load(f)
        size = args.size if args.size is not None else smallest_size(scene)
        if size is None:
            sys.exit("%s: a shape other than prism, box or ring; give --size" % scene_path)
        args.size_value = size
        base = os.path.splitext(os.path.basename(scene_path))[0]
        if args.keep:
            work = os.path.join(args.keep, base)
            os.makedirs(work, exist_ok=True)
        else:
            work = tempfile.mkdtemp(prefix="largest_dt_")
        results = []
        try:
            for dt in dts:
                r = run_one(args.tem, scene, scene_path, dt, args, work)
                results.append(r)
                sys.stderr.write("%s dt %s: %s\n" % (scene_path, fmt_dt(dt), ", ".join(r["failed"]) or "ok"))
        finally:
            if not args.keep:
                shutil.rmtree(work, ignore_errors=True)
        largest = None
        for i, r in enumerate(results):
            if all(not x["failed"] for x in results[i:]):
                largest = r
                break
        if largest is None:
            status = 1
        print(table(scene_path, size, results, largest, args.markdown))
        print()
    return status


if __name__ == "__main__":
    sys.exit(main())
