"""The launch log in a run's file (issue 12): impacts as events resolved at every step, peak
tensions, the seat's filtered acceleration, the limits and the outcome; and the run
figures that mark them."""
import math

import numpy as np

from postproc import figures, layout

G = 9.81

# The III.B boat on 3 m slings swung at 1 m/s against a fixed side 0.2 m away (the paper's
# Hertz law, named so that a change of the default law leaves this test's physics alone).
SWING = """
&simulation
  t_end = 0.4
  dt = 1.0e-5
  output_interval = 0.02
/
&boat
  position = 0.0, 12.0, -15.0
  velocity = 0.0, -1.0, 0.0
/
&slings
  anchor_fore = 4.6, 12.0, -19.55
  anchor_aft = -4.6, 12.0, -19.55
  length = 2.99801
/
&wind
  speed = 0.0
/
&contact
  law = 'hertz_elastoplastic'
  side_y = 10.4
/
"""


def _run(davit, tmp_path, text, name="swing"):
    deck = tmp_path / f"{name}.nml"
    deck.write_text(text)
    out = tmp_path / f"{name}.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return layout.load(out)


def test_impact_events_resolve_what_samples_miss(davit, tmp_path):
    """Both fenders hit at once at the pendulum's speed (1 m/s less the rise over 0.2 m of
    swing on 3 m slings, along the normal); the events' peak forces and the step-resolved
    CG peak are at least what the 0.02 s samples show (here far more: a 5.5 ms contact);
    the 20 Hz filter lowers the seat's peak below the raw one."""
    run = _run(davit, tmp_path, SWING)
    assert run.has(*layout.IMPACTS)
    assert run.get(layout.IMPACT_FENDER).tolist() == [1, 2]
    theta = math.asin(0.2 / 3.0)
    v = math.sqrt(1.0 - 2 * G * 3.0 * (1 - math.cos(theta))) * math.cos(theta)
    np.testing.assert_allclose(run.get(layout.IMPACT_SPEED), v, rtol=0.02)
    sampled_force = run.get(layout.CONTACT_FORCE).max(axis=0)
    assert np.all(run.get(layout.IMPACT_PEAK_FORCE) >= sampled_force)
    sampled = np.linalg.norm(run.get(layout.BOAT_ACCELERATION), axis=1).max()
    peak = run.get(layout.PEAK_CG_ACCELERATION)
    assert peak[0] > 2 * sampled
    # the resolved peak acceleration is the peak force of both fenders over the mass
    assert abs(peak[0] - 2 * run.get(layout.IMPACT_PEAK_FORCE)[0] / 8500.0) < 0.02 * peak[0]
    seat = run.get(layout.PEAK_SEAT_ACCELERATION)[0]
    raw = run.get("seat/raw_peak")[0]
    assert 0.0 < seat < 0.5 * raw
    assert np.all(run.get(layout.IMPACT_DURATION) > 0.004)
    assert run.limit("minimum_breaking_load") == np.float64(0.356 * 0.02**2 * 1960e6)
    assert run.get(layout.LIMIT_IMPACT)[0] == -1.0


def test_fast_impact_is_flagged(davit, tmp_path):
    """A swing at 4 m/s exceeds the LSA Code's 3.5 m/s: the limit's first time is the
    impact's onset."""
    run = _run(davit, tmp_path, SWING.replace("0.0, -1.0, 0.0", "0.0, -4.0, 0.0")
               .replace("t_end = 0.4", "t_end = 0.1"), "fast")
    first, _, count = run.get(layout.LIMIT_IMPACT)
    assert count == 2 and first == run.get(layout.IMPACT_TIME)[0]
    assert run.limit("max_impact_speed") > 3.5


def test_run_figures_mark_events_and_limits(davit, tmp_path):
    run = _run(davit, tmp_path, SWING)
    for name in ("acceleration", "contact", "tension"):
        path = figures.RUN_FIGURES[name](run, str(tmp_path / "fig"), "swing")
        assert path and (tmp_path / "fig" / f"swing_{'sling_tension' if name == 'tension' else name}.png").exists()


def test_launch_table_row(davit, tmp_path):
    """`python -m postproc.launch_table` reads the log's numbers back: 2 impacts at the
    events' fastest speed, the resolved peaks, the first SWL exceedance (the slings snatch
    above 46.5 kN as the boat rebounds and rolls after the impact)."""
    from postproc import launch_table
    run = _run(davit, tmp_path, SWING)
    r = launch_table.row(run.path)
    assert r["impacts"] == 2 and r["v_max"] == float(run.get(layout.IMPACT_SPEED).max())
    assert r["a_cg"] == float(run.get(layout.PEAK_CG_ACCELERATION)[0])
    assert r["swl"] == float(run.get(layout.LIMIT_SWL)[0]) > 0.2
    assert r["sling"] == float(run.get(layout.PEAK_SLING_TENSION).max()) / 1e3 > 46.5
    lines = launch_table.table([run.path]).splitlines()
    assert len(lines) == 3 and "| swing | 2 |" in lines[2]
    assert launch_table.main([str(tmp_path / "missing.h5")]) == 1
