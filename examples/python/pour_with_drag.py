#!/usr/bin/python3
"""100 coins poured into a box through a fluid, the fluid stood in for by a drag field.

Every step, Python writes each coin's load from the state TEM holds (no copies: the arrays are
views on TEM's memory):

    F = -c (v - u(z)),  T = -k w,      u(z) = [0, 0, U (1 - z / H)]

a linear drag towards a slow upward flow that dies out at the height H, with c = m / tau, so
that in still fluid a coin would sink at g tau. Where the flow is faster than that (low down,
with U > g tau) it lifts the coins: they settle, colliding, around the height where
u(z) = g tau, a crude fluidised bed. The plot shows their mean height and kinetic energy
against time.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/pour_with_drag.py [PNG]

(or without PYTHONPATH after `cmake --install build/release --component python --prefix
~/.local`). About half a minute on one core.
"""
import argparse
import json
import pathlib
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
try:
    import tem
except ImportError:  # not installed: the release build's module
    sys.path.insert(0, str(ROOT / "build/release/python"))
    import tem


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("png", nargs="?", default="out/pour_with_drag.png",
                        help="where the plot goes (default: out/pour_with_drag.png)")
    parser.add_argument("--scene", default=str(ROOT / "scenes/bench/coins_100.json"))
    parser.add_argument("--duration", type=float, default=0.4, help="simulated s (0.4)")
    parser.add_argument("--tau", type=float, default=0.05,
                        help="drag time constant m / c, s (0.05: sinks at g tau = 49 cm/s)")
    parser.add_argument("--flow", type=float, default=80.0,
                        help="upward flow speed U at the bottom, cm/s (80)")
    parser.add_argument("--flow-height", type=float, default=2.5,
                        help="height H where the flow has died out, cm (2.5)")
    args = parser.parse_args()

    scene = json.loads(pathlib.Path(args.scene).read_text())
    scene["duration"] = args.duration
    sim = tem.Simulation.from_dict(scene)
    tem.set_threads(1)

    b = sim.bodies
    moving = ~b.fixed
    mass = b.mass
    c = (mass / args.tau)[:, None]  # linear drag, per body
    k = (np.trace(b.inertia_body, axis1=1, axis2=2) / 3 / args.tau)[:, None]  # rotational
    # Views, taken once: they see every step.
    x, v, w = b.position, b.velocity, b.angular_velocity
    force, torque = b.external_force, b.external_torque
    u = np.zeros_like(v)

    g = abs(scene_gravity(scene))
    print(f"{len(b)} bodies, dt {sim.time_step:g} s, {sim.total_steps} steps; "
          f"still-fluid sinking speed g tau = {g * args.tau:.1f} cm/s, "
          f"flow {args.flow:g} cm/s at the bottom, hover height "
          f"{args.flow_height * (1 - g * args.tau / args.flow):.2f} cm")

    every = max(1, round(0.005 / sim.time_step))  # a sample every 5 ms
    times, heights, kinetic = [], [], []
    start = time.perf_counter()
    while sim.step_count < sim.total_steps:
        if sim.step_count % every == 0:
            times.append(sim.time)
            heights.append(x[moving, 2].mean())
            kinetic.append(sim.energies()["kinetic"])
        u[:, 2] = args.flow * np.clip(1 - x[:, 2] / args.flow_height, 0, None)
        np.multiply(c, u - v, out=force)
        np.multiply(-k, w, out=torque)
        sim.step()
    wall = time.perf_counter() - start
    times.append(sim.time)
    heights.append(x[moving, 2].mean())
    kinetic.append(sim.energies()["kinetic"])
    print(f"{sim.total_steps} steps in {wall:.1f} s ({1e6 * wall / sim.total_steps:.0f} us "
          f"a step, Python's drag included); mean height {heights[-1]:.3f} cm, kinetic "
          f"energy {kinetic[-1]:.4g} g cm^2/s^2, {len(sim.contacts())} contacts at the end")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0))
    top.plot(times, heights)
    top.axhline(args.flow_height * (1 - g * args.tau / args.flow), ls="--", c="grey",
                label="where the flow equals g tau")
    top.set_ylabel("mean height (cm)")
    top.legend()
    bottom.plot(times, kinetic)
    bottom.set_yscale("log")
    bottom.set_ylabel("kinetic energy (g cm$^2$/s$^2$)")
    bottom.set_xlabel("time (s)")
    top.set_title(f"{len(b)} coins in a drag field, tau = {args.tau:g} s, U = {args.flow:g} cm/s")
    fig.tight_layout()
    png = pathlib.Path(args.png)
    png.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(png, dpi=120)
    print(f"plot: {png}")


def scene_gravity(scene):
    """The vertical gravity of a scene dict (docs/scene_format.md: "earth" by default)."""
    gravity = scene.get("gravity", "earth")
    if gravity == "earth":
        return -980.665
    if gravity == "paper":
        return -98.0
    return gravity[2]


if __name__ == "__main__":
    main()
