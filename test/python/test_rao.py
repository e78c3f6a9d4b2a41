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
