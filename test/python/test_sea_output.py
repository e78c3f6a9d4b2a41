"""The 'sea' scene's file: layout, and eq. 43 rebuilt independently in numpy from the
recorded component table must reproduce the Fortran record."""
import h5py
import numpy as np

from postproc import __main__ as cli
from postproc import layout


def test_sea_layout(sea_run):
    _, out = sea_run
    with h5py.File(out, "r") as f:
        assert f["sea/elevation"].shape == (601, 3)
        np.testing.assert_allclose(f["sea/probe_position"][()],
                                   [[0, 0, 0], [120, 30, 0], [-40, 75, 0]])
        n = f["sea/components/omega"].shape[0]
        assert n == 100 * 13
        for name in ("omega", "wavenumber", "direction", "amplitude", "phase"):
            assert f["sea/components/" + name].shape == (n,)
        assert f.attrs["seed"] == 7
        assert f["sea"].attrs["wave_type"].decode() == "irregular"


def test_components_follow_the_deck(sea_run):
    _, out = sea_run
    run = layout.load(out)
    w, k = run.get(layout.SEA_OMEGA), run.get(layout.SEA_K)
    np.testing.assert_allclose(k, w ** 2 / 9.81, rtol=1e-14)
    assert w.min() > 0.3 and w.max() < 3.0
    d = np.degrees(run.get(layout.SEA_DIRECTION))
    assert abs(d.min() - 15.0) < 1e-9 and abs(d.max() - 75.0) < 1e-9
    # discrete variance = band integral of eq. 44 for H = 2.5 m (review A1: 0.9943 m0)
    m0 = 0.37 * (6.28 * np.sqrt(2.5) / 9.81) ** 4
    assert abs(np.sum(run.get(layout.SEA_AMPLITUDE) ** 2) / 2 / m0 - 0.9943) < 1e-3


def test_numpy_rebuild_matches_fortran(sea_run):
    _, out = sea_run
    run = layout.load(out)
    t = run.time
    eta = run.get(layout.SEA_ELEVATION)
    probes = run.get(layout.SEA_PROBES)
    for n in range(0, len(t), 37):
        rebuilt = layout.sea_elevation(run, t[n], probes[:, 0], probes[:, 1])
        np.testing.assert_allclose(rebuilt, eta[n], atol=1e-10)
    assert eta[0].tolist() == [0.0, 0.0, 0.0], "the ramp starts from a flat sea"


def test_sea_figures(sea_run, tmp_path):
    _, out = sea_run
    assert cli.main(["run", str(out), "-o", str(tmp_path)]) == 0
    assert sorted(p.name for p in tmp_path.glob("*.png")) == ["sea_spectrum.png",
                                                               "sea_surface.png"]


def test_boat_figure_on_sea_file_is_an_error(sea_run, tmp_path, capsys):
    _, out = sea_run
    assert cli.main(["trajectory", str(out), "-o", str(tmp_path)]) == 1
    assert "no boat trajectory in this file" in capsys.readouterr().err


def test_welch_recovers_a_sine_variance():
    """The spectrum estimate integrates to the variance of a test signal."""
    from postproc.figures import welch
    dt = 0.25
    t = np.arange(8192) * dt
    x = 1.5 * np.cos(0.7 * t + 0.3)
    omega, s = welch(x, dt, 1024)
    assert abs(np.trapezoid(s, omega) / (1.5 ** 2 / 2) - 1) < 0.02
    assert abs(omega[np.argmax(s)] - 0.7) < 2 * np.pi / (1024 * dt)
