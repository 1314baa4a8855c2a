#!/usr/bin/python3
"""A poured pile as a scene of its own: the bodies of a `tem run` at their last poses, at rest.

Reads a run's folder (its scene.json, which must fill one kind of body, and bodies.csv), and
writes a scene whose bodies are those of the last row time, named as in the run, each with its
position and quaternion and no velocity, in the run's container and walls, with the `contact`
given (the scene's defaults for every key it does not set), time step and duration. Step costs of
different solvers on the same settled pile are then `tem run`s of its scenes (docs/benchmarks.md,
"SEMM by Newton"). The pile starts without the run's contact memory (no warm start): its first
steps are what a solver meets on a pile it did not pour. A peer engine's pile reads the same way:
`tem_bullet SCENE --final-run DIR` (bench/peers/peer_run.hpp) writes its last poses as such a
folder. Standard library only.

  /usr/bin/python3 tools/settled_pile.py out/pour --contact '{"solver": "newton"}' \
      --dt 5e-4 --duration 0.02 > settled_newton.json
"""
import argparse
import csv
import json
import os
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="the folder of a finished tem run")
    parser.add_argument("--contact", default="{}", help="the contact object, as JSON")
    parser.add_argument("--dt", type=float, required=True)
    parser.add_argument("--duration", type=float, required=True)
    args = parser.parse_args()

    scene = json.load(open(os.path.join(args.run, "scene.json")))
    fills = scene.get("fill", [])
    if len(fills) != 1 or scene.get("bodies"):
        sys.exit("settled_pile.py: the run must fill one kind of body and have no other bodies")
    template = fills[0]["body"]
    rows = list(csv.DictReader(open(os.path.join(args.run, "bodies.csv"))))
    if not rows:
        sys.exit("settled_pile.py: bodies.csv has no rows")
    last = max(float(r["time"]) for r in rows)
    bodies = []
    for r in rows:
        if float(r["time"]) != last:
            continue
        body = {key: template[key] for key in template if key not in ("velocity", "angular_velocity")}
        body["name"] = r["body"]
        body["position"] = [float(r["x"]), float(r["y"]), float(r["z"])]
        body["quaternion"] = [float(r["qw"]), float(r["qx"]), float(r["qy"]), float(r["qz"])]
        bodies.append(body)
    contact = {"model": "semm", "friction": scene["contact"].get("friction", 0.3)}
    contact.update(json.loads(args.contact))
    out = {"gravity": scene["gravity"], "time_step": args.dt, "duration": args.duration,
           "contact": contact, "bodies": bodies, "output": {"interval": args.duration / 2}}
    for key in ("container", "walls", "materials"):
        if key in scene:
            out[key] = scene[key]
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
