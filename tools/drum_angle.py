#!/usr/bin/python3
"""Rotating drum (scenes/processes/drum.json): dynamic angle of repose and drive torque.

usage: /usr/bin/python3 tools/drum_angle.py DIR [DIR ...] [--labels L ...] [--steady-from T]
           [--figure PNG] [--snapshots PNG] [--times T ...] [--tem build/release/tem]
       /usr/bin/python3 tools/drum_angle.py --run SCENE --out DIR [--tem PATH] ...
           (runs `tem run SCENE --out DIR --threads 1` first, then analyses DIR)

Each DIR is a finished `tem run` of a drum scene (bodies.csv, sensors.csv, scene.json and, for
the grains' masses and the snapshots, the ParaView frames: output.paraview true). The drum is
the scene's body with a `motion`; its axis is `motion.center` along `motion.angular_velocity`,
which must be a world axis (y in drum.json); every other body is a grain.

Per output row it computes, in the drum's cross-section (the grains' centres projected along
the axis; u the horizontal direction across the axis, z up):

  angle   the dynamic angle of repose: the grains' centres are binned along u in bins one grain
          diameter wide; the highest centre of each bin marks the free surface; a straight line
          is fitted (least squares) to the bins of the central 60 % of the surface's extent;
          angle = atan of its slope, in degrees, positive for a bed raised on the rising side.
  centroid angle  the same angle from every grain: a bed under a straight free surface is a
          circular segment, whose centroid lies on the perpendicular from the axis to the
          surface, so the angle of (u_c, z_c) (the bed's centre of mass relative to the axis)
          from straight down is the surface's inclination (exact for a flat surface; an S-shaped
          one gives its mean inclination).
  torque  the contact torque on the drum about its axis, from the `force` sensor on the drum
          (sensors.csv: its torque about the world origin, averaged over the output interval,
          projected on the axis through `center`);
  M g x_c the torque the bed's weight makes about the axis: M the grains' total mass, x_c the
          horizontal offset of their centre of mass from the axis (masses from each grain's
          volume in the last ParaView frame times the scene's density). In steady rotation the
          bed's angular momentum is constant, so the drum's contact torque must balance it:
          torque = M g x_c (sign: about +axis). The drive torque the motor supplies is -torque.

Over the steady window (t >= --steady-from, default 1.0 s) it prints the mean and standard
deviation of the angle, of the torque, of M g x_c, and the torque balance's mean relative
difference; also the means over the window's two halves (a steady state has them equal within
the spread). --figure draws angle and torques against time for every DIR; --snapshots draws a
strip of cross-section views of the first DIR (the front cap left out; the drum's stave 0 dark,
to show its turn), using tools/figures.py's frame reader and shading. --tem is the TEM binary
(used by --run, and for `tem info --json` to check the drum's mass).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  (tools/figures.py: frame list, .vtu reading, shading)


def gravity(scene):
    g = scene.get("gravity", "earth")
    if g == "earth":
        return np.array([0, 0, -980.665])
    if g == "paper":
        return np.array([0, 0, -98.0])
    return np.array(g, dtype=float)


def drum_of(scene):
    """(index in bodies, name, centre, unit axis, omega) of the body with a motion."""
    for i, b in enumerate(scene.get("bodies", [])):
        if "motion" in b:
            m = b["motion"]
            w = np.array(m.get("angular_velocity", [0, 0, 0]), dtype=float)
            axis = w / np.linalg.norm(w)
            return i, b["name"], np.array(m.get("center", b["position"]), float), axis, \
                np.linalg.norm(w)
    sys.exit("drum_angle: no body with a motion in scene.json")


def read_bodies(run_dir):
    """{time: {name: (position, velocity)}} and the times in order."""
    rows = {}
    with open(os.path.join(run_dir, "bodies.csv"), newline="") as f:
        for r in csv.DictReader(f):
            t = float(r["time"])
            rows.setdefault(t, {})[r["body"]] = np.array(
                [float(r[k]) for k in ("x", "y", "z")])
    return rows


def read_sensor(run_dir, name):
    out = {}
    with open(os.path.join(run_dir, "sensors.csv"), newline="") as f:
        for r in csv.DictReader(f):
            if r["sensor"] == name:
                out[float(r["time"])] = r
    return out


def grain_masses(run_dir, scene, drum_name):
    """{name: mass} of the bodies of the last ParaView frame, from their surfaces' volume
    (divergence theorem over each body's triangles) times the density of their template."""
    frames = figures.read_frames(run_dir)
    t, bodies_file, _ = frames[-1]
    points, tri, arrays = figures.read_vtu(bodies_file)
    names = read_names_at(run_dir, t)
    corners = points[tri]
    signed = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])) / 6
    # Per block a closed surface: sum per (body, block), take |.| (orientation-free).
    key = arrays["body_id"].astype(np.int64) * 100000 + arrays["block_id"]
    volume = {}
    uniq, inverse = np.unique(key, return_inverse=True)
    block_vol = np.abs(np.bincount(inverse, weights=signed))
    for k, v in zip(uniq, block_vol):
        b = int(k // 100000)
        volume[b] = volume.get(b, 0) + v
    density = {}
    for fill in scene.get("fill", []):
        density[fill["name"]] = fill["body"].get("density", 1.0)
    for inlet in scene.get("inlets", []):
        density[inlet["name"]] = inlet["body"].get("density", 1.0)
    masses = {}
    for b, vol in volume.items():
        name = names[b]
        if name == drum_name:
            continue
        prefix = name.rsplit("_", 1)[0]
        masses[name] = density.get(prefix, 1.0) * vol
    return masses, t


def read_names_at(run_dir, t):
    """The body names of the rows of bodies.csv at time t, in file order (= body_id order)."""
    names = []
    with open(os.path.join(run_dir, "bodies.csv"), newline="") as f:
        for r in csv.DictReader(f):
            if abs(float(r["time"]) - t) < 1e-9:
                names.append(r["body"])
    return names


def surface_angle(u, z, d):
    """Angle (deg) of the free surface: top centre per bin of width d along u, line fitted to
    the central 60 % of the occupied extent. Positive when the surface rises towards -u."""
    if len(u) < 10:
        return float("nan")
    lo, hi = u.min(), u.max()
    edges = np.arange(lo, hi + d, d)
    idx = np.digitize(u, edges) - 1
    bu, bz = [], []
    for k in np.unique(idx):
        sel = idx == k
        j = np.argmax(z[sel])
        bu.append(u[sel][j])
        bz.append(z[sel][j])
    bu, bz = np.array(bu), np.array(bz)
    mid, half = 0.5 * (lo + hi), 0.3 * (hi - lo)
    keep = np.abs(bu - mid) <= half
    if keep.sum() < 3:
        return float("nan")
    slope = np.polyfit(bu[keep], bz[keep], 1)[0]
    return -math.degrees(math.atan(slope))


def analyse(run_dir, steady_from, tem):
    with open(os.path.join(run_dir, "scene.json")) as f:
        scene = json.load(f)
    g_vec = gravity(scene)
    g = np.linalg.norm(g_vec)
    up = -g_vec / g
    di, drum_name, centre, axis, omega = drum_of(scene)
    # u = axis x up, horizontal across the axis (axis +y, up +z: u = +x); turning about +axis
    # the bottom moves towards -u, so the bed climbs on the -u side.
    across = np.cross(axis, up)
    masses, mass_time = grain_masses(run_dir, scene, drum_name)
    bodies = read_bodies(run_dir)
    sensor_name = next(s["name"] for s in scene.get("sensors", [])
                       if s["type"] == "force" and drum_name in s["bodies"])
    torque_rows = read_sensor(run_dir, sensor_name)
    # Cross-check of the masses from the frames: `tem info` knows the fill's copies (not the
    # inlet's, added during the run) and the drum.
    drum_mass, mass_check = None, None
    if tem and os.path.exists(tem):
        info = json.loads(subprocess.run([tem, "info", os.path.join(run_dir, "scene.json"),
                                          "--json"], capture_output=True, text=True,
                                         check=True).stdout)
        diffs = []
        for b in info.get("bodies", []):
            if b.get("name") == drum_name:
                drum_mass = b.get("mass")
            elif b.get("name") in masses:
                diffs.append(abs(masses[b["name"]] / b["mass"] - 1))
        if diffs:
            mass_check = (len(diffs), max(diffs))
    sizes = sorted((6 * m / scene_density(scene) / math.pi) ** (1 / 3) for m in masses.values())
    d = float(np.median(sizes))
    out = {"t": [], "angle": [], "centroid_angle": [], "torque": [], "weight_torque": [], "count": [], "mass": []}
    for t in sorted(bodies):
        row = bodies[t]
        names = [n for n in row if n != drum_name]
        if not names:
            continue
        p = np.array([row[n] - centre for n in names])
        m = np.array([masses.get(n, np.nan) for n in names])
        u, z = p @ across, p @ up
        out["t"].append(t)
        out["count"].append(len(names))
        out["angle"].append(surface_angle(u, z, d))
        ok = np.isfinite(m)
        M = m[ok].sum()
        xc = (m[ok] * u[ok]).sum() / M
        out["mass"].append(M)
        # torque of the weight about +axis: (r x M g) . axis, r = u across + z up + y axis
        rc = (m[ok][:, None] * p[ok]).sum(axis=0) / M
        out["weight_torque"].append(float(np.cross(rc, M * g_vec) @ axis))
        # A bed whose free surface is a straight chord is a circular segment: its centroid lies
        # on the chord's perpendicular through the axis, so the direction of (u_c, z_c) from
        # straight down is the surface's angle, measured with every grain.
        out["centroid_angle"].append(math.degrees(math.atan2(-(rc @ across), -(rc @ up))))
        tr = torque_rows.get(t)
        if tr is None:
            out["torque"].append(float("nan"))
        else:
            f = np.array([float(tr[k]) for k in ("fx", "fy", "fz")])
            tau0 = np.array([float(tr[k]) for k in ("tx", "ty", "tz")])
            out["torque"].append(float((tau0 - np.cross(centre, f)) @ axis))
    res = {k: np.array(v) for k, v in out.items()}
    res.update(dict(omega=omega, d=d, drum_mass=drum_mass, mass_check=mass_check, mass_time=mass_time,
                    froude=omega ** 2 * drum_radius(scene) / g, scene=scene))
    return res


def scene_density(scene):
    for fill in scene.get("fill", []):
        return fill["body"].get("density", 1.0)
    for inlet in scene.get("inlets", []):
        return inlet["body"].get("density", 1.0)
    return 1.0


def drum_radius(scene):
    """Inner radius of the drum: the smallest distance from the axis to a stave's node, from
    the compound's convex parts (drum.json's staves)."""
    _, _, centre, axis, _ = drum_of(scene)
    r = []
    for b in scene["bodies"]:
        if "motion" not in b:
            continue
        for part in b["shape"].get("blocks", []):
            if part["type"] == "convex":
                for q in part["points"]:
                    q = np.array(q, float)
                    r.append(np.linalg.norm(q - (q @ axis) * axis))
    return min(r) if r else float("nan")


def stats(res, steady_from):
    sel = (res["t"] >= steady_from) & np.isfinite(res["angle"])
    t = res["t"][sel]
    half = t <= 0.5 * (t[0] + t[-1])
    s = {"rows": int(sel.sum()), "from": float(t[0]), "to": float(t[-1])}
    for key in ("angle", "centroid_angle", "torque", "weight_torque"):
        v = res[key][sel]
        s[key] = (float(np.nanmean(v)), float(np.nanstd(v)),
                  float(np.nanmean(v[half])), float(np.nanmean(v[~half])))
    s["balance"] = (s["torque"][0] - s["weight_torque"][0]) / abs(s["weight_torque"][0])
    s["grains"] = int(res["count"][sel][-1])
    s["mass"] = float(res["mass"][sel][-1])
    return s


def report(label, res, s):
    print(f"{label}: {s['grains']} grains, bed mass {s['mass']:.3f} g, grain diameter "
          f"(volume-equivalent, median) {res['d']:.3f} cm, omega {res['omega']:.3g} rad/s, "
          f"Froude omega^2 R/g {res['froude']:.2e}")
    print(f"  steady window {s['from']:.2f}-{s['to']:.2f} s ({s['rows']} rows)")
    for key, name, unit in (("angle", "angle of repose", "deg"),
                            ("centroid_angle", "angle from bed centroid", "deg"),
                            ("torque", "torque on drum (sensor)", "g cm^2/s^2"),
                            ("weight_torque", "M g x_c (bed weight)", "g cm^2/s^2")):
        m, sd, a, b = s[key]
        print(f"  {name:26s} mean {m:11.4g} {unit}, std {sd:9.3g}; halves {a:.4g} / {b:.4g}")
    print(f"  torque balance: (sensor - M g x_c) / |M g x_c| = {100 * s['balance']:+.2f} % "
          f"(spread of the sensor {100 * s['torque'][1] / abs(s['weight_torque'][0]):.1f} %)")
    if res["mass_check"] is not None:
        n, worst = res["mass_check"]
        print(f"  grain masses from the frame's volumes vs tem info (fill copies): {n} grains, "
              f"largest relative difference {worst:.1e}")


def figure(results, labels, steady_from, path):
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 6.2), sharex=True)
    colours = ["#b5523b", "#5b84b1", "#6a9c5a", "#8c6bb1"]
    for (res, s), label, c in zip(results, labels, colours):
        axes[0].plot(res["t"], res["angle"], color=c, lw=1,
                     label=f"{label}: {s['angle'][0]:.1f}° ± {s['angle'][1]:.1f}°")
        axes[0].hlines(s["angle"][0], s["from"], s["to"], color=c, ls="--", lw=1)
        axes[0].plot(res["t"], res["centroid_angle"], color=c, lw=2, alpha=0.45,
                     label=f"{label}, from the bed's centroid: "
                           f"{s['centroid_angle'][0]:.1f}° ± {s['centroid_angle'][1]:.1f}°")
        axes[1].plot(res["t"], -res["torque"] / 1e3, color=c, lw=1,
                     label=f"{label}: drive torque (sensor)")
        axes[1].plot(res["t"], -res["weight_torque"] / 1e3, color=c, lw=2, alpha=0.45,
                     label=f"{label}: $M g |x_c|$")
    axes[0].axvline(steady_from, color="#888888", lw=0.8)
    axes[1].axvline(steady_from, color="#888888", lw=0.8)
    axes[0].set_ylabel("dynamic angle of repose (deg)")
    axes[0].set_ylim(0, 60)
    axes[1].set_ylabel("torque about the axis (10³ g cm²/s²)")
    axes[1].set_xlabel("time (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    print(path)


def snapshots(run_dir, times, path):
    with open(os.path.join(run_dir, "scene.json")) as f:
        scene = json.load(f)
    di, drum_name, centre, axis, _ = drum_of(scene)
    frames = figures.read_frames(run_dir)
    chosen = figures.pick_frames(frames, times, 5)
    fig, axs = plt.subplots(1, len(chosen), figsize=(2.6 * len(chosen), 2.9))
    for ax, (t, bodies_file, _) in zip(np.atleast_1d(axs), chosen):
        points, tri, arrays = figures.read_vtu(bodies_file)
        names = read_names_at(run_dir, t)
        drum_id = names.index(drum_name) if drum_name in names else -1
        corners = points[tri]
        ycent = corners[:, :, 1].mean(axis=1)
        is_drum = arrays["body_id"] == drum_id
        # The drum's caps are its last two blocks: the front one (towards -y) is left out.
        ncap = arrays["block_id"][is_drum].max()
        front_cap = is_drum & (arrays["block_id"] == ncap - 1)
        back_cap = is_drum & (arrays["block_id"] == ncap)
        staves = is_drum & ~front_cap & ~back_cap
        grains = ~is_drum
        _, shade = figures.shaded_triangles(points, tri, arrays["body_id"])
        xz = corners[:, :, [0, 2]]
        ax.add_collection(PolyCollection(xz[back_cap], facecolors="#eeeeee",
                                         edgecolors="none"))
        stave_colour = np.where((arrays["block_id"][staves] == 0)[:, None],
                                matplotlib.colors.to_rgb("#333333"),
                                matplotlib.colors.to_rgb("#9a9a9a"))
        ax.add_collection(PolyCollection(xz[staves], facecolors=stave_colour,
                                         edgecolors="none"))
        order = np.where(grains)[0]
        order = order[np.argsort(-ycent[order])]  # far (large y) first, near last
        ax.add_collection(PolyCollection(xz[order], facecolors=shade[order],
                                         edgecolors="none"))
        r = np.abs(points[:, [0, 2]]).max()
        ax.set_xlim(-r, r)
        ax.set_ylim(-r, r)
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(f"t = {t:.2f} s", fontsize=10, y=-0.12)
    fig.subplots_adjust(left=0, right=1, top=1, bottom=0.08, wspace=0.02)
    fig.savefig(path, dpi=80)
    plt.close(fig)
    print(path)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("dirs", nargs="*")
    p.add_argument("--run", help="scene to run first (then its --out DIR is analysed)")
    p.add_argument("--out", help="output directory of --run")
    p.add_argument("--tem", default="build/release/tem", help="TEM binary")
    p.add_argument("--labels", nargs="+")
    p.add_argument("--steady-from", type=float, default=1.0)
    p.add_argument("--figure", help="PNG: angle and torques against time")
    p.add_argument("--snapshots", help="PNG: cross-section strip of the first DIR")
    p.add_argument("--times", type=float, nargs="+", help="snapshot times")
    args = p.parse_args()
    dirs = list(args.dirs)
    if args.run:
        if not args.out:
            sys.exit("drum_angle: --run needs --out DIR")
        subprocess.run([args.tem, "run", args.run, "--out", args.out, "--threads", "1"],
                       check=True)
        dirs.insert(0, args.out)
    if not dirs:
        p.error("give at least one run directory (or --run SCENE --out DIR)")
    labels = args.labels or dirs
    results = []
    for run_dir, label in zip(dirs, labels):
        res = analyse(run_dir, args.steady_from, args.tem)
        s = stats(res, args.steady_from)
        report(label, res, s)
        results.append((res, s))
    if args.figure:
        figure(results, labels, args.steady_from, args.figure)
    if args.snapshots:
        snapshots(dirs[0], args.times, args.snapshots)


if __name__ == "__main__":
    main()
