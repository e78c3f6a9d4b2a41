"""The operability table of a `davit sweep` summary (issue 16): in which sea states,
headings and clearances a launch is acceptable, how sure that is, and which rule limits it.

    python -m postproc operability SUMMARY.h5 [-o OUTDIR] [--risk 0.05] [--by sea,angle,...]

The finished launches (status 1) are grouped into cells by sea state (the level where the
summary gives one, else the wave height), heading, initial clearance and, where the sweep
has more than one, wave period (--by keeps only some of these; the rest are pooled). Per
cell: the collisions k of n launches, P(collision) with its 95 % Wilson interval; for each
rule check the summary holds (layout.CHECKS), the share of the launches where the rule
applies that break it (margin < 0), with its interval; a Gumbel fit of the per-launch
maxima (impact acceleration, fall and sling tension) for n >= 10: most probable maximum and
90 % fractile; the verdict at risk r: 'acceptable' if every failure probability's upper
bound is <= r, 'not acceptable' if one's lower bound is > r, else 'undecided (need more
launches)'; and the limiting criterion, the one with the largest estimated failure
probability (ties: the larger upper bound; 'none' when nothing failed). Failed runs
(status 2) and cases not run are counted per cell, never dropped silently.

Writes OUTDIR/<stem>_operability.csv, .md and .png (heat map of P(collision)) and
_limiting.png. The .md of the paper's own operability sweeps (input/sweep_operability*.nml,
PAPER_SWEEPS) ends with the paper's conclusion as a tested statement (conclusion()); a
user's sweep tests no claim of the paper's.
"""
import csv
import math
import os
import pathlib
import re
from dataclasses import dataclass, field

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

from . import assessment, layout  # noqa: E402
from .figures import _save  # noqa: E402

CONFIDENCE = 0.95
RISK = 0.05
MIN_MAXIMA = 10
COLLISION = "collision"
ACCEPTABLE = "acceptable"
NOT_ACCEPTABLE = "not acceptable"
UNDECIDED = "undecided (need more launches)"
NO_DATA = "no finished launch"
NONE = "none"
DIMENSIONS = ("sea", "period", "angle", "clearance")
MAXIMA_LABELS = {"peak_horizontal_acceleration": "impact acceleration [m/s^2]",
                 "peak_fall_tension": "fall tension [kN]",
                 "peak_sling_tension": "sling tension [kN]"}
MAXIMA_SCALE = {"peak_horizontal_acceleration": 1.0, "peak_fall_tension": 1e-3,
                "peak_sling_tension": 1e-3}
# the height of the paper's Level 5 sea: the threshold where a summary gives no level
LEVEL5_HEIGHT = 4.0
# The paper's own operability sweeps: only their tables test the paper's conclusion.
PAPER_SWEEPS = ("sweep_operability.nml", "sweep_operability_lsa.nml")
INPUT = pathlib.Path(__file__).resolve().parents[1] / "input"


@dataclass
class Summary:
    """The columns of a sweep summary the table reads: the required ones, the per-launch
    maxima it holds and its rule checks ({id: {value, limit, margin}})."""
    path: str
    columns: dict
    maxima: dict
    checks: dict

    @property
    def ncase(self):
        return self.columns["status"].size


def load(path):
    """Summary of the sweep summary file `path` (ValueError naming a missing dataset)."""
    return Summary(path=str(path),
                   columns=layout.load_sweep_columns(path, layout.OPERABILITY_FIELDS),
                   maxima=layout.load_sweep_optional(path, layout.OPERABILITY_MAXIMA),
                   checks=layout.load_checks(path))


@dataclass(frozen=True)
class Rate:
    """k failures of a criterion in the n launches where it applies, with the Wilson
    interval at `confidence`."""
    name: str
    k: int
    n: int
    lower: float
    upper: float

    @property
    def estimate(self):
        return self.k / self.n if self.n else math.nan


def rate(name, failed, confidence=CONFIDENCE):
    """Rate of the boolean array `failed` (one entry per applicable launch)."""
    k, n = int(np.sum(failed)), int(np.size(failed))
    return Rate(name, k, n, *assessment.wilson_interval(k, n, confidence))


def verdict(rates, risk=RISK):
    """'acceptable' if every applicable rate's upper bound is <= risk, 'not acceptable' if
    any lower bound is > risk, else undecided: the interval straddles the risk level."""
    rates = [r for r in rates if r.n > 0]
    if not rates:
        return NO_DATA
    if any(r.lower > risk for r in rates):
        return NOT_ACCEPTABLE
    if all(r.upper <= risk for r in rates):
        return ACCEPTABLE
    return UNDECIDED


def limiting(rates):
    """The criterion with the largest estimated failure probability (ties: the larger
    upper bound, i.e. the less tested), or 'none' where no criterion failed at all."""
    failing = [r for r in rates if r.n > 0 and r.k > 0]
    if not failing:
        return NONE
    return max(failing, key=lambda r: (r.estimate, r.upper)).name


@dataclass
class Cell:
    """One cell of the table: its key (NaN where pooled), the case counts, the rates of
    collision and of each rule check, the Gumbel fits of the maxima, verdict, limiting."""
    sea: float
    period: float
    angle: float
    clearance: float
    cases: int
    failed: int
    not_run: int
    collision: Rate
    checks: dict = field(default_factory=dict)
    maxima: dict = field(default_factory=dict)
    verdict: str = NO_DATA
    limiting: str = NONE

    @property
    def n(self):
        return self.collision.n

    @property
    def rates(self):
        return [self.collision] + list(self.checks.values())


def sea_state(summary):
    """('level', levels) where the summary gives a level for every case, else
    ('wave_height', heights): the sea-state axis of the table."""
    level = summary.columns["level"]
    if level.size and np.all(level >= 0):
        return "level", level.astype(float)
    return "wave_height", summary.columns["wave_height"].astype(float)


def _keys(summary, by):
    """(keys, used): the (ncase, 4) cell keys (sea, period, angle, clearance) and which of
    them are keys at all (the others are pooled); the period is a key only where the sweep
    has more than one."""
    c = summary.columns
    periods = c["wave_period"].astype(float)
    columns = {"sea": sea_state(summary)[1], "period": periods,
               "angle": c["angle_deg"].astype(float),
               "clearance": c["clearance_b"].astype(float)}
    used = np.array([d in by and (d != "period" or np.unique(periods).size > 1)
                     for d in DIMENSIONS])
    return np.column_stack([columns[d] for d in DIMENSIONS]), used


def _maxima(summary, rows):
    """{field: GumbelFit or None} of the maxima of the finished launches `rows` (None below
    MIN_MAXIMA launches or where the law cannot be fitted)."""
    out = {}
    for name, values in summary.maxima.items():
        x = values[rows]
        x = x[np.isfinite(x)]
        out[name] = assessment.fit_gumbel(x) if x.size >= MIN_MAXIMA else None
    return out


def cell(summary, rows, key, risk=RISK, confidence=CONFIDENCE):
    """The Cell of the cases `rows` (boolean mask) with key (sea, period, angle,
    clearance)."""
    c = summary.columns
    status = c["status"]
    ok = rows & (status == layout.SWEEP_OK)
    defined = ok & (c["collided"] >= 0)
    checks = {}
    for check_id, parts in summary.checks.items():
        margin = parts["margin"][ok]
        margin = margin[~np.isnan(margin)]
        checks[check_id] = rate(check_id, margin < 0, confidence)
    out = Cell(*key, cases=int(rows.sum()),
               failed=int(np.sum(rows & (status == layout.SWEEP_FAILED))),
               not_run=int(np.sum(rows & (status == layout.SWEEP_NOT_RUN))),
               collision=rate(COLLISION, c["collided"][defined] == 1, confidence),
               checks=checks, maxima=_maxima(summary, ok))
    out.verdict = verdict(out.rates, risk)
    out.limiting = limiting(out.rates)
    return out


def table(summary, risk=RISK, by=DIMENSIONS, confidence=CONFIDENCE):
    """The cells of the summary (every case in exactly one), sorted by their key."""
    if isinstance(summary, (str, os.PathLike)):
        summary = load(summary)
    keys, used = _keys(summary, by)
    keys = keys[:, used]
    cells = []
    for key in np.unique(keys, axis=0):
        rows = np.all(keys == key, axis=1)
        full = np.full(len(DIMENSIONS), np.nan)
        full[used] = key
        cells.append(cell(summary, rows, tuple(float(v) for v in full), risk, confidence))
    return cells


# --- the paper's conclusion --------------------------------------------------------------

@dataclass(frozen=True)
class Conclusion:
    """The pooled collision count of the launches the paper's conclusion speaks of, its
    Wilson interval, the verdict at the risk level and how many further collision-free
    launches would bring the upper bound to the risk level."""
    k: int
    n: int
    lower: float
    upper: float
    risk: float
    confidence: float
    more_launches: int
    verdict: str
    pool: str
    criterion: str = "collision"

    def statement(self):
        """The conclusion and its verdict, in one paragraph."""
        event, word, noun = CRITERIA[self.criterion]
        share = f"{self.k}/{self.n} {word}" if self.n else "no finished launch in this pool"
        text = (f"Claim: a launch from {self.pool} does not {event} "
                f"(probability <= {self.risk:g}). Evidence: {share}, "
                f"P({noun}) in [{self.lower:.4f}, {self.upper:.4f}] "
                f"({self.confidence:.0%} Wilson). Verdict: {self.verdict}.")
        if self.verdict != "supported":
            text += (f" {self.more_launches} further launches without one would bring "
                     f"the upper bound to <= {self.risk:g}.")
        return text


# What a conclusion counts: the paper's collision (any fender touching the ship's side) or
# a rule check's failure (e.g. 'impact_speed': an impact faster than the LSA Code's
# 3.5 m/s, which a lifeboat is built to withstand): (claim, count word, noun).
CRITERIA = {
    "collision": ("collide with the ship's side", "collided", "collision"),
    "impact_speed": ("hit the ship's side faster than the LSA Code's 3.5 m/s (4.4.1)",
                     "hit faster", "impact > 3.5 m/s"),
}


def conclusion(summary, min_clearance_b=1.5, below_level=5, risk=RISK,
               confidence=CONFIDENCE, below_height=LEVEL5_HEIGHT, criterion="collision"):
    """The paper's conclusion tested: pool the finished launches with clearance_b >=
    min_clearance_b in sea states below `below_level` (a case without a level, -1, counts
    as below it when its wave height is < below_height, the Level 5 height) and call it
    'supported' (upper bound <= risk), 'refuted' (lower bound > risk) or 'undecided'.
    `criterion` (CRITERIA) is what counts against it: the paper's collision, or a rule
    check's failure (a launch where the check does not apply is left out)."""
    if isinstance(summary, (str, os.PathLike)):
        summary = load(summary)
    c = summary.columns
    level = c["level"]
    calm_enough = np.where(level >= 0, level < below_level, c["wave_height"] < below_height)
    if criterion == "collision":
        defined, failed = c["collided"] >= 0, c["collided"] == 1
    else:
        margin = summary.checks[criterion]["margin"]
        defined, failed = ~np.isnan(margin), np.nan_to_num(margin, nan=0.0) < 0
    rows = ((c["status"] == layout.SWEEP_OK) & defined
            & (c["clearance_b"] >= min_clearance_b) & calm_enough)
    k, n = int(np.sum(failed[rows])), int(rows.sum())
    lower, upper = assessment.wilson_interval(k, n, confidence)
    word = "supported" if n and upper <= risk else "refuted" if lower > risk else "undecided"
    pool = (f"an initial clearance >= {min_clearance_b:g} B in sea states below Level "
            f"{below_level:g} (H < {below_height:g} m where no level is given)")
    return Conclusion(k, n, lower, upper, risk, confidence,
                      assessment.launches_needed(k, n, risk, confidence), word, pool,
                      criterion)


# --- CSV, Markdown -------------------------------------------------------------------------

def _sea_name(summary):
    return sea_state(summary)[0]


def _num(value, digits=4):
    return "" if value is None or (isinstance(value, float) and math.isnan(value)) \
        else f"{value:.{digits}g}"


def _key_text(value, unit=""):
    return "all" if math.isnan(value) else f"{value:g}{unit}"


def csv_rows(cells, summary):
    """Header and rows of the CSV: one row per cell, every count and bound in full."""
    header = [_sea_name(summary), "wave_period", "angle_deg", "clearance_b", "cases", "ok",
              "failed", "not_run", "collisions", "p_collision", "p_collision_lower",
              "p_collision_upper"]
    for check_id in summary.checks:
        header += [f"{check_id}_{part}" for part in
                   ("applicable", "failures", "p", "lower", "upper")]
    for name in summary.maxima:
        header += [f"{name}_mpm", f"{name}_p90", f"{name}_fit"]
    header += ["verdict", "limiting"]
    rows = []
    for c in cells:
        row = [_key_text(c.sea), _key_text(c.period), _key_text(c.angle),
               _key_text(c.clearance), c.cases, c.n, c.failed, c.not_run, c.collision.k,
               _num(c.collision.estimate, 6), _num(c.collision.lower, 6),
               _num(c.collision.upper, 6)]
        for check_id in summary.checks:
            r = c.checks[check_id]
            row += [r.n, r.k, _num(r.estimate, 6), _num(r.lower, 6), _num(r.upper, 6)]
        for name in summary.maxima:
            fit = c.maxima.get(name)
            row += ["", "", ""] if fit is None else \
                [_num(fit.mpm, 6), _num(fit.p90, 6), "ok" if fit.fits else "poor"]
        rows.append(row + [c.verdict, c.limiting])
    return header, rows


def _interval(r):
    """'k/n [lo, hi] %' of a rate, '-' where it never applied."""
    if r.n == 0:
        return "-"
    return f"{r.k}/{r.n} [{100 * r.lower:.1f}, {100 * r.upper:.1f}] %"


def _fit_text(fit, scale):
    if fit is None:
        return ""
    mark = "" if fit.fits else " (poor fit)"
    return f"{fit.mpm * scale:.3g} / {fit.p90 * scale:.3g}{mark}"


def markdown(cells, summary, risk, conclusions=()):
    """The table as Markdown, with the checks' legend, the statistics used and the
    conclusion."""
    sea = "Level" if _sea_name(summary) == "level" else "H [m]"
    head = [sea, "T [s]", "heading [deg]", "clearance [B]", "ok", "failed / not run",
            "collisions (95 % CI)"] + list(summary.checks) \
        + [f"{MAXIMA_LABELS[m]} MPM / P90" for m in summary.maxima] \
        + ["verdict", "limiting"]
    lines = [f"# Operability of {os.path.basename(summary.path)} (risk r = {risk:g})", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for c in cells:
        row = [_key_text(c.sea), _key_text(c.period), _key_text(c.angle),
               _key_text(c.clearance), str(c.n), f"{c.failed} / {c.not_run}",
               _interval(c.collision)] + [_interval(c.checks[i]) for i in summary.checks] \
            + [_fit_text(c.maxima.get(m), MAXIMA_SCALE[m]) for m in summary.maxima] \
            + [c.verdict, c.limiting]
        lines.append("| " + " | ".join(row) + " |")
    lines += ["", "Failure shares are k/n with the 95 % Wilson score interval (n: the finished "
              "launches where the criterion applies). Verdict: acceptable if every upper bound "
              f"is <= {risk:g}, not acceptable if a lower bound is > {risk:g}, else undecided. "
              "MPM / P90: most probable maximum and 90 % fractile of a Gumbel law fitted by "
              f"maximum likelihood (n >= {MIN_MAXIMA}); 'poor fit' where the probability-plot "
              "correlation or the Anderson-Darling test rejects it at 5 %.", ""]
    checks = [ch for ch in layout.CHECKS if ch.id in summary.checks]
    if checks:
        lines += ["| check | meaning | source |", "|---|---|---|"]
        lines += [f"| {ch.id} | {ch.meaning} | {ch.source} |" for ch in checks]
    else:
        lines.append("This summary holds no rule checks: collisions only.")
    if conclusions:
        lines += ["", "## The paper's conclusion", ""]
        lines += [f"- {found.statement()}" for found in conclusions]
    return "\n".join(lines) + "\n"


# --- figures -------------------------------------------------------------------------------

def _panels(cells):
    """{(sea, period): cells} in key order. A pooled key is NaN, and NaN equals nothing,
    not even itself: keyed by None instead, so one period (a pooled key) makes one panel per
    sea, not one per cell."""
    out = {}
    for c in cells:
        key = tuple(None if math.isnan(v) else v for v in (c.sea, c.period))
        out.setdefault(key, []).append(c)
    return out


def _axis_values(cells, attr):
    values = sorted({getattr(c, attr) for c in cells if not math.isnan(getattr(c, attr))})
    return values or [math.nan]


def _grid(cells, sea_name, draw):
    """A figure of one panel per (sea, period), heading along x and clearance along y;
    draw(ax, i, j, cell) fills a cell. Returns (fig, axes)."""
    panels = _panels(cells)
    angles, clearances = _axis_values(cells, "angle"), _axis_values(cells, "clearance")
    ncol = min(len(panels), 3)
    nrow = math.ceil(len(panels) / ncol)
    fig, axes = plt.subplots(nrow, ncol, squeeze=False, constrained_layout=True,
                             figsize=(2.5 + 1.4 * len(angles) * ncol,
                                      1.4 + 1.1 * len(clearances) * nrow))
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    label = "Level" if sea_name == "level" else "H"
    for ax, group in zip(axes.ravel(), panels.values()):
        sea, period = group[0].sea, group[0].period
        ax.set_xlim(-0.5, len(angles) - 0.5)
        ax.set_ylim(-0.5, len(clearances) - 0.5)
        for c in group:
            i = angles.index(c.angle) if not math.isnan(c.angle) else 0
            j = clearances.index(c.clearance) if not math.isnan(c.clearance) else 0
            draw(ax, i, j, c)
        ax.set_xticks(range(len(angles)), [_key_text(a) for a in angles])
        ax.set_yticks(range(len(clearances)), [_key_text(b) for b in clearances])
        ax.set_xlabel("heading [deg]")
        ax.set_ylabel("clearance [B]")
        title = f"{label} {_key_text(sea, '' if sea_name == 'level' else ' m')}"
        ax.set_title(title + ("" if math.isnan(period) else f", T {period:.3g} s"), fontsize=9)
    return fig, axes


def heat_map(cells, summary, outdir, stem, risk=RISK):
    """P(collision) per cell, annotated k/n and the interval; hatched '///' where not
    acceptable, dotted where undecided, grey where no launch finished."""
    vmax = max([2 * risk] + [c.collision.estimate for c in cells if c.n])
    cmap = plt.get_cmap("YlOrRd")

    def draw(ax, i, j, c):
        colour = cmap(c.collision.estimate / vmax) if c.n else "lightgrey"
        ax.add_patch(Rectangle((i - 0.5, j - 0.5), 1, 1, facecolor=colour, edgecolor="white"))
        hatch = {NOT_ACCEPTABLE: "///", UNDECIDED: ".."}.get(c.verdict)
        if hatch:
            ax.add_patch(Rectangle((i - 0.5, j - 0.5), 1, 1, fill=False, hatch=hatch,
                                   edgecolor="0.35", lw=0))
        text = f"{c.collision.k}/{c.n}"
        if c.n:
            text += f"\n[{100 * c.collision.lower:.0f}, {100 * c.collision.upper:.0f}] %"
        if c.failed:
            text += f"\n{c.failed} failed"
        ax.text(i, j, text, ha="center", va="center", fontsize=7,
                bbox=dict(facecolor="white", alpha=0.7, lw=0, pad=1))

    fig, axes = _grid(cells, _sea_name(summary), draw)
    mappable = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0, vmax))
    fig.colorbar(mappable, ax=axes.ravel().tolist(), label="P(collision), estimate")
    fig.suptitle(f"Collisions: k/n [95 % Wilson]; /// not acceptable, .. undecided "
                 f"(r = {risk:g})", fontsize=9)
    return _save(fig, outdir, f"{stem}_operability.png")


def limiting_map(cells, summary, outdir, stem):
    """The limiting criterion of each cell, one colour per criterion, with its verdict."""
    names = [NONE, COLLISION] + list(summary.checks)
    colours = plt.get_cmap("tab20")

    def draw(ax, i, j, c):
        colour = ("lightgrey" if not c.n else "white" if c.limiting == NONE
                  else colours(names.index(c.limiting) % 20))
        ax.add_patch(Rectangle((i - 0.5, j - 0.5), 1, 1, facecolor=colour, edgecolor="white"))
        short = {ACCEPTABLE: "ok", NOT_ACCEPTABLE: "NOT ok", UNDECIDED: "undecided"}
        ax.text(i, j, f"{c.limiting}\n{short.get(c.verdict, '-')}", ha="center",
                va="center", fontsize=7, bbox=dict(facecolor="white", alpha=0.7, lw=0, pad=1))

    fig, _ = _grid(cells, _sea_name(summary), draw)
    fig.suptitle("Limiting criterion (largest estimated failure probability) and verdict",
                 fontsize=9)
    return _save(fig, outdir, f"{stem}_operability_limiting.png")


def _deck_values(text):
    """A deck's text without its comments and blanks: what it sets, whatever its notes."""
    return "".join(re.sub(r"!.*", "", text).split())


def is_paper_sweep(path):
    """Whether summary `path` is of one of the paper's operability sweeps: its sweep deck
    (root attribute sweep_namelist) sets what input/sweep_operability*.nml sets."""
    with h5py.File(path, "r") as f:
        text = layout._text(f.attrs.get(layout.SWEEP_NAMELIST, ""))
    values = _deck_values(str(text))
    return bool(values) and any(
        (INPUT / name).is_file() and _deck_values((INPUT / name).read_text()) == values
        for name in PAPER_SWEEPS)


def write(path, outdir="out", risk=RISK, by=DIMENSIONS, confidence=CONFIDENCE):
    """Write the CSV, the Markdown and the two figures of the summary `path`; returns
    (paths, conclusions, Markdown text): the paper's conclusion only for its own sweeps."""
    summary = load(path)
    cells = table(summary, risk, by, confidence)
    found = []
    if is_paper_sweep(path):
        found.append(conclusion(summary, risk=risk, confidence=confidence))
    if found and "impact_speed" in summary.checks:
        found.append(conclusion(summary, risk=risk, confidence=confidence,
                                criterion="impact_speed"))
    stem = os.path.splitext(os.path.basename(str(path)))[0]
    os.makedirs(outdir, exist_ok=True)
    csv_path = os.path.join(outdir, f"{stem}_operability.csv")
    header, rows = csv_rows(cells, summary)
    with open(csv_path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(header)
        writer.writerows(rows)
    md_path = os.path.join(outdir, f"{stem}_operability.md")
    text = markdown(cells, summary, risk, found)
    with open(md_path, "w") as f:
        f.write(text)
    paths = [csv_path, md_path]
    if cells:
        paths += [heat_map(cells, summary, outdir, stem, risk),
                  limiting_map(cells, summary, outdir, stem)]
    return paths, found, text
