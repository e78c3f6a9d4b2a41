"""Launch statistics of two sweeps that differ in one modelling choice (e.g. the sea's
double summation, eq. 43, against a single summation, or a sweep deck against its fast
level of detail): `davit-post compare-sweeps A.h5 B.h5 [--pool] [-o TABLE.md]` (also
`davit-post summation-compare`, its first name). Any two sweep summaries are accepted.

For every cell (level, encounter angle, clearance) both summaries hold, over the launches
that completed: the collision probability (a fender touched the ship's side) with its
Wilson 95 % interval, and the P50 and P90 of the peak sling tension and of the fastest
impact speed on the ship's side (0 for a launch without impact), each with its
distribution-free 95 % interval from order statistics. The difference B - A is judged
with Newcombe's hybrid score interval for two proportions (Newcombe 1998, method 10) and
a seeded percentile bootstrap for the quantiles: "equal" when the 95 % interval of the
difference holds 0, else the difference is reported. `--pool` also compares every completed
launch of each summary as one cell ("all"): a sweep of a few launches per cell (8 in
sweep_fig19) leaves each cell's intervals too wide to see a difference that the pooled
launches can.
"""
import argparse
import math
import sys

import numpy as np

from . import assessment, layout

CONFIDENCE = 0.95
BOOTSTRAP = 2000
SEED = 20211
FIELDS = {"level": layout.SWEEP_CASE_LEVEL, "angle_deg": layout.SWEEP_CASE_ANGLE,
          "clearance_b": layout.SWEEP_CASE_CLEARANCE, "status": layout.SWEEP_STATUS,
          "collided": layout.SWEEP_COLLIDED}
MAXIMA = {"sling": layout.OPERABILITY_MAXIMA["peak_sling_tension"],
          "impact": layout.check_columns("impact_speed")["value"]}


def newcombe_difference(k1, n1, k2, n2, confidence=CONFIDENCE):
    """Newcombe's hybrid score interval for p1 - p2 (1998, method 10, no continuity
    correction), from the two Wilson intervals."""
    p1, p2 = k1 / n1, k2 / n2
    l1, u1 = assessment.wilson_interval(k1, n1, confidence)
    l2, u2 = assessment.wilson_interval(k2, n2, confidence)
    d = p1 - p2
    return (d - math.sqrt((p1 - l1) ** 2 + (u2 - p2) ** 2),
            d + math.sqrt((u1 - p1) ** 2 + (p2 - l2) ** 2))


def _binom_cdfs(n, p):
    """P(X <= k), k = 0..n, for X ~ Binomial(n, p), from the pmf in log space (the exact
    integer binomial coefficients overflow a float beyond n ~ 1000: a pooled sweep)."""
    k = np.arange(n + 1)
    if p <= 0.0 or p >= 1.0:
        return np.where(k >= (0 if p <= 0.0 else n), 1.0, 0.0)
    logc = np.array([math.lgamma(n + 1) - math.lgamma(i + 1) - math.lgamma(n - i + 1)
                     for i in k])
    return np.cumsum(np.exp(logc + k * math.log(p) + (n - k) * math.log1p(-p)))


def _binom_cdf(k, n, p, cdfs=None):
    """P(X <= k) for X ~ Binomial(n, p) (0 for k < 0)."""
    if k < 0:
        return 0.0
    cdfs = _binom_cdfs(n, p) if cdfs is None else cdfs
    return float(cdfs[min(k, n)])


def quantile_interval(x, q, confidence=CONFIDENCE):
    """Distribution-free interval (x_(l), x_(u)) of the q-quantile of the sample x: the
    narrowest symmetric pair of order statistics with P(l <= B < u) >= confidence, B ~
    Binomial(n, q) (ranks 1-based; NaN where n is too small for the confidence)."""
    x = np.sort(np.asarray(x, dtype=float))
    n = x.size
    centre = int(math.floor(n * q))
    cdfs = _binom_cdfs(n, q)
    for width in range(0, n + 1):
        lo, hi = max(centre - width, 1), min(centre + width + 1, n)
        # the q-quantile lies in [x_(lo), x_(hi)] unless fewer than lo or at least hi of
        # the n draws fall below it
        cover = _binom_cdf(hi - 1, n, q, cdfs) - _binom_cdf(lo - 1, n, q, cdfs)
        if cover >= confidence:
            return float(x[lo - 1]), float(x[hi - 1])
        if lo == 1 and hi == n:
            break
    return math.nan, math.nan


def bootstrap_difference(a, b, q, confidence=CONFIDENCE, draws=BOOTSTRAP, seed=SEED):
    """Percentile bootstrap interval of quantile_q(b) - quantile_q(a) (seeded)."""
    rng = np.random.default_rng(seed)
    a, b = np.asarray(a, float), np.asarray(b, float)
    d = np.array([np.quantile(rng.choice(b, b.size), q) - np.quantile(rng.choice(a, a.size), q)
                  for _ in range(draws)])
    tail = (1 - confidence) / 2
    return float(np.quantile(d, tail)), float(np.quantile(d, 1 - tail))


def _load(path):
    columns = layout.load_sweep_columns(path, FIELDS)
    columns.update(layout.load_sweep_optional(path, MAXIMA))
    missing = [m for m in MAXIMA if m not in columns]
    if missing:
        raise ValueError(f"{path}: no {', '.join(MAXIMA[m] for m in missing)}")
    return columns


def _cells(columns):
    ok = columns["status"] == 1
    keys = sorted({(columns["level"][i], columns["angle_deg"][i], columns["clearance_b"][i])
                   for i in np.flatnonzero(ok)})
    return {key: ok & (columns["level"] == key[0]) & (columns["angle_deg"] == key[1])
            & (columns["clearance_b"] == key[2]) for key in keys}


POOLED = ("all", "", "")


def compare(path_a, path_b, pool=False):
    """Rows (dicts) of the comparison, one per cell and statistic; with `pool` first the
    rows of every completed launch of each summary as one cell (POOLED)."""
    a, b = _load(path_a), _load(path_b)
    cells_a, cells_b = _cells(a), _cells(b)
    rows = []
    if pool and cells_a and cells_b:
        rows += _cell_rows(a, b, POOLED, a["status"] == 1, b["status"] == 1)
    for key in sorted(set(cells_a) & set(cells_b)):
        rows += _cell_rows(a, b, key, cells_a[key], cells_b[key])
    return rows


def _cell_rows(a, b, key, ma, mb):
    """The five rows of one cell: launches `ma` of summary a against `mb` of b."""
    rows = []
    ka, na = int(a["collided"][ma].sum()), int(ma.sum())
    kb, nb = int(b["collided"][mb].sum()), int(mb.sum())
    lo, hi = newcombe_difference(kb, nb, ka, na)
    rows.append(dict(cell=key, statistic="collision probability", a=ka / na,
                     a_int=assessment.wilson_interval(ka, na), b=kb / nb,
                     b_int=assessment.wilson_interval(kb, nb), diff=(lo, hi),
                     n=(na, nb)))
    for name, unit, scale in (("sling", "kN", 1e-3), ("impact", "m/s", 1.0)):
        xa, xb = a[name][ma] * scale, b[name][mb] * scale
        for q in (0.5, 0.9):
            rows.append(dict(cell=key, statistic=f"P{int(q * 100)} "
                             f"{'peak sling tension' if name == 'sling' else 'fastest impact'}"
                             f" ({unit})", a=float(np.quantile(xa, q)),
                             a_int=quantile_interval(xa, q), b=float(np.quantile(xb, q)),
                             b_int=quantile_interval(xb, q),
                             diff=bootstrap_difference(xa, xb, q), n=(na, nb)))
    return rows


def markdown(rows, name_a, name_b):
    lines = [f"| cell (level, angle, clearance B) | statistic | {name_a} [95 %] | "
             f"{name_b} [95 %] | difference B - A [95 %] | verdict |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lo, hi = r["diff"]
        same = lo <= 0.0 <= hi
        where = ("all launches" if r["cell"] == POOLED else
                 f"L{int(r['cell'][0])}, {r['cell'][1]:g} deg, {r['cell'][2]:g}")
        cell = f"{where} (n = {r['n'][0]}/{r['n'][1]})"
        lines.append(f"| {cell} | {r['statistic']} | {r['a']:.3g} [{r['a_int'][0]:.3g}, "
                     f"{r['a_int'][1]:.3g}] | {r['b']:.3g} [{r['b_int'][0]:.3g}, "
                     f"{r['b_int'][1]:.3g}] | {r['b'] - r['a']:+.3g} [{lo:+.3g}, {hi:+.3g}] | "
                     f"{'equal' if same else 'differs'} |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="davit-post compare-sweeps",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("a", help="sweep summary A (e.g. the double summation)")
    parser.add_argument("b", help="sweep summary B (e.g. the single summation)")
    parser.add_argument("--pool", action="store_true",
                        help="first compare all completed launches of each summary as one cell")
    parser.add_argument("-o", "--output", help="write the Markdown table here too")
    args = parser.parse_args(argv)
    try:
        rows = compare(args.a, args.b, args.pool)
    except (OSError, ValueError, KeyError) as exc:
        print(f"davit-post compare-sweeps: {exc}", file=sys.stderr)
        return 1
    if not rows:
        print("davit-post compare-sweeps: the two summaries share no completed cell",
              file=sys.stderr)
        return 1
    text = markdown(rows, "A", "B")
    print(text)
    if args.output:
        with open(args.output, "w") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
