"""Issue 16: the statistics of postproc.assessment (Wilson interval, launches needed, Gumbel
fit and its goodness-of-fit check) and the operability table of postproc.operability, on
made-up sweep summaries whose counts are known by hand."""
import csv
import math

import h5py
import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import assessment, layout, operability

# --- Wilson score interval ---------------------------------------------------------------


@pytest.mark.parametrize("k, n, lower, upper", [
    (81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605), (0, 20, 0.0000, 0.1611),
    (1, 29, 0.0061, 0.1718)])
def test_wilson_matches_newcombe_1998_table_1_method_3(k, n, lower, upper):
    lo, hi = assessment.wilson_interval(k, n)
    assert (round(lo, 4), round(hi, 4)) == (lower, upper)


def test_wilson_edges():
    assert assessment.wilson_interval(0, 0) == (0.0, 1.0)
    lo, hi = assessment.wilson_interval(20, 20)
    assert hi == 1.0 and lo == pytest.approx(1 - assessment.wilson_interval(0, 20)[1])
    # wider with more confidence
    assert assessment.wilson_interval(3, 30, 0.99)[1] > assessment.wilson_interval(3, 30)[1]
    with pytest.raises(ValueError):
        assessment.wilson_interval(5, 3)


def test_normal_quantile():
    assert assessment.normal_quantile(0.975) == pytest.approx(1.959963984540054, abs=1e-12)
    assert assessment.normal_quantile(0.999) == pytest.approx(3.090232306167813, abs=1e-12)
    assert assessment.normal_quantile(0.5) == pytest.approx(0.0, abs=1e-15)
    for p in (1e-6, 0.001, 0.02, 0.3):
        assert assessment.normal_quantile(p) == \
            pytest.approx(-assessment.normal_quantile(1 - p), rel=1e-9)
    for p in (1e-12, 1e-6, 0.001, 0.02, 0.3):
        z = assessment.normal_quantile(p)
        assert 0.5 * math.erfc(-z / math.sqrt(2)) == pytest.approx(p, rel=1e-12)


@pytest.mark.parametrize("k, n, risk", [(0, 0, 0.05), (0, 20, 0.05), (1, 29, 0.05),
                                        (3, 100, 0.05), (0, 100, 0.01), (2, 10, 0.1)])
def test_launches_needed_is_the_least_that_brings_the_bound_below_risk(k, n, risk):
    m = assessment.launches_needed(k, n, risk)
    assert assessment.wilson_interval(k, n + m)[1] <= risk
    if m > 0:
        assert assessment.wilson_interval(k, n + m - 1)[1] > risk


def test_launches_needed_by_hand():
    # 0 of N: upper = z^2/(N + z^2) <= 0.05 <=> N >= 19 z^2 = 72.99
    assert assessment.launches_needed(0, 0, 0.05) == 73
    assert assessment.launches_needed(0, 80, 0.05) == 0


# --- Gumbel --------------------------------------------------------------------------------

MU, BETA, N = 3.0, 0.7, 2000


@pytest.fixture(scope="module")
def gumbel_sample():
    return np.random.default_rng(16).gumbel(MU, BETA, N)


def test_gumbel_mle_recovers_the_law_within_three_standard_errors(gumbel_sample):
    fit = assessment.fit_gumbel(gumbel_sample)
    # asymptotic MLE standard errors: var(mu) = 1.1087 beta^2/n, var(beta) = 0.6079 beta^2/n
    assert fit.se_mu == pytest.approx(math.sqrt(1.1087 / N) * fit.beta)
    assert fit.se_beta == pytest.approx(math.sqrt(0.6079 / N) * fit.beta)
    assert abs(fit.mu - MU) < 3 * math.sqrt(1.1087 / N) * BETA
    assert abs(fit.beta - BETA) < 3 * math.sqrt(0.6079 / N) * BETA
    assert fit.mpm == fit.mu
    assert fit.fits, fit


def test_gumbel_mle_solves_the_likelihood_equations(gumbel_sample):
    mu, beta = assessment.gumbel_mle(gumbel_sample)
    z = (gumbel_sample - mu) / beta
    # d lnL/d mu = (n - sum e^-z)/beta, d lnL/d beta = (-n + sum z - sum z e^-z)/beta
    assert np.sum(np.exp(-z)) == pytest.approx(N, rel=1e-9)
    assert np.sum(z) - np.sum(z * np.exp(-z)) == pytest.approx(N, rel=1e-9)
    m_mu, m_beta = assessment.gumbel_moments(gumbel_sample)
    assert m_mu == pytest.approx(mu, abs=0.05) and m_beta == pytest.approx(beta, abs=0.05)


def test_gumbel_90_percent_fractile(gumbel_sample):
    exact = MU - BETA * math.log(-math.log(0.9))
    fit = assessment.fit_gumbel(gumbel_sample)
    assert fit.p90 == pytest.approx(fit.mu - fit.beta * math.log(-math.log(0.9)))
    # its asymptotic standard error: beta^2/n (1.1087 + 2 (0.2570) y + 0.6079 y^2), y = -ln(-ln p)
    y = -math.log(-math.log(0.9))
    se = BETA * math.sqrt((1.1087 + 0.5140 * y + 0.6079 * y * y) / N)
    assert abs(fit.p90 - exact) < 3 * se


@pytest.mark.parametrize("make", [
    lambda rng: rng.uniform(0.0, 1.0, 200),
    lambda rng: np.concatenate([rng.normal(0.0, 0.3, 100), rng.normal(5.0, 0.3, 100)])],
    ids=["uniform", "bimodal"])
def test_a_non_gumbel_sample_is_flagged(make):
    fit = assessment.fit_gumbel(make(np.random.default_rng(7)))
    assert not fit.ppcc_ok and not fit.ad_ok and not fit.fits


def test_ppcc_critical_value_is_reproducible_and_grows_with_n():
    assert assessment.ppcc_critical(20) == assessment.ppcc_critical(20, 5.0, 3.0)
    values = [assessment.ppcc_critical(n) for n in (10, 20, 50, 100)]
    assert values == sorted(values) and 0.85 < values[0] < values[-1] < 1


def test_gumbel_fit_needs_a_spread():
    assert assessment.fit_gumbel([1.0, 1.0, 1.0, 1.0]) is None
    assert assessment.fit_gumbel([1.0, 2.0]) is None
    assert assessment.fit_gumbel([1.0, np.nan, 2.0, 3.0]).n == 3


# --- made-up summaries ---------------------------------------------------------------------

def _write(path, cases, checks=(), maxima=True):
    """A summary with the operability columns of `cases` (dicts with level, height, period,
    angle, clearance, status, collided and margins {check: value}), written under the
    names of postproc.layout; `checks` get all three columns, NaN where a case has no
    margin; maxima: Gumbel-like peaks of every ok case."""
    rng = np.random.default_rng(3)
    ok = np.array([c["status"] == layout.SWEEP_OK for c in cases])
    columns = {
        layout.SWEEP_CASE_LEVEL: [c.get("level", -1) for c in cases],
        layout.SWEEP_CASE_WAVE_HEIGHT: [c.get("height", 2.0) for c in cases],
        layout.SWEEP_CASE_WAVE_PERIOD: [c.get("period", 8.0) for c in cases],
        layout.SWEEP_CASE_ANGLE: [c["angle"] for c in cases],
        layout.SWEEP_CASE_CLEARANCE: [c["clearance"] for c in cases],
        layout.SWEEP_STATUS: [c["status"] for c in cases],
        layout.SWEEP_COLLIDED: [c.get("collided", 0) if c["status"] == 1 else -1
                                for c in cases]}
    if maxima:
        for name in layout.OPERABILITY_MAXIMA.values():
            columns[name] = np.where(ok, rng.gumbel(5.0, 1.0, len(cases)), np.nan)
    for check in checks:
        margin = [c.get("margins", {}).get(check, np.nan) for c in cases]
        names = layout.check_columns(check)
        columns[names["margin"]] = margin
        columns[names["value"]] = np.ones(len(cases))
        columns[names["limit"]] = np.ones(len(cases))
    with h5py.File(path, "w") as f:
        for name, values in columns.items():
            f.create_dataset(name, data=np.asarray(values))
    return path


def _cases(n, **fields):
    return [dict(fields) for _ in range(n)]


def _known_cells():
    """Five cells: A (L4, 90 deg, 0.5 B): 20 ok, 2 collided, 1 failed, 1 not run, fall_swl
    broken in 3 of the 15 cases where it applies (5 NaN); B (L4, 90, 2.0): 30 ok, nothing
    failed; C (L5, 135, 2.0): 5 of 5 collided; D (L4, 135, 0.5): 2 failed runs only; E (L4,
    135, 2.0): 80 ok, nothing failed. impact_speed is NaN (not applicable) everywhere."""
    a = dict(level=4, angle=90.0, clearance=0.5, status=1)
    cases = (_cases(2, **a, collided=1, margins={"fall_swl": 0.2})
             + _cases(3, **a, margins={"fall_swl": -0.1})
             + _cases(10, **a, margins={"fall_swl": 0.3})
             + _cases(5, **a)
             + [dict(a, status=2), dict(a, status=0)])
    cases += _cases(30, level=4, angle=90.0, clearance=2.0, status=1,
                    margins={"fall_swl": 0.5})
    cases += _cases(5, level=5, angle=135.0, clearance=2.0, status=1, collided=1)
    cases += _cases(2, level=4, angle=135.0, clearance=0.5, status=2)
    cases += _cases(80, level=4, angle=135.0, clearance=2.0, status=1,
                    margins={"fall_swl": 0.0})
    return cases


CHECKS = ("impact_speed", "fall_swl")


@pytest.fixture
def known(tmp_path):
    return _write(tmp_path / "known.h5", _known_cells(), CHECKS)


def _by_key(cells):
    return {(c.sea, c.angle, c.clearance): c for c in cells}


def test_table_counts_by_hand(known):
    summary = operability.load(known)
    assert list(summary.checks) == list(CHECKS)  # layout.CHECKS' order
    cells = _by_key(operability.table(summary))
    assert len(cells) == 5 and all(math.isnan(c.period) for c in cells.values())
    a = cells[(4.0, 90.0, 0.5)]
    assert (a.cases, a.n, a.failed, a.not_run, a.collision.k) == (22, 20, 1, 1, 2)
    assert (a.collision.lower, a.collision.upper) == assessment.wilson_interval(2, 20)
    assert (a.checks["fall_swl"].k, a.checks["fall_swl"].n) == (3, 15)   # NaN ignored
    assert a.checks["impact_speed"].n == 0                                # never applies
    assert a.checks["fall_swl"].lower == pytest.approx(0.0705, abs=1e-4)   # > 0.05
    assert a.verdict == operability.NOT_ACCEPTABLE
    assert a.limiting == "fall_swl"            # 3/15 = 0.2 > 2/20 = 0.1
    assert a.maxima["peak_fall_tension"] is not None    # n = 20 >= 10
    b = cells[(4.0, 90.0, 2.0)]
    assert (b.n, b.collision.k, b.collision.upper) == (30, 0, assessment.wilson_interval(0, 30)[1])
    assert b.verdict == operability.UNDECIDED and b.limiting == operability.NONE
    c = cells[(5.0, 135.0, 2.0)]
    assert (c.n, c.collision.k, c.checks["fall_swl"].n) == (5, 5, 0)
    assert c.verdict == operability.NOT_ACCEPTABLE and c.limiting == operability.COLLISION
    assert all(fit is None for fit in c.maxima.values())               # n = 5 < 10
    d = cells[(4.0, 135.0, 0.5)]
    assert (d.cases, d.n, d.failed) == (2, 0, 2) and d.verdict == operability.NO_DATA
    e = cells[(4.0, 135.0, 2.0)]
    assert e.n == 80 and e.verdict == operability.ACCEPTABLE          # margin 0 passes
    assert sum(c.cases for c in cells.values()) == summary.ncase     # none dropped


def test_risk_level_moves_the_verdict(known):
    cells = _by_key(operability.table(known, risk=0.2))
    assert cells[(4.0, 90.0, 2.0)].verdict == operability.ACCEPTABLE   # 0/30: upper 0.114
    cells = _by_key(operability.table(known, risk=0.01))
    assert cells[(4.0, 135.0, 2.0)].verdict == operability.UNDECIDED


def test_by_pools_the_other_keys(known):
    cells = operability.table(known, by=("sea",))
    assert [(c.sea, c.cases) for c in cells] == [(4.0, 134), (5.0, 5)]
    assert all(math.isnan(c.angle) and math.isnan(c.clearance) for c in cells)
    assert cells[0].collision.k == 2 and cells[0].failed == 3


def test_periods_become_a_key_only_when_there_are_several(tmp_path):
    cases = (_cases(4, height=1.0, period=6.0, angle=90.0, clearance=1.0, status=1)
             + _cases(4, height=1.0, period=9.0, angle=90.0, clearance=1.0, status=1,
                      collided=1))
    cells = operability.table(_write(tmp_path / "t.h5", cases))
    assert [(c.sea, c.period, c.collision.k) for c in cells] == [(1.0, 6.0, 0), (1.0, 9.0, 4)]


def test_rules():
    rate = operability.Rate
    assert operability.verdict([]) == operability.NO_DATA
    assert operability.verdict([rate("a", 0, 0, 0.0, 1.0)]) == operability.NO_DATA
    assert operability.verdict([rate("a", 0, 80, 0.0, 0.04), rate("b", 0, 0, 0.0, 1.0)]) \
        == operability.ACCEPTABLE
    assert operability.verdict([rate("a", 0, 80, 0.0, 0.04), rate("b", 1, 9, 0.02, 0.4)]) \
        == operability.UNDECIDED
    # ties in the estimate go to the larger upper bound
    tie = [rate("a", 1, 10, 0.02, 0.40), rate("b", 2, 20, 0.03, 0.30)]
    assert operability.limiting(tie) == "a"
    assert operability.limiting([rate("a", 0, 10, 0.0, 0.3)]) == operability.NONE


def test_checks_and_maxima_are_optional(tmp_path):
    path = _write(tmp_path / "old.h5", _cases(12, level=3, angle=45.0, clearance=1.0,
                                              status=1), maxima=False)
    summary = operability.load(path)
    assert summary.checks == {} and summary.maxima == {}
    (c,) = operability.table(summary)
    assert c.rates == [c.collision] and c.verdict == operability.UNDECIDED


# --- the paper's conclusion -----------------------------------------------------------------

def test_conclusion_pools_clear_launches_below_level_5(known):
    found = operability.conclusion(known)
    # B (0/30) and E (0/80); A is too close, C is Level 5
    assert (found.k, found.n, found.verdict, found.more_launches) == (0, 110, "supported", 0)
    assert (found.lower, found.upper) == assessment.wilson_interval(0, 110)
    assert "supported" in found.statement()
    found = operability.conclusion(known, below_level=6)   # C's 5 collisions join
    assert (found.k, found.n) == (5, 115) and found.verdict == "undecided"
    assert found.more_launches == assessment.launches_needed(5, 115, 0.05) > 0
    found = operability.conclusion(known, min_clearance_b=0.5, below_level=6, risk=0.01)
    assert found.verdict == "refuted"     # 7/135: lower bound 0.025 > 0.01


def test_conclusion_on_a_rule_check(tmp_path):
    """Counted on the LSA's impact speed instead of the paper's contact: launches where the
    check does not apply (NaN) are left out; a collided launch with a positive margin does
    not count against it."""
    cases = (_cases(20, level=4, angle=90.0, clearance=2.0, status=1, collided=1,
                    margins={"impact_speed": 0.4})
             + _cases(2, level=4, angle=90.0, clearance=2.0, status=1, collided=1,
                      margins={"impact_speed": -0.02})
             + _cases(5, level=4, angle=90.0, clearance=2.0, status=1))
    path = _write(tmp_path / "impact.h5", cases, ("impact_speed",))
    found = operability.conclusion(path, criterion="impact_speed")
    assert (found.k, found.n) == (2, 22)
    assert (found.lower, found.upper) == assessment.wilson_interval(2, 22)
    assert "3.5 m/s" in found.statement() and "2/22 hit faster" in found.statement()
    paper = operability.conclusion(path)
    assert (paper.k, paper.n, paper.verdict) == (22, 27, "refuted")


def test_conclusion_falls_back_to_wave_height_without_levels(tmp_path):
    cases = (_cases(10, height=3.0, angle=90.0, clearance=2.0, status=1)
             + _cases(10, height=4.5, angle=90.0, clearance=2.0, status=1, collided=1)
             + _cases(3, height=3.0, angle=90.0, clearance=1.0, status=1, collided=1))
    found = operability.conclusion(_write(tmp_path / "h.h5", cases))
    assert (found.k, found.n, found.verdict) == (0, 10, "undecided")
    assert found.more_launches == 63      # 0/73 is the first below 5 %


# --- the command -----------------------------------------------------------------------------

def test_command_writes_table_figures_and_conclusion(known, tmp_path, capsys):
    """The made-up summary as the paper's own sweep (its deck text): the conclusion too."""
    with h5py.File(known, "r+") as f:
        f.attrs[layout.SWEEP_NAMELIST] = (operability.INPUT / "sweep_operability.nml").read_text()
    out = tmp_path / "out"
    assert cli.main(["operability", str(known), "-o", str(out), "--risk", "0.05"]) == 0
    printed = capsys.readouterr().out
    for suffix in ("_operability.csv", "_operability.md", "_operability.png",
                   "_operability_limiting.png"):
        path = out / f"known{suffix}"
        assert path.exists() and f"wrote {path}" in printed
    rows = list(csv.DictReader(open(out / "known_operability.csv")))
    assert len(rows) == 5
    row = next(r for r in rows if (r["level"], r["angle_deg"], r["clearance_b"])
               == ("4", "90", "0.5"))
    assert (row["ok"], row["failed"], row["not_run"], row["collisions"]) == ("20", "1", "1", "2")
    assert (row["fall_swl_applicable"], row["fall_swl_failures"]) == ("15", "3")
    assert row["impact_speed_applicable"] == "0" and row["impact_speed_p"] == ""
    assert row["verdict"] == "not acceptable" and row["limiting"] == "fall_swl"
    md = (out / "known_operability.md").read_text()
    assert "| 4 | all | 90 | 0.5 | 20 | 1 / 1 | 2/20 [2.8, 30.1] % | - | 3/15" in md
    assert "supported" in md and "S8 LSA Code 6.1.1" in md
    assert printed.index("| Level") < printed.index("The paper's conclusion")


def test_command_pools_and_rejects(known, tmp_path, capsys):
    assert cli.main(["operability", str(known), "-o", str(tmp_path), "--by", "sea"]) == 0
    assert len(list(csv.DictReader(open(tmp_path / "known_operability.csv")))) == 2
    assert cli.main(["operability", str(known), "--by", "colour"]) == 1
    assert cli.main(["operability", str(known), "--risk", "2"]) == 1
    with h5py.File(tmp_path / "bad.h5", "w") as f:
        f.create_dataset(layout.SWEEP_STATUS, data=[1])
    assert cli.main(["operability", str(tmp_path / "bad.h5"), "-o", str(tmp_path)]) == 1
    assert "/cases/level" in capsys.readouterr().err


def test_layout_names_the_checks():
    assert [c.id for c in layout.CHECKS] == [
        "lowering_speed", "impact_speed", "fall_swl", "fall_mbl", "sling_swl", "sling_mbl",
        "brake_load", "release_load", "seat_srss", "seat_dri"]
    assert [c.bound for c in layout.CHECKS].count("lower") == 1
    assert all(c.meaning and c.source for c in layout.CHECKS)
    assert layout.check_columns("seat_dri") == {
        "value": "results/check_seat_dri_value", "limit": "results/check_seat_dri_limit",
        "margin": "results/check_seat_dri_margin"}
