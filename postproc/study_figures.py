"""Charts of the speed-versus-accuracy studies written by `python -m postproc.study`:
work-precision (error against single-thread wall time) and the stability map (largest
stable step against the stiffness variant, with the analytic RK4 limit 2.83/|lambda|max)
and the spurious damping of the bounce (measured against the stability functions).
Each function takes a study file and returns the PNG path, or None for another kind."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import layout  # noqa: E402
from .figures import _save  # noqa: E402
from .stability import stability_function  # noqa: E402

COLOURS = {"rk4": "tab:blue", "dopri5": "tab:orange", "rosenbrock": "tab:green",
           "rosw": "tab:red"}


def _png_name(path):
    """<study file stem>.png"""
    return os.path.splitext(os.path.basename(path))[0] + ".png"


PRECISION_PANELS = (("err_smooth", "max boat CG error before first contact [m]"),
                    ("err_falls", "max boat CG error on the falls (to hook release) [m]"),
                    ("sling_err", "relative error of the resolved peak sling tension [-]"),
                    ("segment_err", "relative error of the resolved peak segment tension [-]"))


def work_precision(path, outdir):
    """Errors against wall time, per run: the CG before and after the first contact and
    the resolved peak sling and segment tensions (older study files: the smooth-phase CG
    and the sampled peak tension)."""
    d = layout.load_study(path, "work_precision")
    if d is None:
        return None
    panels = [p for p in PRECISION_PANELS if p[0] in d] or [
        ("err_smooth", "max boat CG position error before first contact [m]"),
        ("tension_err", "relative error of peak cable segment tension [-]")]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 5))
    for i, label in enumerate(d["label"]):
        if not d["ok"][i]:
            continue
        integ = label.split()[0]
        lod = any(k in label for k in ("lumps", "sheaves", "strips", "frozen", "wave_update",
                                       "n_frequencies", "blocks"))
        style = dict(color=COLOURS.get(integ, "k"), marker="s" if lod else "o",
                     markerfacecolor="none" if lod else COLOURS.get(integ, "k"))
        for ax, (key, _) in zip(axes, panels):
            y = max(d[key][i], 1e-13)
            ax.loglog(d["wall"][i], y, linestyle="none", **style)
            ax.annotate(" ".join(label.split()[1:]) or label, (d["wall"][i], y), fontsize=6,
                        xytext=(3, 2), textcoords="offset points")
    for ax, (_, ylabel) in zip(axes, panels):
        ax.set_ylabel(ylabel)
        ax.set_xlabel("wall time, one thread [s]")
        ax.grid(True, which="both", alpha=0.3)
    handles = [plt.Line2D([], [], color=c, marker="o", linestyle="none", label=n)
               for n, c in COLOURS.items()]
    handles.append(plt.Line2D([], [], color="k", marker="s", markerfacecolor="none",
                              linestyle="none", label="level-of-detail switch"))
    axes[0].legend(handles=handles, fontsize=8)
    a = d["attrs"]
    span = f"{a['t_end']:.0f} s" if a["t_end"] > 0 else "whole launch"
    fig.suptitle(f"Work-precision on {os.path.basename(a['base'])}, {span}; "
                 f"reference: {a['reference']}")
    fig.tight_layout()
    return _save(fig, outdir, _png_name(path), dpi=120)


def stability(path, outdir):
    """Largest stable RK4 step vs the analytic limit, and the adaptive methods' steps."""
    d = layout.load_study(path, "stability")
    if d is None:
        return None
    x = np.arange(len(d["label"]))
    fig, ax = plt.subplots(figsize=(10, 5))
    ax.semilogy(x, d["rk4_limit"], "k--", label="RK4 limit 2.83/|lambda|max (linearised)")
    ax.semilogy(x, d["rk4_stable"], "o", color=COLOURS["rk4"],
                label="RK4: largest step that runs")
    ax.semilogy(x, d["dopri5_step"], "^", color=COLOURS["dopri5"],
                label="dopri5: mean accepted step (settles at its stability boundary)")
    ax.semilogy(x, d["rosenbrock_step"], "v", color=COLOURS["rosenbrock"],
                label="RODAS3: mean step (set by accuracy)")
    ax.set_xticks(x)
    ax.set_xticklabels([" ".join(s.split()[1:]) for s in d["label"]], rotation=20,
                       fontsize=8)
    ax.set_ylabel("time step [s]")
    ax.set_xlabel("stiffness variant (lumps per sling, sheaves)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"Stability map on {os.path.basename(d['attrs']['base'])}, "
                 f"{d['attrs']['t_end']:.1f} s runs")
    fig.tight_layout()
    return _save(fig, outdir, _png_name(path), dpi=120)


def damping(path, outdir):
    """Apparent damping ratio of the bounce against omega h: measured (markers) and from
    each method's stability function (lines), with the physical value."""
    d = layout.load_study(path, "damping")
    if d is None:
        return None
    zeta = float(d["zeta_physical"][0])
    lam = complex(-zeta, np.sqrt(1 - zeta**2))
    wh = np.geomspace(0.03, 10, 400)
    fig, ax = plt.subplots(figsize=(8, 5))
    for method, name in (("rk4", "RK4"), ("rosenbrock", "RODAS3, fixed step")):
        r = np.abs(stability_function(method, wh * lam))
        with np.errstate(divide="ignore", invalid="ignore"):
            pred = np.where(r <= 1, -np.log(r) / wh, np.nan)
        ax.loglog(wh, pred, "-", color=COLOURS[method], label=f"{name}: -ln|R(h lambda)|/(omega h)")
        pick = [i for i, s in enumerate(d["label"]) if s.split()[0] == method]
        ax.loglog(d["omega_h"][pick], d["zeta_measured"][pick], "o", color=COLOURS[method],
                  label=f"{name}: measured")
    ax.axhline(zeta, color="k", ls=":", label=f"physical zeta = {zeta:.4f} (slings)")
    ax.axvline(2.83, color="tab:blue", ls="--", lw=0.8, label="RK4 limit omega h = 2.83")
    ax.set_xlabel("omega h (bounce 70 rad/s times the step)")
    ax.set_ylabel("apparent damping ratio of the bounce")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"Spurious damping of the bounce on {os.path.basename(d['attrs']['base'])}")
    fig.tight_layout()
    return _save(fig, outdir, _png_name(path), dpi=120)


STUDY_FIGURES = {"work_precision": work_precision, "stability": stability,
                 "damping": damping}
