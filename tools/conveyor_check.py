#!/usr/bin/python3
"""Measures a run of scenes/processes/conveyor.json (a belt conveyor with a plough feeding a bin).

usage: /usr/bin/python3 tools/conveyor_check.py [RUN_DIR] [--tem build/release/tem]
           [--scene scenes/processes/conveyor.json] [--run] [--window T0 T1] [--plot PNG]

With --run (or when RUN_DIR has no sensors.csv) it first runs `TEM run SCENE --out RUN_DIR
--threads 1` (RUN_DIR defaults to /tmp/tem_conveyor). Then, from RUN_DIR's scene.json,
bodies.csv, sensors.csv and removed.csv, it reports:

 (a) belt speed: each grain's velocity along the belt while it rides the belt (centre less than
     0.3 cm above the belt's top, upstream of the plough): the time from its landing (first row
     with the centre that low) until |vx - v| < 2 % of v for good, against v / (mu g) (mu the
     belt-grain pair's friction); and the mean and spread of vx over the riding grains in the
     steady window;
 (b) delivery: the rate of the `delivered` plane sensor (least-squares slope of its count over
     the window) against the inlet's rate; mass balance: bodies inserted (every grain name seen in
     bodies.csv or removed.csv) = present at the end + removed, and the mass crossing the plane
     = the mass the `bin` region gained (the bin body's own mass, read at t = 0, taken off) + the
     mass of the grains removed below;
 (c) the belt's horizontal push on the grains (minus the `belt` force sensor's fx, mean over the
     window) against the momentum given to the arriving grains, mdot v (mdot the mass rate
     through the plane), and the momentum balance of the grains with the other sensors:
     push = F_plough,x + F_bin,x + dP/dt (dP/dt from bodies.csv with the mean grain mass), and
     an estimate of the rest, the belt's drag on the grains held back by the plough: mu times
     the belt's normal load (its sensor's -fz) less the weight of the grains riding on it without
     slipping, times the mean x part of the slipping grains' slip directions (an upper
     estimate), and with only the slipping grains' own weight as their load (a lower one).

--plot writes the delivered count against time with the inlet's rate (the figure of
docs/processes/conveyor.md). Needs only Debian's python3-numpy (and python3-matplotlib for --plot).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np

G = 980.665


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def pair_friction(scene, a, b):
    for p in scene.get("contact", {}).get("pairs", []):
        if sorted(p["materials"]) == sorted([a, b]) and "friction" in p:
            return p["friction"]
    m = scene["materials"]
    return min(m[a]["friction"], m[b]["friction"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir", nargs="?", default="/tmp/tem_conveyor")
    ap.add_argument("--tem", default="build/release/tem", help="the TEM binary")
    ap.add_argument("--scene", default="scenes/processes/conveyor.json")
    ap.add_argument("--run", action="store_true", help="run the scene first")
    ap.add_argument("--window", type=float, nargs=2, default=[2.0, None],
                    help="steady window (s); default 2 s to the end")
    ap.add_argument("--plot", help="PNG of delivered count vs time")
    args = ap.parse_args()
    d = args.run_dir
    if args.run or not os.path.exists(os.path.join(d, "sensors.csv")):
        subprocess.run([args.tem, "run", args.scene, "--out", d, "--threads", "1"], check=True)

    scene = json.load(open(os.path.join(d, "scene.json")))
    belt = next(b for b in scene["bodies"] if b["name"] == "belt")
    plough = next(b for b in scene["bodies"] if b["name"] == "plough")
    inlet = scene["inlets"][0]
    v = belt["motion"]["velocity"][0]
    belt_top = belt["position"][2] + belt["shape"]["size"][2] / 2
    mu = pair_friction(scene, belt["material"], inlet["body"]["material"])
    # the plough's upstream end along x: grains ride freely before it
    half = plough["shape"]["size"][0] / 2
    x_plough = plough["position"][0] - half * abs(np.cos(np.radians(plough["euler_zxz_deg"][0])))
    x_inlet = inlet["region"]["max"][0]
    t_end = scene["duration"]
    t0, t1 = args.window[0], args.window[1] if args.window[1] is not None else t_end

    rows = read_csv(os.path.join(d, "bodies.csv"))
    prefix = inlet["name"] + "_"
    grains = {}
    for r in rows:
        if r["body"].startswith(prefix):
            grains.setdefault(r["body"], []).append(
                [float(r[k]) for k in ("time", "x", "y", "z", "vx", "vy", "vz")])
    grains = {k: np.array(a) for k, a in grains.items()}
    removed = read_csv(os.path.join(d, "removed.csv")) if os.path.exists(
        os.path.join(d, "removed.csv")) else []
    sensors = {}
    for r in read_csv(os.path.join(d, "sensors.csv")):
        sensors.setdefault(r["sensor"], []).append(
            [float(r[k]) for k in ("time", "count", "mass", "fx", "fy", "fz")])
    sensors = {k: np.array(a) for k, a in sensors.items()}

    print(f"belt speed v = {v} cm/s, belt-grain friction mu = {mu}, "
          f"v/(mu g) = {v / (mu * G) * 1e3:.1f} ms; steady window {t0}-{t1} s")

    # (a) belt speed
    low = belt_top + 0.3
    transients, riding_vx = [], []
    for name, a in grains.items():
        on = (a[:, 3] < low) & (a[:, 1] < x_plough - 0.5)
        if not on.any():
            continue
        i_land = np.argmax(on)
        seg = a[i_land:][on[i_land:].cumprod().astype(bool)]  # riding rows after landing
        if len(seg) < 3:
            continue
        bad = np.abs(seg[:, 4] - v) >= 0.02 * v
        if bad[-1]:
            continue  # never settled while riding
        last_bad = np.nonzero(bad)[0]
        k = last_bad[-1] + 1 if len(last_bad) else 0
        transients.append(seg[k, 0] - seg[0, 0])
        sel = seg[(seg[:, 0] >= t0) & (seg[:, 0] <= t1) & (seg[:, 1] > x_inlet + 1)]
        riding_vx.extend(sel[:, 4])
    tr = np.array(transients)
    rv = np.array(riding_vx)
    dt_out = scene["output"]["interval"]
    print(f"(a) {len(tr)} grains landed and settled on the belt; time from landing to "
          f"|vx - v| < 2% for good (output rows every {dt_out * 1e3:.0f} ms): "
          f"median {np.median(tr) * 1e3:.0f} ms, 90th percentile "
          f"{np.percentile(tr, 90) * 1e3:.0f} ms, max {tr.max() * 1e3:.0f} ms "
          f"(v/(mu g) = {v / (mu * G) * 1e3:.1f} ms)")
    print(f"    riding grains downstream of the inlet in the window ({len(rv)} samples): "
          f"vx mean {rv.mean():.4f} cm/s = v x {rv.mean() / v:.5f}, "
          f"std {rv.std():.2e}, largest |vx - v| {np.abs(rv - v).max():.2e} cm/s")

    # (b) delivery rate and mass balance
    pl = sensors["delivered"]
    w = (pl[:, 0] >= t0) & (pl[:, 0] <= t1)
    rate = np.polyfit(pl[w, 0], pl[w, 1], 1)[0]
    mrate = np.polyfit(pl[w, 0], pl[w, 2], 1)[0]
    print(f"(b) delivery through the plane {t0}-{t1} s: {rate:.1f} grains/s "
          f"(inlet rate {inlet['rate']}/s, ratio {rate / inlet['rate']:.3f}); "
          f"mass rate {mrate:.3f} g/s")
    inserted = set(grains) | {r["body"] for r in removed}
    present = {k for k, a in grains.items() if abs(a[-1, 0] - t_end) < 1e-9}
    gone = {r["body"] for r in removed}
    expect = min(inlet["count"], int(np.floor((t_end - inlet.get("start", 0)) * inlet["rate"])) + 1)
    print(f"    inserted {len(inserted)} (rate x time allows {expect}), present at the end "
          f"{len(present)}, removed {len(gone)}: "
          f"{'balanced' if len(inserted) == len(present) + len(gone) and not present & gone else 'NOT balanced'}")
    binr = sensors["bin"]
    bin_own = binr[0, 2]
    m_bin = binr[-1, 2] - bin_own
    m_removed = sum(float(r["mass"]) for r in removed)
    print(f"    mass through the plane {pl[-1, 2]:.4f} g = in the bin {m_bin:.4f} g "
          f"(region reads {binr[-1, 2]:.4f} g less the bin's own {bin_own:.4f} g, "
          f"{int(binr[-1, 1] - binr[0, 1])} grains) + removed {m_removed:.4f} g "
          f"({len(removed)} grains): difference {pl[-1, 2] - m_bin - m_removed:+.4f} g")

    # (c) forces
    def mean_fx(name):
        s = sensors[name]
        ww = (s[:, 0] > t0) & (s[:, 0] <= t1)
        return s[ww, 3].mean(), s[ww, 3].std() / np.sqrt(ww.sum())

    push, push_err = mean_fx("belt")
    push, push_err = -push, push_err
    fp, fp_err = mean_fx("plough")
    fb, fb_err = mean_fx("bin_load") if "bin_load" in sensors else (0.0, 0.0)
    m_mean = pl[-1, 2] / max(pl[-1, 1], 1)
    times = sorted({round(t, 9) for a in grains.values() for t in a[:, 0]})

    def px_at(t):
        return m_mean * sum(a[np.abs(a[:, 0] - t) < 1e-9, 4].sum() for a in grains.values())

    t_a = min(times, key=lambda t: abs(t - t0))
    t_b = min(times, key=lambda t: abs(t - t1))
    dpdt = (px_at(t_b) - px_at(t_a)) / (t_b - t_a)
    # The belt's drag on the grains that slip on it (held back at the plough): Coulomb friction
    # mu N along each one's slip. N: the belt's measured normal load (-fz of its sensor) less the
    # weight of the grains riding with it (touching it without slipping), shared among the
    # slipping ones in proportion to their count; the x part of the slip direction averaged.
    belt_s = sensors["belt"]
    drags, drags_w, slip_counts = [], [], []
    for t in times:
        if t < t0 or t > t1:
            continue
        n_ride, dirs = 0, []
        for a in grains.values():
            r = a[np.abs(a[:, 0] - t) < 1e-9]
            if not len(r) or r[0, 3] > low or abs(r[0, 2]) > 2.0:
                continue
            slip = np.array([v - r[0, 4], -r[0, 5]])
            s_ = np.linalg.norm(slip)
            if s_ > 0.1 * v:
                dirs.append(slip[0] / s_)
            else:
                n_ride += 1
        k = np.argmin(np.abs(belt_s[:, 0] - t))
        load = -belt_s[k, 5] - n_ride * m_mean * G
        if dirs:
            drags.append(mu * load * np.mean(dirs))
            drags_w.append(mu * m_mean * G * np.sum(dirs))
            slip_counts.append(len(dirs))
    drag, drag_w = np.mean(drags), np.mean(drags_w)
    print(f"(c) belt's push on the grains along x (window mean of -fx of sensor 'belt'): "
          f"{push:.1f} +- {push_err:.1f} dyn")
    print(f"    mdot v = {mrate:.3f} g/s x {v} cm/s = {mrate * v:.1f} dyn "
          f"(with the inlet's rate x mean mass: {inlet['rate'] * m_mean * v:.1f} dyn)")
    print(f"    momentum balance of the grains: F_plough,x {fp:.1f} +- {fp_err:.1f} + "
          f"F_bin,x {fb:.1f} +- {fb_err:.1f} + dPx/dt {dpdt:.1f} = {fp + fb + dpdt:.1f} dyn "
          f"(push - that = {push - fp - fb - dpdt:+.1f} dyn)")
    print(f"    mdot v + the belt's drag on the grains slipping on it at the plough "
          f"(mu x (belt's normal load - riding grains' weight) x mean slip direction along x, "
          f"{np.mean(slip_counts):.0f} slipping grains on average): {mrate * v:.1f} + {drag:.1f} = "
          f"{mrate * v + drag:.1f} dyn (push / that = {push / (mrate * v + drag):.3f}); with only "
          f"the slipping grains' own weight as their load: {mrate * v:.1f} + {drag_w:.1f} = "
          f"{mrate * v + drag_w:.1f} dyn (push / that = {push / (mrate * v + drag_w):.3f})")

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.6))
        ax.plot(pl[:, 0], pl[:, 1], label="delivered (plane sensor)")
        ins_t = np.sort([a[0, 0] for a in grains.values()] +
                        [float(r["time"]) for r in removed if r["body"] not in grains])
        ax.plot(ins_t, np.arange(1, len(ins_t) + 1), "--", label="inserted by the inlet")
        b = np.polyfit(pl[w, 0], pl[w, 1], 1)
        tt = np.array([t0 - 0.7, t1])
        ax.plot(tt, pl[w, 1][0] + inlet["rate"] * (tt - pl[w, 0][0]), ":k",
                label=f"inlet rate {inlet['rate']}/s")
        ax.axvspan(t0, t1, color="0.9", zorder=0)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("grains")
        ax.set_title(f"delivered {b[0]:.1f}/s in the grey window")
        ax.legend(loc="upper left", fontsize=8)
        fig.tight_layout()
        fig.savefig(args.plot, dpi=110)
        print(f"wrote {args.plot}")


if __name__ == "__main__":
    sys.exit(main())
