"""Figures of `davit sweep` summaries in the style of the paper's Figs. 19-23.

fig19: horizontal acceleration of the colliding launches, one panel per sea-state level:
time histories if the sweep wrote per-case series (`--series DIR`), otherwise the peak of
every launch (dots) and the median per encounter angle (bars), with the number of
colliding launches. min_distance (Figs. 20-23): the minimum fender-to-ship-side distance
of every launch by encounter angle, one row per level and one column per initial
clearance; below zero is a collision.
"""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import layout  # noqa: E402
from .figures import _save  # noqa: E402


def _finished(summary):
    ok = summary.ok
    if not ok.any():
        raise ValueError(f"{summary.path}: no finished case (status 1) to plot")
    return ok


def _wave_label(summary, rows):
    names = sorted({layout.SWEEP_WAVE_TYPES.get(int(c), str(c))
                    for c in summary.wave_type[rows]})
    return ", ".join(names)


def _histories(summary, rows):
    """(level, angle, t, |a_h|) of the colliding launches that have a series file."""
    curves = []
    for i in np.flatnonzero(rows & (summary.collided == 1)):
        path = summary.series_file(summary.index[i])
        if path is None:
            continue
        run = layout.load(path)
        a = run.get(layout.BOAT_ACCELERATION)
        curves.append((summary.level[i], summary.angle_deg[i], run.time,
                       np.hypot(a[:, 0], a[:, 1])))
    return curves


def fig19(summary, outdir, stem):
    """Horizontal acceleration of the colliding launches (Fig. 19)."""
    ok = _finished(summary)
    levels = np.unique(summary.level[ok])
    angles = np.unique(summary.angle_deg[ok])
    curves = _histories(summary, ok)
    fig, axes = plt.subplots(1, levels.size, figsize=(6 * levels.size, 4.5), squeeze=False)
    colours = {a: plt.cm.viridis(k / max(1, angles.size - 1)) for k, a in enumerate(angles)}
    for ax, level in zip(axes[0], levels):
        rows = ok & (summary.level == level)
        if curves:
            seen = set()
            for lev, angle, t, a in curves:
                if lev != level:
                    continue
                label = None if angle in seen else f"{angle:g} deg"
                seen.add(angle)
                ax.plot(t, a, lw=0.7, color=colours[angle], label=label)
            ax.set(xlabel="t [s]", ylabel="horizontal acceleration [m/s^2]")
            if seen:
                ax.legend(title="encounter angle")
        else:
            _peak_bars(ax, summary, rows, angles)
        ax.set_title(f"Level {level}: {int(summary.collided[rows].sum())} of "
                     f"{int(rows.sum())} launches collide")
        ax.grid(True, alpha=0.3)
    kind = "time histories (output samples)" if curves else "peak per launch, median bars"
    fig.suptitle(f"Horizontal boat acceleration, {_wave_label(summary, ok)} waves: {kind}")
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_fig19.png")


def _peak_bars(ax, summary, rows, angles):
    """Peak horizontal acceleration of every launch (red: collided) and the medians."""
    for k, angle in enumerate(angles):
        sel = rows & (summary.angle_deg == angle)
        peaks = summary.peak_horizontal_acceleration[sel]
        hit = summary.collided[sel] == 1
        ax.bar(k, np.median(peaks), width=0.6, color="0.85", edgecolor="0.5")
        x = k + np.linspace(-0.2, 0.2, peaks.size) if peaks.size > 1 else np.full(1, k)
        ax.plot(x[~hit], peaks[~hit], "o", ms=3, color="tab:blue")
        ax.plot(x[hit], peaks[hit], "o", ms=4, color="tab:red")
        ax.annotate(f"{int(hit.sum())}/{peaks.size}", (k, peaks.max()),
                    textcoords="offset points", xytext=(0, 4), ha="center", fontsize=8)
    ax.set_xticks(range(angles.size), [f"{a:g}" for a in angles])
    ax.set(xlabel="encounter angle [deg]", ylabel="peak horizontal acceleration [m/s^2]")
    ax.set_yscale("symlog", linthresh=1.0)
    top = np.nanmax(summary.peak_horizontal_acceleration[rows])
    ax.set_ylim(0.0, 3.0 * top if top > 1.0 else 2.0)


def min_distance(summary, outdir, stem):
    """Minimum fender-to-ship-side distance of every launch (Figs. 20-23)."""
    ok = _finished(summary)
    levels = np.unique(summary.level[ok])
    clearances = np.unique(summary.clearance_b[ok])
    angles = np.unique(summary.angle_deg[ok])
    fig, axes = plt.subplots(levels.size, clearances.size, figsize=(
        max(6.0, 4.2 * clearances.size), 3.6 * levels.size), squeeze=False, sharey="row")
    for r, level in enumerate(levels):
        for c, clearance in enumerate(clearances):
            ax = axes[r, c]
            rows = ok & (summary.level == level) & (summary.clearance_b == clearance)
            for k, angle in enumerate(angles):
                sel = rows & (summary.angle_deg == angle)
                d = summary.min_clearance[sel]
                x = k + np.linspace(-0.3, 0.3, d.size) if d.size > 1 else np.full(d.size, k)
                ax.plot(x[d >= 0], d[d >= 0], ".", ms=3, color="tab:blue")
                ax.plot(x[d < 0], d[d < 0], "x", ms=4, color="tab:red")
            ax.axhline(0.0, color="k", lw=0.8)
            ax.set_xticks(range(angles.size), [f"{a:g}" for a in angles])
            ax.set(xlabel="encounter angle [deg]", ylabel="minimum distance [m]")
            ax.set_title(f"Level {level}, initial {clearance:g} B: "
                         f"{int(summary.collided[rows].sum())}/{int(rows.sum())} collide",
                         fontsize=9)
            ax.grid(True, alpha=0.3)
    fig.suptitle(f"Shortest distance between lifeboat and ship side\n"
                 f"({_wave_label(summary, ok)} waves)")
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_min_distance.png")


SWEEP_FIGURES = {"fig19": fig19, "min_distance": min_distance}
