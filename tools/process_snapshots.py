#!/usr/bin/python3
"""Snapshots of a process run (output.paraview true) cropped to a box, grains coloured by size.

usage: /usr/bin/python3 tools/process_snapshots.py RUN_DIR --box X0 Y0 Z0 X1 Y1 Z1
           --times T ... [--out PNG] [--elevation E] [--azimuth A] [--cut-front Y]
           [--stack STEP]

tools/figures.py draws every body whole, so a 56 cm belt squeezes the grains on it to dots.
This draws the same shaded triangles (tools/figures.py's reader and shading) inside the box
only: a body larger than the box (the belt, a plate, a bin) is clipped to it by clamping its
corners (exact for axis-aligned boxes), a grain with a corner outside is left out. Bodies are
coloured by size: scenery (larger than 2 cm) grey, grains gold, grains more than 1.5 times the
median grain size red (the large grains of a mixed bed). --cut-front Y leaves out the triangles
of scenery that lie wholly at y < Y (a container's front wall, to see inside). --stack STEP
stacks the panels top to bottom instead, each panel square (matplotlib's 3D axes always are) and
the next one STEP panel widths lower, overlapping: for a long, flat scene (a belt) that fills
only a band across its square.
Needs only Debian's python3-numpy and python3-matplotlib.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  (tools/figures.py: read_frames, read_vtu, pick_frames, LIGHT)

SCENERY, GRAIN, LARGE = "#9a9a9a", "#c8a24a", "#b5523b"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--box", type=float, nargs=6, required=True)
    ap.add_argument("--times", type=float, nargs="+", required=True)
    ap.add_argument("--out", default=None)
    ap.add_argument("--elevation", type=float, default=30)
    ap.add_argument("--azimuth", type=float, default=-60)
    ap.add_argument("--cut-front", type=float, default=None)
    ap.add_argument("--height", type=float, default=3.0, help="inches per panel")
    ap.add_argument("--zoom", type=float, default=1.0)
    ap.add_argument("--stack", type=float, default=None,
                    help="stack the panels, each this fraction of the width below the last")
    args = ap.parse_args()
    lo, hi = np.array(args.box[:3]), np.array(args.box[3:])
    chosen = figures.pick_frames(figures.read_frames(args.run_dir), args.times, 0)
    sides = hi - lo
    tilt = np.radians(args.elevation)
    across = np.hypot(sides[0], sides[1])
    upright = sides[2] * np.cos(tilt) + across * np.sin(tilt)
    h = args.height
    n_pan = len(chosen)
    if args.stack:
        fig_h = h * (1 + args.stack * (n_pan - 1))
        fig = plt.figure(figsize=(h, fig_h))
    else:
        fig = plt.figure(figsize=(n_pan * h * np.clip(across / upright, 0.5, 2.5), h))
    for k, (t, bodies, _) in enumerate(chosen):
        points, tris, arrays = figures.read_vtu(bodies)
        bid = arrays["body_id"]
        ids = np.unique(bid)
        size = {}
        for i in ids:
            p = points[tris[bid == i].ravel()]
            size[i] = np.max(p.max(axis=0) - p.min(axis=0))
        grain_sizes = [s for s in size.values() if s <= 2.0]
        median = np.median(grain_sizes) if grain_sizes else 1.0
        keep, colours = [], []
        for i in ids:
            c = tris[bid == i]
            corners = points[c]
            if size[i] > 2.0:
                if args.cut_front is not None:
                    corners = corners[~np.all(corners[:, :, 1] < args.cut_front, axis=1)]
                corners = np.clip(corners, lo, hi)
                colour = SCENERY
            else:
                inside = np.all((corners >= lo) & (corners <= hi), axis=(1, 2))
                if not inside.all():
                    continue
                colour = LARGE if size[i] > 1.5 * median else GRAIN
            keep.append(corners)
            colours += [colour] * len(corners)
        corners = np.concatenate(keep)
        n = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        norm = np.linalg.norm(n, axis=1)
        ok = norm > 1e-12  # clamping can flatten a triangle
        corners, n, norm = corners[ok], n[ok], norm[ok]
        light = 0.35 + 0.65 * np.clip((n / norm[:, None]) @ figures.LIGHT, 0, None)
        base = np.array([matplotlib.colors.to_rgb(c) for c in np.array(colours)[ok]])
        if args.stack:
            ax = fig.add_axes([0, (n_pan - 1 - k) * args.stack * h / fig_h, 1, h / fig_h],
                              projection="3d", computed_zorder=False)
            ax.set_facecolor("none")  # the panels overlap
        else:
            ax = fig.add_subplot(1, n_pan, k + 1, projection="3d", computed_zorder=False)
        ax.add_collection3d(Poly3DCollection(corners, facecolors=np.clip(base * light[:, None], 0, 1),
                                             edgecolor="none"))
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(sides, zoom=args.zoom)
        ax.view_init(elev=args.elevation, azim=args.azimuth)
        ax.set_axis_off()
        if args.stack:
            ax.text2D(0.02, 0.5 + 0.5 * args.stack, f"t = {t:.3g} s", transform=ax.transAxes,
                      fontsize=10)
        else:
            ax.text2D(0.5, -0.04, f"t = {t:.3g} s", transform=ax.transAxes, ha="center",
                      fontsize=10)
    if not args.stack:
        fig.subplots_adjust(left=0, right=1, bottom=0.05, top=1, wspace=0)
    out = args.out or os.path.join(args.run_dir, "snapshots.png")
    fig.savefig(out, dpi=100, bbox_inches="tight", pad_inches=0.05)
    if args.stack:  # the square panels leave white bands above and below: trim them
        img = plt.imread(out)
        ink = np.nonzero((img[:, :, :3] < 0.98).any(axis=(1, 2)))[0]
        plt.imsave(out, img[max(ink[0] - 8, 0):ink[-1] + 9])
    print(f"wrote {out}")


if __name__ == "__main__":
    sys.exit(main())
