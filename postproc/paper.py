"""Multi-run figures of the paper's Section III.B (Figs. 15-19) from the runs of its decks.

The paper decks are named input/iiib_level{4,5}_{000,045,090,135,180}[_irregular][_nowind].nml
and `bash make.sh paper` writes each to out/<deck name>.h5: the level, the encounter angle,
the wave kind and the wind are read from that name, so a folder of outputs is all these
figures need. Plots are in the paper's frame oxy1z1 (N turned 180 deg about x: y1 = -y,
z1 = -z, z1 up).
"""
import os
import re
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import layout  # noqa: E402
from .figures import _save  # noqa: E402

RUN_NAME = re.compile(r"^iiib_level([45])_(\d{3})(_irregular)?(_nowind)?\.h5$")
ANGLES = (0, 45, 90, 135, 180)
# Sea-state levels of the paper (III.B, review F6/G19): wave height [m], wind speed [m/s]
LEVELS = {4: (2.5, 8.0), 5: (4.0, 10.0)}
# Paper figure numbers of the regular-wave trajectory plots: (level, wind) -> figure
TRAJECTORY_FIGURES = {(4, False): 15, (4, True): 16, (5, False): 17, (5, True): 18}
ANGLE_COLOURS = dict(zip(ANGLES, ("tab:blue", "tab:orange", "tab:red", "tab:green",
                                  "tab:purple")))


@dataclass(frozen=True)
class PaperRun:
    """One output of a paper deck, identified by its file name."""
    path: str
    level: int
    angle: int
    irregular: bool
    wind: bool


def collect_runs(folder):
    """Every paper-deck output in `folder`, sorted by level, wave kind, wind and angle."""
    runs = []
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
        match = RUN_NAME.match(name)
        if match:
            runs.append(PaperRun(path=os.path.join(folder, name), level=int(match.group(1)),
                                 angle=int(match.group(2)), irregular=bool(match.group(3)),
                                 wind=not match.group(4)))
    return sorted(runs, key=lambda r: (r.level, r.irregular, r.wind, r.angle))


def _groups(runs):
    """{(level, irregular, wind): [runs]}: one multi-run figure per group."""
    groups = {}
    for run in runs:
        groups.setdefault((run.level, run.irregular, run.wind), []).append(run)
    return groups


def _condition(level, irregular, wind):
    """Words for a sea state: the paper's level, its wave and wind (III.B)."""
    height, speed = LEVELS[level]
    waves = (f"irregular, H = {height:g} m" if irregular
             else f"regular Stokes-2, H = {height:g} m")
    air = f"wind {speed:g} m/s along the waves" if wind else "no wind"
    return f"Level {level} ({waves}), {air}"


def _trajectory_stem(level, irregular, wind):
    """fig15_level4_nowind_trajectories, ..., level5_irregular_wind_trajectories."""
    number = None if irregular else TRAJECTORY_FIGURES.get((level, wind))
    head = f"fig{number}_" if number else ""
    return (f"{head}level{level}{'_irregular' if irregular else ''}"
            f"_{'wind' if wind else 'nowind'}_trajectories")


def _end_index(run):
    """Samples up to the waterborne event (the lowering proper), or all."""
    t_water = run.event(layout.WATERBORNE_TIME)
    return len(run.time) if t_water is None else int(np.searchsorted(run.time, t_water)) + 1


def trajectory_figure(group, outdir):
    """Figs. 15-18: boat CG trajectories of one sea state and wind setting, the encounter
    angles overlaid, in the planes ox1z1 and oy1z1; a dot marks the waterborne event and a
    cross the first fender contact."""
    first = group[0]
    fig, (axz, ayz) = plt.subplots(1, 2, figsize=(12, 5.5))
    for item in group:
        run = layout.load(item.path)
        run.require(layout.BOAT, "boat trajectory")
        p = layout.to_plot_frame(run.get(layout.BOAT_POSITION))
        colour = ANGLE_COLOURS.get(item.angle)
        label = f"chi = {item.angle} deg" + ("" if run.complete else " (incomplete)")
        for ax, k in ((axz, 0), (ayz, 1)):
            ax.plot(p[:, k], p[:, 2], lw=0.8, color=colour, label=label)
            n = _end_index(run)
            if n < len(run.time):
                ax.plot(p[n - 1, k], p[n - 1, 2], "o", ms=4, color=colour)
            t_contact = run.event(layout.FIRST_CONTACT_TIME)
            if t_contact is not None:
                i = min(int(np.searchsorted(run.time, t_contact)), len(run.time) - 1)
                ax.plot(p[i, k], p[i, 2], "x", ms=7, mew=1.5, color=colour)
    axz.set(xlabel="x1 [m] (= x, along the ship)", ylabel="z1 [m] (up, still water 0)",
            title="(a) ox1z1 plane")
    ayz.set(xlabel="y1 [m] (= -y; the ship is on the y1 > y1(0) side)",
            ylabel="z1 [m] (up, still water 0)", title="(b) oy1z1 plane")
    for ax in (axz, ayz):
        ax.grid(True, alpha=0.3)
        ax.axhline(0.0, color="k", lw=0.5)
    ayz.legend(fontsize=8, title="encounter angle (o waterborne, x first contact)",
               title_fontsize=8)
    number = None if first.irregular else TRAJECTORY_FIGURES.get((first.level, first.wind))
    head = f"Fig. {number}: " if number else ""
    fig.suptitle(f"{head}lifeboat CG trajectories, "
                 f"{_condition(first.level, first.irregular, first.wind)}; frame oxy1z1")
    fig.tight_layout()
    return _save(fig, outdir,
                 _trajectory_stem(first.level, first.irregular, first.wind) + ".png")


def collision_figure(group, outdir):
    """Fig. 19: horizontal CG acceleration against time of the runs of one sea-state group
    whose fenders hit the ship's side before the boat was waterborne; None if none did.
    The curves are the samples (every output_interval); each impact's peak CG acceleration,
    resolved at every step by the launch log, is marked on them (a contact shorter than the
    interval, ~6 ms with the paper's Hertz law, falls between samples)."""
    fig, ax = plt.subplots(figsize=(10, 4.8))
    drawn = 0
    for item in group:
        run = layout.load(item.path)
        run.require([layout.BOAT_ACCELERATION], "boat acceleration")
        t_contact = run.event(layout.FIRST_CONTACT_TIME)
        t_water = run.event(layout.WATERBORNE_TIME)
        if t_contact is None or (t_water is not None and t_contact > t_water):
            continue
        a = run.get(layout.BOAT_ACCELERATION)
        n = _end_index(run)
        ax.plot(run.time[:n], np.hypot(a[:n, 0], a[:n, 1]), lw=0.8,
                color=ANGLE_COLOURS.get(item.angle), ls="--" if item.level == 4 else "-",
                label=f"Level {item.level}, chi = {item.angle} deg "
                      f"(first contact {t_contact:.1f} s)")
        t_hit, a_hit = run.get(layout.IMPACT_TIME), run.get(layout.IMPACT_PEAK_ACCELERATION)
        if t_hit is not None and len(t_hit):
            keep = t_hit <= run.time[n - 1]
            ax.plot(t_hit[keep], a_hit[keep], "v", ms=5, color=ANGLE_COLOURS.get(item.angle))
        drawn += 1
    if not drawn:
        plt.close(fig)
        return None
    first = group[0]
    dt = float(run.time[1] - run.time[0])
    waves = "irregular waves" if first.irregular else "regular Stokes-2 waves"
    air = "wind along the waves" if first.wind else "no wind"
    ax.set(xlabel="t [s]", ylabel="horizontal acceleration |(a_x1, a_y1)| [m/s^2]",
           title=f"Fig. 19: colliding runs at 0.5 B clearance, {waves}, {air}\n"
                 f"(inertial frame, sampled every {dt:g} s, until waterborne; "
                 f"triangles: each impact's peak over every step)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, outdir, f"fig19_collisions_{'irregular' if first.irregular else 'regular'}"
                              f"_{'wind' if first.wind else 'nowind'}.png")


def trajectories(folder, outdir):
    """Figs. 15-18 (and the same for irregular runs) for every group found in `folder`."""
    return [trajectory_figure(group, outdir) for group in _groups(collect_runs(folder)).values()]


def collisions(folder, outdir):
    """Fig. 19 for every group of `folder` that has a colliding run (Level 4 and 5 together
    per wave kind and wind setting, as the paper draws its four colliding runs in one)."""
    merged = {}
    for run in collect_runs(folder):
        merged.setdefault((run.irregular, run.wind), []).append(run)
    return [collision_figure(group, outdir) for group in merged.values()]


FOLDER_FIGURES = {"trajectories": trajectories, "collisions": collisions}
