#!/usr/bin/python3
"""Measures a run of scenes/processes/conveyor.json (a belt conveyor discharging into a bin).

usage: /usr/bin/python3 tools/conveyor_check.py [RUN_DIR] [--tem build/release/tem]
           [--scene scenes/processes/conveyor.json] [--run] [--work] [--window T0 T1]
           [--plot PNG]

The belt is a fixed box whose surface slides at `motion.surface_velocity` v along x; the inlet
drops grains on it near its upstream end, the belt carries them to its downstream end, where they
fall into a fixed bin. With --run (or when RUN_DIR has no sensors.csv) it first runs `TEM run
SCENE --out RUN_DIR --threads 1` (RUN_DIR defaults to /tmp/tem_conveyor). With --work it also
steps the scene in TEM's Python module (`import tem`, on PYTHONPATH) and writes RUN_DIR/work.csv,
the belt's driven work at every output time (`sim.energies()['driven_work']`). Then, from
RUN_DIR's scene.json, bodies.csv, sensors.csv, removed.csv (and work.csv), it reports:

 (a) belt speed: each grain's velocity along the belt while it rides it (centre less than 0.3 cm
     above the belt's top, at least 0.5 cm before its end): the time from landing (first row
     with the centre that low) until |vx - v| < 2 % of v for good, against v / (mu g) (mu the
     belt-grain pair's friction); and the mean and spread of vx over the riding grains more than
     1 cm downstream of the inlet in the steady window;
 (b) delivery: the rate of the `delivered` plane sensor (least-squares slope of its count over
     the window) against the inlet's rate, and how often its count fell (grains crossing back);
     mass balance: bodies inserted (every grain name seen in bodies.csv or removed.csv) =
     present at the end + removed, and the mass through the plane = the mass in the `bin`
     region + the mass removed below;
 (c) the belt's push on the grains along x (minus the `belt` force sensor's fx, mean over the
     window) against the momentum given to the arriving grains, mdot v (mdot the mass rate
     through the plane; grains land with no velocity along x), and the grains' momentum balance
     push = F_bin,x + dPx/dt (dPx/dt from bodies.csv);
 (d) with work.csv: the belt's power (slope of driven_work over the window) against mdot v^2,
     split into the kinetic energy carried off, mdot v^2 / 2, and the rest (sliding).

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


def slope(t, y):
    return np.polyfit(t, y, 1)[0]


def record_work(scene_path, out_csv):
    import tem  # TEM's Python module
    sim = tem.Simulation(scene_path)
    scene = json.load(open(scene_path))
    every = int(round(scene["output"]["interval"] / sim.time_step))
    with open(out_csv, "w") as f:
        f.write("time,driven_work,kinetic,potential,total\n")
        while True:
            e = sim.energies()
            f.write(f"{sim.time!r},{e['driven_work']!r},{e['kinetic']!r},{e['potential']!r},"
                    f"{e['total']!r}\n")
            if sim.time >= scene["duration"] - 1e-9:
                break
            sim.step(every)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir", nargs="?", default="/tmp/tem_conveyor")
    ap.add_argument("--tem", default="build/release/tem", help="the TEM binary")
    ap.add_argument("--scene", default="scenes/processes/conveyor.json")
    ap.add_argument("--run", action="store_true", help="run the scene first")
    ap.add_argument("--work", action="store_true",
                    help="step the scene in the Python module too, for the belt's driven work")
    ap.add_argument("--window", type=float, nargs=2, default=[1.5, None],
                    help="steady window (s); default 1.5 s to the end")
    ap.add_argument("--plot", help="PNG of delivered count vs time")
    args = ap.parse_args()
    d = args.run_dir
    if args.run or not os.path.exists(os.path.join(d, "sensors.csv")):
        subprocess.run([args.tem, "run", args.scene, "--out", d, "--threads", "1"], check=True)
    if args.work:
        record_work(args.scene, os.path.join(d, "work.csv"))

    scene = json.load(open(os.path.join(d, "scene.json")))
    belt = next(b for b in scene["bodies"] if b["name"] == "belt")
    inlet = scene["inlets"][0]
    v = belt["motion"]["surface_velocity"][0]
    belt_top = belt["position"][2] + belt["shape"]["size"][2] / 2
    belt_end = belt["position"][0] + belt["shape"]["size"][0] / 2
    mu = pair_friction(scene, belt["material"], inlet["body"]["material"])
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

    print(f"belt surface speed v = {v} cm/s, belt-grain friction mu = {mu}, "
          f"v/(mu g) = {v / (mu * G) * 1e3:.1f} ms; steady window {t0}-{t1} s")

    # (a) belt speed
    low = belt_top + 0.3
    transients, riding_vx = [], []
    for name, a in grains.items():
        on = (a[:, 3] < low) & (a[:, 1] < belt_end - 0.5)
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
    print(f"    riding grains > 1 cm downstream of the inlet in the window ({len(rv)} samples): "
          f"vx mean {rv.mean():.4f} cm/s = v x {rv.mean() / v:.5f}, "
          f"std {rv.std():.2e}, largest |vx - v| {np.abs(rv - v).max():.2e} cm/s")

    # (b) delivery rate and mass balance
    pl = sensors["delivered"]
    w = (pl[:, 0] >= t0) & (pl[:, 0] <= t1)
    rate = slope(pl[w, 0], pl[w, 1])
    mrate = slope(pl[w, 0], pl[w, 2])
    first = pl[np.argmax(pl[:, 1] > 0), 0]
    drops = int((np.diff(pl[:, 1]) < 0).sum())
    print(f"(b) first grain through the plane at {first:.2f} s; delivery {t0}-{t1} s: "
          f"{rate:.1f} grains/s (inlet rate {inlet['rate']}/s, ratio {rate / inlet['rate']:.3f}); "
          f"mass rate {mrate:.3f} g/s; rows where the count fell: {drops}")
    inserted = set(grains) | {r["body"] for r in removed}
    present = {k for k, a in grains.items() if abs(a[-1, 0] - t_end) < 1e-9}
    gone = {r["body"] for r in removed}
    expect = min(inlet["count"], int(np.floor((t_end - inlet.get("start", 0)) * inlet["rate"])) + 1)
    print(f"    inserted {len(inserted)} (rate x time allows {expect}), present at the end "
          f"{len(present)}, removed {len(gone)}: "
          f"{'balanced' if len(inserted) == len(present) + len(gone) and not present & gone else 'NOT balanced'}")
    binr = sensors["bin"]
    m_removed = sum(float(r["mass"]) for r in removed)
    sens = {s_["name"]: s_ for s_ in scene["sensors"]}
    x_plane = sens["delivered"]["point"][0]
    reg = sens["bin"]["region"]
    # grains past the plane at the end but outside the bin's region: in flight, falling into it
    flying = [k for k in present if grains[k][-1, 1] > x_plane and not all(
        reg["min"][i] <= grains[k][-1, 1 + i] <= reg["max"][i] for i in range(3))]
    m_mean = pl[-1, 2] / max(pl[-1, 1], 1)
    m_fly = len(flying) * m_mean  # bodies.csv has no masses: the mean grain mass
    print(f"    at the end: mass through the plane {pl[-1, 2]:.4f} g ({int(pl[-1, 1])} grains) = "
          f"in the bin {binr[-1, 2]:.4f} g ({int(binr[-1, 1])} grains) + falling between "
          f"{len(flying)} grains (~{m_fly:.4f} g with the mean grain mass) + removed "
          f"{m_removed:.4f} g ({len(removed)} grains): count difference "
          f"{int(pl[-1, 1]) - int(binr[-1, 1]) - len(flying) - len(removed):+d}, "
          f"mass difference {pl[-1, 2] - binr[-1, 2] - m_fly - m_removed:+.4f} g")
    # each grain's velocity just past the plane (its first row there): in free flight
    exit_v = []
    for k, a in grains.items():
        i = np.nonzero(a[:, 1] > x_plane)[0]
        if len(i) and t0 <= a[i[0], 0] <= t1:
            exit_v.append(a[i[0], 4:7])
    exit_v = np.array(exit_v)
    print(f"    grains crossing the plane in the window ({len(exit_v)}), first row past it: "
          f"vx mean {exit_v[:, 0].mean():.2f} cm/s (= v x {exit_v[:, 0].mean() / v:.3f}; "
          f"5-95 % {np.percentile(exit_v[:, 0], 5):.2f}-{np.percentile(exit_v[:, 0], 95):.2f}), "
          f"vz mean {exit_v[:, 2].mean():.2f} cm/s")

    # (c) forces
    def mean_f(name, col):
        s = sensors[name]
        ww = (s[:, 0] > t0) & (s[:, 0] <= t1)
        return s[ww, col].mean(), s[ww, col].std() / np.sqrt(ww.sum())

    push, push_err = mean_f("belt", 3)
    push = -push
    fb, fb_err = mean_f("bin_load", 3)
    times = np.array(sorted({round(t, 9) for a in grains.values() for t in a[:, 0]}))
    masses = {r["body"]: float(r["mass"]) for r in removed}

    def px_at(t):
        return m_mean * sum(a[np.abs(a[:, 0] - t) < 1e-9, 4].sum() for a in grains.values())

    t_a = times[np.argmin(np.abs(times - t0))]
    t_b = times[np.argmin(np.abs(times - t1))]
    dpdt = (px_at(t_b) - px_at(t_a)) / (t_b - t_a)
    # grains on the belt in the window and their weight, against the belt's normal load
    on_belt = []
    for t in times[(times >= t0) & (times <= t1)]:
        n = 0
        for a in grains.values():
            r = a[np.abs(a[:, 0] - t) < 1e-9]
            if len(r) and r[0, 3] < low and r[0, 1] < belt_end + 0.3:
                n += 1
        on_belt.append(n)
    load, load_err = mean_f("belt", 5)
    print(f"(c) belt's push on the grains along x (window mean of -fx of sensor 'belt'): "
          f"{push:.2f} +- {push_err:.2f} dyn")
    print(f"    mdot v = {mrate:.4f} g/s x {v} cm/s = {mrate * v:.2f} dyn "
          f"(push / mdot v = {push / (mrate * v):.4f}; with the inlet's rate x mean grain mass "
          f"{m_mean:.5f} g: {inlet['rate'] * m_mean * v:.2f} dyn)")
    vx_exit = exit_v[:, 0].mean()
    print(f"    mdot x mean vx past the end = {mrate:.4f} x {vx_exit:.2f} = {mrate * vx_exit:.2f} dyn "
          f"(push / that = {push / (mrate * vx_exit):.4f}): the grains tip over the belt's end "
          f"and leave it faster than v")
    # the push over successive half-second blocks (how much it wanders)
    bs = sensors["belt"]
    edges = np.arange(t0, t1 + 1e-9, 0.5)
    blocks = [-bs[(bs[:, 0] > a_) & (bs[:, 0] <= b_), 3].mean() for a_, b_ in zip(edges[:-1], edges[1:])]
    print(f"    push over 0.5 s blocks: " + ", ".join(f"{b_:.1f}" for b_ in blocks) + " dyn")
    print(f"    grains' momentum balance along x: F_bin,x {fb:.2f} +- {fb_err:.2f} + dPx/dt "
          f"{dpdt:.2f} = {fb + dpdt:.2f} dyn (push - that = {push - fb - dpdt:+.2f} dyn)")
    print(f"    belt's normal load (-fz) {-load:.1f} +- {load_err:.1f} dyn; grains riding "
          f"{np.mean(on_belt):.1f} on average, their weight {np.mean(on_belt) * m_mean * G:.1f} dyn")

    # (d) the belt's work
    wpath = os.path.join(d, "work.csv")
    if os.path.exists(wpath):
        wk = np.array([[float(r[k]) for k in ("time", "driven_work", "kinetic", "total")]
                       for r in read_csv(wpath)])
        ww = (wk[:, 0] >= t0) & (wk[:, 0] <= t1)
        power = slope(wk[ww, 0], wk[ww, 1])
        print(f"(d) belt's power (slope of driven_work, {t0}-{t1} s): {power:.1f} erg/s; "
              f"mdot v^2 = {mrate * v * v:.1f} erg/s (ratio {power / (mrate * v * v):.4f}); "
              f"push x v = {push * v:.1f} erg/s (ratio {power / (push * v):.4f})")
        ke_x = 0.5 * mrate * np.mean(exit_v[:, 0] ** 2)
        print(f"    of it, kinetic energy along x carried off the end, mdot <vx^2>/2 = {ke_x:.1f} "
              f"erg/s (mdot v^2/2 = {mrate * v * v / 2:.1f}); the rest, {power - ke_x:.1f} erg/s "
              f"= {(power - ke_x) / (mrate * v * v / 2):.3f} x mdot v^2/2, is lost to sliding "
              f"(and to the tipping at the end); driven work by {wk[-1, 0]:g} s {wk[-1, 1]:.1f} erg")

    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.6))
        ax.plot(pl[:, 0], pl[:, 1], label="delivered (plane past the belt's end)")
        ins_t = np.sort([a[0, 0] for a in grains.values()] +
                        [float(r["time"]) for r in removed if r["body"] not in grains])
        ax.plot(ins_t, np.arange(1, len(ins_t) + 1), "--", label="inserted by the inlet")
        ax.plot(binr[:, 0], binr[:, 1], "-.", label="in the bin (region sensor)")
        b = np.polyfit(pl[w, 0], pl[w, 1], 1)
        tt = np.array([t0 - 0.5, t1])
        ax.plot(tt, np.polyval(b, t0) + inlet["rate"] * (tt - t0), ":k",
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
