"""Passivity of the fitted radiation memory as a matrix (postproc.bem_fit's fits).

Cummins' memory force mu(t) = int K(t - tau) u(tau) dtau absorbs, over a period of a
harmonic motion u = Re[U e^{i w t}], the mean power 1/2 U^H B(w) U, B(w) the symmetric part
of Re K(i w). The memory as a whole makes no energy (the model is passive) if and only if
B(w) is positive semi-definite at every w. postproc.bem_fit fits each pair K_ij on its own
and makes only the diagonal fits passive (B_ii >= 0); the couplings can still make B
indefinite, e.g. a surge-pitch pole beyond the grid.

enforce() restores it by residue perturbation for the matrix case (Gustavsen and Semlyen,
IEEE Trans. Power Syst. 16(1), 2001; Grivet-Talocia, IEEE Trans. Circuits Syst. I 51(9),
2004): the poles stay, the residues move by the least change of the fits in a weighted
norm (the sum over pairs and the grid the fits used of |weight (K_fit - K_before)|^2: by
default relative to each pair's largest |K|; the build weights each pair by the RAO error
it makes, rao_weights; K(0) = 0 kept) subject to v_m^T B(w_m) v_m >= -tol/4 at each
frequency w_m where the smallest eigenvalue of the scaled matrix dips below -tol/2, v_m its
eigenvector there. v^T B v is linear in the residues, so each constraint is exact for its
v; new (w_m, v_m) join until no eigenvalue on the dense grid is below -tol/2, each step a
least-distance problem solved by non-negative least squares (_min_norm). Pairs absent
from the fits (zero by symmetry, or insignificant) stay exactly zero. The matrix is scaled
by D = diag(sqrt(max B_ii)) (D^-1 B D^-1: the same definiteness), so tol is relative to
the diagonal's peaks. Where the couplings' fits make the matrix indefinite just beyond
the grid, the build first gives the diagonal fits of the DOFs involved a damped pole pair
there with zero residue (augment), so that B_ii can rise where the grid has no data.
"""
from dataclasses import dataclass, field

import numpy as np

from . import bem_fit

TOLERANCE = 1e-3          # smallest eigenvalue allowed (scaled matrix): -TOLERANCE
# dense grid: 0..max(OMEGA_FACTOR w_N, POLE_FACTOR max |p|), POINTS uniform points plus
# points within +-4 |Re p| of each resonant pole (the narrowest resonances)
OMEGA_FACTOR = 20.0
POLE_FACTOR = 10.0
POINTS = 20000
REGULARISATION = 1e-9     # of the residues' change, relative (rank-deficient directions)
# augment: a damped pole pair p = AUGMENT_FACTOR w_N (-z + i sqrt(1 - z^2)), z =
# AUGMENT_DAMPING, given with zero residue to the diagonal fits of the DOFs in the worst
# violation; their residue lets the enforcement raise B_ii just beyond the grid, where the
# fits of the couplings made the matrix indefinite (the default box ship: sway-roll at
# 2.1-2.5 rad/s), instead of bending the fits on the grid (its roll kernel: 13 % of max
# B_44 at 1.6 rad/s without it, 3 % with it). 1.25 w_N, 0.5: among the smallest roll
# changes of 1.1-2 w_N and 0.2-0.7 tried on that ship.
AUGMENT_FACTOR = 1.25
AUGMENT_DAMPING = 0.5
AUGMENT_COMPONENT = 0.1   # |v_i| of the violation's eigenvector that selects DOF i


@dataclass
class Result:
    """What enforce did: smallest scaled eigenvalue before and after, where it was before,
    iterations, whether it converged, and per pair the RMS over the grid of the fit's
    weighted error (weight (K_fit - K), enforce's weights) before and after."""
    min_eigenvalue_before: float
    min_eigenvalue_after: float
    omega_at_min_before: float
    iterations: int
    converged: bool
    rms_before: dict = field(default_factory=dict)
    rms_after: dict = field(default_factory=dict)


def dense_grid(fits, omega_max, points=POINTS):
    """Frequencies (ascending, > 0) on which the fitted matrix is checked: uniform up to
    max(20 w_N, 10 |p|max), where every fitted pole's response has died away, plus 33
    points across each resonant pole's half-power band."""
    poles = [p for f in fits.values() for p in f.poles]
    top = max(OMEGA_FACTOR * omega_max, POLE_FACTOR * max([abs(p) for p in poles] + [0.0]))
    w = [np.linspace(1e-3, top, points)]
    for p in poles:
        if p.imag > 0:
            w.append(p.imag + abs(p.real) * np.linspace(-4.0, 4.0, 33))
    w = np.unique(np.concatenate(w))
    return w[w > 0]


def _null(poles):
    """Columns spanning the residue vectors with K(0) = 0."""
    g = bem_fit._basis(np.array([0.0 + 0.0j]), poles).real[0]
    return np.linalg.svd(g[None, :])[2][1:].T


def _scale(damping):
    return np.sqrt(np.maximum(np.abs(damping).max(axis=0).diagonal(), 1e-300))


def damping_matrix(fits, w, damping):
    """(nw, 6, 6) symmetric part of the fitted damping matrix, scaled by D^-1 . D^-1."""
    b = np.zeros((w.size, 6, 6))
    for (i, j), f in fits.items():
        b[:, i, j] = bem_fit.evaluate(f.poles, f.coef, 1j * w).real
    d = _scale(damping)
    b = b / np.outer(d, d)
    return 0.5 * (b + b.transpose(0, 2, 1))


def min_eigenvalue(fits, omega_max, damping, w=None):
    """(smallest eigenvalue of the scaled fitted damping matrix over the dense grid, its w)."""
    w = dense_grid(fits, omega_max) if w is None else w
    ev = np.linalg.eigvalsh(damping_matrix(fits, w, damping))[:, 0]
    k = int(np.argmin(ev))
    return float(ev[k]), float(w[k])


def _violations(fits, w, damping, tol):
    """(frequencies, eigenvectors) at the local minima over w of the smallest eigenvalue
    where it is below -tol."""
    ev, vec = np.linalg.eigh(damping_matrix(fits, w, damping))
    low = ev[:, 0]
    excess = -tol - low
    peak = (excess > 0) & (excess >= np.roll(excess, 1)) & (excess >= np.roll(excess, -1))
    idx = np.nonzero(peak)[0]
    return w[idx], vec[idx, :, 0]


def _rms(fit, kdata, weight, shift, omega):
    kf = bem_fit.evaluate(fit.poles, fit.coef, 1j * omega) + 1j * omega * shift
    return float(np.sqrt(np.mean(np.abs(weight * (kf - kdata))**2)))


def rao_weights(omega, added_mass, damping, mass, stiffness, pairs):
    """dict (i, j) -> w / sqrt(|Z_ii(w)| |Z_jj(w)|), Z_ii = C_ii - w^2 (M_ii + A_ii) + i w
    B_ii: an error dK_ij of the kernel changes the RAO by dxi = -Z^-1 (i w dK) xi, i.e. by
    about w |dK_ij| / sqrt(|Z_ii| |Z_jj|) relative to the motions' scale (largest near
    the resonances, where |Z| is the damping alone); dimensionless."""
    z = [bem_fit._impedance(omega, added_mass[:, i, i], damping[:, i, i], mass[i, i],
                            stiffness[i, i]) for i in range(6)]
    return {(i, j): omega / np.sqrt(z[i] * z[j]) for (i, j) in pairs}


def augment(fits, omega_max, damping, tol=TOLERANCE):
    """Give each diagonal fit of a DOF with |v_i| >= AUGMENT_COMPONENT in the eigenvector of
    the smallest eigenvalue over dense_grid (if below -tol) one more pole pair (see
    AUGMENT_FACTOR), its residue zero: the fits are unchanged, the enforcement gets a
    direction beyond the grid. Changes fits in place; returns the DOFs augmented."""
    w = dense_grid(fits, omega_max)
    ev, vec = np.linalg.eigh(damping_matrix(fits, w, damping))
    k = int(np.argmin(ev[:, 0]))
    if ev[k, 0] >= -tol:
        return []
    z = AUGMENT_DAMPING
    pole = AUGMENT_FACTOR * omega_max * complex(-z, np.sqrt(1.0 - z * z))
    dofs = [i for i in range(6) if abs(vec[k, i, 0]) >= AUGMENT_COMPONENT and (i, i) in fits]
    for i in dofs:
        f = fits[(i, i)]
        f.poles = list(f.poles) + [pole]
        f.coef = np.concatenate([f.coef, [0.0, 0.0]])
        f.order += 2
        f.a, f.b, f.c = bem_fit.realisation(f.poles, f.coef)
    return dofs


def enforce(fits, omega, added_mass, damping, added_mass_inf, weights=None, omega_max=None,
            tol=TOLERANCE, iterations=60, added_mass_zero=None):
    """Perturb the residues of `fits` (dict (i, j) -> PairFit, changed in place: coef, c,
    the grid errors, min_damping) until the symmetric part of the fitted damping matrix
    has no eigenvalue below -tol (scaled) over dense_grid. omega, added_mass, damping: the
    grid and data the fits used; weights: dict (i, j) -> (nw,), each pair's error K_fit - K
    multiplied by it in the least change (default 1 / max |K_ij|: the relative error;
    rao_weights: the RAO's); omega_max: the database's last frequency (default omega[-1]).
    added_mass_zero: (6, 6) A(0) of the BEM data, or None; given, every pair's memory keeps
    its zero-frequency added mass A_inf(fit) + K'(0) equal to it (an equality constraint on
    the residues, _zero_frequency_rows, held in every step; the result is then passive by
    the same check, on the dense grid, as without it). Without it always feasible (zero
    residues satisfy every constraint). Returns a Result."""
    omega = np.asarray(omega, float)
    w_top = omega[-1] if omega_max is None else omega_max
    wd = dense_grid(fits, w_top)
    d = _scale(damping)
    pairs = sorted(fits)
    before, w_before = min_eigenvalue(fits, w_top, damping, wd)
    blocks, y0, offsets, rms_before, data = [], [], [0], {}, {}
    for (i, j) in pairs:
        f = fits[(i, j)]
        null = _null(f.poles)
        kdata = damping[:, i, j] + 1j * omega * (added_mass[:, i, j] - added_mass_inf[i, j])
        if weights is None or (i, j) not in weights:
            wt = np.full(omega.size, 1.0 / max(np.max(np.abs(kdata)), 1e-300))
        else:
            wt = np.asarray(weights[(i, j)], float)
        shift = f.added_mass_shift
        data[(i, j)] = (null, kdata, wt, shift)
        rms_before[(i, j)] = _rms(f, kdata, wt, shift, omega)
        phi = bem_fit._basis(1j * omega, f.poles) @ null * wt[:, None]
        blocks.append(np.vstack([phi.real, phi.imag]))
        y0.append(np.linalg.lstsq(null, f.coef, rcond=None)[0])
        offsets.append(offsets[-1] + null.shape[1])
    result = Result(before, before, w_before, 0, before >= -tol, rms_before, dict(rms_before))
    if result.converged and added_mass_zero is None:
        return result
    n = offsets[-1]
    # least change || M (y - y0) ||^2, M block-diagonal over the pairs, = ||z||^2 with
    # z = R (y - y0), M = Q R (R regularised where M does not see a direction)
    # (columns scaled to unit norm first: the weights span orders of magnitude)
    r_inv = np.zeros((n, n))
    for k, m in enumerate(blocks):
        col = np.linalg.norm(m, axis=0)
        col[col == 0.0] = 1.0
        rk = np.linalg.qr(np.vstack([m / col, REGULARISATION * np.eye(m.shape[1])]),
                          mode="r")
        r_inv[offsets[k]:offsets[k + 1], offsets[k]:offsets[k + 1]] = (
            np.linalg.inv(rk) / col[:, None])
    y0 = np.concatenate(y0)
    # the equalities h . y = c (A(0) held) in the least-change variable z = R (y - y0):
    # z = z_p + Q t, z_p the least z that meets them, Q spanning the z that keep them;
    # ||z||^2 = ||z_p||^2 + ||t||^2, so the least change is the least ||t||
    z_p, q = np.zeros(n), np.eye(n)
    if added_mass_zero is not None:
        h, c = _zero_frequency_rows(fits, pairs, data, offsets, added_mass_zero,
                                    added_mass_inf)
        e = h @ r_inv
        z_p = np.linalg.lstsq(e, c - h @ y0, rcond=None)[0]
        vt = np.linalg.svd(e)[2]
        q = vt[np.linalg.matrix_rank(e):].T

    def rows(wm, vm):
        """g such that g . y = v^T (D^-1 B(w) D^-1) v for each (w, v)."""
        g = np.zeros((wm.size, n))
        for k, (i, j) in enumerate(pairs):
            re = bem_fit._basis(1j * wm, fits[(i, j)].poles).real @ data[(i, j)][0]
            g[:, offsets[k]:offsets[k + 1]] = (vm[:, i] * vm[:, j] / (d[i] * d[j]))[:, None] * re
        return g

    def apply(y):
        for k, (i, j) in enumerate(pairs):
            f = fits[(i, j)]
            f.coef = data[(i, j)][0] @ y[offsets[k]:offsets[k + 1]]
            f.a, f.b, f.c = bem_fit.realisation(f.poles, f.coef)

    g = np.zeros((0, n))
    y = y0 + r_inv @ z_p
    apply(y)
    for it in range(1, iterations + 1):
        # constraints where it dips below -tol / 2: a margin for grids other than wd
        wm, vm = _violations(fits, wd, damping, 0.5 * tol)
        if wm.size == 0:
            break
        g = np.vstack([g, rows(wm, vm)])
        # v^T B v >= -tol / 4 there (not >= 0: where B_fit -> 0, w -> 0 or beyond the
        # poles, exact zero can cost the fit far more than the tolerance allows for)
        gz = g @ r_inv
        y = y0 + r_inv @ (z_p + q @ _min_norm(gz @ q, -(g @ y0) - 0.25 * tol - gz @ z_p))
        apply(y)
        result.iterations = it
    result.converged = _violations(fits, wd, damping, tol)[0].size == 0
    result.min_eigenvalue_after = min_eigenvalue(fits, w_top, damping, wd)[0]
    for (i, j) in pairs:
        f = fits[(i, j)]
        null, kdata, wt, shift = data[(i, j)]
        result.rms_after[(i, j)] = _rms(f, kdata, wt, shift, omega)
        f.error_added_mass, f.error_damping = bem_fit.fit_errors(
            f.poles, f.coef, omega, added_mass[:, i, j], damping[:, i, j],
            added_mass_inf[i, j], shift)
        f.min_damping = bem_fit.min_damping(f, w_top, damping[:, i, j])
    return result


def _slope_at_zero(poles):
    """d/ds of bem_fit._basis at s = 0 (real): -1/p^2 for a real pole; for a pair,
    -(1/p^2 + 1/p*^2) and -(i/p^2 - i/p*^2). K'(0) = this . coef is the memory's
    zero-frequency added mass less A_inf: A(w) = A_inf + Im K(i w)/w -> A_inf + K'(0)."""
    cols = []
    for p, m in bem_fit._split_poles(poles):
        if m == 1:
            cols.append(-1.0 / p.real**2)
        else:
            cols.append(-(1.0 / p**2 + 1.0 / np.conj(p)**2).real)
            cols.append(-(1j / p**2 - 1j / np.conj(p)**2).real)
    return np.array(cols)


def _zero_frequency_rows(fits, pairs, data, offsets, added_mass_zero, added_mass_inf):
    """(h, c): h . y = c holds every pair's zero-frequency added mass at the data's,
    A_inf_ij + shift_ij + K_ij'(0) = A_ij(0) (shift: the impedance fit's, bem_fit)."""
    h = np.zeros((len(pairs), offsets[-1]))
    c = np.zeros(len(pairs))
    for k, (i, j) in enumerate(pairs):
        null, shift = data[(i, j)][0], data[(i, j)][3]
        h[k, offsets[k]:offsets[k + 1]] = _slope_at_zero(fits[(i, j)].poles) @ null
        c[k] = added_mass_zero[i, j] - added_mass_inf[i, j] - shift
    return h, c


def _min_norm(g, b):
    """min ||z|| subject to g z >= b (each row): least-distance programming by
    non-negative least squares (Lawson and Hanson, Solving Least Squares Problems, 1974,
    ch. 23): u >= 0 minimising ||E u - f|| with E = [g^T; b^T], f = (0, .., 0, 1) gives
    z = -r[:n] / r[n], r = E u - f. Raises ValueError if the rows cannot all hold."""
    from scipy.optimize import nnls
    norm = np.linalg.norm(g, axis=1)
    norm[norm == 0.0] = 1.0
    g, b = g / norm[:, None], b / norm
    n = g.shape[1]
    e = np.vstack([g.T, b[None, :]])
    f = np.zeros(n + 1)
    f[n] = 1.0
    u = nnls(e, f, maxiter=50 * e.shape[1])[0]
    r = e @ u - f
    if abs(r[n]) < 1e-12:
        raise ValueError("passivity constraints that cannot all hold with these poles")
    return -r[:n] / r[n]


def fits_from_database(base):
    """dict (i, j) -> PairFit of a database's stored realisations (postproc.bem_fit's block
    form: a real pole [p] with c = coef, a pair [[Re p, -Im p], [Im p, Re p]] with
    c = [2 Re r, -2 Im r] and coef = (Re r, Im r))."""
    from . import bem_db as db
    order, a, b, c = base[db.SS_ORDER], base[db.SS_A], base[db.SS_B], base[db.SS_C]
    fits = {}
    for i in range(6):
        for j in range(6):
            n = int(order[i, j])
            if n == 0:
                continue
            poles, coef, k = [], [], 0
            while k < n:
                if k + 1 < n and a[i, j, k + 1, k] != 0.0:
                    poles.append(complex(a[i, j, k, k], a[i, j, k + 1, k]))
                    coef += [0.5 * c[i, j, k], -0.5 * c[i, j, k + 1]]
                    k += 2
                else:
                    poles.append(complex(a[i, j, k, k], 0.0))
                    coef.append(c[i, j, k])
                    k += 1
            coef = np.array(coef)
            am, bm, cm = bem_fit.realisation(poles, coef)
            fits[(i, j)] = bem_fit.PairFit(n, am, bm, cm, poles, coef, float("nan"),
                                           float("nan"), float("nan"))
    return fits
