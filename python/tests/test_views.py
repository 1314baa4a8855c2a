"""sim.bodies: arrays that are views on TEM's memory, their shapes, flags and lifetime, and the
constants (mass, volume, inertia) against closed forms."""
import gc
import math

import numpy as np
import pytest

import tem
from conftest import scene_path


def data_pointer(a):
    return a.__array_interface__["data"][0]


def rotation(q):
    """The rotation matrix (body to world) of the quaternion [w, x, y, z]."""
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


@pytest.fixture
def pile():
    return tem.Simulation(scene_path("tests/scenes/small_pile.json"))


def test_views_see_the_next_step_without_a_copy(pile):
    b = pile.bodies
    arrays = {name: getattr(b, name)
              for name in ("position", "velocity", "quaternion", "angular_velocity")}
    before = {name: (a.copy(), data_pointer(a)) for name, a in arrays.items()}
    pile.step(20)  # falling at 30 cm/s and more, hitting walls: every part of the state moves
    for name, a in arrays.items():
        values, pointer = before[name]
        assert data_pointer(a) == pointer, name
        assert not np.array_equal(a, values), f"{name} did not change"
        # A fresh access gives a new array object on the same memory, with the same values.
        fresh = getattr(pile.bodies, name)
        assert np.shares_memory(fresh, a), name
        assert data_pointer(fresh) == pointer, name
        np.testing.assert_array_equal(fresh, a)
        assert not a.flags.writeable, name
        assert not a.flags.owndata, name
        with pytest.raises(ValueError):
            a[0, 0] = 1.0
        with pytest.raises(ValueError):
            a.flags.writeable = True


def test_views_hold_the_current_state(pile):
    pile.step(30)
    b = pile.bodies
    n = len(b)
    assert n == 40 == len(pile)
    assert b.position.shape == (n, 3) and b.velocity.shape == (n, 3)
    assert b.quaternion.shape == (n, 4) and b.angular_velocity.shape == (n, 3)
    assert b.position.dtype == np.float64
    # position and velocity stride over TEM's per-body state records; quaternion is contiguous.
    assert b.position.strides[1] == 8 and b.position.strides[0] > 24
    assert b.quaternion.flags.c_contiguous and b.angular_velocity.flags.c_contiguous
    np.testing.assert_allclose(np.linalg.norm(b.quaternion, axis=1), 1.0, atol=1e-12)
    assert (b.quaternion[:, 0] >= 0).all()
    # The bodies fall: the total momentum points down, and kinetic energy matches the views.
    assert (b.mass[:, None] * b.velocity).sum(axis=0)[2] < 0
    inertia = b.inertia
    omega = b.angular_velocity
    kinetic = 0.5 * (b.mass * (b.velocity ** 2).sum(axis=1)).sum() \
        + 0.5 * np.einsum("ni,nij,nj->", omega, inertia, omega)
    assert kinetic == pytest.approx(pile.energies()["kinetic"], rel=1e-12)


def test_arrays_keep_the_simulation_alive():
    sim = tem.Simulation(scene_path("tests/scenes/small_pile.json"))
    position = sim.bodies.position
    force = sim.bodies.external_force
    start = position.copy()
    del sim
    gc.collect()
    np.testing.assert_array_equal(position, start)  # the memory is still TEM's and alive
    force[:] = 1.0
    assert position.base is force.base  # both hold the Simulation
    position.base.step(5)
    assert not np.array_equal(position, start)


def test_external_force_is_a_writable_view(pile):
    b = pile.bodies
    f = b.external_force
    assert f.shape == (40, 3) and f.flags.writeable and f.flags.c_contiguous
    assert not f.any()  # zero at the start
    f[3] = [1.0, 2.0, 3.0]
    np.testing.assert_array_equal(pile.bodies.external_force[3], [1.0, 2.0, 3.0])
    assert data_pointer(pile.bodies.external_force) == data_pointer(f)
    pile.bodies.external_torque = [0.0, 0.0, 0.5]  # broadcast over every body
    assert (pile.bodies.external_torque[:, 2] == 0.5).all()
    with pytest.raises(ValueError):
        pile.bodies.external_force = np.zeros((39, 3))
    pile.clear_external_loads()
    assert not pile.bodies.external_force.any() and not pile.bodies.external_torque.any()


def test_constants_of_a_box():
    a, b_, c, density = 0.3, 0.2, 0.1, 2.5
    sim = tem.Simulation.from_dict({
        "gravity": [0, 0, 0],
        "bodies": [
            {"name": "slab", "shape": {"type": "box", "size": [a, b_, c]}, "density": density,
             "position": np.array([1.0, 2.0, 3.0]), "euler_zxz_deg": [30, 40, 50],
             "angular_velocity": [1.0, 2.0, 3.0]},
            {"name": "floor", "shape": {"type": "box", "size": [1, 1, 0.1]},
             "position": [0, 0, -5], "fixed": True},
        ],
    })
    b = sim.bodies
    energy = sim.energies()["kinetic"]
    assert b.names == ["slab", "floor"]
    assert sim.body_index("floor") == 1
    assert b.fixed.dtype == np.bool_ and b.fixed.tolist() == [False, True]
    m = density * a * b_ * c
    assert b.mass[0] == pytest.approx(m, rel=1e-14)
    assert b.volume[0] == pytest.approx(a * b_ * c, rel=1e-14)
    body = np.diag([m / 12 * (b_ ** 2 + c ** 2), m / 12 * (a ** 2 + c ** 2),
                    m / 12 * (a ** 2 + b_ ** 2)])
    np.testing.assert_allclose(b.inertia_body[0], body, rtol=1e-13, atol=1e-17)
    for _ in range(2):
        r = rotation(b.quaternion[0])
        np.testing.assert_allclose(b.inertia[0], r @ body @ r.T, rtol=1e-12, atol=1e-15)
        sim.step(100)  # it turns; inertia (a copy) follows, inertia_body does not change
    assert not b.mass.flags.writeable and not b.inertia_body.flags.writeable
    assert b.inertia.flags.writeable and b.inertia.flags.owndata  # a copy
    # No gravity, no load: the free body stays put and keeps its energy (the default
    # integrator conserves it to round-off).
    np.testing.assert_allclose(b.position[0], [1.0, 2.0, 3.0], atol=1e-15)
    assert sim.energies()["kinetic"] == pytest.approx(energy, rel=1e-12)
    assert sim.time == pytest.approx(200 * sim.time_step)


def test_names_and_indices(pile):
    names = pile.bodies.names
    assert len(names) == 40 and len(set(names)) == 40
    for i in (0, 17, 39):
        assert pile.body_index(names[i]) == i
        assert pile.body_name(i) == names[i]
    with pytest.raises(KeyError):
        pile.body_index("no such body")
    with pytest.raises(IndexError):
        pile.body_name(40)
    with pytest.raises(IndexError):
        pile.body_name(-1)
    assert pile.step_count == 0 and pile.time == 0 and pile.total_steps == 400
    assert math.isclose(pile.time_step, 2e-4)
    assert pile.warnings == []
    assert "40 bodies" in repr(pile)


def test_contacts_array_layout(pile):
    assert len(pile.contacts()) == 0  # before the first step
    pile.step(60)
    c = pile.contacts()
    assert len(c) > 0
    assert c.dtype.names == ("body_a", "body_b", "wall", "point", "normal", "depth", "fn", "ft")
    assert c["body_a"].dtype == np.int32 and c["point"].shape == (len(c), 3)
    np.testing.assert_allclose(np.linalg.norm(c["normal"], axis=1), 1.0, rtol=1e-12)
    on_walls = c["body_b"] == -1
    assert ((c["wall"] >= 0) == on_walls).all()
    assert (c["fn"] >= 0).all() and (c["ft"] >= 0).all()
    assert (c["body_a"] >= 0).all() and (c["body_a"] < 40).all()


def test_step_arguments(pile):
    pile.step(0)
    assert pile.step_count == 0
    with pytest.raises(ValueError):
        pile.step(-1)
    pile.step()
    pile.step(n=2)
    assert pile.step_count == 3


def test_module_documents_the_lifetime():
    assert "view" in tem.__doc__ and "alive" in tem.__doc__
    assert "no copy" in tem.Bodies.position.__doc__
    assert issubclass(tem.SceneError, ValueError)


def test_bodies_follow_the_live_set_when_bodies_come_and_go():
    """Inlets add rows at the end, outlets and a gate take rows out; arrays taken before keep
    valid memory, and sim.bodies read again has the live bodies with their names."""
    sim = tem.Simulation(scene_path("tests/scenes/processes/gate_outlet.json"))
    first = sim.bodies.position
    at_load = len(sim)  # the gate and the inlet's first grain, due at t = 0
    assert at_load == 2
    pointer = data_pointer(first)
    counts = []
    for _ in range(80):
        sim.step(10)
        b = sim.bodies
        counts.append(len(b))
        assert b.position.shape == (len(sim), 3)
        assert len(b.names) == len(sim)
        # Views on the live rows: the memory never moves (room is reserved at load); with no
        # body left the array is an empty one of its own.
        if len(b):
            assert data_pointer(b.position) == pointer
        for i, name in enumerate(b.names):
            assert sim.bodies.names[i] == name
        # Masses of the copies within their size factors (0.8..1.2 of a 0.5 cm cube of 2.5).
        grains = [i for i, n in enumerate(b.names) if n.startswith("grain_")]
        if grains:
            m = b.mass[grains]
            assert (m >= 0.8 ** 3 * 0.3125 * (1 - 1e-12)).all()
            assert (m <= 1.2 ** 3 * 0.3125 * (1 + 1e-12)).all()
    assert max(counts) > 30  # grains came in
    assert counts[-1] == 0   # then the gate went and the outlet took every grain
    assert first.shape[0] == at_load  # an old array keeps its length
    e = sim.energies()
    assert set(e) >= {"kinetic", "potential", "total", "driven_work"}
