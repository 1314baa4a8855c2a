#!/usr/bin/python3
"""Figures of one `tem run` output directory (run with output.paraview true):

  PREFIX_snapshots.png  a strip of 3D snapshots of the bodies (as the paper's figures 14 and 15),
                        triangles shaded by their normal, the floor drawn, equal axis scaling,
                        the time under each snapshot;
  PREFIX_energy.png     kinetic, potential and total energy, contact count and deepest overlap
                        against time (from energy.csv).

usage: /usr/bin/python3 tools/figures.py RUN_DIR [--out PREFIX] [--times T ...] [--frames N]

PREFIX defaults to RUN_DIR/figure. --times picks the frames nearest to those times; by default
N (6) frames evenly spaced over the run. Needs only Debian's python3-numpy and
python3-matplotlib: the .vtu files (binary, written by src/io/paraview_frames.cpp) are read by
tools/tem_vtu.py.
"""
import argparse
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import tem_vtu  # noqa: E402  (tools/tem_vtu.py, beside this script)

LIGHT = np.array([0.4, -0.5, 0.77])  # towards the light, world axes (from above, front left)
LIGHT /= np.linalg.norm(LIGHT)
BODY_COLOURS = ["#c8a24a", "#5b84b1", "#b5523b", "#6a9c5a", "#8c6bb1", "#d08c3c"]


def read_frames(run_dir):
    """[(time, bodies file, contacts file)] in the order of tem.pvd. A run without ParaView
    files is refused with the reason, for every tool that reads frames."""
    pvd = os.path.join(run_dir, "tem.pvd")
    if not os.path.exists(pvd):
        sys.exit(f"{os.path.basename(sys.argv[0])}: {pvd} not found: the ParaView frames are "
                 "written when the scene sets \"output\": {\"paraview\": true}")
    frames = {}
    order = []
    root = ET.parse(pvd).getroot()
    for d in root.iter("DataSet"):
        t = float(d.attrib["timestep"])
        if t not in frames:
            order.append(t)
        frames.setdefault(t, {})[d.attrib["part"]] = os.path.join(run_dir, d.attrib["file"])
    return [(t, frames[t]["0"], frames[t].get("1")) for t in order]


def read_vtu(path):
    """Points, cell connectivity (one row per cell) and every named DataArray of a .vtu file
    (one cell type per file as TEM writes them)."""
    piece, arrays, _ = tem_vtu.read_vtu(path)
    cells = int(piece.attrib["NumberOfCells"])
    connectivity = arrays["connectivity"].reshape(cells, -1) if cells else np.zeros((0, 3), int)
    return arrays["Points"].reshape(-1, 3), connectivity, arrays


def floor_height(run_dir):
    """Height of the floor (a wall facing +z) from the scene as run, or None."""
    with open(os.path.join(run_dir, "scene.json")) as f:
        scene = json.load(f)
    heights = []
    if scene.get("container"):
        heights.append(scene["container"]["min"][2])
    for wall in scene.get("walls", []):
        n = np.array(wall["normal"], dtype=float)
        if np.allclose(n / np.linalg.norm(n), [0, 0, 1]):
            heights.append(wall["point"][2])
    return max(heights) if heights else None


def pick_frames(frames, times, count):
    if times:
        all_times = np.array([f[0] for f in frames])
        return [frames[int(np.argmin(np.abs(all_times - t)))] for t in times]
    indices = np.linspace(0, len(frames) - 1, min(count, len(frames))).round().astype(int)
    return [frames[i] for i in indices]


def shaded_triangles(points, triangles, body_id):
    """Triangle corner coordinates and Lambert-shaded colours, one per triangle."""
    corners = points[triangles]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    light = 0.35 + 0.65 * np.clip(normals @ LIGHT, 0, None)
    base = np.array([matplotlib.colors.to_rgb(BODY_COLOURS[b % len(BODY_COLOURS)])
                     for b in body_id])
    return corners, np.clip(base * light[:, None], 0, 1)


def snapshots(run_dir, chosen, prefix, elevation, azimuth):
    meshes = [read_vtu(bodies) for _, bodies, _ in chosen]
    # One box for every snapshot, just around the bodies and down to the floor; its sides keep
    # the data's proportions, so the three axes scale equally.
    everything = np.vstack([m[0] for m in meshes])
    low, high = everything.min(axis=0), everything.max(axis=0)
    floor = floor_height(run_dir)
    if floor is not None:
        low[2] = min(low[2], floor)
    margin = 0.08 * np.max(high - low)
    box_low, box_high = low - margin, high + margin
    if floor is not None:  # the floor at the bottom of the box, not mid-air
        box_low[2] = floor

    sides = box_high - box_low
    # Each panel shaped like the box as the camera sees it, so the box fills it.
    tilt = np.radians(elevation)
    across = np.hypot(sides[0], sides[1])
    upright = sides[2] * np.cos(tilt) + across * np.sin(tilt)
    height = 3.4
    fig = plt.figure(figsize=(len(chosen) * height * np.clip(across / upright, 0.4, 2.0), height))
    for k, ((t, _, _), (points, triangles, arrays)) in enumerate(zip(chosen, meshes)):
        ax = fig.add_subplot(1, len(chosen), k + 1, projection="3d", computed_zorder=False)
        if floor is not None:
            x0, y0, x1, y1 = box_low[0], box_low[1], box_high[0], box_high[1]
            ax.add_collection3d(Poly3DCollection(
                [[(x0, y0, floor), (x1, y0, floor), (x1, y1, floor), (x0, y1, floor)]],
                facecolor="#d9d9d9", edgecolor="#a0a0a0", linewidth=0.5, zorder=0))
        corners, colours = shaded_triangles(points, triangles, arrays["body_id"])
        ax.add_collection3d(Poly3DCollection(corners, facecolors=colours, edgecolor="none",
                                             zorder=1))
        ax.set_xlim(box_low[0], box_high[0])
        ax.set_ylim(box_low[1], box_high[1])
        ax.set_zlim(box_low[2], box_high[2])
        ax.set_box_aspect(sides, zoom=1.25)
        ax.view_init(elev=elevation, azim=azimuth)
        ax.set_axis_off()
        ax.text2D(0.5, -0.06, f"t = {t:.3g} s", transform=ax.transAxes, ha="center",
                  fontsize=11)
    fig.subplots_adjust(left=0, right=1, bottom=0.06, top=1, wspace=0)
    path = prefix + "_snapshots.png"
    fig.savefig(path, dpi=90, bbox_inches="tight", pad_inches=0.05)
    plt.close(fig)
    return path


def energy_plot(run_dir, prefix):
    with open(os.path.join(run_dir, "energy.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    column = {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}
    t = column["time"]
    fig, axes = plt.subplots(3, 1, figsize=(7, 6.5), sharex=True,
                             gridspec_kw={"height_ratios": [2, 1, 1]})
    for key in ("kinetic", "potential", "total"):
        axes[0].plot(t, column[key], label=key, linewidth=1.2)
    axes[0].set_ylabel("energy")
    axes[0].legend(loc="best", fontsize=9)
    axes[1].step(t, column["contacts"], where="post", color="#444444", linewidth=1)
    axes[1].set_ylabel("contact patches")
    axes[2].plot(t, column["max_depth"], color="#b5523b", linewidth=1)
    axes[2].set_ylabel("deepest overlap")
    axes[2].set_xlabel("time (s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    path = prefix + "_energy.png"
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--out", help="prefix of the PNG files (default RUN_DIR/figure)")
    parser.add_argument("--times", type=float, nargs="+", help="snapshot times (s)")
    parser.add_argument("--frames", type=int, default=6, help="snapshots when no --times")
    parser.add_argument("--elevation", type=float, default=18, help="view elevation (deg)")
    parser.add_argument("--azimuth", type=float, default=-60, help="view azimuth (deg)")
    args = parser.parse_args()
    prefix = args.out or os.path.join(args.run_dir, "figure")
    chosen = pick_frames(read_frames(args.run_dir), args.times, args.frames)
    print(snapshots(args.run_dir, chosen, prefix, args.elevation, args.azimuth))
    print(energy_plot(args.run_dir, prefix))


if __name__ == "__main__":
    main()
