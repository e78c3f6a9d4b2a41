"""Frequency-domain RAOs of the BEM database (`python -m postproc.bem rao`), the reference
for verifying davit's time-domain ship.

For each frequency w and relative heading beta, the 6x6 complex system
    [-w^2 (M + A(w)) + i w (B(w) + B_visc) + C] xi = X(w, beta)
is solved with all couplings, in davit's body frame (x forward, y starboard, z down; roll
positive starboard down, pitch positive bow up). A, B and X are interpolated linearly in w
(and X in beta) from the database. B_visc is zero but for a linear roll damping
B44_visc = zeta 2 sqrt(C44 (I44 + A44(w_roll))) at the undamped roll frequency.
C44 may be replaced by m g GM (with_roll_gm: e.g. the lifeboat with the paper's h_m = 2 m
instead of the GM_T its hull and CG give).

The response to eta = a cos(w t + eps - k (x_G cos g + y_G sin g)) is
x_i(t) = Re[xi_i a exp(i (w t + eps - k (...)))], so |xi_i| is the amplitude per unit wave
amplitude (m/m, rad/m) and arg(xi_i) the phase lead over the elevation at the CG. In long
waves heave -> -1 (z down: the ship rises with the crest), pitch -> -i k cos(beta) and roll
-> +i k sin(beta) (the deck follows the surface slope).

Output (.h5, root datasets, names in postproc.layout BEM_RAO_*; numpy shapes): omega (nw)
[rad/s], heading (nb) [rad], rao_re, rao_im, amplitude, phase (nw, nb, 6) [m/m or rad/m;
phase rad], natural_period (6) [s] (nan for surge, sway, yaw), radiation_damping_ratio (6)
[-] (B_ii / (2 sqrt(C_ii (M_ii + A_ii)))) at the undamped natural frequency; nan for surge,
sway, yaw), and root attributes database, roll_damping_ratio, roll_damping_visc [N m s],
roll_stiffness (C44 [N m]) and roll_gm (C44 / (m g) [m]). (.csv: one row per omega,
heading, DOF: omega_rad_s, heading_deg, dof, amplitude, phase_rad, re, im.)
"""
import copy

import numpy as np

from . import bem_db as db
from . import layout

OMEGA = layout.BEM_RAO_OMEGA
HEADING = layout.BEM_RAO_HEADING
RAO_RE = layout.BEM_RAO_RE
RAO_IM = layout.BEM_RAO_IM
AMPLITUDE = layout.BEM_RAO_AMPLITUDE
PHASE = layout.BEM_RAO_PHASE
NATURAL_PERIOD = layout.BEM_RAO_NATURAL_PERIOD
DAMPING_RATIO = layout.BEM_RAO_DAMPING_RATIO
RESTORED = (2, 3, 4)   # heave, roll, pitch


def _interp_omega(data, omega_db, omega):
    """Linear interpolation along the first axis (frequency) of an array."""
    if np.any(omega < omega_db[0] - 1e-12) or np.any(omega > omega_db[-1] + 1e-12):
        raise ValueError(f"frequencies outside the database's {omega_db[0]:g}.."
                         f"{omega_db[-1]:g} rad/s")
    flat = data.reshape(len(omega_db), -1)
    out = np.stack([np.interp(omega, omega_db, flat[:, k].real)
                    + (1j * np.interp(omega, omega_db, flat[:, k].imag)
                       if np.iscomplexobj(flat) else 0.0)
                    for k in range(flat.shape[1])], axis=-1)
    return out.reshape((len(omega),) + data.shape[1:])


def _interp_heading(data, heading_db, heading):
    """Linear interpolation along axis 1 (heading, periodic 2 pi) of an array."""
    h_db = np.asarray(heading_db)
    h = np.mod(heading, 2 * np.pi)
    order = np.argsort(h_db)
    h_db, data = h_db[order], data[:, order]
    if h_db[0] > 1e-9 or h_db[-1] < 2 * np.pi - 1e-9:   # close the circle
        h_db = np.concatenate([h_db, [h_db[0] + 2 * np.pi]])
        data = np.concatenate([data, data[:, :1]], axis=1)
    out = np.empty((data.shape[0], len(h)) + data.shape[2:], dtype=data.dtype)
    for n, hv in enumerate(h):
        i = int(np.clip(np.searchsorted(h_db, hv) - 1, 0, len(h_db) - 2))
        t = (hv - h_db[i]) / (h_db[i + 1] - h_db[i])
        out[:, n] = (1 - t) * data[:, i] + t * data[:, i + 1]
    return out


def added_mass_at(base, dof, w):
    """A_ii(w): interpolated within the grid, A(inf) above it, the lowest value below."""
    om = base.omega
    if w >= om[-1]:
        return base.added_mass_inf[dof, dof]
    return float(np.interp(w, om, base.added_mass[:, dof, dof]))


def natural_frequency(base, dof, iterations=100):
    """Undamped natural frequency w = sqrt(C_ii / (M_ii + A_ii(w))), iterated."""
    c = base.stiffness[dof, dof]
    m = base.mass[dof, dof]
    if c <= 0:
        return float("nan")
    w = np.sqrt(c / m)
    for _ in range(iterations):
        w_new = np.sqrt(c / (m + added_mass_at(base, dof, w)))
        if abs(w_new - w) < 1e-10:
            break
        w = 0.5 * (w + w_new)  # damped fixed point: A(w) can be steep near resonance
    return float(w)


def roll_damping(base, zeta):
    w_roll = natural_frequency(base, 3)
    return zeta * 2.0 * np.sqrt(base.stiffness[3, 3] * (base.mass[3, 3]
                                                        + added_mass_at(base, 3, w_roll)))


def check_restoring(base, g=9.81):
    """Raise ValueError unless heave, roll and pitch have positive restoring (C_ii > 0):
    with C44 <= 0 (negative GM) the roll has no natural frequency and the RAOs are NaN."""
    for dof in RESTORED:
        c = float(base.stiffness[dof, dof])
        if not c > 0.0:
            why = ""
            if dof in (3, 4):
                why = (f" (GM {c / (base.mass[0, 0] * g):.4g} m <= 0: unstable; give --gm, "
                       f"or rebuild with a lower --cg)")
            raise ValueError(f"the hull has no {db.DOFS[dof]} restoring: C{dof + 1}{dof + 1} "
                             f"= {c:.4g}{why}")


def covered_headings(base, headings, tol=1e-6):
    """Raise ValueError if a one-heading database is asked for another heading: it says
    nothing about the others (davit's time-domain ship refuses it for that reason)."""
    if len(base.heading) > 1:
        return
    other = np.abs(np.angle(np.exp(1j * (np.asarray(headings) - base.heading[0])))) > tol
    if np.any(other):
        raise ValueError(f"the database covers the one heading "
                         f"{np.degrees(base.heading[0]):g} deg only; asked for "
                         f"{', '.join(f'{np.degrees(h):g}' for h in np.asarray(headings)[other])}"
                         f" deg (give --headings-deg {np.degrees(base.heading[0]):g}, or "
                         f"rebuild it with more headings)")


def raos(base, omegas=None, headings=None, zeta=0.05):
    """Complex RAOs (nw, nb, 6) in davit's body frame, and B44_visc. ValueError for a
    heading a one-heading database does not cover, or a response that is not finite."""
    omegas = base.omega if omegas is None else np.asarray(omegas, float)
    headings = base.heading if headings is None else np.asarray(headings, float)
    covered_headings(base, headings)
    a = _interp_omega(base.added_mass, base.omega, omegas)
    b = _interp_omega(base.damping, base.omega, omegas)
    x = _interp_heading(_interp_omega(base.excitation, base.omega, omegas), base.heading,
                        headings)
    b44 = roll_damping(base, zeta) if zeta > 0 else 0.0
    bv = np.zeros((6, 6))
    bv[3, 3] = b44
    xi = np.empty((len(omegas), len(headings), 6), complex)
    for n, w in enumerate(omegas):
        z = -w**2 * (base.mass + a[n]) + 1j * w * (b[n] + bv) + base.stiffness
        xi[n] = np.linalg.solve(z, x[n].T).T
    if not np.all(np.isfinite(xi)):
        bad = sorted({float(omegas[n]) for n in np.nonzero(~np.isfinite(xi))[0]})
        raise ValueError(f"the RAOs are not finite at omega {', '.join(f'{w:g}' for w in bad)}"
                         f" rad/s (check the database's stiffness, mass and roll damping)")
    return xi, b44


def with_roll_gm(base, gm, g=9.81):
    """A copy of the database with C44 = m g GM (the other stiffnesses unchanged)."""
    other = copy.copy(base)
    other.values = dict(base.values)
    c = np.array(base.stiffness, float)
    c[3, 3] = base.mass[0, 0] * g * gm
    other.values[db.STIFFNESS] = c
    return other


def roll_gm(base, g=9.81):
    """GM_T = C44 / (m g) of the database [m]."""
    return float(base.stiffness[3, 3] / (base.mass[0, 0] * g))


def damping_ratios(base):
    """Radiation damping ratio B_ii / (2 sqrt(C_ii (M_ii + A_ii))) at the undamped natural
    frequency of heave, roll and pitch (nan for the others): the waves a DOF makes as the
    only damping, evaluated where it resonates."""
    zeta = np.full(6, np.nan)
    for dof in RESTORED:
        w = natural_frequency(base, dof)
        b = float(np.interp(w, base.omega, base.damping[:, dof, dof]))
        zeta[dof] = b / (2.0 * np.sqrt(base.stiffness[dof, dof]
                                       * (base.mass[dof, dof] + added_mass_at(base, dof, w))))
    return zeta


def natural_periods(base):
    t = np.full(6, np.nan)
    for dof in RESTORED:
        t[dof] = 2 * np.pi / natural_frequency(base, dof)
    return t


def write(path, omegas, headings, xi, periods, database, zeta, b44, ratios=None,
          c44=float("nan"), gm=float("nan")):
    if str(path).endswith(".csv"):
        with open(path, "w") as f:
            f.write("omega_rad_s,heading_deg,dof,amplitude,phase_rad,re,im\n")
            for n, w in enumerate(omegas):
                for m, h in enumerate(headings):
                    for d in range(6):
                        v = xi[n, m, d]
                        f.write(f"{w:.6g},{np.degrees(h):.6g},{db.DOFS[d]},{abs(v):.8g},"
                                f"{np.angle(v):.8g},{v.real:.8g},{v.imag:.8g}\n")
        return
    import h5py
    with h5py.File(path, "w") as f:
        for name, value, units, desc in (
                (OMEGA, omegas, "rad/s", "wave frequency"),
                (HEADING, headings, "rad", "relative heading (0 following, pi/2 waves to "
                 "starboard, pi head seas)"),
                (RAO_RE, xi.real, "m/m (surge, sway, heave), rad/m (roll, pitch, yaw)",
                 "Re xi, (omega, heading, dof), davit body frame (z down)"),
                (RAO_IM, xi.imag, "as rao_re", "Im xi"),
                (AMPLITUDE, np.abs(xi), "as rao_re", "|xi| per unit wave amplitude"),
                (PHASE, np.angle(xi), "rad", "phase lead over the wave elevation at the CG"),
                (NATURAL_PERIOD, periods, "s", "undamped natural periods (nan: no restoring)"),
                (DAMPING_RATIO, np.full(6, np.nan) if ratios is None else ratios, "-",
                 "radiation damping ratio at the undamped natural frequency (nan: no "
                 "restoring)")):
            ds = f.create_dataset(name, data=np.asarray(value, float))
            ds.attrs[layout.UNITS] = units
            ds.attrs[layout.DESCRIPTION] = desc
        f.attrs[layout.BEM_RAO_DATABASE] = str(database)
        f.attrs[layout.BEM_RAO_ROLL_DAMPING_RATIO] = zeta
        f.attrs[layout.BEM_RAO_ROLL_DAMPING_VISC] = b44
        f.attrs[layout.BEM_RAO_ROLL_STIFFNESS] = c44
        f.attrs[layout.BEM_RAO_ROLL_GM] = gm
