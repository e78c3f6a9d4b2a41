"""davit rao: file layout and the figure; physics checks are in the Fortran suite."""
import h5py
import numpy as np

from postproc import __main__ as cli

RAO_DECK = """&rao omegas = 0.3, 0.6, 0.9, headings_deg = 90.0, 180.0,
     settle_time = 60.0, measure_periods = 3 /
"""


def test_rao_file_and_figure(davit, tmp_path):
    deck = tmp_path / "rao.nml"
    deck.write_text(RAO_DECK)
    out = tmp_path / "rao.h5"
    result = davit("rao", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        assert f["rao/amplitude"].shape == (2, 3, 6)  # (heading, omega, dof) in h5py
        assert f["rao/phase"].shape == (2, 3, 6)
        np.testing.assert_allclose(f["rao/omega"][()], [0.3, 0.6, 0.9])
        np.testing.assert_allclose(np.degrees(f["rao/heading"][()]), [90, 180])
        amp = f["rao/amplitude"][()]
        assert f.attrs["complete"] == 1
        np.testing.assert_array_equal(f["rao/failed"][()], np.zeros((2, 3)))
    assert np.all(np.isfinite(amp))
    # beam seas roll more than head seas; head seas pitch more than beam seas
    assert amp[0, 1, 3] > 5 * amp[1, 1, 3]
    assert amp[1, 1, 4] > 5 * amp[0, 1, 4]
    assert cli.main(["run", str(out), "-o", str(tmp_path)]) == 0
    assert (tmp_path / "rao_rao.png").exists()


def test_rao_usage(davit):
    result = davit("rao")
    assert result.returncode == 2
    assert "'rao' needs a deck file" in result.stderr


# explicit RK4 is stable for rate * dt < 2.785: a roll damped at twice its critical value,
# with GM = 20 m (w_roll ~ 0.95 rad/s), has a mode decaying at w (zeta + sqrt(zeta^2 - 1))
# ~ 3.5 /s, unstable at dt ~ 1 s: the runs diverge
DIVERGING_DECK = """&ship zeta_roll = 2.0, gm = 20.0 /
&rao omegas = 0.3, 0.5, headings_deg = 90.0, dt = 1.0, settle_time = 300.0,
     measure_periods = 1 /
"""


def test_rao_reports_failed_runs_and_exits_nonzero(davit, tmp_path):
    """Each diverging run is named (frequency, heading, why), davit exits 1, and its
    values are written as NaN with rao/failed = 1 and complete = 0 (never zeros)."""
    deck = tmp_path / "diverge.nml"
    deck.write_text(DIVERGING_DECK)
    out = tmp_path / "diverge.h5"
    result = davit("rao", deck, "-o", out)
    assert result.returncode == 1, result.stderr
    assert "2 of 2 runs failed" in result.stderr
    for w in ("0.3", "0.5"):
        assert f"omega {w} rad/s, heading 90 deg: " in result.stderr
    assert "capsized" in result.stderr or "diverged" in result.stderr
    with h5py.File(out, "r") as f:
        np.testing.assert_array_equal(f["rao/failed"][()], [[1.0, 1.0]])
        assert f.attrs["complete"] == 0
        assert np.all(np.isnan(f["rao/amplitude"][()]))
        assert np.all(np.isnan(f["rao/phase"][()]))


def test_rao_refuses_an_unresolvable_database_before_writing(davit, tmp_path):
    deck = tmp_path / "nodb.nml"
    deck.write_text("&ship model = 'bem', database = 'no_such_bem.nc' /\n"
                    "&rao omegas = 0.5, headings_deg = 180.0 /\n")
    out = tmp_path / "nodb.h5"
    result = davit("rao", deck, "-o", out)
    assert result.returncode == 1
    assert "no_such_bem.nc" in result.stderr
    assert not out.exists()
