"""davit-post summation-compare: the intervals against published values and exact binomial
coverage, and the verdicts on synthetic summaries whose difference is known."""
import h5py
import numpy as np
import pytest
from scipy import stats

from postproc import layout, summation_compare as sc


# Newcombe (1998), Statistics in Medicine 17, 873-890, Table II, method 10 (hybrid score,
# no continuity correction): the six worked examples
NEWCOMBE_TABLE_II = [((56, 70, 48, 80), (0.0524, 0.3339)), ((9, 10, 3, 10), (0.1705, 0.8090)),
                     ((6, 7, 2, 7), (0.0582, 0.8062)), ((5, 56, 0, 29), (-0.0381, 0.1926)),
                     ((0, 10, 0, 20), (-0.1611, 0.2775)), ((10, 10, 0, 20), (0.6791, 1.0))]


@pytest.mark.parametrize("counts,published", NEWCOMBE_TABLE_II)
def test_newcombe_difference_is_table_ii(counts, published):
    assert sc.newcombe_difference(*counts) == pytest.approx(published, abs=5e-5)


def test_quantile_interval_is_the_order_statistic_interval():
    # the median of n = 100: ranks 40 and 61 (the classical distribution-free table)
    assert sc.quantile_interval(np.arange(1.0, 101.0), 0.5) == (40.0, 61.0)
    # coverage of the ranks chosen for the P90, from scipy's binomial: >= 95 %
    for n in (30, 100, 300):
        lo, hi = sc.quantile_interval(np.arange(1.0, n + 1.0), 0.9)
        cover = stats.binom.cdf(hi - 1, n, 0.9) - stats.binom.cdf(lo - 1, n, 0.9)
        assert cover >= 0.95
        narrower = stats.binom.cdf(hi - 2, n, 0.9) - stats.binom.cdf(lo, n, 0.9)
        assert narrower < 0.95
    assert np.isnan(sc.quantile_interval(np.arange(5.0), 0.9)[0])


def _summary(path, collided, sling, impact):
    n = len(collided)
    with h5py.File(path, "w") as f:
        f[layout.SWEEP_CASE_LEVEL] = np.full(n, 5)
        f[layout.SWEEP_CASE_ANGLE] = np.full(n, 90.0)
        f[layout.SWEEP_CASE_CLEARANCE] = np.full(n, 0.5)
        f[layout.SWEEP_STATUS] = np.ones(n, dtype=int)
        f[layout.SWEEP_COLLIDED] = np.asarray(collided, dtype=int)
        f[sc.MAXIMA["sling"]] = np.asarray(sling, float)
        f[sc.MAXIMA["impact"]] = np.asarray(impact, float)


def test_verdicts_on_known_differences(tmp_path):
    rng = np.random.default_rng(3)
    n = 400
    sling = rng.gumbel(60e3, 8e3, n)
    impact = rng.gumbel(1.0, 0.3, n)
    a, same, other = tmp_path / "a.h5", tmp_path / "same.h5", tmp_path / "other.h5"
    collided = rng.random(n) < 0.3
    _summary(a, collided, sling, impact)
    # the same launches in another order: every statistic "equal"
    order = rng.permutation(n)
    _summary(same, collided[order], sling[order], impact[order])
    # collision probability 0.3 -> 0.6 and the loads 20 % higher: every statistic differs
    _summary(other, rng.random(n) < 0.6, 1.2 * rng.gumbel(60e3, 8e3, n),
             1.2 * rng.gumbel(1.0, 0.3, n) + 0.3)
    rows = sc.compare(a, same)
    assert len(rows) == 5
    assert all(r["diff"][0] <= 0.0 <= r["diff"][1] for r in rows)
    rows = sc.compare(a, other)
    assert not any(r["diff"][0] <= 0.0 <= r["diff"][1] for r in rows)
    table = sc.markdown(rows, "A", "B")
    assert table.count("differs") == 5 and "n = 400/400" in table


def _summary_cells(path, angles, collided, sling, impact):
    """A summary of one launch per element, the cells told apart by their angle."""
    _summary(path, collided, sling, impact)
    with h5py.File(path, "r+") as f:
        f[layout.SWEEP_CASE_ANGLE][...] = np.asarray(angles, float)


def test_pooled_cell_sees_what_small_cells_cannot(tmp_path):
    # ten cells of 8 launches (sweep_fig19's design): 1 of 8 collide in A, 4 of 8 in B.
    # Per cell, Newcombe's interval of 4/8 - 1/8 holds 0 (n too small); pooled, 40/80 -
    # 10/80 = 0.375 lies in [0.235, 0.496] (the same formula at n = 80), which excludes 0.
    angles = np.repeat(np.arange(10) * 10.0, 8)
    first = np.tile(np.arange(8), 10)
    rng = np.random.default_rng(7)
    sling, impact = rng.gumbel(60e3, 8e3, 80), rng.gumbel(1.0, 0.3, 80)
    a, b = tmp_path / "a.h5", tmp_path / "b.h5"
    _summary_cells(a, angles, first < 1, sling, impact)
    _summary_cells(b, angles, first < 4, sling, impact)
    assert len(sc.compare(a, b)) == 50                 # no pooled row unless asked
    rows = sc.compare(a, b, pool=True)
    assert len(rows) == 55 and rows[0]["cell"] == sc.POOLED
    pooled = rows[0]
    assert pooled["n"] == (80, 80) and (pooled["a"], pooled["b"]) == (0.125, 0.5)
    assert pooled["diff"][0] > 0.2 and pooled["diff"][1] < 0.5
    cells = [r for r in rows[5:] if r["statistic"] == "collision probability"]
    assert len(cells) == 10 and all(r["diff"][0] < 0.0 < r["diff"][1] for r in cells)
    # the same loads in both: the pooled quantiles agree
    assert all(r["diff"][0] <= 0.0 <= r["diff"][1] for r in rows[1:5])


def test_compare_sweeps_command_writes_the_pooled_table(tmp_path):
    from postproc import __main__ as cli
    angles = np.repeat([45.0, 90.0], 20)
    rng = np.random.default_rng(5)
    a, b, out = tmp_path / "a.h5", tmp_path / "b.h5", tmp_path / "t.md"
    for path in (a, b):
        _summary_cells(path, angles, rng.random(40) < 0.5, rng.gumbel(60e3, 8e3, 40),
                       rng.gumbel(1.0, 0.3, 40))
    assert cli.main(["compare-sweeps", str(a), str(b), "--pool", "-o", str(out)]) == 0
    table = out.read_text()
    assert table.count("| all launches (n = 40/40) |") == 5
    assert table.count("| L5, 45 deg, 0.5 (n = 20/20) |") == 5


def test_quantile_interval_of_a_pooled_sweep_is_the_normal_approximation():
    """n = 1800 (a pooled 1800-launch sweep; the integer binomial sums overflowed a float
    there): the order-statistic ranks agree with the normal approximation of the
    binomial, n q -/+ 1.96 sqrt(n q (1 - q)), to within 2 ranks."""
    n = 1800
    for q in (0.5, 0.9):
        lo, hi = sc.quantile_interval(np.arange(1.0, n + 1.0), q)
        half = 1.96 * np.sqrt(n * q * (1 - q))
        assert abs(lo - (n * q - half)) <= 2 and abs(hi - (n * q + half)) <= 2, (q, lo, hi)
