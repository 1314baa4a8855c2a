"""step() releases the GIL: other Python threads run while TEM steps; Ctrl-C stops a long
step() at a whole step; a second thread cannot use a Simulation that is stepping."""
import _thread
import threading
import time

import pytest

import tem
from conftest import scene_path

PILE = scene_path("tests/scenes/small_pile.json")  # 400 steps: about 0.4 s on one core


def test_another_thread_counts_while_step_runs():
    sim = tem.Simulation(PILE)
    ticks = []  # perf_counter() of every count of the second thread
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())

    counter = threading.Thread(target=count)
    counter.start()
    try:
        time.sleep(0.01)
        start = time.perf_counter()
        sim.step(sim.total_steps)
        end = time.perf_counter()
    finally:
        stop.set()
        counter.join()
    duration = end - start
    assert duration > 0.05, "the step is too short to tell"
    # Had step() held the GIL, the counter would stand still from start to end (the GIL is
    # handed over only between Python bytecodes). Count in the middle 80 % of the step, and
    # find the longest pause there.
    lo, hi = start + 0.1 * duration, end - 0.1 * duration
    inside = [t for t in ticks if lo <= t <= hi]
    assert len(inside) > 1000, f"{len(inside)} counts in {0.8 * duration:.3f} s of stepping"
    gaps = [b - a for a, b in zip([lo] + inside, inside + [hi])]
    assert max(gaps) < 0.5 * duration
    assert sim.step_count == sim.total_steps


def test_ctrl_c_stops_a_long_step_at_a_whole_step():
    reference = tem.Simulation(PILE)
    reference.step(reference.total_steps)
    sim = tem.Simulation(PILE)

    def interrupt_once_stepping():
        while True:
            try:
                sim.energies()  # refused while step() runs
            except RuntimeError:
                break
            time.sleep(0.001)
        time.sleep(0.05)
        _thread.interrupt_main()  # as Ctrl-C does

    interrupter = threading.Thread(target=interrupt_once_stepping)
    interrupter.start()
    with pytest.raises(KeyboardInterrupt):
        sim.step(100 * sim.total_steps)  # 40,000 steps, half a minute and more
    interrupter.join()
    stopped_at = sim.step_count
    assert 0 < stopped_at < sim.total_steps
    # Stopped cleanly: going on from there gives the uninterrupted run's result.
    sim.step(sim.total_steps - stopped_at)
    assert sim.state_hash() == reference.state_hash()


def test_a_stepping_simulation_refuses_other_threads():
    sim = tem.Simulation(PILE)
    stepper = threading.Thread(target=sim.step, args=(sim.total_steps,))
    refused = 0
    stepper.start()
    while stepper.is_alive():
        try:
            sim.energies()
        except RuntimeError as e:
            assert "stepping in another thread" in str(e)
            refused += 1
        time.sleep(0.001)
    stepper.join()
    assert refused > 0
    assert sim.step_count == sim.total_steps
    sim.energies()  # free again
