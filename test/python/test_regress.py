"""The regression report's logic (postproc/regress.py) on synthetic inputs whose answers are
known by construction: step tensions, sinusoidal swings, case tables laid out to match or
break the paper's collision facts, and sweep summaries written here with h5py."""
import h5py
import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import layout, regress

G = layout.GRAVITY
W = 8500.0 * G
RIGGED = (8500.0 + 100.0 + 3.2) * G


def step_tension(t_settle, level, peak=1.3, nseg=3, dt=0.01):
    """Tension `peak` x level before t_settle, exactly `level` after: settles at t_settle."""
    t = np.arange(0.0, 10.0 + dt / 2, dt)
    tension = np.where(t[:, None] < t_settle, peak * level, level) * np.ones((1, nseg))
    return t, tension


def by_fact(verdicts):
    return {v.fact: v for v in verdicts}


def test_f2_step_tension_known_mean_and_settling():
    t, tension = step_tension(2.0, RIGGED / 4)
    steady, settle, spread = regress.tension_settling(t, tension)
    assert steady == pytest.approx(RIGGED / 4, rel=1e-12)
    assert settle == pytest.approx(2.0, abs=1e-9)
    assert spread == 0.0
    rows = by_fact(regress.fact_f2(t, tension, W, RIGGED))
    assert {v.result for v in rows.values()} == {regress.PASS}


def test_f2_fails_off_weight_late_settling_and_unequal_sections():
    t, tension = step_tension(2.0, 1.08 * W / 4)           # 8 % above W/4
    rows = by_fact(regress.fact_f2(t, tension, W, RIGGED))
    assert rows["F2 tension ~ W/4"].result == regress.FAIL
    assert rows["F2 with rigging"].result == regress.FAIL
    t, tension = step_tension(4.5, W / 4, peak=1.08)        # settles 2 s late; the
    # window mean (1.5 x 1.08 + 3.5)/5 = 1.024 W/4 is still within 5 %, 1.08 is not
    rows = by_fact(regress.fact_f2(t, tension, W, RIGGED))
    assert rows["F2 settling"].result == regress.FAIL
    assert rows["F2 tension ~ W/4"].result == regress.PASS
    tension[:, 0] *= 1.03                                    # one section 3 % higher
    rows = by_fact(regress.fact_f2(t, tension, W, RIGGED))
    assert rows["F2 sections"].result == regress.FAIL


def test_f2_equilibrium_start_has_no_transient_rows():
    """A run started at equilibrium has no settling time or first peak to judge; the label
    names which run a row belongs to."""
    t, tension = step_tension(0.0, W / 4)
    rows = regress.fact_f2(t, tension, W, RIGGED, label=" [III.A 1]", transient=False)
    assert [v.fact for v in rows] == ["F2 tension ~ W/4 [III.A 1]", "F2 with rigging [III.A 1]"]
    assert rows[0].result == regress.PASS


def test_swing_amplitude_of_a_drifting_sine():
    """sqrt(2) RMS of the detrended horizontal motion: a sine of amplitude A at the wave
    period on a linear drift gives A; an orthogonal cosine B adds to sqrt(A^2 + B^2)."""
    period, dt = 10.02, 0.02                                 # 501 samples per period
    t = np.arange(0.0, 120.0, dt)
    w = 2 * np.pi / period
    pos = np.zeros((len(t), 3))
    pos[:, 1] = 2.5 * np.sin(w * t) + 0.3 * t
    t_end = 20.0 + 9 * period                     # the window [t0 + T/2, t1 - T/2]: 8 periods
    assert regress.swing_amplitude(t, pos, period, 20.0, t_end) == pytest.approx(2.5, rel=1e-4)
    pos[:, 0] = 1.5 * np.cos(w * t) - 0.1 * t
    assert regress.swing_amplitude(t, pos, period, 20.0, t_end) == \
        pytest.approx(np.hypot(2.5, 1.5), rel=1e-4)
    with pytest.raises(ValueError, match="shorter than two wave periods"):
        regress.swing_amplitude(t, pos, period, 20.0, 35.0)


def test_f9_wind_pairs_and_frozen_ship():
    assert regress.fact_f9({}).result == regress.NO_INPUT
    assert regress.fact_f9({(4, 90): (3.1, 3.0), (5, 45): (1.9, 2.0)}).result == regress.PASS
    worse = regress.fact_f9({(4, 90): (3.1, 3.0), (5, 45): (2.5, 2.0)})   # +25 %
    assert worse.result == regress.FAIL and "+25.0 %" in worse.davit
    assert regress.fact_f9({(4, 0): (0.01, 0.03)}).result == regress.PASS  # below the floor
    assert regress.fact_f9_ship(1.4, 0.3).result == regress.PASS
    assert regress.fact_f9_ship(1.4, 0.9).result == regress.FAIL
    assert regress.fact_f9_ship(1.4, None).result == regress.NO_INPUT


def make_cases(rows):
    """Cases from (level, angle, clearance_b, wave_type, wind, status, collided, min
    clearance, peak horizontal acceleration) tuples."""
    cols = list(zip(*rows))
    names = ("level", "angle_deg", "clearance_b", "wave_type", "wind", "status", "collided",
             "min_clearance", "peak_horizontal_acceleration")
    return regress.Cases(**{n: np.array(c) for n, c in zip(names, cols)})


def paper_pattern(n=8, hits_expected=5, hits_other=2, extra=()):
    """n realisations per (level, angle) at 0.5 B, regular, wind: `hits_expected` collide
    where the paper has a collision, `hits_other` at 45/90/135 where it has none, none at
    0/180; `extra` rows appended."""
    rows = []
    for level in (4, 5):
        for angle in (0, 45, 90, 135, 180):
            if angle in (0, 180):
                k = 0
            elif angle in regress.EXPECTED_COLLISIONS[level]:
                k = hits_expected
            else:
                k = hits_other
            rows += [(level, angle, 0.5, 2, 1, 1, int(i < k), 0.0 if i < k else 0.4,
                      5.0 + angle / 10) for i in range(n)]
    return make_cases(rows + list(extra))


def test_f7_majority_pattern_passes_and_each_break_fails():
    assert regress.fact_f7(paper_pattern(), "s").result == regress.PASS
    # other clearances, irregular seas and failed cases do not count
    noise = [(4, 45, 1.0, 2, 1, 1, 1, 0.0, 9.0)] * 8 + [(4, 45, 0.5, 3, 1, 1, 1, 0.0, 9.0)] * 8 \
        + [(4, 0, 0.5, 2, 1, 2, 1, 0.0, 9.0)] * 8
    assert regress.fact_f7(paper_pattern(extra=noise), "s").result == regress.PASS
    # one collision at 180 deg breaks "never at 0/180"
    one = regress.fact_f7(paper_pattern(extra=[(5, 180, 0.5, 2, 1, 1, 1, 0.0, 9.0)]), "s")
    assert one.result == regress.FAIL and "180 deg: 1 of 9" in one.details[0]
    # a majority at Level 4, 45 deg where the paper has none
    assert regress.fact_f7(paper_pattern(hits_other=5), "s").result == regress.FAIL
    # a tie is not a majority
    assert regress.fact_f7(paper_pattern(hits_expected=4), "s").result == regress.FAIL
    assert regress.fact_f7(None, "s").result == regress.NO_INPUT


def test_f7_prefers_the_with_wind_runs():
    cases = paper_pattern(extra=[(4, 45, 0.5, 2, 0, 1, 1, 0.0, 9.0)] * 20)   # no wind
    assert regress.fact_f7(cases, "s").result == regress.PASS


def test_f8_compares_level5_medians():
    rows = [(5, 90, 0.5, 2, 1, 1, 1, 0.0, a) for a in (10.0, 12.0, 14.0)]
    rows += [(5, 45, 0.5, 2, 1, 1, 1, 0.0, a) for a in (5.0, 20.0, 6.0)]      # median 6
    rows += [(5, 135, 0.5, 2, 1, 1, 1, 0.0, a) for a in (7.0, 8.0, 9.0)]      # median 8
    rows += [(4, 45, 0.5, 2, 1, 1, 1, 0.0, 99.0)]                             # Level 4
    verdict = regress.fact_f8(make_cases(rows), "s")
    assert verdict.result == regress.PASS and "90: 12.0" in verdict.davit
    rows += [(5, 135, 0.5, 2, 1, 1, 1, 0.0, a) for a in (30.0, 31.0, 32.0, 33.0)]  # median 30
    assert regress.fact_f8(make_cases(rows), "s").result == regress.FAIL
    no90 = [r for r in rows if r[1] != 90]
    assert regress.fact_f8(make_cases(no90), "s").result == regress.NO_INPUT


def test_f10_signs_of_the_median_differences():
    rows = []
    def group(angle, regular, irregular):
        rows.extend((4, angle, 1.0, 2, 1, 1, 0, d, 1.0) for d in regular)
        rows.extend((4, angle, 1.0, 3, 1, 1, 0, d, 1.0) for d in irregular)
    group(90, (0.1, 0.2, 0.3), (0.3, 0.4, 0.5))      # regular smaller: agrees
    group(45, (0.7, 0.8, 0.9), (0.4, 0.5, 0.6))      # regular larger: agrees
    verdict = regress.fact_f10(make_cases(rows))
    assert verdict.result == regress.PASS and verdict.davit.startswith("2 of 2")
    group(135, (0.2, 0.3, 0.4), (0.4, 0.5, 0.6))     # regular smaller at 135: disagrees
    verdict = regress.fact_f10(make_cases(rows))
    assert verdict.result == regress.FAIL and verdict.davit.startswith("2 of 3")
    assert regress.fact_f10(None).result == regress.NO_INPUT


def test_f11_one_percent_per_group_at_level4_from_1p5_b():
    def cases(hits, level=4, clearance=1.5):
        return make_cases([(level, 90, clearance, 2, 1, 1, int(i < hits), 0.5, 1.0)
                           for i in range(100)])
    assert regress.fact_f11(cases(1)).result == regress.PASS
    assert regress.fact_f11(cases(2)).result == regress.FAIL
    assert regress.fact_f11(cases(50, level=5)).result == regress.NO_INPUT
    assert regress.fact_f11(cases(50, clearance=1.0)).result == regress.NO_INPUT
    mixed = regress.Cases.concat([cases(0), cases(50, level=5), cases(30, clearance=1.0),
                                  cases(0, clearance=2.0)])
    verdict = regress.fact_f11(mixed)
    assert verdict.result == regress.PASS and verdict.davit.startswith("0 collisions in 200")


def write_summary(path, cases, drop=()):
    """A sweep summary in the contract's layout (plus fields regress does not read)."""
    with h5py.File(path, "w") as f:
        for field, name in layout.SUMMARY_FIELDS.items():
            if name not in drop:
                f[name] = getattr(cases, field)
        f["cases/seed"] = np.arange(len(cases))
        f["results/message"] = np.array([b"ok"] * len(cases))


def test_report_reads_sweep_summaries_in_a_folder(tmp_path):
    write_summary(tmp_path / "sweep_a.h5", paper_pattern())
    write_summary(tmp_path / "sweep_b.h5", make_cases(
        [(4, 90, 1.5, 3, 1, 1, 0, 1.2, 1.0)] * 100))
    rows = by_fact(regress.report(str(tmp_path)))
    assert rows["F7 collisions (sweeps)"].result == regress.PASS
    assert rows["F7 collisions (paper decks)"].result == regress.NO_INPUT
    assert rows["F11 safe distance"].result == regress.PASS
    assert rows["F2 tension ~ W/4"].result == regress.NO_INPUT


def test_summary_missing_dataset_is_named(tmp_path, capsys):
    write_summary(tmp_path / "broken.h5", paper_pattern(), drop=(layout.SUMMARY_COLLIDED,))
    with pytest.raises(ValueError, match=r"broken\.h5.*missing dataset /results/collided"):
        regress.gather_sweeps(str(tmp_path))
    assert cli.main(["regress", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert "broken.h5" in err and "/results/collided" in err


def test_regress_without_inputs_reports_no_input(tmp_path, capsys):
    assert cli.main(["regress", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "0 pass, 0 FAIL" in out and "| FAIL |" not in out


def test_strict_regress_exits_1_on_a_fail(tmp_path):
    write_summary(tmp_path / "sweep.h5", paper_pattern(hits_other=6))
    assert cli.main(["regress", str(tmp_path)]) == 0
    assert cli.main(["regress", str(tmp_path), "--strict"]) == 1


def test_cases_reject_unequal_lengths():
    with pytest.raises(ValueError, match="collided has 2 entries"):
        regress.Cases(level=[4], angle_deg=[90], clearance_b=[0.5], wave_type=[2], wind=[1],
                      status=[1], collided=[0, 1], min_clearance=[0.1],
                      peak_horizontal_acceleration=[1.0])
