#!/usr/bin/python3
"""The flat-bottomed silo of scenes/processes/silo.json, as a function of the orifice width.

usage: /usr/bin/python3 tools/silo_scene.py [--orifice D] [--count N] [--duration T]
                                            [--gate T] [--time-step DT] [--out FILE]

Writes the scene (to stdout or FILE). tools/beverloo.py imports `silo_scene()` to write its
variants; scenes/processes/silo.json is `tools/silo_scene.py --out scenes/processes/silo.json`.

Geometry (cm, g, s): a square silo of inner width WIDTH whose side walls are the container's
faces; its floor (top at z = 0, THICK deep) is four fixed steel plates that leave a square
orifice of width D in the middle; a fixed gate plate closes the orifice from below until `gate`
seconds; grains that fall through are removed by an outlet region 1.5 cm under the floor. The
grains are irregular convex hexahedra (a cube of side SIDE with its corners moved by up to 15 %,
the same shape for every grain, turned at random by `fill`), sizes drawn in [0.9, 1.1] x.
Sensors: `orifice` (a plane 0.6 cm under the floor top: cumulative discharged count and mass),
`contents` (the whole silo above the floor), `core` (a sub-volume of the settled fill, away from
the walls, the floor and the free surface, for the bulk density) and `floor` (the force on the
four floor plates).
"""
import argparse
import json
import random
import sys

WIDTH = 4.5          # silo inner width, cm (x and y)
THICK = 0.3          # floor plate thickness, cm
SIDE = 0.25          # grain: side of the cube it is cut from, cm
DENSITY = 2.5        # grain density, g/cm^3 (glass)
BOTTOM = -3.0        # container floor, cm
CORE = {"min": [-1.5, -1.5, 0.4], "max": [1.5, 1.5, 1.9]}  # bulk-density sub-volume
COUNT = 2000         # grains
GATE = 0.3           # s: the gate is removed then (the fill has settled)
ORIFICE = 2.0        # cm: the orifice width of scenes/processes/silo.json
GRAIN_FRICTION = 0.3  # grain-grain (0.5 clogged orifices of 6 and 8 cube sides: docs/processes/silo.md)
WALL_FRICTION = 0.2   # grain-steel


def grain_points(seed=11, jitter=0.15):
    """Corners of a cube of side SIDE, each moved by up to jitter*SIDE along each axis: an
    irregular convex hexahedron (8 corners; its non-planar faces become triangles)."""
    rng = random.Random(seed)
    h = SIDE / 2
    pts = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                pts.append([round(s * h + rng.uniform(-jitter, jitter) * SIDE, 4)
                            for s in (sx, sy, sz)])
    return pts


def silo_scene(orifice=ORIFICE, count=COUNT, duration=1.0, gate=GATE, time_step=4e-4,
               fill_top=None, paraview=False, interval=0.01):
    D, W, T = orifice, WIDTH, THICK
    if fill_top is None:  # `fill` places ~4.2 grains per cm^3 (bounding spheres apart)
        fill_top = round(count / (4.0 * W * W) + 1.0, 1)
    h = W / 2
    # Floor: two plates across the whole width (y beyond +-D/2), two between them (x beyond).
    wing = h - D / 2
    plates = [
        ("floor_north", [W, wing, T], [0, D / 2 + wing / 2, -T / 2]),
        ("floor_south", [W, wing, T], [0, -D / 2 - wing / 2, -T / 2]),
        ("floor_east", [wing, D, T], [D / 2 + wing / 2, 0, -T / 2]),
        ("floor_west", [wing, D, T], [-D / 2 - wing / 2, 0, -T / 2]),
    ]
    bodies = [{"name": n, "shape": {"type": "box", "size": s}, "position": p, "fixed": True,
               "material": "steel"} for n, s, p in plates]
    bodies.append({"name": "gate", "shape": {"type": "box", "size": [D + 0.6, D + 0.6, 0.2]},
                   "position": [0, 0, -T - 0.11], "fixed": True, "material": "steel",
                   "removed_at": gate})
    return {
        "gravity": "earth",
        "time_step": time_step,
        "duration": duration,
        "materials": {"grain": {"friction": GRAIN_FRICTION, "restitution": 0.1},
                      "steel": {"friction": 0.3, "restitution": 0.1}},
        "contact": {"model": "semm", "solver": "rows", "tolerance": 1e-3, "max_sweeps": 20,
                    "pairs": [{"materials": ["grain", "steel"], "friction": WALL_FRICTION}]},
        "container": {"min": [-h, -h, BOTTOM], "max": [h, h, fill_top + 0.5],
                      "material": "steel"},
        "bodies": bodies,
        "fill": [{"name": "grain", "count": count, "seed": 1,
                  "region": {"min": [-h, -h, 0.0], "max": [h, h, fill_top]},
                  "body": {"shape": {"type": "convex", "points": grain_points()},
                           "density": DENSITY, "material": "grain",
                           "velocity": [0, 0, -50],
                                                      "scale": {"min": 0.9, "max": 1.1}}}],
        "outlets": [{"name": "bin", "region": {"min": [-h, -h, BOTTOM], "max": [h, h, -1.5]}}],
        "sensors": [
            {"name": "orifice", "type": "plane", "point": [0, 0, -0.6], "normal": [0, 0, -1]},
            {"name": "contents", "type": "region",
             "region": {"min": [-h, -h, 0.0], "max": [h, h, fill_top]}},
            {"name": "core", "type": "region", "region": CORE},
            {"name": "floor", "type": "force", "bodies": [n for n, _, _ in plates]},
        ],
        "output": {"interval": interval, "paraview": paraview},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--orifice", type=float, default=ORIFICE)
    ap.add_argument("--count", type=int, default=COUNT)
    ap.add_argument("--duration", type=float, default=1.0)
    ap.add_argument("--gate", type=float, default=GATE)
    ap.add_argument("--time-step", type=float, default=4e-4)
    ap.add_argument("--fill-top", type=float)
    ap.add_argument("--interval", type=float, default=0.01)
    ap.add_argument("--paraview", action="store_true")
    ap.add_argument("--out")
    a = ap.parse_args()
    s = silo_scene(a.orifice, a.count, a.duration, a.gate, a.time_step, a.fill_top,
                   a.paraview, a.interval)
    text = json.dumps(s, indent=1) + "\n"
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
