#!/usr/bin/python3
"""Angle of repose of a poured heap (scenes/processes/heap.json) against grain friction and
rolling resistance.

For each (friction, rolling_resistance) of the grid, writes a copy of the scene with the grain
material changed (`materials.grain`), runs `tem run` on it (one at a time, one thread), and
measures from bodies.csv:

  angle     the angle of repose at the end of the pour (T_POUR + SETTLE s) and 1 s later.
            Method: of the grains present (centres above the base), a grain is a surface
            grain when no other grain's centre within 0.7 d horizontally lies more than 0.2 d
            higher (d: the grain size, the mean extent of the template). r is the distance from
            the heap's axis (the vertical through the grains' mean x, y); R, the heap's radius,
            the 95th percentile of r over all grains. The angle is atan of minus the slope of a
            least-squares line z = a - r tan(theta) through the surface grains with
            0.25 R <= r <= 0.85 R (the flanks: the peak and the toe left out). The spread
            printed with it is the standard deviation of the same fit made in each of 6
            azimuthal sectors.
  creep     the largest speed of any grain (and the largest |omega| * d/2) over the second
            after the end of the pour, from every row of bodies.csv (output.interval 0.01 s);
            and the largest speed at the last row.
  cone      atan(H / R), H the highest grain centre, R as above: a cruder second measure of
            the same angle (a cone through the top grain and the toe).
  lost      grains that rolled off the base (removed.csv).

Writes a table (stdout and, with --table, a Markdown file), results as JSON (--json), and the
figure docs/figures/processes_heap_angles.png (with --figure).

Usage:
  /usr/bin/python3 tools/repose.py [--tem /tmp/tem-repose] [--work /tmp/repose]
      [--friction 0.2 0.4 0.7] [--rolling 0 0.05 0.15] [--only-analyse]
      [--json FILE] [--table FILE] [--figure FILE] [--tight]

--tight runs with contact.tolerance 1e-6 and max_sweeps 200 (the solver-convergence check).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "processes", "heap.json")

SETTLE = 0.5   # s after the inlet's last copy before "the end of the pour"
HOLD = 1.0     # s the heap must keep its angle


def pour_times(scene, run_dir=None):
    """t_stop: when the inlet's last copy is due (count / rate); t_in: the first output row at
    which every copy is in (a copy that finds no room waits and comes late; the outlet's
    removals counted as in); the end of the pour is t_in + SETTLE, and the hold ends HOLD s
    later."""
    inlet = scene["inlets"][0]
    t_stop = inlet.get("start", 0.0) + inlet["count"] / inlet["rate"]
    t_in = t_stop
    if run_dir is not None:
        t_in = first_full_row(run_dir, inlet["count"])
    return t_stop, t_in + SETTLE, t_in + SETTLE + HOLD


def first_full_row(run_dir, count):
    """Time of the first row of bodies.csv at which count grains exist or were removed."""
    removed = []
    rem = os.path.join(run_dir, "removed.csv")
    if os.path.exists(rem):
        removed = sorted(float(r["time"]) for r in csv.DictReader(open(rem)))
    seen = {}
    with open(os.path.join(run_dir, "bodies.csv")) as f:
        next(f)
        for line in f:
            t, name = line.split(",", 2)[:2]
            if name.startswith("grain_"):
                seen[t] = seen.get(t, 0) + 1
    for t in sorted(seen, key=float):
        gone = sum(1 for r in removed if r <= float(t))
        if seen[t] + gone >= count:
            return float(t)
    raise RuntimeError(f"{run_dir}: the inlet never finished (extend the run)")


def grain_size(scene):
    pts = np.array(scene["inlets"][0]["body"]["shape"]["points"])
    return float(np.mean(pts.max(axis=0) - pts.min(axis=0)))


def read_bodies(path):
    names, cols = [], []
    with open(path) as f:
        reader = csv.reader(f)
        header = next(reader)
        for row in reader:
            names.append(row[1])
            cols.append([float(row[i]) for i in (0, 2, 3, 4, 9, 10, 11, 12, 13, 14)])
    a = np.array(cols)
    grain = np.array([n.startswith("grain_") for n in names])
    keys = ["t", "x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz"]
    out = {k: a[grain, i] for i, k in enumerate(keys)}
    out["name"] = np.array(names)[grain]
    return out


def angle_at(b, t, d, sectors=6):
    """Angle of repose (deg) of the heap at row time t, its spread over sectors, R, height."""
    m = (np.abs(b["t"] - t) < 1e-7) & (b["z"] > 0.0)
    x, y, z = b["x"][m], b["y"][m], b["z"][m]
    cx, cy = x.mean(), y.mean()
    r = np.hypot(x - cx, y - cy)
    phi = np.arctan2(y - cy, x - cx)
    R = np.percentile(r, 95)
    # a surface grain: no other centre within 0.7 d horizontally lies more than 0.2 d higher
    h = np.hypot(x[:, None] - x[None, :], y[:, None] - y[None, :])
    covered = ((h < 0.7 * d) & (z[None, :] > z[:, None] + 0.2 * d)).any(axis=1)
    idx = np.flatnonzero(~covered)
    rs, zs = r[idx], z[idx]
    ss = np.floor((phi[idx] + math.pi) / (2 * math.pi) * sectors).astype(int) % sectors
    flank = (rs >= 0.25 * R) & (rs <= 0.85 * R)
    slope = np.polyfit(rs[flank], zs[flank], 1)[0]
    per = []
    for s in range(sectors):
        k = flank & (ss == s)
        if k.sum() >= 3:
            per.append(math.degrees(math.atan(-np.polyfit(rs[k], zs[k], 1)[0])))
    return (math.degrees(math.atan(-slope)), float(np.std(per)), float(R), float(z.max()),
            int(m.sum()), (rs, zs, flank))


def creep(b, t0, t1, d):
    """Over [t0, t1]: the largest grain speed, the largest |omega| d/2, the largest speed at t1,
    how many grains ever exceed 1e-3 cm/s, and the largest displacement of a grain's centre
    from t0 to t1 (a rattling grain has speed but no drift)."""
    m = (b["t"] >= t0 - 1e-7) & (b["t"] <= t1 + 1e-7)
    v = np.sqrt(b["vx"] ** 2 + b["vy"] ** 2 + b["vz"] ** 2)
    w = np.sqrt(b["wx"] ** 2 + b["wy"] ** 2 + b["wz"] ** 2) * d / 2
    last = np.abs(b["t"] - t1) < 1e-7
    first = np.abs(b["t"] - t0) < 1e-7
    fast = len(set(b["name"][m & (v > 1e-3)]))
    p0 = {n: (x, y, z) for n, x, y, z in zip(b["name"][first], b["x"][first], b["y"][first],
                                             b["z"][first])}
    drift = 0.0
    for n, x, y, z in zip(b["name"][last], b["x"][last], b["y"][last], b["z"][last]):
        if n in p0:
            drift = max(drift, math.dist((x, y, z), p0[n]))
    return float(v[m].max()), float(w[m].max()), float(v[last].max()), fast, drift


def analyse(run_dir, scene):
    d = grain_size(scene)
    t_stop, t_end, t_hold = pour_times(scene, run_dir)
    b = read_bodies(os.path.join(run_dir, "bodies.csv"))
    a0 = angle_at(b, t_end, d)
    a1 = angle_at(b, t_hold, d)
    vmax, wmax, vlast, fast, drift = creep(b, t_end, t_hold, d)
    lost = 0
    rem = os.path.join(run_dir, "removed.csv")
    if os.path.exists(rem):
        lost = sum(1 for _ in open(rem)) - 1
    depth = 0.0
    with open(os.path.join(run_dir, "energy.csv")) as f:
        for row in csv.DictReader(f):
            depth = max(depth, float(row["max_depth"]))
    return {"angle_end": a0[0], "spread_end": a0[1], "angle_hold": a1[0], "spread_hold": a1[1],
            "R": a1[2], "height": a1[3], "cone": math.degrees(math.atan(a1[3] / a1[2])), "grains": a1[4], "lost": lost,
            "vmax_hold": vmax, "wmax_hold": wmax, "v_last": vlast,
            "grains_over_1e-3": fast, "drift": drift, "max_depth": depth,
            "t_end": t_end, "t_hold": t_hold}


def last_time(run_dir):
    with open(os.path.join(run_dir, "energy.csv")) as f:
        return float(f.readlines()[-1].split(",")[0])


def run_case(args, mu, mur, tight=False):
    scene = json.load(open(SCENE))
    if args.seed is not None:
        scene["inlets"][0]["seed"] = args.seed
    scene["materials"]["grain"]["friction"] = mu
    scene["materials"]["grain"]["rolling_resistance"] = mur
    t_stop, _, _ = pour_times(scene)
    scene["duration"] = round(1.3 * t_stop + SETTLE + HOLD, 6)   # extended below if need be
    tag = f"mu{mu:g}_mur{mur:g}" + ("_tight" if tight else "")
    if args.seed is not None:
        tag += f"_seed{args.seed}"
    if tight:
        scene["contact"]["tolerance"] = 1e-6
        scene["contact"]["max_sweeps"] = 200
    out = os.path.join(args.work, tag)
    path = os.path.join(args.work, tag + ".json")
    logf = os.path.join(args.work, tag + ".log")
    if not args.only_analyse:
        os.makedirs(args.work, exist_ok=True)
        done = os.path.exists(os.path.join(out, "checkpoint.bin")) and os.path.exists(path)
        if done:   # a finished run of this case: keep it (extend it below if need be)
            scene["duration"] = json.load(open(path))["duration"]
        while True:
            if done:
                try:
                    _, _, need = pour_times(scene, out)
                except RuntimeError:
                    need = scene["duration"] + 0.5
                if need <= scene["duration"] + 1e-9:
                    break
                scene["duration"] = round(need, 6)   # the inlet came late: run on (--resume)
            target = scene["duration"]
            reached = last_time(out) if done else 0.0
            while reached < target - 1e-9:   # in pieces of --segment s (each its own process)
                scene["duration"] = round(min(target, reached + args.segment), 6)
                json.dump(scene, open(path, "w"), indent=1)
                t0 = time.time()
                cmd = ["nice", "-n", "5", args.tem, "run", path, "--out", out, "--threads", "1"]
                if reached > 0:
                    cmd.append("--resume")
                with open(logf, "a") as log:
                    subprocess.run(cmd, check=True, stdout=log, stderr=subprocess.STDOUT)
                print(f"  {tag}: to t = {scene['duration']:g} s, {time.time() - t0:.0f} s wall",
                      file=sys.stderr)
                reached = scene["duration"]
            done = True
    else:
        scene["duration"] = json.load(open(path))["duration"]
    res = analyse(out, scene)
    res.update({"friction": mu, "rolling_resistance": mur, "tight": tight, "run": out,
                "seed": scene["inlets"][0]["seed"]})
    if os.path.exists(logf):
        for line in open(logf):
            if line.startswith("tem run:") and "steps/s" in line:
                res["log"] = line.strip()
            if "contact solver" in line and "solver" not in res:  # the averages' line
                res["solver"] = line.strip()
    return res


def figure(results, path, scene):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4))
    rolls = sorted({r["rolling_resistance"] for r in results if not r["tight"]})
    mus = np.linspace(0.05, 1.0, 100)
    for mur in rolls:
        rs = sorted((r for r in results if r["rolling_resistance"] == mur and not r["tight"]),
                    key=lambda r: r["friction"])
        mu = [r["friction"] for r in rs]
        e = ax.errorbar(mu, [r["angle_end"] for r in rs], yerr=[r["spread_end"] for r in rs],
                        marker="o", capsize=3, label=f"$\\mu_r$ = {mur:g}: flank fit")
        ax.plot(mu, [r["cone"] for r in rs], "s--", mfc="none", color=e[0].get_color(),
                label=f"$\\mu_r$ = {mur:g}: atan(H/R)")
        ax.plot(mu, [r["angle_hold"] for r in rs], "k+", ms=9)
    ax.plot([], [], "k+", label="flank fit 1 s later")
    ax.set_xlabel("grain friction $\\mu_s$ (grain-grain)")
    ax.set_ylabel("angle of repose (deg)")
    ax.set_title("Poured heap of angular grains (scenes/processes/heap.json)", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def side_view(run_dir, scene, path):
    """Side view of one heap at 1 s after the end of the pour: every grain's centre (x, z), and
    the surface grains and flank fit of angle_at against r (right panel)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    d = grain_size(scene)
    _, t_end, t_hold = pour_times(scene, run_dir)
    b = read_bodies(os.path.join(run_dir, "bodies.csv"))
    ang, spread, R, H, n, (rs, zs, flank) = angle_at(b, t_hold, d)
    m = (np.abs(b["t"] - t_hold) < 1e-7) & (b["z"] > 0.0)
    x, y, z = b["x"][m], b["y"][m], b["z"][m]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.2), gridspec_kw={"width_ratios": [3, 2]})
    sc = a1.scatter(x - x.mean(), z, c=y - y.mean(), s=14, cmap="viridis", edgecolors="none")
    fig.colorbar(sc, ax=a1, label="y (cm)", shrink=0.6)
    a1.set_aspect("equal")
    a1.set_xlabel("x (cm)")
    a1.set_ylabel("z (cm)")
    a1.set_title(f"grain centres at t = {t_hold:g} s (side view, {n} grains)", fontsize=9)
    a2.plot(rs[~flank], zs[~flank], ".", color="0.6", label="surface grains")
    a2.plot(rs[flank], zs[flank], ".", color="C0", label="surface grains on the flank (0.25 R to 0.85 R)")
    k = np.polyfit(rs[flank], zs[flank], 1)
    rr = np.array([0.25 * R, 0.85 * R])
    a2.plot(rr, np.polyval(k, rr), "r-", label=f"fit: {ang:.1f} deg")
    a2.set_xlabel("distance from the axis r (cm)")
    a2.set_ylabel("z of surface grains (cm)")
    a2.legend(fontsize=7, loc="upper right", framealpha=0.6)
    a2.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--tem", default="/tmp/tem-repose")
    p.add_argument("--work", default="/tmp/repose")
    p.add_argument("--friction", type=float, nargs="+", default=[0.2, 0.4, 0.7])
    p.add_argument("--rolling", type=float, nargs="+", default=[0.0, 0.05, 0.15])
    p.add_argument("--only-analyse", action="store_true", help="reuse the runs in --work")
    p.add_argument("--tight", action="store_true",
                   help="tolerance 1e-6, max_sweeps 200 (each case of the grid)")
    p.add_argument("--segment", type=float, default=1e9,
                   help="run in pieces of this many simulated seconds (--resume between)")
    p.add_argument("--seed", type=int, help="the inlet's seed (default: the scene's)")
    p.add_argument("--json")
    p.add_argument("--table")
    p.add_argument("--figure")
    p.add_argument("--side", nargs=2, metavar=("RUN_DIR", "PNG"),
                   help="draw the side view of one run and exit")
    args = p.parse_args()
    scene = json.load(open(SCENE))
    if args.side:
        side_view(args.side[0], scene, args.side[1])
        return
    results = []
    for mur in args.rolling:
        for mu in args.friction:
            results.append(run_case(args, mu, mur, args.tight))
    head = ("| mu_s | mu_r | angle end of pour (deg) | angle 1 s later (deg) | R (cm) | height (cm) "
            "| atan(H/R) (deg) | grains (lost) | max grain speed over 1 s (cm/s) | max |w| d/2 (cm/s) "
            "| speed at the end (cm/s) | grains > 1e-3 cm/s | largest drift over 1 s (cm) |")
    lines = [head, "|" + "---|" * 13]
    for r in results:
        lines.append(
            f"| {r['friction']:g} | {r['rolling_resistance']:g}"
            f"{' (tight)' if r['tight'] else ''} | {r['angle_end']:.1f} ± {r['spread_end']:.1f} "
            f"| {r['angle_hold']:.1f} ± {r['spread_hold']:.1f} | {r['R']:.2f} | {r['height']:.2f} "
            f"| {r['cone']:.1f} | {r['grains']} ({r['lost']}) | {r['vmax_hold']:.2g} | {r['wmax_hold']:.2g} "
            f"| {r['v_last']:.2g} | {r['grains_over_1e-3']} | {r['drift']:.2g} |")
    print("\n".join(lines))
    if args.table:
        open(args.table, "w").write("\n".join(lines) + "\n")
    if args.json:
        json.dump(results, open(args.json, "w"), indent=1)
    if args.figure:
        figure(results, args.figure, scene)


if __name__ == "__main__":
    main()
