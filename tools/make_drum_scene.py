#!/usr/bin/python3
"""Writes the rotating-drum scene (scenes/processes/drum.json) and its variants.

usage: /usr/bin/python3 tools/make_drum_scene.py [--out scenes/processes/drum.json]
           [--grain-friction 0.7] [--omega 1.9] [--duration 2.0] [--dt 2.5e-4]
           [--interval 0.02] [--paraview | --no-paraview] [--box]

The drum is ONE body: a compound of SIDES trapezoidal staves (convex hulls of 8 points) that
tile the annulus between the inner polygon (apothem R_IN) and the outer one (apothem R_IN + WALL),
plus the two end caps (SIDES-gon prisms), so the caps turn with the staves. Its axis is the
world y axis through the origin, and it turns with `motion.angular_velocity` [0, omega, 0] from
t = 0 (started at once, while the grains fall in). With omega > 0 about +y the bottom moves
towards -x, so the bed climbs on the -x side (centre of mass at x_c < 0).

Grains: one irregular convex polyhedron (the hull of 10 jittered points on a sphere of radius
GRAIN_R, drawn once with a fixed seed), copied with size factors 0.9-1.1: `fill` places as many
as fit inside the drum (the block rule lets the fill region lie inside the drum body), and an
inlet in the drum's upper half adds the rest over the first 0.1 s (fill's loose placement of
bounding spheres cannot reach a 35 % filling by itself; see docs/processes/drum.md).

--box writes instead the cost reference: the same grains (fill + inlet counts, same dt and
contact settings) poured into a closed box of the drum's inner volume, no drum.
"""
import argparse
import json
import math
import random

SIDES = 20          # staves
R_IN = 2.5          # inner apothem, cm
WALL = 0.4          # stave thickness, cm
LENGTH = 1.5        # inner length along the axis, cm
CAP = 0.3           # end cap thickness, cm
GRAIN_R = 0.3       # grain circumradius (template), cm: volume-equivalent diameter ~0.40 cm
FILL_COUNT = 60
INLET_COUNT = 120


def grain_points(seed=11, n=10):
    """Hull corners of an irregular convex grain: n points, uniform on the sphere, radii
    jittered in [0.8, 1] GRAIN_R. Rounded to 1e-4 cm."""
    rng = random.Random(seed)
    pts = []
    while len(pts) < n:
        v = [rng.gauss(0, 1) for _ in range(3)]
        norm = math.sqrt(sum(c * c for c in v))
        r = GRAIN_R * rng.uniform(0.8, 1.0)
        p = [round(r * c / norm, 4) for c in v]
        if all(math.dist(p, q) > 0.6 * GRAIN_R for q in pts):  # no slivers
            pts.append(p)
    centre = [sum(p[k] for p in pts) / n for k in range(3)]
    return [[round(p[k] - centre[k], 4) for k in range(3)] for p in pts]


def drum_shape():
    """Compound: SIDES staves and two caps, in the drum frame (axis y, centre at the origin).
    Stave k spans the angles (k -/+ 1/2) 2 pi / SIDES measured from +z towards +x."""
    half = math.pi / SIDES
    r_in = R_IN / math.cos(half)            # circumradius of the inner polygon
    r_out = (R_IN + WALL) / math.cos(half)  # and of the outer one
    blocks = []
    for k in range(SIDES):
        a0, a1 = (2 * k - 1) * half, (2 * k + 1) * half
        pts = []
        for r in (r_in, r_out):
            for a in (a0, a1):
                for y in (-LENGTH / 2, LENGTH / 2):
                    pts.append([round(r * math.sin(a), 6), y, round(r * math.cos(a), 6)])
        blocks.append({"type": "convex", "points": pts})
    for side in (-1, 1):
        # The prism about y has its first node on +z, as the staves' corners: the same polygon.
        blocks.append({"type": "prism", "sides": SIDES, "radius": round(r_out, 6),
                       "height": CAP, "axis": "y",
                       "position": [0, side * (LENGTH + CAP) / 2, 0]})
    return {"type": "compound", "blocks": blocks}


def grain_body(friction_material="grain"):
    return {"shape": {"type": "convex", "points": grain_points()}, "density": 2.5,
            "material": friction_material, "scale": {"min": 0.9, "max": 1.1}}


def contact(args):
    return {"model": "semm", "solver": "rows", "friction": 0.5, "restitution": 0.0,
            "tolerance": 1e-3, "max_sweeps": 20,
            "pairs": [{"materials": ["drum", "grain"], "friction": 0.7}]}


def drum_scene(args):
    # The fill region: a square in the cross-section whose corners lie inside the staves'
    # material (a sqrt 2 <= outer apothem), so no copy can land outside the drum; copies that
    # would cut a stave are refused by the block rule.
    a = round((R_IN + WALL) / math.sqrt(2) - 0.01, 3)
    h = LENGTH / 2
    return {
        "gravity": "earth",
        "time_step": args.dt,
        "duration": args.duration,
        "contact": contact(args),
        "materials": {"drum": {"friction": 0.7, "restitution": 0.0},
                      "grain": {"friction": args.grain_friction, "restitution": 0.0}},
        "bodies": [{"name": "drum", "shape": drum_shape(), "position": [0, 0, 0],
                    "density": 7.8, "material": "drum",
                    "motion": {"angular_velocity": [0, args.omega, 0], "center": [0, 0, 0],
                               "start": 0.0}}],
        "fill": [{"name": "grain", "count": FILL_COUNT, "seed": 4,
                  "region": {"min": [-a, -h, -a], "max": [a, h, a]},
                  "body": grain_body()}],
        "inlets": [{"name": "topup", "region": {"min": [-1.6, -h, 0.3], "max": [1.6, h, 1.9]},
                    "rate": 1000, "count": INLET_COUNT, "start": 0.0, "seed": 5,
                    "velocity": [0, 0, 0], "body": grain_body()}],
        # Grains that left the drum (none should) are caught and written to removed.csv.
        "outlets": [{"name": "escaped", "region": {"min": [-20, -20, -40], "max": [20, 20, -10]}}],
        "sensors": [{"name": "drum", "type": "force", "bodies": ["drum"]},
                    {"name": "inside", "type": "region",
                     "region": {"min": [-R_IN - WALL, -h, -R_IN - WALL],
                                "max": [R_IN + WALL, h, R_IN + WALL]}}],
        "output": {"interval": args.interval, "paraview": args.paraview},
    }


def box_scene(args):
    """The cost reference: the same grains in a closed box of the drum's inner volume."""
    area = SIDES * R_IN * R_IN * math.tan(math.pi / SIDES)  # inner polygon's area
    side = round(math.sqrt(area), 4)
    h = LENGTH / 2
    return {
        "gravity": "earth",
        "time_step": args.dt,
        "duration": args.duration,
        "contact": contact(args),
        "materials": {"drum": {"friction": 0.7, "restitution": 0.0},
                      "grain": {"friction": args.grain_friction, "restitution": 0.0}},
        "container": {"min": [-side / 2, -h, -side / 2], "max": [side / 2, h, 3.5 * side],
                      "material": "drum"},
        "fill": [{"name": "grain", "count": FILL_COUNT + INLET_COUNT, "seed": 4,
                  "region": {"min": [-side / 2, -h, -side / 2], "max": [side / 2, h, 3.5 * side]},
                  "body": grain_body()}],
        "output": {"interval": args.interval},
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", default="scenes/processes/drum.json")
    p.add_argument("--grain-friction", type=float, default=0.7)
    p.add_argument("--omega", type=float, default=1.9, help="rad/s")
    p.add_argument("--duration", type=float, default=2.5)
    p.add_argument("--dt", type=float, default=2.5e-4)
    p.add_argument("--interval", type=float, default=0.02)
    p.add_argument("--paraview", action=argparse.BooleanOptionalAction, default=True)
    p.add_argument("--box", action="store_true")
    args = p.parse_args()
    scene = box_scene(args) if args.box else drum_scene(args)
    text = json.dumps(scene, indent=1)
    with open(args.out, "w") as f:
        f.write(text + "\n")
    print(args.out)


if __name__ == "__main__":
    main()
