#!/usr/bin/python3
"""Is a pour right? Judges one or more `tem run` output directories of a pile.

For each DIR (bodies.csv, energy.csv, scene.json of a finished `tem run`), prints:

  outside    body centres outside the container box, over every row of bodies.csv;
  overlap    the largest max_depth of energy.csv over every row, as % of the smallest body size
             (body_size: centre of mass to farthest node; prisms and boxes only, else --size);
  rise       the largest rise of the total energy between two rows, relative to
             |total| + |potential| at the first row (the issue's measure);
  at rest    bodies whose speed at the last row is below --rest (cm/s, default 0.1) and whose
             angular speed times their size is too; and the fastest body's speed;
  height     the pile's height 2 * mean(z of the centres) at the last row (a pile filling
             [0, H] evenly has its centres' mean at H/2) and the packing fraction
             N V / (container floor area * height), V the body volume (prisms and boxes);
  wall time  from tem's stderr log, if DIR/../NAME.log or --log gives it (optional).

With two or more directories, the last ones are compared with the first (the reference, e.g.
the same pour at dt 2e-5): relative differences of height and packing fraction.

Usage: /usr/bin/python3 tools/pile_check.py DIR [DIR ...] [--rest V] [--size L]
"""
import csv
import json
import math
import sys


def body_template(scene):
    """The shape and count of each body kind: the scene's bodies and its fill templates."""
    kinds = [(b["shape"], 1) for b in scene.get("bodies", [])]
    kinds += [(f["body"]["shape"], f["count"]) for f in scene.get("fill", [])]
    return kinds


def size_and_volume(shape):
    if shape["type"] == "prism":
        n, r, h = shape.get("sides", 6), shape["radius"], shape["height"]
        area = 0.5 * n * r * r * math.sin(2 * math.pi / n)
        return math.sqrt(r * r + h * h / 4), area * h
    if shape["type"] == "box":
        a, b, c = shape["size"]
        return math.sqrt(a * a + b * b + c * c) / 2, a * b * c
    return None, None


def check(directory, rest, size_override):
    scene = json.load(open(f"{directory}/scene.json"))
    sizes, volume, count = [], 0.0, 0
    for shape, n in body_template(scene):
        size, v = size_and_volume(shape)
        if size is not None:
            sizes.append(size)
            volume += n * v
        count += n
    smallest = size_override or min(sizes)
    box = scene.get("container")
    rows = list(csv.DictReader(open(f"{directory}/bodies.csv")))
    outside = 0
    for r in rows:
        p = (float(r["x"]), float(r["y"]), float(r["z"]))
        if box and any(not (box["min"][k] <= p[k] <= box["max"][k]) for k in range(3)):
            outside += 1
    energy = list(csv.DictReader(open(f"{directory}/energy.csv")))
    deepest = max(float(e["max_depth"]) for e in energy)
    scale = abs(float(energy[0]["total"])) + abs(float(energy[0]["potential"]))
    rise = max((float(b["total"]) - float(a["total"]) for a, b in zip(energy, energy[1:])),
               default=0.0)
    last_time = rows[-1]["time"]
    last = [r for r in rows if r["time"] == last_time]
    speeds = [math.sqrt(sum(float(r[k]) ** 2 for k in ("vx", "vy", "vz"))) for r in last]
    spins = [math.sqrt(sum(float(r[k]) ** 2 for k in ("wx", "wy", "wz"))) for r in last]
    at_rest = sum(1 for v, w in zip(speeds, spins) if v < rest and w * smallest < rest)
    mean_z = sum(float(r["z"]) for r in last) / len(last)
    height = 2 * mean_z
    fraction = None
    if box and volume > 0:
        floor = (box["max"][0] - box["min"][0]) * (box["max"][1] - box["min"][1])
        fraction = volume / (floor * (height - box["min"][2]))
    return {
        "dir": directory, "time": float(last_time), "bodies": len(last), "outside": outside,
        "overlap_pct": 100 * deepest / smallest, "rise": rise / scale if scale else rise,
        "at_rest": at_rest, "fastest": max(speeds), "height": height, "fraction": fraction,
    }


def main(argv):
    rest, size = 0.1, None
    dirs = []
    i = 0
    while i < len(argv):
        if argv[i] == "--rest":
            rest = float(argv[i + 1]); i += 2
        elif argv[i] == "--size":
            size = float(argv[i + 1]); i += 2
        else:
            dirs.append(argv[i]); i += 1
    if not dirs:
        print(__doc__)
        return 2
    results = [check(d, rest, size) for d in dirs]
    for r in results:
        frac = f"{r['fraction']:.4f}" if r["fraction"] is not None else "-"
        print(f"{r['dir']}: t {r['time']:g} s, {r['bodies']} bodies, outside {r['outside']}, "
              f"deepest overlap {r['overlap_pct']:.3f} % of the smallest size, largest energy "
              f"rise {r['rise']:.2e}, at rest (< {rest:g} cm/s) {r['at_rest']}/{r['bodies']}, "
              f"fastest {r['fastest']:.3g} cm/s, height {r['height']:.4f} cm, packing "
              f"fraction {frac}")
    ref = results[0]
    for r in results[1:]:
        dh = (r["height"] - ref["height"]) / ref["height"]
        line = f"{r['dir']} against {ref['dir']}: height {100 * dh:+.2f} %"
        if r["fraction"] and ref["fraction"]:
            line += f", packing fraction {100 * (r['fraction'] - ref['fraction']) / ref['fraction']:+.2f} %"
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
