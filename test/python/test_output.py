"""The HDF5 file of a run: layout, metadata and physical sanity of what was written."""
import h5py
import numpy as np

from postproc import layout

G = 9.81


def test_layout_and_attributes(short_run):
    deck, out = short_run
    with h5py.File(out, "r") as f:
        for name in (layout.TIME,) + layout.BOAT:
            assert name in f, name
        for name in layout.ROOT_ATTRIBUTES:
            assert name in f.attrs, name
        assert f.attrs["input_namelist"].decode() == deck.read_text()
        assert f.attrs["complete"] == 1
        assert f.attrs["steps"] == 2000
        assert f.attrs["rhs_evaluations"] == 4 * 2000
        assert f.attrs["seed"] == 12345
        nt = f["time"].shape[0]
        assert nt == 1001
        for name in ("position", "euler", "velocity", "angular_velocity", "acceleration"):
            assert f["boat/" + name].shape == (nt, 3)
    for name, (units, description) in layout.dataset_metadata(out).items():
        assert units and description, f"{name} lacks units or description"


def test_recorded_kinematics_are_consistent(short_run):
    """velocity = d(position)/dt and acceleration = d(velocity)/dt (central differences),
    and the initial state is the deck's."""
    _, out = short_run
    run = layout.load(out)
    t = run.time
    p = run.get(layout.BOAT_POSITION)
    v = run.get(layout.BOAT_VELOCITY)
    a = run.get(layout.BOAT_ACCELERATION)
    np.testing.assert_allclose(p[0], [0.0, 13.3, -15.0], atol=1e-12)
    np.testing.assert_allclose(v[0], [0.0, 0.5, 0.0], atol=1e-12)
    dt = t[1] - t[0]
    dv = (p[2:] - p[:-2]) / (2 * dt)
    np.testing.assert_allclose(dv, v[1:-1], atol=2e-3)
    # the first sample is free fall (still air) onto unstretched slings, the boat moving
    # at 0.5 m/s to starboard: a = g down (z down) plus the air drag (eq. 15, C_w 0.5 on
    # A2 = 26.2 m^2) and the symmetric lift (C_L 1.2, D_b 3.29 m, l_b 11.5 m, upward)
    m, rho_air, vy = 8500.0, 1.225, 0.5
    drag = 0.5 * rho_air * 26.2 * 0.5 * vy * vy
    lift = 0.5 * rho_air * 3.29 * 11.5 * 1.2 * vy * vy
    np.testing.assert_allclose(a[0], [0.0, -drag / m, G - lift / m], atol=1e-9)
