#!/usr/bin/python3
"""Discharge of the flat-bottomed silo (tools/silo_scene.py) against the Beverloo law.

usage: /usr/bin/python3 tools/beverloo.py [--tem build/release/tem] [--orifices 1.75 2 2.25 2.5]
           [--work /tmp/beverloo] [--count 2000] [--max-duration 1.3] [--stop-fraction 0.6]
           [--window 0.05 0.35] [--reuse] [--figures docs/figures/processes_silo]

For each orifice width D it writes a variant of the silo scene to WORK/silo_D<D>.json, runs it
(`nice -n 5 TEM run ... --threads 1`, one run at a time) and stops the run (SIGTERM: TEM writes
its checkpoint and the rows so far) once the `orifice` plane sensor has counted stop-fraction of
the settled fill's mass, or at max-duration. With --reuse, a run directory that already has a
sensors.csv is analysed as it is.

What it computes, from WORK/D<D>/sensors.csv:
  rho_b   bulk density of the settled fill: the mass of the grains whose centres are in the
          `core` sensor's box (3 x 3 x 1.5 cm, away from walls, floor and free surface), averaged
          over the rows of the 0.05 s before the gate opens, divided by the box's volume;
  M0, H0  the mass in the silo (`contents`) when the gate opens, and the fill height M0/(rho_b A);
  W       the discharge rate: least-squares slope of the orifice sensor's cumulative mass against
          time over the window from the time 5 % of M0 has passed (at least 0.1 s after the
          gate) to the time 35 % has (--window 0.05 0.35; or the run's end), the same range of
          bed heights for every orifice; W1, W2 the slopes over the window's first and second
          halves (steadiness while the fill height falls); R^2 of the fit;
  Beverloo  a straight line W^(2/5) = a D + b through the orifices that did not clog. For a
          square orifice of side D the law with the orifice's area and hydraulic diameter
          (D_h = 4A/P = D), W = (4/pi) C rho_b sqrt(g) A_eff sqrt(D_h,eff), A_eff = (D - k d)^2,
          is W = (4/pi) C rho_b sqrt(g) (D - k d)^(5/2), so
              C = (pi/4) a^(5/2) / (rho_b sqrt(g)),   k = -b / (a d),
          C comparable with Beverloo's circular-orifice C. d is the diameter of the sphere of the
          mean grain's volume (the grain's volume from `TEM info`, times E[s^3] of the size
          factors s in [0.9, 1.1]); k per cube side SIDE is printed too.
Prints a table (markdown) and writes FIGURES_discharge.png (cumulative mass against time after
the gate, each D, with the fitted rate) and FIGURES_beverloo.png (W^(2/5) against D, the line).
Only Debian's python3-numpy and python3-matplotlib are needed.
"""
import argparse
import csv
import json
import math
import os
import signal
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import silo_scene  # noqa: E402  (tools/silo_scene.py)

G = 980.665


def read_sensors(path):
    """{sensor: {column: np.array}} from sensors.csv."""
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            s = rows.setdefault(r["sensor"], {k: [] for k in r if k != "sensor"})
            for k, v in r.items():
                if k != "sensor":
                    s[k].append(float(v))
    return {s: {k: np.array(v) for k, v in cols.items()} for s, cols in rows.items()}


def grain_volume(tem, work):
    """Volume of the template grain (size factor 1), from `TEM info` on a one-grain scene."""
    scene = {"time_step": 1e-3, "duration": 1e-3,
             "bodies": [{"name": "g", "position": [0, 0, 0],
                         "shape": {"type": "convex", "points": silo_scene.grain_points()}}]}
    path = os.path.join(work, "one_grain.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    out = subprocess.run([tem, "info", path], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        if line.strip().startswith("volume"):
            return float(line.split()[1])
    raise RuntimeError("no volume in `tem info` output:\n" + out)


def run_variant(tem, scene_path, out_dir, gate, stop_fraction):
    """Run TEM; stop it once the orifice sensor has counted stop_fraction of the fill's mass."""
    log = open(os.path.join(os.path.dirname(out_dir), os.path.basename(out_dir) + ".log"), "w")
    t0 = time.time()
    p = subprocess.Popen(["nice", "-n", "5", tem, "run", scene_path, "--out", out_dir,
                          "--threads", "1"], stdout=log, stderr=subprocess.STDOUT)
    sensors = os.path.join(out_dir, "sensors.csv")
    m0 = None
    stopped = False
    while p.poll() is None:
        time.sleep(2)
        if stopped or not os.path.exists(sensors):
            continue
        try:
            s = read_sensors(sensors)
        except (ValueError, KeyError):
            continue  # a row being written
        if "contents" not in s or "orifice" not in s:
            continue
        t = s["contents"]["time"]
        if m0 is None and t[-1] >= gate:
            m0 = s["contents"]["mass"][np.searchsorted(t, gate - 1e-9) - 1]
        if m0 is not None and s["orifice"]["mass"][-1] >= stop_fraction * m0:
            p.send_signal(signal.SIGTERM)
            stopped = True
    log.close()
    return time.time() - t0, stopped


def fit_line(x, y):
    """Slope, intercept, R^2 and the slope's standard error of a least-squares line."""
    A = np.vstack([x, np.ones_like(x)]).T
    (a, b), res, _, _ = np.linalg.lstsq(A, y, rcond=None)
    resid = y - (a * x + b)
    ss_tot = ((y - y.mean()) ** 2).sum()
    r2 = 1 - (resid ** 2).sum() / ss_tot if ss_tot > 0 else float("nan")
    n = len(x)
    se = math.sqrt((resid ** 2).sum() / (n - 2) / ((x - x.mean()) ** 2).sum()) if n > 2 else 0
    return a, b, r2, se


def analyse(run_dir, gate, core_volume, area, window):
    s = read_sensors(os.path.join(run_dir, "sensors.csv"))
    core, cont, orf = s["core"], s["contents"], s["orifice"]
    before = (core["time"] > gate - 0.05 - 1e-9) & (core["time"] < gate - 1e-9)
    rho_b = core["mass"][before].mean() / core_volume
    m0 = cont["mass"][np.searchsorted(cont["time"], gate - 1e-9) - 1]
    t, m = orf["time"], orf["mass"]
    # The window: from 0.1 s after the gate and lo of the fill discharged, to hi of it
    # discharged (or the run's end): the same range of bed heights for every orifice.
    lo, hi = window
    first = np.nonzero(m >= lo * m0)[0]
    start = max(gate + 0.1, t[first[0]] if len(first) else gate + 0.1)
    last_ = np.nonzero(m >= hi * m0)[0]
    end = t[last_[0]] if len(last_) else t[-1]
    w = (t >= start - 1e-9) & (t <= end + 1e-9)
    r = {"rho_b": rho_b, "m0": m0, "h0": m0 / (rho_b * area), "t_end": t[-1],
         "start": start, "end": end, "discharged": m[-1], "t": t, "m": m}
    if w.sum() < 6:
        r.update(W=float("nan"), W1=float("nan"), W2=float("nan"), r2=float("nan"), se=0)
        return r
    W, b, r2, se = fit_line(t[w], m[w])
    mid = 0.5 * (start + end)
    w1 = w & (t <= mid + 1e-9)
    w2 = w & (t >= mid - 1e-9)
    r.update(W=W, b=b, r2=r2, se=se, W1=fit_line(t[w1], m[w1])[0], W2=fit_line(t[w2], m[w2])[0])
    # Clogged: less than half of the fill left and, over the run's last 0.1 s, less than a
    # tenth of the window's first-half rate (a grain or two rattling through an arch).
    last = t >= t[-1] - 0.1 - 1e-9
    late = (m[last][-1] - m[last][0]) / max(t[last][-1] - t[last][0], 1e-12)
    r["clogged"] = bool(m[-1] < 0.5 * m0 and late < 0.1 * r["W1"])
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tem", default="build/release/tem")
    ap.add_argument("--orifices", type=float, nargs="+", default=[1.75, 2.0, 2.25, 2.5])
    ap.add_argument("--work", default="/tmp/beverloo")
    ap.add_argument("--count", type=int, default=silo_scene.COUNT)
    ap.add_argument("--gate", type=float, default=silo_scene.GATE)
    ap.add_argument("--max-duration", type=float, default=1.3)
    ap.add_argument("--stop-fraction", type=float, default=0.6)
    ap.add_argument("--window", type=float, nargs=2, default=[0.05, 0.35],
                    help="fractions of the settled fill discharged that bound the fit window")
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--figures", default="docs/figures/processes_silo")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    tem = os.path.abspath(a.tem)

    results = {}
    for D in a.orifices:
        tag = f"D{D:g}"
        scene = silo_scene.silo_scene(orifice=D, count=a.count, duration=a.max_duration,
                                      gate=a.gate)
        path = os.path.join(a.work, f"silo_{tag}.json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=1)
        out = os.path.join(a.work, tag)
        if not (a.reuse and os.path.exists(os.path.join(out, "sensors.csv"))):
            wall, stopped = run_variant(tem, path, out, a.gate, a.stop_fraction)
            print(f"{tag}: ran in {wall:.0f} s wall{' (stopped by the tool)' if stopped else ''}",
                  file=sys.stderr)
        core = silo_scene.CORE
        vol = np.prod(np.subtract(core["max"], core["min"]))
        results[D] = analyse(out, a.gate, vol, silo_scene.WIDTH ** 2, a.window)

    v1 = grain_volume(tem, a.work)
    s3 = (1.1 ** 4 - 0.9 ** 4) / (4 * 0.2)  # E[s^3], s uniform in [0.9, 1.1]
    d = (6 * v1 * s3 / math.pi) ** (1 / 3)

    print("| D (cm) | D/d | rho_b (g/cm^3) | fill M0 (g), H0 (cm) | window (s after gate) |"
          " W (g/s) | W 1st half | W 2nd half | R^2 | state |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    good = []
    for D, r in results.items():
        state = "clogged" if r.get("clogged") else "flowing"
        print(f"| {D:g} | {D / d:.1f} | {r['rho_b']:.3f} | {r['m0']:.1f}, {r['h0']:.2f} | "
              f"{r['start'] - a.gate:.2f}-{r['end'] - a.gate:.2f} | {r['W']:.1f} ± {r['se']:.1f} | "
              f"{r['W1']:.1f} | {r['W2']:.1f} | {r['r2']:.4f} | {state} |")
        if not r.get("clogged") and np.isfinite(r["W"]):
            good.append(D)
    rho_b = np.mean([results[D]["rho_b"] for D in results])
    print(f"\ngrain: volume {v1:.5f} cm^3 at size factor 1, E[s^3] {s3:.4f}, "
          f"d (equal-volume sphere) {d:.4f} cm; rho_b mean {rho_b:.4f} g/cm^3 "
          f"(solid fraction {rho_b / silo_scene.DENSITY:.3f})")
    fit = None
    if len(good) >= 3:
        x = np.array(good)
        y = np.array([results[D]["W"] for D in good]) ** 0.4
        slope, icpt, r2, se = fit_line(x, y)
        C = math.pi / 4 * slope ** 2.5 / (rho_b * math.sqrt(G))
        kd = -icpt / slope
        fit = (slope, icpt, r2)
        # Spread of C and k from the slope's standard error (the intercept moves with it).
        print(f"Beverloo fit over D = {', '.join(f'{D:g}' for D in good)}: "
              f"W^(2/5) = {slope:.4f} D + {icpt:.4f}, R^2 = {r2:.5f}, slope s.e. {se:.4f}")
        print(f"  C = {C:.3f} (circular-orifice equivalent; square-orifice prefactor "
              f"{C * 4 / math.pi:.3f}), k d = {kd:.3f} cm, k = {kd / d:.2f} (d = {d:.3f} cm), "
              f"k = {kd / silo_scene.SIDE:.2f} per cube side {silo_scene.SIDE} cm")
        print("  published: C 0.55-0.65, k 1.3-1.6 for spheres (Beverloo et al. 1961), "
              "k up to ~2.9 for angular grains (Nedderman 1992)")
    else:
        print("fewer than three flowing orifices: no Beverloo fit")

    if a.figures:
        os.makedirs(os.path.dirname(a.figures) or ".", exist_ok=True)
        fig, ax = plt.subplots(figsize=(6, 4))
        for D, r in results.items():
            label = f"D = {D:g} cm" + (f", W = {r['W']:.0f} g/s" if np.isfinite(r["W"]) else "")
            line, = ax.plot(r["t"] - a.gate, r["m"], label=label)
            if np.isfinite(r["W"]):
                tt = np.array([r["start"], r["end"]])
                ax.plot(tt - a.gate, r["W"] * tt + r["b"], "k--", lw=1)
        ax.set_xlim(left=-0.05)
        ax.set_xlabel("time after the gate opened (s)")
        ax.set_ylabel("discharged mass (g)")
        ax.set_title("Silo discharge (dashed: the rate fitted over the window)", fontsize=10)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.figures + "_discharge.png", dpi=110)
        fig, ax = plt.subplots(figsize=(5, 4))
        for D, r in results.items():
            ax.plot(D, r["W"] ** 0.4, "o", color="C0" if D in good else "C3")
        if fit:
            xs = np.linspace(-fit[1] / fit[0], max(good) * 1.05, 50)
            ax.plot(xs, fit[0] * xs + fit[1], "k--", lw=1,
                    label=f"{fit[0]:.3f} D {fit[1]:+.3f}  (R$^2$ = {fit[2]:.4f})\n"
                          f"C = {C:.2f}, k = {kd / d:.2f}")
            ax.legend(fontsize=8, loc="upper left")
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.set_xlabel("orifice width D (cm)")
        ax.set_ylabel("W$^{2/5}$ ((g/s)$^{2/5}$)")
        ax.set_title("Beverloo: W$^{2/5}$ linear in D", fontsize=10)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(a.figures + "_beverloo.png", dpi=110)


if __name__ == "__main__":
    main()
