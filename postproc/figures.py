"""Figures of a single run."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import layout  # noqa: E402


def _save(fig, outdir, name):
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def trajectory(run, outdir, stem):
    """Boat CG trajectory in the paper's planes ox1z1 and oy1z1 (z1 up), and against time."""
    p = layout.to_plot_frame(run.get(layout.BOAT_POSITION))
    t = run.time
    fig, ax = plt.subplots(2, 2, figsize=(10, 8))
    ax[0, 0].plot(p[:, 0], p[:, 2], lw=0.8)
    ax[0, 0].set(xlabel="x1 [m]", ylabel="z1 [m] (up)", title="ox1z1 plane")
    ax[0, 1].plot(p[:, 1], p[:, 2], lw=0.8)
    ax[0, 1].set(xlabel="y1 [m] (= -y, port positive)", ylabel="z1 [m] (up)",
                 title="oy1z1 plane")
    for k, label in enumerate(("x1", "y1", "z1")):
        ax[1, 0].plot(t, p[:, k] - p[0, k], label=f"{label} - {label}(0)")
    ax[1, 0].set(xlabel="t [s]", ylabel="displacement [m]", title="CG displacement")
    ax[1, 0].legend()
    euler = np.degrees(run.get(layout.BOAT_EULER))
    for k, label in enumerate(("roll", "pitch", "yaw")):
        ax[1, 1].plot(t, euler[:, k], label=label)
    ax[1, 1].set(xlabel="t [s]", ylabel="angle [deg]", title="attitude (ZYX, z down)")
    ax[1, 1].legend()
    for a in ax.flat:
        a.grid(True, alpha=0.3)
    status = "" if run.complete else "  [INCOMPLETE RUN]"
    fig.suptitle(f"Lifeboat trajectory: {os.path.basename(run.path)}{status}")
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_trajectory.png")


def sling_tension(run, outdir, stem):
    """Sling tensions against time, with the static share W/2 for reference."""
    tension = run.get(layout.SLING_TENSION)
    if tension is None:
        return None
    t = run.time
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for k, label in enumerate(("fore", "aft")[: tension.shape[1]]):
        ax.plot(t, tension[:, k] / 1e3, lw=0.8, label=label)
    ax.set(xlabel="t [s]", ylabel="tension [kN]", title="Sling tension")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_sling_tension.png")


def acceleration(run, outdir, stem):
    """Horizontal and vertical CG acceleration (inertial frame, gravity not subtracted)."""
    a = run.get(layout.BOAT_ACCELERATION)
    t = run.time
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.plot(t, np.hypot(a[:, 0], a[:, 1]), lw=0.8, label="horizontal |a_xy|")
    ax.plot(t, -a[:, 2], lw=0.8, label="vertical a_z1 (up)")
    ax.set(xlabel="t [s]", ylabel="acceleration [m/s^2]", title="Boat acceleration")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_acceleration.png")


RUN_FIGURES = {"trajectory": trajectory, "tension": sling_tension,
               "acceleration": acceleration}
