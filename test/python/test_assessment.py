"""The rule checks of a launch (issue 16) in the run file (/assessment), in the words
`davit run` prints at its end, and as sweep columns: the same numbers in all three, the
margins' signs as the rules' bounds say, and the lowering speed a drum over four parts
gives."""
import math

import h5py
import numpy as np

from postproc import layout

# The calm lowering of input/lowering.nml for 12 s: the drum at 0.7 m/s after a 1 s ramp,
# four parts of reeving A, so the boat comes down at 0.175 m/s (0.14 % more: the falls lean
# in by half the heads' spacing); H = 20.55 m.
LOWERING = """
&simulation scene = 'lowering', t_end = 12.0, dt = 1.0e-3, output_interval = 0.1 /
&rigging reeving = 'a', sheaves = 'quasi_static', blocks = 'quasi_static', lumps = 0,
         drum_speed = 0.7, ramp_time = 1.0 /
&wind speed = 0.0 /
&sea wave_type = 'calm' /
"""


def _margin(value, limit, bound):
    return (value - limit) / limit if bound == "lower" else (limit - value) / limit


def _run(davit, tmp_path):
    deck = tmp_path / "lowering.nml"
    deck.write_text(LOWERING)
    out = tmp_path / "lowering.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return deck, out, result.stdout


def test_run_file_and_report(davit, tmp_path):
    """Every check in /assessment with its source and verdict; margins as the bounds say;
    the lowering speed and its limit from the rope kinematics and H; the printed table
    names every check with the same verdict."""
    _, out, stdout = _run(davit, tmp_path)
    with h5py.File(out, "r") as f:
        rows = {c.id: f[layout.assessment_dataset(c.id)][()] for c in layout.CHECKS}
        verdicts = {c.id: f[layout.assessment_dataset(c.id)].attrs["verdict"]
                    for c in layout.CHECKS}
        sources = {c.id: f[layout.assessment_dataset(c.id)].attrs["source"]
                   for c in layout.CHECKS}
        head_height = f[layout.ASSESSMENT].attrs["head_height"]
    np.testing.assert_allclose(head_height, 20.55, rtol=1e-9)
    value, limit, margin = rows["lowering_speed"]
    np.testing.assert_allclose(value, 0.175, rtol=3e-3)
    np.testing.assert_allclose(limit, 0.4 + 0.02 * 20.55, rtol=1e-9)
    for check in layout.CHECKS:
        v, lim, m = rows[check.id]
        assert all(len(str(s)) > 0 for s in (sources[check.id],))
        if math.isnan(m):
            continue
        np.testing.assert_allclose(m, _margin(v, lim, check.bound), rtol=1e-12, atol=1e-15)
    assert verdicts["lowering_speed"] in (b"FAIL", "FAIL")
    assert verdicts["brake_load"] in (b"not applicable", "not applicable")
    lines = [line.split() for line in stdout.splitlines() if line.startswith("  ")]
    printed = {words[0]: words[1] for words in lines if words}
    assert printed["lowering_speed"] == "FAIL"
    assert printed["fall_swl"] == "pass"
    assert set(printed) == {c.id for c in layout.CHECKS}


def test_sweep_columns_equal_the_run(davit, tmp_path):
    """A one-case sweep of the same deck writes the same values, limits and margins
    (bitwise: the same launch log computes them) as the run's /assessment."""
    deck, out, _ = _run(davit, tmp_path)
    sweep = tmp_path / "one.nml"
    sweep.write_text("&sweep base_deck = 'lowering.nml' /\n")
    summary = tmp_path / "one.h5"
    result = davit("sweep", sweep, "-o", summary, "--quiet")
    assert result.returncode == 0, result.stderr
    checks = layout.load_checks(summary)
    assert set(checks) == {c.id for c in layout.CHECKS}
    with h5py.File(out, "r") as f:
        for check in layout.CHECKS:
            row = f[layout.assessment_dataset(check.id)][()]
            got = [checks[check.id][part][0] for part in layout.CHECK_PARTS]
            np.testing.assert_array_equal(np.array(got), row, err_msg=check.id)
