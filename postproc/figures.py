"""Figures of a single run."""
import os
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import layout  # noqa: E402


def _save(fig, outdir, name, dpi=110):
    """Write `fig` to outdir/name (the folder made if missing) at `dpi`, close it and
    return the path. The one figure writer of postproc (study charts use dpi=120). Titles
    wider than the figure are wrapped first (_fit_titles)."""
    os.makedirs(outdir, exist_ok=True)
    path = os.path.join(outdir, name)
    _fit_titles(fig)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def _titles(fig):
    """The figure's title and every axes' titles that hold text."""
    texts = [fig._suptitle] + [t for ax in fig.axes if ax.get_visible()
                               for t in (ax.title, ax._left_title, ax._right_title)]
    return [t for t in texts if t is not None and t.get_text()]


def _fit_titles(fig, margin=4.0):
    """Wrap every title that reaches past the figure's edges (a long outcome, a one-panel
    figure's suptitle) so that it fits, `margin` pixels inside; then lay the figure out
    again (titles grew taller). Centred titles are wrapped to twice the room on their
    narrower side."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    width = fig.bbox.width
    wrapped = False
    for text in _titles(fig):
        for _ in range(4):
            box = text.get_window_extent(renderer)
            if box.x0 >= margin and box.x1 <= width - margin:
                break
            centre = 0.5 * (box.x0 + box.x1)
            room = 2 * min(centre - margin, width - margin - centre)
            lines = text.get_text().split("\n")
            longest = max(len(line) for line in lines)
            chars = max(16, int(longest * room / box.width * 0.95))
            text.set_text("\n".join(textwrap.fill(line, chars) for line in lines))
            wrapped = True
    if wrapped and fig.get_layout_engine() is None:
        fig.tight_layout()


def trajectory(run, outdir, stem):
    """Boat CG trajectory in the paper's planes ox1z1 and oy1z1 (z1 up), and against time."""
    run.require(layout.BOAT, "boat trajectory")
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
    fig.suptitle(f"Lifeboat CG trajectory, frame oxy1z1 (z1 up, still water 0): "
                 f"{os.path.basename(run.path)}{status}")
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
    title = "Sling tension"
    peak, when = run.get(layout.PEAK_SLING_TENSION), run.get(layout.PEAK_SLING_TENSION_TIME)
    if peak is not None and len(peak):
        ax.plot(when, peak / 1e3, "v", color="crimson", label="peak over every step")
        _mark_limits(ax, run, float(np.max(peak)) / 1e3)
        title += f": resolved peak {np.max(peak) / 1e3:.1f} kN"
    ax.set(xlabel="t [s]", ylabel="tension [kN]", title=title + _title_outcome(run))
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_sling_tension.png")


def _title_outcome(run):
    """The run's outcome (launches), for a figure's title."""
    text = run.attrs.get(layout.OUTCOME, "")
    return f"\n{text}" if text else ""


def _mark_impacts(ax, run, values, label, fmt="{:.0f}"):
    """Mark each impact event (resolved at every step) at its onset with `values`."""
    t = run.get(layout.IMPACT_TIME)
    if t is None or len(t) == 0:
        return
    ax.plot(t, values, "v", color="crimson", ms=5, label=label)
    k = int(np.argmax(values))
    ax.annotate(fmt.format(values[k]), (t[k], values[k]), textcoords="offset points",
                xytext=(4, 4), fontsize=8, color="crimson")


def acceleration(run, outdir, stem):
    """Horizontal and vertical CG acceleration at the output samples (inertial frame,
    gravity not subtracted), the seat's filtered acceleration, and the peaks resolved at
    every step: each impact's CG peak and the largest step-mean CG acceleration, which
    the samples miss."""
    run.require([layout.BOAT_ACCELERATION], "boat acceleration")
    a = run.get(layout.BOAT_ACCELERATION)
    t = run.time
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.plot(t, np.hypot(a[:, 0], a[:, 1]), lw=0.8, label="CG horizontal |a_xy| (sampled)")
    ax.plot(t, -a[:, 2], lw=0.8, label="CG vertical a_z1 (up, sampled)")
    seat = run.get(layout.SEAT_ACCELERATION)
    if seat is not None and len(seat):
        hz = float(np.ravel(run.group_attrs[layout.SEAT_GROUP]["filter_hz"])[0])
        ax.plot(run.seat_time(), np.linalg.norm(seat, axis=1), lw=0.8,
                label=f"seat |a|, {hz:g} Hz phaseless Butterworth")
    _mark_impacts(ax, run, run.get(layout.IMPACT_PEAK_ACCELERATION),
                  "impact: CG peak (every step)", fmt="{:.3g}")
    peak = run.get(layout.PEAK_CG_ACCELERATION)
    title = "Boat acceleration"
    if peak is not None:
        sampled = float(np.max(np.linalg.norm(a, axis=1))) if len(a) else 0.0
        # three significant digits: a calm launch's 1.44 m/s^2 is not "1"
        title += (f": resolved CG peak {peak[0]:.3g} m/s^2 at {peak[1]:.2f} s "
                  f"(samples show {sampled:.3g})")
    ax.set(xlabel="t [s]", ylabel="acceleration [m/s^2]", title=title + _title_outcome(run))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_acceleration.png")


def _mark_limits(ax, run, peak_kn):
    """The wire's safe working load, and its breaking load where a peak comes near it."""
    swl, mbl = run.limit("safe_working_load"), run.limit("minimum_breaking_load")
    if swl is not None:
        ax.axhline(swl / 1e3, color="darkorange", ls="--", lw=0.8,
                   label=f"SWL = MBL/6 = {swl / 1e3:.1f} kN")
    if mbl is not None and peak_kn > 0.5 * mbl / 1e3:
        ax.axhline(mbl / 1e3, color="red", ls="--", lw=0.8, label=f"MBL = {mbl / 1e3:.0f} kN")


def _sea_height(run):
    """H of the recorded sea: the deck's &sea height, else its level's preset (G19)."""
    height = run.deck("sea", "height")
    return height if height is not None else {4: 2.5, 5: 4.0}[int(run.deck("sea", "level", 5))]


def surface(run, outdir, stem, size=200.0, n=161):
    """Paper Fig. 6: the sea surface over a size x size patch at the last recorded time,
    rebuilt from the component table, drawn in the paper's frame oxy1z1 (y1 = -y, z1 up)."""
    run.require(layout.SEA, "sea")
    t = float(run.time[-1])
    x = np.linspace(-size / 2, size / 2, n)
    xx, yy = np.meshgrid(x, x, indexing="ij")
    eta = np.empty_like(xx)
    for i in range(n):  # row by row keeps memory at n * components
        eta[i] = layout.sea_elevation(run, t, xx[i], yy[i])
    fig = plt.figure(figsize=(9, 7))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(xx, -yy, eta, cmap="viridis", linewidth=0, antialiased=True)
    ax.set(xlabel="x1 [m] (= x)", ylabel="y1 [m] (= -y)", zlabel="z1 = eta [m] (up)")
    ax.set_zlim(-3 * np.std(eta) * 2, 3 * np.std(eta) * 2)
    ax.set_title(f"Fig. 6: sea surface at t = {t:.1f} s, frame oxy1z1\n"
                 f"({os.path.basename(run.path)}; {len(run.get(layout.SEA_OMEGA))} components)")
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_surface.png")


def welch(x, dt, nseg):
    """One-sided spectral density of x (per rad/s) by Welch's method with Hann windows and
    50 % overlap."""
    x = np.asarray(x, dtype=float) - np.mean(x)
    step = nseg // 2
    window = np.hanning(nseg)
    scale = 1.0 / (np.sum(window ** 2))
    acc = None
    count = 0
    for start in range(0, len(x) - nseg + 1, step):
        seg = x[start:start + nseg] * window
        p = np.abs(np.fft.rfft(seg)) ** 2 * scale
        acc = p if acc is None else acc + p
        count += 1
    p = acc / count
    p[1:-1] *= 2.0  # one-sided
    omega = 2 * np.pi * np.fft.rfftfreq(nseg, dt)
    return omega, p * dt / (2 * np.pi)


def spectrum(run, outdir, stem):
    """Spectrum of the first probe's record (after the ramp) against eq. 44."""
    run.require(layout.SEA, "sea")
    t = run.time
    dt = float(t[1] - t[0])
    ramp_time = layout.sea_ramp_time(run)
    eta = run.get(layout.SEA_ELEVATION)[:, 0][t >= ramp_time]
    nseg = int(2 ** np.floor(np.log2(max(len(eta) // 8, 16))))
    omega, s = welch(eta, dt, nseg)
    height = _sea_height(run)
    fig, ax = plt.subplots(figsize=(9, 5))
    ax.plot(omega, s, lw=1, label=f"probe record (Welch, {nseg * dt:.0f} s segments)")
    w = np.linspace(0.2, 3.5, 400)
    ax.plot(w, layout.chinese_spectrum(w, height), "k--", lw=1.2,
            label=f"eq. 44, H = {height:g} m")
    hs = 4 * np.std(eta)
    ax.set(xlim=(0, 3.5), xlabel="omega [rad/s]", ylabel="S [m^2 s]",
           title=f"Wave spectrum: record Hs = 4 std = {hs:.2f} m, "
                 f"eq. 44 Hs = {0.9971 * height:.2f} m")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_spectrum.png")


def rao(run, outdir, stem):
    """Heave, roll and pitch RAOs against frequency, one line per wave heading."""
    run.require(layout.RAO, "RAO")
    w = run.get(layout.RAO_OMEGA)
    headings = np.degrees(run.get(layout.RAO_HEADING))
    amp = run.get(layout.RAO_AMPLITUDE)  # h5py: (heading, omega, dof)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.5))
    for ax, dof, unit in zip(axes, (2, 3, 4), ("m/m", "deg/m", "deg/m")):
        for h, heading in enumerate(headings):
            values = amp[h, :, dof] * (1 if dof == 2 else 180 / np.pi)
            ax.plot(w, values, marker=".", lw=1, label=f"{heading:.0f} deg")
        ax.set(xlabel="omega [rad/s]", ylabel=f"{layout.RAO_DOFS[dof]} RAO [{unit}]",
               title=f"{layout.RAO_DOFS[dof]}")
        ax.grid(True, alpha=0.3)
    axes[0].legend(title="wave heading")
    fig.suptitle("Ship response amplitude operators (0 = following, 90 = from port, "
                 "180 = head sea)")
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_rao.png")


def segment_tension(run, outdir, stem):
    """Cable segment tensions against time (the paper's Fig. 13 for its deck), with the static shares W/4 and
    (W + blocks + slings)/4 (weights from the run's deck, else the paper's III.B values).
    Drawn up to the hook release: after it the falls no longer carry the boat."""
    run.require([layout.RIGGING_SEGMENT_TENSION], "cable segment tensions")
    tension = run.get(layout.RIGGING_SEGMENT_TENSION)
    t = run.time
    t_release = run.event(layout.RELEASE_TIME)
    n = len(t) if t_release is None else int(np.searchsorted(t, t_release))
    mass = run.deck("boat", "mass", 8500.0)
    rigging = (2 * run.deck("rigging", "block_mass", 50.0) + 2 *
               run.deck("rigging", "sling_length", 1.0) *
               run.deck("rigging", "sling_mass_per_length", 1.6))
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for k in range(tension.shape[1]):
        ax.plot(t[:n], tension[:n, k] / 1e3, lw=0.7, label=f"segment {k + 1}")
    peak = run.get(layout.PEAK_SEGMENT_TENSION)
    if peak is not None and len(peak):
        ax.plot(run.get(layout.PEAK_SEGMENT_TENSION_TIME), peak / 1e3, "v", color="crimson",
                label=f"peaks over every step (max {np.max(peak) / 1e3:.1f} kN)")
        _mark_limits(ax, run, float(np.max(peak)) / 1e3)
    ax.axhline(mass * layout.GRAVITY / 4e3, color="k", ls="--", lw=0.8,
               label=f"W/4 = {mass * layout.GRAVITY / 4e3:.2f} kN")
    ax.axhline((mass + rigging) * layout.GRAVITY / 4e3, color="k", ls=":", lw=0.8,
               label="(W + blocks + slings)/4")
    until = "" if t_release is None else f", until the hook release at {t_release:.1f} s"
    # the paper's figure number only on the paper's own deck's run
    head = "Fig. 13: c" if _deck_stem(run) == FIG13_DECK else "C"
    ax.set(xlabel="t [s]", ylabel="tension [kN]",
           title=f"{head}able segment tension, drum to dead end{until}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_segment_tension.png")


# The paper deck whose run is the paper's Fig. 13 (input/fig13_tension.nml).
FIG13_DECK = "fig13_tension"


def _deck_stem(run):
    """The name of the deck a run came from, without folder and .nml ("" if unknown)."""
    name = os.path.basename(str(run.attrs.get(layout.INPUT_FILE, "")))
    return name[:-4] if name.endswith(".nml") else name


def contact(run, outdir, stem):
    """Smallest fender-to-side distance and each fender's normal force against time."""
    run.require(layout.CONTACT, "fender contact record")
    t = run.time
    force = run.get(layout.CONTACT_FORCE)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    top.plot(t, run.get(layout.CONTACT_CLEARANCE), lw=0.8)
    top.axhline(0.0, color="k", lw=0.6)
    top.set(ylabel="clearance [m]", title="Fenders against the ship's side "
            "(clearance < 0: indentation)")
    for k in range(force.shape[1]):
        bottom.plot(t, force[:, k] / 1e3, lw=0.8, label=f"fender {k + 1}")
    peak = run.get(layout.IMPACT_PEAK_FORCE)
    if peak is not None and len(peak):
        _mark_impacts(bottom, run, peak / 1e3, "impact peak (every step)")
        speed = run.get(layout.IMPACT_SPEED)
        limit = run.limit("impact_speed") or 3.5
        top.set_title(f"Fenders against the ship's side: {len(peak)} impacts, fastest "
                      f"{np.max(speed):.2f} m/s (limit {limit:g} m/s)" + _title_outcome(run))
    bottom.set(xlabel="t [s]", ylabel="normal force [kN]")
    for ax in (top, bottom):
        ax.grid(True, alpha=0.3)
    bottom.legend()
    fig.tight_layout()
    return _save(fig, outdir, f"{stem}_contact.png")


RUN_FIGURES = {"trajectory": trajectory, "tension": sling_tension,
               "acceleration": acceleration, "surface": surface, "spectrum": spectrum,
               "rao": rao, "contact": contact, "segment_tension": segment_tension}


def figures_for(run):
    """The figures that a file's contents support."""
    names = []
    if run.has(*layout.BOAT):
        names += ["trajectory", "acceleration"]
    if run.has(layout.SLING_TENSION):
        names.append("tension")
    if run.has(layout.RIGGING_SEGMENT_TENSION):
        names.append("segment_tension")
    if run.has(*layout.CONTACT):
        names.append("contact")
    if run.has(*layout.SEA):
        names += ["surface", "spectrum"]
    if run.has(*layout.RAO):
        names.append("rao")
    return names
