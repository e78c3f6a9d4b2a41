"""Regression report: the facts the paper states in words (review §3.1: F2, F7-F11) checked
against davit's latest outputs in a folder, printed as a table.

The checks are pure functions over numpy arrays (tested on synthetic data with known
answers); the functions below the "gathering" line read the files. A fact whose files are
absent is reported as "no input", never as a failure. Where davit disagrees with the paper the row says
FAIL with both numbers: the model is not tuned to agree (README, "Regression report").
"""
import os
from dataclasses import dataclass, field, fields

import numpy as np

from . import layout, paper

PASS, FAIL, NO_INPUT = "pass", "FAIL", "no input"

# Output stems of the decks the single-file facts read (input/<stem>.nml -> out/<stem>.h5):
# F2 on the Fig. 13 transient deck (III.B boat, falls unstretched at t = 0) and on the
# paper's own Fig. 13 experiments, III.A 1 and 2 at full scale (equilibrium start)
F2_STEM = "fig13_tension"
F2_STEMS = {F2_STEM: "", "iiia_model_scale_1": " [III.A 1]", "iiia_model_scale_2": " [III.A 2]"}
FROZEN_STEM = "iiib_level5_090_frozen"
FREE_STEM = "iiib_level5_090"

# The paper's collision pattern at 0.5 B (III.B, Fig. 19, review F7): level -> angles
EXPECTED_COLLISIONS = {4: (90,), 5: (45, 90, 135)}
NEVER_COLLIDE = (0, 180)
CLEARANCE_TOL = 0.05            # boat widths: 1.5 m / 2.8 m = 0.54 B counts as 0.5 B
# Peak periods of eq. 44 at the levels' heights (review G18): the default regular period
PEAK_PERIOD = {4: 10.06, 5: 12.72}
REGULAR_TYPES = (1, 2)          # airy, stokes2 (summary wave_type)
IRREGULAR_TYPE = layout.SUMMARY_WAVE_IRREGULAR


@dataclass
class Verdict:
    """One row of the report."""
    fact: str
    paper: str
    davit: str
    result: str
    details: list = field(default_factory=list)


@dataclass
class Cases:
    """Per-case arrays (one element per run or sweep case), the sweep-summary contract's
    fields that the collision facts need."""
    level: np.ndarray
    angle_deg: np.ndarray
    clearance_b: np.ndarray
    wave_type: np.ndarray
    wind: np.ndarray
    status: np.ndarray
    collided: np.ndarray
    min_clearance: np.ndarray
    peak_horizontal_acceleration: np.ndarray
    realisation: np.ndarray = None

    def __post_init__(self):
        n = len(np.ravel(self.level))
        if self.realisation is None:
            self.realisation = np.zeros(n, dtype=int)
        for f in fields(self):
            setattr(self, f.name, np.ravel(np.asarray(getattr(self, f.name))))
            if len(getattr(self, f.name)) != n:
                raise ValueError(f"case field {f.name} has {len(getattr(self, f.name))} "
                                 f"entries, level has {n}")

    def __len__(self):
        return len(self.level)

    def where(self, mask):
        """The cases where mask holds."""
        return Cases(**{f.name: getattr(self, f.name)[mask] for f in fields(self)})

    @classmethod
    def concat(cls, parts):
        parts = [p for p in parts if p is not None and len(p)]
        if not parts:
            return None
        return cls(**{f.name: np.concatenate([getattr(p, f.name) for p in parts])
                      for f in fields(cls)})


# --------------------------------------------------------------------------- pure checks

def tension_settling(time, tension, window=(3.0, 8.0), band=0.05):
    """(steady mean over the window [N], settling time [s], spread of the segments' window
    means relative to the steady mean): the settling time is the first sample after the
    last one, before the window ends, at which any segment is outside +-band of the steady
    mean (0 if none ever is)."""
    time = np.asarray(time, dtype=float)
    tension = np.asarray(tension, dtype=float).reshape(len(time), -1)
    inside = (time >= window[0]) & (time <= window[1])
    if not inside.any():
        raise ValueError(f"no samples in [{window[0]}, {window[1]}] s")
    means = tension[inside].mean(axis=0)
    steady = means.mean()
    upto = time <= window[1]
    outside = np.nonzero(np.abs(tension[upto] - steady).max(axis=1) > band * steady)[0]
    settle = 0.0 if len(outside) == 0 else float(time[min(outside[-1] + 1, upto.sum() - 1)])
    return steady, settle, float((means.max() - means.min()) / steady)


def fact_f2(time, tension, weight, rigged_weight, label="", transient=True):
    """F2 (III.A, Fig. 13): the cable tension settles by about 2.5 s to about W/4 (two
    movable blocks), the sections agreeing; review tolerances: W/4 within 5 %,
    (W + blocks + slings)/4 within 2 %, settling into +-5 % at 2.5 +- 1.5 s, sections within
    2 % after 3 s. `transient`: the run starts from unstretched falls, so it has a
    transient whose settling and peaks can be judged (an equilibrium start has neither)."""
    steady, settle, spread = tension_settling(time, tension)
    w4, r4 = weight / 4, rigged_weight / 4
    peaks = np.asarray(tension, dtype=float).reshape(len(time), -1).max(axis=0)
    rows = [
        Verdict(f"F2 tension ~ W/4{label}", "steady cable tension about W/4 (5 %)",
                f"{steady:.0f} N = {steady / w4:.4f} W/4 (W/4 = {w4:.0f} N)",
                PASS if abs(steady / w4 - 1) <= 0.05 else FAIL),
        Verdict(f"F2 with rigging{label}", "(W + blocks + slings)/4 (2 %)",
                f"{steady / r4:.4f} x {r4:.0f} N",
                PASS if abs(steady / r4 - 1) <= 0.02 else FAIL)]
    if transient:
        rows += [
            Verdict(f"F2 settling{label}", "steady at about 2.5 s (2.5 +- 1.5 s into +-5 %)",
                    f"{settle:.2f} s", PASS if abs(settle - 2.5) <= 1.5 else FAIL),
            Verdict(f"F2 sections{label}",
                    "all sections agree, only the first peak differs (2 %)",
                    f"means within {100 * spread:.2f} %, peaks {peaks.min() / steady:.2f}-"
                    f"{peaks.max() / steady:.2f} x steady",
                    PASS if spread <= 0.02 else FAIL)]
    return rows


def swing_amplitude(time, position, period, t_start, t_end):
    """Horizontal swing amplitude [m]: sqrt(2) x RMS of the CG's horizontal position minus
    its centred moving average over one wave period, over [t_start + T/2, t_end - T/2].
    The moving average takes out the slow drift (the ship and the boat drift with the wind,
    which the paper's statement is not about) and keeps the oscillation; a sine of
    amplitude A at the wave period gives A."""
    time = np.asarray(time, dtype=float)
    xy = np.asarray(position, dtype=float).reshape(len(time), -1)[:, :2]
    dt = float(time[1] - time[0])
    n = max(int(round(period / dt)) // 2 * 2 + 1, 1)
    kernel = np.ones(n) / n
    residual = np.stack([xy[:, k] - np.convolve(xy[:, k], kernel, mode="same")
                         for k in range(xy.shape[1])], axis=1)
    keep = (time >= t_start + period / 2) & (time <= t_end - period / 2)
    if keep.sum() < n:
        raise ValueError(f"swing window [{t_start:.1f}, {t_end:.1f}] s shorter than two "
                         f"wave periods ({period:.2f} s)")
    return float(np.sqrt(2 * np.mean(np.sum(residual[keep] ** 2, axis=1))))


def fact_f9(amplitudes, tolerance=0.20, floor=0.05):
    """F9 (III.B, Figs. 15-18): wind hardly changes the swing amplitudes. `amplitudes`:
    {(level, angle): (with wind, without wind) [m]}; pass when every pair differs by less
    than `tolerance` of the no-wind amplitude (pairs both below `floor` count as equal)."""
    if not amplitudes:
        return Verdict("F9 wind", "wind hardly changes the swing amplitude (< 20 %)", "",
                       NO_INPUT)
    changes = {key: (0.0 if max(pair) < floor else pair[0] / pair[1] - 1)
               for key, pair in amplitudes.items()}
    worst = max(changes, key=lambda key: abs(changes[key]))
    details = [f"Level {lv}, chi = {ang:3d} deg: {w:.2f} m with wind, {nw:.2f} m without "
               f"({100 * changes[(lv, ang)]:+.1f} %)"
               for (lv, ang), (w, nw) in sorted(amplitudes.items())]
    ok = all(abs(c) < tolerance for c in changes.values())
    return Verdict("F9 wind", "wind hardly changes the swing amplitude (< 20 %)",
                   f"largest change {100 * changes[worst]:+.1f} % (Level {worst[0]}, "
                   f"{worst[1]} deg) over {len(changes)} pairs", PASS if ok else FAIL, details)


def fact_f9_ship(free, frozen):
    """F9, second half (III.B, V.2): the ship's motion dominates the swing above Level 4;
    review: with the ship frozen the Level 5 amplitude drops by more than 2x."""
    if free is None or frozen is None:
        return Verdict("F9 ship motion", "ship motion dominates at Level 5 (frozen: < 1/2)",
                       "", NO_INPUT)
    return Verdict("F9 ship motion", "ship motion dominates at Level 5 (frozen: < 1/2)",
                   f"{free:.2f} m free ship, {frozen:.2f} m frozen (ratio {frozen / free:.2f})",
                   PASS if frozen < 0.5 * free else FAIL)


def _near(values, target):
    return np.abs(np.asarray(values, dtype=float) - target) <= CLEARANCE_TOL


def _regular(cases):
    return np.isin(cases.wave_type, REGULAR_TYPES)


def _paper_setting(cases):
    """OK regular-wave cases at the paper's 0.5 B clearance, with wind if any case has it
    (the paper's colliding runs are its figures' with-wind runs)."""
    ok = (cases.status == layout.SUMMARY_STATUS_OK) & _regular(cases) & \
        _near(cases.clearance_b, 0.5)
    if np.any(ok & (cases.wind != 0)):
        ok &= cases.wind != 0
    return cases.where(ok)


def collision_counts(cases):
    """{(level, angle): (collided runs, runs)}."""
    counts = {}
    for level, angle, hit in zip(cases.level, np.rint(cases.angle_deg).astype(int),
                                 cases.collided):
        k, n = counts.get((int(level), int(angle)), (0, 0))
        counts[(int(level), int(angle))] = (k + int(hit != 0), n + 1)
    return counts


def fact_f7(cases, label):
    """F7 (III.B, Fig. 19): at 0.5 B, Level 4 collides only at 90 deg and Level 5 at 45, 90
    and 135 deg: the majority outcome (more than half the realisations) must match at
    every level and angle present, and 0 and 180 deg must never collide."""
    statement = "0.5 B: L4 collides only at 90; L5 at 45/90/135; never at 0/180"
    sel = _paper_setting(cases) if cases is not None else None
    if sel is None or not len(sel):
        return Verdict(f"F7 collisions ({label})", statement, "", NO_INPUT)
    counts = collision_counts(sel)
    wrong, parts = [], []
    for level in sorted({lv for lv, _ in counts}):
        hits = []
        for angle in sorted(a for lv, a in counts if lv == level):
            k, n = counts[(level, angle)]
            if k:
                hits.append(f"{angle} ({k}/{n})")
            expected = angle in EXPECTED_COLLISIONS.get(level, ())
            if angle in NEVER_COLLIDE:
                good = k == 0
            else:
                good = (k > n / 2) == expected
            if not good:
                wrong.append(f"Level {level}, {angle} deg: {k} of {n} collided, paper: "
                             f"{'collides' if expected else 'no collision'}")
        parts.append(f"L{level} at {', '.join(hits) if hits else 'none'}")
    return Verdict(f"F7 collisions ({label})", statement, "; ".join(parts),
                   FAIL if wrong else PASS, wrong)


def fact_f8(cases, label):
    """F8 (III.B, Fig. 19): the collision's horizontal acceleration is largest at 90 deg:
    Level 5, 0.5 B, median peak over the realisations at 90 deg above those at 45 and
    135 deg."""
    statement = "L5 collision acceleration largest at 90 deg"
    sel = _paper_setting(cases) if cases is not None else None
    if sel is not None:
        sel = sel.where(sel.level == 5)
    medians = {} if sel is None else {
        angle: float(np.median(sel.peak_horizontal_acceleration[
            np.rint(sel.angle_deg).astype(int) == angle]))
        for angle in (45, 90, 135) if np.any(np.rint(sel.angle_deg).astype(int) == angle)}
    if 90 not in medians or len(medians) < 2:
        return Verdict(f"F8 acceleration ({label})", statement, "", NO_INPUT)
    others = [medians[a] for a in medians if a != 90]
    value = ", ".join(f"{a}: {m:.1f}" for a, m in sorted(medians.items())) + " m/s^2"
    return Verdict(f"F8 acceleration ({label})", statement, value,
                   PASS if medians[90] > max(others) else FAIL)


def fact_f10(cases):
    """F10 (III.B, Figs. 20-23): regular-wave minimum distance slightly less than irregular
    at 90 deg, greater at 45 and 135 deg; compared by medians per (level, clearance,
    angle), sign only. Equal medians (both always colliding) are ties, not counted."""
    statement = "min distance: regular < irregular at 90; > at 45/135"
    if cases is None:
        return Verdict("F10 regular vs irregular", statement, "", NO_INPUT)
    ok = cases.where(cases.status == layout.SUMMARY_STATUS_OK)
    angles = np.rint(ok.angle_deg).astype(int)
    agree, disagree, ties, details = 0, 0, 0, []
    for level in sorted(set(ok.level.tolist())):
        for clearance in sorted(set(np.round(ok.clearance_b, 2).tolist())):
            for angle in (45, 90, 135):
                here = (ok.level == level) & _near(ok.clearance_b, clearance) & \
                    (angles == angle)
                reg = ok.min_clearance[here & _regular(ok)]
                irr = ok.min_clearance[here & (ok.wave_type == IRREGULAR_TYPE)]
                if not len(reg) or not len(irr):
                    continue
                diff = float(np.median(reg) - np.median(irr))
                want = -1 if angle == 90 else 1
                verdict = "tie" if diff == 0 else ("agrees" if np.sign(diff) == want
                                                   else "disagrees")
                agree += verdict == "agrees"
                disagree += verdict == "disagrees"
                ties += verdict == "tie"
                details.append(f"Level {level}, {clearance:g} B, {angle} deg: regular "
                               f"{np.median(reg):.2f} m, irregular {np.median(irr):.2f} m "
                               f"({verdict})")
    if agree + disagree + ties == 0:
        return Verdict("F10 regular vs irregular", statement, "", NO_INPUT)
    result = PASS if disagree == 0 and agree > 0 else FAIL
    return Verdict("F10 regular vs irregular", statement,
                   f"{agree} of {agree + disagree} groups agree ({ties} ties)", result,
                   details)


def fact_f11(cases, limit=0.01):
    """F11 (III.B, abstract, V.3): safe if the initial distance exceeds 1.5 B below Level 5:
    Level 4 at >= 1.5 B, regular and irregular, every angle: at most 1 % of the runs of any
    (wave kind, clearance, angle) group collide."""
    statement = "L4, clearance >= 1.5 B: no collisions (<= 1 % per group)"
    if cases is None:
        return Verdict("F11 safe distance", statement, "", NO_INPUT)
    sel = cases.where((cases.status == layout.SUMMARY_STATUS_OK) & (cases.level == 4) &
                      (cases.clearance_b >= 1.5 - CLEARANCE_TOL))
    if not len(sel):
        return Verdict("F11 safe distance", statement, "", NO_INPUT)
    groups = {}
    for kind, clearance, angle, hit in zip(np.where(_regular(sel), "regular", "irregular"),
                                           np.round(sel.clearance_b, 2),
                                           np.rint(sel.angle_deg).astype(int), sel.collided):
        k, n = groups.get((kind, clearance, angle), (0, 0))
        groups[(kind, clearance, angle)] = (k + int(hit != 0), n + 1)
    bad = [f"{kind}, {c:g} B, {a} deg: {k} of {n} collided"
           for (kind, c, a), (k, n) in sorted(groups.items()) if k > limit * n]
    total = sum(k for k, _ in groups.values())
    return Verdict("F11 safe distance", statement,
                   f"{total} collisions in {len(sel)} runs ({len(groups)} groups)",
                   FAIL if bad else PASS, bad)


# ------------------------------------------------------------------------------- gathering

def _period(run, level):
    period = run.deck("sea", "period")
    return float(period) if period is not None else PEAK_PERIOD[level]


def run_swing(run, level):
    """Swing amplitude of one paper run while in the air, after the 2-period wave ramp."""
    period = _period(run, level)
    ramp = run.deck("sea", "ramp_periods", 2.0) * period
    t_water = run.event(layout.WATERBORNE_TIME)
    t_end = float(run.time[-1]) if t_water is None else t_water
    return swing_amplitude(run.time, run.get(layout.BOAT_POSITION), period, ramp, t_end)


def run_case(item):
    """A paper run as one case: collided if a fender touched the ship before the boat was
    waterborne; minimum clearance and peak horizontal acceleration over that window: the
    largest of the samples' |(a_x, a_y)| and of the launch log's impact peaks |a| (resolved
    at every step; files without a log: the samples, which can miss a contact shorter than
    output_interval)."""
    run = layout.load(item.path)
    run.require(layout.BOAT + layout.CONTACT + (layout.FIRST_CONTACT_TIME,),
                "paper-run record")
    t_water = run.event(layout.WATERBORNE_TIME)
    t_contact = run.event(layout.FIRST_CONTACT_TIME)
    window = run.time <= (t_water if t_water is not None else np.inf)
    collided = t_contact is not None and (t_water is None or t_contact <= t_water)
    clearance = run.get(layout.CONTACT_CLEARANCE)
    a = run.get(layout.BOAT_ACCELERATION)[window]
    beam = run.deck("boat", "beam", 2.8)
    return Cases(level=[item.level], angle_deg=[item.angle],
                 clearance_b=[clearance[0] / beam],
                 wave_type=[IRREGULAR_TYPE if item.irregular else 2],
                 wind=[int(item.wind)], status=[1 if run.complete else 2],
                 collided=[int(collided)],
                 min_clearance=[min(clearance[window].min(), 0.0) if collided
                                else clearance[window].min()],
                 peak_horizontal_acceleration=[max(np.hypot(a[:, 0], a[:, 1]).max(),
                                                   _impact_peak(run, t_water))])


def _impact_peak(run, t_water):
    """Largest step-resolved CG acceleration of the impacts before t_water (0: none)."""
    t_hit, a_hit = run.get(layout.IMPACT_TIME), run.get(layout.IMPACT_PEAK_ACCELERATION)
    if t_hit is None or len(t_hit) == 0:
        return 0.0
    keep = t_hit <= (t_water if t_water is not None else np.inf)
    return float(a_hit[keep].max()) if np.any(keep) else 0.0


def gather_runs(folder):
    """Cases from the paper decks' single runs (one wave phase each) in `folder`."""
    return Cases.concat([run_case(item) for item in paper.collect_runs(folder)])


def gather_sweeps(folder):
    """Cases of every davit sweep summary in `folder`, concatenated."""
    parts = []
    for path in _h5_files(folder):
        if layout.file_kind(path) == "sweep":
            parts.append(Cases(**layout.load_summary_fields(path)))
    return Cases.concat(parts)


def gather_f2(folder):
    """F2 rows from each of the F2_STEMS runs present (weights from their decks); "no input"
    if none is, or one ends before the [3, 8] s window does."""
    rows = []
    for stem, label in F2_STEMS.items():
        path = os.path.join(folder, stem + ".h5")
        if os.path.exists(path):
            rows += _f2_rows(path, stem, label)
    return rows or [Verdict("F2 tension ~ W/4", "steady cable tension about W/4 (5 %)",
                            f"none of {', '.join(s + '.h5' for s in F2_STEMS)}", NO_INPUT)]


def _f2_rows(path, stem, label):
    run = layout.load(path)
    run.require([layout.RIGGING_SEGMENT_TENSION], "cable segment tensions")
    if run.time[-1] < 8.0:
        return [Verdict(f"F2 tension ~ W/4{label}", "steady cable tension about W/4 (5 %)",
                        f"{stem}.h5 ends at {run.time[-1]:.2f} s, before 8 s", NO_INPUT)]
    g = layout.GRAVITY
    mass = run.deck("boat", "mass", 8500.0)
    rigging = (2 * run.deck("rigging", "block_mass", 50.0) +
               2 * run.deck("rigging", "sling_length", 1.0) *
               run.deck("rigging", "sling_mass_per_length", 1.6))
    return fact_f2(run.time, run.get(layout.RIGGING_SEGMENT_TENSION), mass * g,
                   (mass + rigging) * g, label,
                   transient=run.deck("rigging", "initial", "equilibrium") == "unstretched")


def _swing_or_none(path, level, skipped):
    """The in-air swing amplitude of a complete run long enough to measure it, else None
    (with the reason appended to `skipped`)."""
    run = layout.load(path)
    run.require([layout.BOAT_POSITION], "boat trajectory")
    if not run.complete:
        skipped.append(f"{os.path.basename(path)}: incomplete run")
        return None
    try:
        return run_swing(run, level)
    except ValueError as exc:
        skipped.append(f"{os.path.basename(path)}: {exc}")
        return None


def gather_f9(folder):
    """F9 rows: wind/no-wind pairs of the regular paper runs, and the frozen-ship run."""
    runs = {(r.level, r.angle, r.wind): r for r in paper.collect_runs(folder)
            if not r.irregular}
    amplitudes, skipped = {}, []
    for (level, angle, wind), item in sorted(runs.items()):
        other = runs.get((level, angle, False))
        if wind and other:
            pair = (_swing_or_none(item.path, level, skipped),
                    _swing_or_none(other.path, level, skipped))
            if None not in pair:
                amplitudes[(level, angle)] = pair
    swing = {}
    for stem in (FREE_STEM, FROZEN_STEM):
        path = os.path.join(folder, stem + ".h5")
        swing[stem] = _swing_or_none(path, 5, skipped) if os.path.exists(path) else None
    wind = fact_f9(amplitudes)
    wind.details += [f"skipped {s}" for s in skipped]
    return [wind, fact_f9_ship(swing[FREE_STEM], swing[FROZEN_STEM])]


def _h5_files(folder):
    if not os.path.isdir(folder):
        return []
    return [os.path.join(folder, n) for n in sorted(os.listdir(folder)) if n.endswith(".h5")]


def report(folder):
    """Every fact's verdict on the outputs in `folder`."""
    runs = gather_runs(folder)
    sweeps = gather_sweeps(folder)
    return (gather_f2(folder)
            + [fact_f7(runs, "paper decks"), fact_f7(sweeps, "sweeps"),
               fact_f8(runs, "paper decks"), fact_f8(sweeps, "sweeps")]
            + gather_f9(folder)
            + [fact_f10(sweeps), fact_f11(sweeps)])


def format_table(verdicts):
    """A Markdown table (fact, paper, davit, result), then the details of each row."""
    lines = ["| fact | paper | davit | result |", "|---|---|---|---|"]
    lines += [f"| {v.fact} | {v.paper} | {v.davit or '-'} | {v.result} |" for v in verdicts]
    for v in verdicts:
        if v.details:
            lines.append("")
            lines.append(f"{v.fact}:")
            lines += [f"  {d}" for d in v.details]
    counts = {r: sum(v.result == r for v in verdicts) for r in (PASS, FAIL, NO_INPUT)}
    lines.append("")
    lines.append(f"regress: {counts[PASS]} pass, {counts[FAIL]} FAIL, "
                 f"{counts[NO_INPUT]} no input")
    return "\n".join(lines)
