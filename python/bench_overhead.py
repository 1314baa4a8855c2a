#!/usr/bin/python3
"""What the Python module costs on top of TEM's C++: per step() call and per array access.

Scenes without contacts (N coins in free space, no container, far apart, falling together), so
that a step is cheap and the overhead shows. The C++ time per step is step(K) / K (one call);
the time per call of step(1) from Python minus it is the module's overhead (argument
conversion, releasing and taking back the GIL, and the per-call refresh of the quaternion and
angular-velocity arrays, O(N), which step(K) does once).

    PYTHONPATH=build/release/python /usr/bin/python3 python/bench_overhead.py

Each figure is the best of several repeats (the machine may be shared); one thread.
"""
import pathlib
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
try:
    import tem
except ImportError:
    sys.path.insert(0, str(ROOT / "build/release/python"))
    import tem


def free_coins(n):
    side = int(round(n ** (1 / 3))) + 1
    bodies = []
    for i in range(n):
        x, y, z = i % side, (i // side) % side, i // (side * side)
        bodies.append({"name": f"c{i}", "position": [x, y, z], "euler_zxz_deg": [i, 30, 0],
                       "angular_velocity": [0, 0, 1.0],
                       "shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1}})
    return tem.Simulation.from_dict({"time_step": 1e-5, "duration": 1.0, "bodies": bodies})


def best(f, repeats, inner):
    """Seconds per call of f, the best of `repeats` runs of `inner` calls."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(inner):
            f()
        times.append((time.perf_counter() - start) / inner)
    return min(times)


def main():
    tem.set_threads(1)
    print("seconds per call, best of several repeats; one thread")
    print(f"{'bodies':>7} {'C++ step':>11} {'step(1)':>11} {'difference':>11} {'step(0)':>9} "
          f"{'bodies.position':>16} {'b.position':>11} {'energies()':>11} {'contacts()':>11}")
    for n in (10, 10_000):
        sim = free_coins(n)
        k = 20_000 if n == 10 else 100
        repeats = 5 if n == 10 else 3
        sim.step(k // 10)  # warm up
        cxx = best(lambda: sim.step(k), repeats, 1) / k
        one = best(lambda: sim.step(1), repeats, k)
        none = best(lambda: sim.step(0), 5, 2_000)  # the call alone: GIL, refresh of the arrays
        assert not sim.contacts().size
        position = best(lambda: sim.bodies.position, 5, 20_000)
        b = sim.bodies
        cached = best(lambda: b.position, 5, 20_000)
        energies = best(sim.energies, 5, 200)
        contacts = best(sim.contacts, 5, 20_000)
        print(f"{n:>7} {us(cxx)} {us(one)} {us(one - cxx)} {us(none, 9)} {us(position, 16)} "
              f"{us(cached)} {us(energies)} {us(contacts)}")


def us(seconds, width=11):
    return f"{seconds * 1e6:>{width - 3}.2f} us"


if __name__ == "__main__":
    main()
