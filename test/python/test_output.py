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
    # the first sample is free fall onto unstretched slings: a = g down (z down)
    np.testing.assert_allclose(a[0], [0.0, 0.0, G], atol=1e-9)
