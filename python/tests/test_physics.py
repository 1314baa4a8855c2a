"""Real physics through the module: a load applied from Python every step (linear drag) and the
contact forces of bodies at rest."""
import numpy as np
import pytest

import tem

G = 980.665  # "earth", cm/s^2


def falling_coin(time_step, duration):
    return tem.Simulation.from_dict({
        "gravity": [0, 0, -G],
        "time_step": time_step,
        "duration": duration,
        # No container, no walls: free space.
        "bodies": [{"name": "coin",
                    "shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1},
                    "density": 7.0, "position": [0, 0, 0], "euler_zxz_deg": [10, 80, 10],
                    "angular_velocity": [0, 0, 4.0]}],
    })


def test_linear_drag_gives_the_terminal_speed():
    """F = -c v, written from Python before every step, against gravity: the speed tends to
    m g / c with time constant tau = m / c. TEM holds the force through the step, so the speed
    follows v[k+1] = v[k] + dt (-g - (c/m) v[k]) exactly (up to round-off), whose fixed point
    is m g / c for any dt and which converges as (1 - dt/tau)^k: after 12 tau (1,200 steps of
    tau/100) the error is 0.99^1200 = 5.8e-6 of the terminal speed, far inside 0.1 %."""
    dt, tau = 1e-3, 0.1
    steps = 1200  # 12 tau
    sim = falling_coin(dt, steps * dt)
    b = sim.bodies
    m = b.mass[0]
    assert m == pytest.approx(7.0 * 1.5 * np.sqrt(3) * 0.15 ** 2 * 0.1, rel=1e-13)
    c = m / tau
    terminal = m * G / c
    velocity, force = b.velocity, b.external_force  # views: no copy each step
    expected = 0.0
    for _ in range(steps):
        force[:] = -c * velocity
        sim.step()
        expected += dt * (-G - (c / m) * expected)
        assert velocity[0, 2] == pytest.approx(expected, rel=1e-12, abs=1e-12)
    speed = -velocity[0, 2]
    error = abs(speed - terminal) / terminal
    assert error < 1e-4, f"terminal speed {speed} vs m g / c = {terminal}: error {error:.2e}"
    assert error == pytest.approx((1 - dt / tau) ** steps, rel=1e-6)  # converged as predicted
    np.testing.assert_allclose(velocity[0, :2], 0.0, atol=1e-12)  # straight down
    # The drag acts through the centre of mass: the spin about the body's axis is untouched.
    assert np.linalg.norm(b.angular_velocity[0]) == pytest.approx(4.0, rel=1e-9)
    assert sim.contacts().size == 0


def test_without_the_drag_the_coin_falls_freely():
    """The control for the test above: no load written, v = -g t."""
    sim = falling_coin(1e-3, 1.0)
    sim.step(500)
    assert sim.bodies.velocity[0, 2] == pytest.approx(-G * 0.5, rel=1e-12)
    assert sim.bodies.position[0, 2] == pytest.approx(-0.5 * G * 0.5 ** 2, rel=1e-2)


def test_forces_of_a_stack_at_rest():
    """A small box resting on a larger one on the floor. `fn` is a force (the impulse over the
    step divided by dt, docs of Simulation.contacts), so at rest the floor carries
    (m1 + m2) g and the contact between the boxes m2 g. At rest the velocities do not change
    over a step, so the contact impulses cancel gravity's exactly; what is left is the
    solver's tolerance (contact.tolerance, 1e-9 of the largest impulse by default) and
    round-off: 1e-9 relative is the bound."""
    sim = tem.Simulation.from_dict({
        "time_step": 1e-4, "duration": 0.3,
        "contact": {"model": "semm", "friction": 0.3},
        "container": {"min": [0, 0, 0], "max": [1, 1, 1]},
        "bodies": [
            {"name": "base", "shape": {"type": "box", "size": [0.3, 0.3, 0.1]},
             "position": [0.5, 0.5, 0.052], "density": 2.0},
            {"name": "top", "shape": {"type": "box", "size": [0.1, 0.1, 0.1]},
             "position": [0.52, 0.49, 0.155], "euler_zxz_deg": [20, 0, 0], "density": 7.0},
        ],
    })
    m = sim.bodies.mass.copy()
    sim.step(sim.total_steps)  # dropped 2 and 3 mm, settled
    b = sim.bodies
    assert np.abs(b.velocity).max() < 1e-9 and np.abs(b.angular_velocity).max() < 1e-9
    c = sim.contacts()
    floor = c[(c["body_a"] == 0) & (c["wall"] == 4)]  # the container's bottom face
    between = c[(c["body_a"] == 0) & (c["body_b"] == 1)]
    assert len(floor) + len(between) == len(c)
    np.testing.assert_allclose(floor["normal"], [[0, 0, -1]] * len(floor), atol=1e-9)
    np.testing.assert_allclose(between["normal"], [[0, 0, 1]] * len(between), atol=1e-9)
    assert floor["fn"].sum() == pytest.approx((m[0] + m[1]) * G, rel=1e-9)
    assert between["fn"].sum() == pytest.approx(m[1] * G, rel=1e-9)
    # Nothing pushes sideways: friction carries nothing.
    assert np.abs(c["ft"]).max() < 1e-9 * m.sum() * G


def test_box_on_the_floor_one_step_after_landing():
    """tests/scenes/drop_box.json's box, tilted 5 degrees, lands and settles; then one patch
    on the floor holds m g (a force, see above) to 1e-9 while the box stays at rest."""
    from conftest import scene_path
    sim = tem.Simulation(scene_path("tests/scenes/drop_box.json"))
    sim.step(3000)
    b = sim.bodies
    m = b.mass[0]
    z = b.position[0, 2]
    sim.step()
    assert np.abs(b.velocity).max() < 1e-9
    assert b.position[0, 2] == pytest.approx(z, abs=1e-12)
    c = sim.contacts()
    assert len(c) >= 1 and (c["wall"] == 4).all()
    assert c["fn"].sum() == pytest.approx(m * G, rel=1e-9)
    assert (c["fn"] * c["normal"][:, 2]).sum() == pytest.approx(-m * G, rel=1e-9)
