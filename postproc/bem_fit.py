"""Radiation memory of the BEM database: retardation functions and state-space fits.

Cummins' equation: (M + A_inf) u' + mu + C eta = F, with the memory force
mu_i(t) = sum_j int_0^t K_ij(t - tau) u_j(tau) dtau and the retardation function
K_ij(t) = (2/pi) int_0^inf B_ij(w) cos(w t) dw. Its transfer function (Fourier transform,
e^{+i w t}) is K_ij(i w) = B_ij(w) + i w (A_ij(w) - A_ij(inf)), so a fit K_fit reproduces
B_fit(w) = Re K_fit(i w) and A_fit(w) = A_inf + Im K_fit(i w) / w.

Each pair (i, j) is fitted on its own by vector fitting (Gustavsen and Semlyen 1999:
iterated pole relocation of a partial-fraction model, unstable poles reflected into the
left half-plane) with the structure of a radiation kernel imposed: strictly proper
(relative degree >= 1, no constant or s term) and K(0) = 0 exactly (one linear constraint
on the residues in the final least-squares step). The order grows until the frequency-domain
error drops below a tolerance. The realisation is real and block-diagonal: a real pole p
with residue c gives [p], [1], [c]; a complex pair p, conj(p) with residue c gives
A = [[Re p, -Im p], [Im p, Re p]], B = [1, 0], C = [2 Re c, -2 Im c].
A diagonal pair whose fit misses the tolerance is refitted for the RAO instead
(fit_impedance): frequencies weighted by w / |Z(w)|, A_inf shifted by a fitted constant e
(the model's A(w) = A_inf + e + Im K_fit(i w) / w), the residues perturbed to passivity.
Frequencies beyond the first with a negative diagonal damping are not fitted
(resolved_frequencies).
numpy only (no scipy), so that the RAO tool and the tests need no more than numpy and h5py.
"""
from dataclasses import dataclass

import numpy as np

# Tail of B(w) beyond the last grid frequency in the cosine transform: B_N (w_N / w)^p,
# p = 2 as in the fitted models (relative degree 1: Re K(i w) ~ 1/w^2)
TAIL_POWER = 2.0
TAIL_FACTOR = 10.0         # the tail is integrated up to TAIL_FACTOR * w_N
DW_FINE = 2.0e-3           # [rad/s] quadrature step of the cosine transform


def retardation(omega, damping, time, damping_zero=None):
    """K(t) = (2/pi) int_0^inf B(w) cos(w t) dw for B given at omega (ascending, > 0),
    shape (nw, ...) -> (nt, ...). B is piecewise linear between the grid points and from
    B(0) (damping_zero, default 0: no wave radiation at w = 0) to the first point, and
    decays as (w_N / w)^TAIL_POWER beyond the last one."""
    omega = np.asarray(omega, float)
    b = np.asarray(damping, float)
    shape = b.shape[1:]
    b = b.reshape(len(omega), -1)
    b0 = np.zeros(b.shape[1]) if damping_zero is None else np.asarray(damping_zero).reshape(-1)
    wg = np.concatenate([[0.0], omega])
    bg = np.vstack([b0[None, :], b])
    w_fine = np.arange(0.0, omega[-1], DW_FINE)
    w_fine = np.append(w_fine, omega[-1])
    b_fine = np.stack([np.interp(w_fine, wg, bg[:, k]) for k in range(b.shape[1])], axis=1)
    w_tail = np.arange(omega[-1], TAIL_FACTOR * omega[-1], DW_FINE)
    b_tail = b[-1][None, :] * (omega[-1] / w_tail[:, None])**TAIL_POWER
    w_all = np.concatenate([w_fine, w_tail[1:]])
    b_all = np.vstack([b_fine, b_tail[1:]])
    weights = np.gradient(w_all)  # trapezoid-like weights on a near-uniform grid
    weights[0] *= 0.5
    weights[-1] *= 0.5
    k = (2.0 / np.pi) * np.cos(np.outer(time, w_all)) @ (weights[:, None] * b_all)
    return k.reshape((len(time),) + shape)


def _split_poles(poles):
    """Poles as a list of (real pole) or (pair with Im > 0), each with its column count."""
    return [(p, 1) if p.imag == 0.0 else (p, 2) for p in poles]


def _basis(s, poles):
    """Real-coefficient partial-fraction basis at s: 1/(s - p) for a real pole; for a pair,
    1/(s - p) + 1/(s - p*) and i/(s - p) - i/(s - p*)."""
    cols = []
    for p, m in _split_poles(poles):
        if m == 1:
            cols.append(1.0 / (s - p.real))
        else:
            cols.append(1.0 / (s - p) + 1.0 / (s - np.conj(p)))
            cols.append(1j / (s - p) - 1j / (s - np.conj(p)))
    return np.array(cols).T


def realisation(poles, coef):
    """(A, B, C) of sum of the basis functions weighted by coef (see the module doc)."""
    n = len(coef)
    a, b, c = np.zeros((n, n)), np.zeros(n), np.zeros(n)
    k = 0
    for p, m in _split_poles(poles):
        if m == 1:
            a[k, k], b[k], c[k] = p.real, 1.0, coef[k]
        else:
            a[k:k + 2, k:k + 2] = [[p.real, -p.imag], [p.imag, p.real]]
            b[k] = 1.0
            c[k], c[k + 1] = 2.0 * coef[k], -2.0 * coef[k + 1]
        k += m
    return a, b, c


def _relocate(zeros, min_damping):
    """Canonical stable pole list from the eigenvalues of the sigma function: real ones and
    one of each conjugate pair, reflected into the left half-plane with Re p <=
    -min_damping |p|."""
    poles = []
    scale = np.max(np.abs(zeros)) if len(zeros) else 1.0
    for z in zeros:
        if abs(z.imag) <= 1e-9 * max(abs(z), scale * 1e-6):
            re = -max(abs(z.real), min_damping * scale)
            poles.append(complex(re, 0.0))
        elif z.imag > 0:
            re = -max(abs(z.real), min_damping * abs(z))
            poles.append(complex(re, z.imag))
    return poles


def _initial_poles(order, w_lo, w_hi):
    poles = []
    npair = order // 2
    for beta in np.linspace(w_lo, w_hi, max(npair, 1))[:npair]:
        poles.append(complex(-beta / 100.0, beta))
    if order % 2:
        poles.append(complex(-0.5 * (w_lo + w_hi), 0.0))
    return poles


def _lstsq_real(m, rhs):
    mr = np.vstack([m.real, m.imag])
    rr = np.concatenate([rhs.real, rhs.imag])
    scale = np.linalg.norm(mr, axis=0)
    scale[scale == 0.0] = 1.0
    x = np.linalg.lstsq(mr / scale, rr, rcond=None)[0]
    return x / scale


def vector_fit(s, f, order, iterations=40, min_damping=1e-3):
    """Stable strictly proper rational fit of f(s) with f(0) = 0 of the given order.
    Returns (poles, coef) with the real coefficients of _basis."""
    w = np.abs(s.imag)
    wpos = w[w > 0]
    poles = _initial_poles(order, wpos.min(), wpos.max())
    for _ in range(iterations):
        phi = _basis(s, poles)
        x = _lstsq_real(np.hstack([phi, -f[:, None] * phi]), f)
        a, b, c = realisation(poles, x[order:])
        zeros = np.linalg.eigvals(a - np.outer(b, c))
        new = _relocate(zeros, min_damping)
        if sum(m for _, m in _split_poles(new)) != order:
            break
        poles = new
    # residues with K(0) = 0: coef = N y, N spanning the null space of the row basis(0)
    phi = _basis(s, poles)
    g = _basis(np.array([0.0 + 0.0j]), poles).real[0]
    _, _, vt = np.linalg.svd(g[None, :])
    null = vt[1:].T
    y = _lstsq_real(phi @ null, f)
    return poles, null @ y


def passive_residues(s, f, poles, coef, omega_max, slack=1e-3, bound=None, iterations=30,
                     weight=30.0):
    """Residues (same poles) of a fit of f(s) (scaled data, K(0) = 0 kept) whose real part,
    the damping, stays within its bounds over 0..20 omega_max: the least-squares fit of
    vector_fit with rows Re K(i w_m) = (the bound) added, heavily weighted, at the extrema
    where it leaves them, until it no longer does (an active set; Gustavsen's residue
    perturbation in its simplest form). Bounds: Re K >= -slack max|Re f| (a diagonal
    pair: passive), or |Re K| <= bound(w) + slack max|Re f| with bound a function of w.
    Returns coef, or None if it does not converge."""
    g = _basis(np.array([0.0 + 0.0j]), poles).real[0]
    null = np.linalg.svd(g[None, :])[2][1:].T
    phi = _basis(s, poles) @ null
    w = np.linspace(1e-3, 20.0 * omega_max, 20000)
    dense = _basis(1j * w, poles).real @ null
    tol = slack * np.max(np.abs(f.real))
    upper = None if bound is None else bound(w)
    rows, targets = np.zeros((0, null.shape[1])), np.zeros(0)
    y = np.linalg.lstsq(null, coef, rcond=None)[0]
    for _ in range(iterations):
        b = dense @ y
        if upper is None:
            excess, target = -tol - b, np.zeros_like(b)
        else:
            excess, target = np.abs(b) - upper - tol, np.sign(b) * upper
        peak = (excess > 0) & (excess >= np.roll(excess, 1)) & (excess >= np.roll(excess, -1))
        low = np.nonzero(peak)[0]
        if low.size == 0:
            return null @ y
        rows = np.vstack([rows, dense[low]])
        targets = np.concatenate([targets, target[low]])
        m = np.vstack([np.vstack([phi.real, phi.imag]), weight * rows])
        r = np.concatenate([f.real, f.imag, weight * targets])
        scale = np.linalg.norm(m, axis=0)
        scale[scale == 0.0] = 1.0
        y = np.linalg.lstsq(m / scale, r, rcond=None)[0] / scale
    return None


def evaluate(poles, coef, s):
    return _basis(np.atleast_1d(s), poles) @ coef


def impulse_response(poles, coef, time):
    """K(t) = C exp(A t) B of the realisation."""
    k = np.zeros(len(time))
    i = 0
    for p, m in _split_poles(poles):
        if m == 1:
            k += coef[i] * np.exp(p.real * time)
        else:
            c = coef[i] + 1j * coef[i + 1]
            k += 2.0 * np.real(c * np.exp(p * time))
        i += m
    return k


@dataclass
class PairFit:
    order: int
    a: np.ndarray           # (n, n)
    b: np.ndarray           # (n,)
    c: np.ndarray           # (n,)
    poles: list
    coef: np.ndarray
    error_added_mass: float     # max |A_fit - A| / max |A - A_inf| over the grid
    error_damping: float        # max |B_fit - B| / max |B| over the grid
    error_retardation: float    # ||K_ss - K|| / ||K|| (L2 over 0..30 s), nan if not computed
    min_damping: float = float("nan")   # min over 0..20 w_N of B_fit / max |B| (diagonal)
    tail: bool = False          # fitted with the tail beyond the grid (fit_all)
    added_mass_shift: float = 0.0   # fitted A_inf - BEM A_inf (fit_impedance; else 0)
    error_impedance: float = float("nan")   # max w |K_fit - K| / |Z| (diagonal, impedance)

    @property
    def error(self):
        return max(self.error_added_mass, self.error_damping)


def fit_errors(poles, coef, omega, added_mass, damping, added_mass_inf, shift=0.0):
    kf = evaluate(poles, coef, 1j * omega)
    a_fit = added_mass_inf + shift + kf.imag / omega
    b_fit = kf.real
    scale_a = max(np.max(np.abs(added_mass - added_mass_inf)), 1e-300)
    scale_b = max(np.max(np.abs(damping)), 1e-300)
    return (float(np.max(np.abs(a_fit - added_mass)) / scale_a),
            float(np.max(np.abs(b_fit - damping)) / scale_b))


def fit_pair(omega, added_mass, damping, added_mass_inf, nmax=12, tol=0.02, passive=False,
             omega_max=None):
    """Lowest order in 2..nmax whose A and B errors are both below tol (else the best one);
    the data are K(0) = 0 and the grid. With passive (a diagonal pair), only fits whose
    damping B_fit(w) >= -PASSIVE_SLACK max B over 0..20 omega_max count, as long as one
    order gives one: a fit that makes energy can drive the time-domain motion unbounded."""
    omega = np.asarray(omega, float)
    s = np.concatenate([[0.0], omega]) * 1j
    k = np.concatenate([[0.0], damping + 1j * omega * (added_mass - added_mass_inf)])
    scale = np.max(np.abs(k))
    w_top = omega[-1] if omega_max is None else omega_max
    best, best_passive = None, None
    for order in range(2, nmax + 1):
        try:
            poles, coef = vector_fit(s, k / scale, order)
        except np.linalg.LinAlgError:
            continue
        if passive and _min_fit_damping(poles, coef * scale, w_top, damping) < -PASSIVE_SLACK:
            best_raw = (poles, coef * scale)
            coef = passive_residues(s, k / scale, poles, coef, w_top)
            if coef is None:
                poles, coef = best_raw
                coef = coef / scale
        coef = coef * scale
        ea, eb = fit_errors(poles, coef, omega, added_mass, damping, added_mass_inf)
        candidate = (max(ea, eb), order, poles, coef, ea, eb)
        if best is None or max(ea, eb) < best[0] - 1e-12:
            best = candidate
        ok = not passive or _min_fit_damping(poles, coef, w_top, damping) >= -PASSIVE_SLACK
        if ok and (best_passive is None or max(ea, eb) < best_passive[0] - 1e-12):
            best_passive = candidate
        if ok and max(ea, eb) < tol:
            break
    _, order, poles, coef, ea, eb = best_passive if best_passive is not None else best
    a, b, c = realisation(poles, coef)
    return PairFit(order, a, b, c, poles, coef, ea, eb, float("nan"))


# DOF parity under the reflections y -> -y (about the centreline plane) and x -> -x (about
# the transverse plane through the CG): +1 even, -1 odd. A pair of opposite parity under a
# symmetry of the hull has A_ij = B_ij = K_ij = 0 identically.
PARITY_Y = np.array([1, -1, 1, -1, 1, -1])      # surge, heave, pitch even; sway, roll, yaw odd
PARITY_X = np.array([-1, 1, 1, 1, -1, -1])      # sway, heave, roll even; surge, pitch, yaw odd


def _mirror_of_itself(points, axis, tol):
    """Whether the point set maps onto itself when coordinate `axis` changes sign."""
    key = np.round(points / tol).astype(np.int64)
    mirrored = key.copy()
    mirrored[:, axis] = -mirrored[:, axis]
    # compare as sorted row sets (rounding may split a point across a cell: allow +-1)
    a = key[np.lexsort(key.T[::-1])]
    b = mirrored[np.lexsort(mirrored.T[::-1])]
    return a.shape == b.shape and bool(np.all(np.abs(a - b) <= 1))


def symmetry_zero_pairs(vertices, cg, tol=None):
    """(6, 6) bool: the radiation pairs that the hull's symmetries make zero, from its mesh
    vertices (mesh frame, Capytaine's: y to port) and the CG (rotation centre): a mesh equal
    to its mirror image in y about the CG's plane kills the pairs of opposite y-parity
    (surge/heave/pitch with sway/roll/yaw), in x likewise with PARITY_X."""
    v = np.asarray(vertices, float) - np.asarray(cg, float)
    if tol is None:
        tol = 1e-6 * max(float(np.ptp(v, axis=0).max()), 1e-300)
    zero = np.zeros((6, 6), bool)
    for axis, parity in ((1, PARITY_Y), (0, PARITY_X)):
        if _mirror_of_itself(v, axis, tol):
            zero |= np.outer(parity, parity) < 0
    return zero


def significant_pairs(kernel, relative=1e-3):
    """(6, 6) bool: pairs whose max |K_ij| exceeds `relative` times the geometric mean of
    max |K_ii| and max |K_jj| (the scale of the diagonal kernels of the same two DOFs)."""
    peak = np.max(np.abs(kernel), axis=0)
    diag = np.sqrt(np.outer(np.diag(peak), np.diag(peak)))
    return peak > relative * diag


# passivity: a diagonal kernel's fitted damping may dip below zero by this fraction of its
# largest value, anywhere over 0..20 w_N (the lifeboat's shipped database; fit_pair now
# prefers fits within PASSIVE_SLACK, the rounding of a positive fit)
PASSIVITY_FLOOR = 0.05
PASSIVE_SLACK = 1e-3


def _min_fit_damping(poles, coef, omega_max, damping):
    w = np.linspace(1e-3, 20.0 * omega_max, 20000)
    return float(np.min(evaluate(poles, coef, 1j * w).real)
                 / max(np.max(np.abs(damping)), 1e-300))


MIN_RESOLVED = 4    # fewer resolved frequencies than this: the grid is kept whole


def resolved_frequencies(omega, damping):
    """(nw,) bool: the frequencies a fit uses. A diagonal damping B_ii < 0 is impossible for a
    body that radiates (the mean power it radiates, w^2 B_ii |xi_i|^2 / 2, is >= 0): the
    mesh does not resolve that wave (the 288-panel Wigley hull at 16 rad/s: a 0.24 m wave on
    0.125 m panels, B_55 < 0 and B_33 a sixth of its trend). That frequency and every higher
    one are left out, the lower ones kept; if fewer than MIN_RESOLVED would be left (a grid
    too short to fit without them) all are kept."""
    diag = np.diagonal(np.asarray(damping, float), axis1=1, axis2=2)
    bad = np.nonzero(np.any(diag < 0.0, axis=1))[0]
    keep = np.ones(len(omega), bool)
    if bad.size and bad[0] >= MIN_RESOLVED:
        keep[bad[0]:] = False
    return keep


def _impedance(omega, added_mass, damping, mass, stiffness):
    """|Z(w)| = |C - w^2 (M + A) + i w B| of one degree of freedom."""
    return np.abs(stiffness - omega**2 * (mass + added_mass) + 1j * omega * damping)


def impedance_error(fit, omega, added_mass, damping, added_mass_inf, mass, stiffness):
    """max over the grid of w |K_fit(i w) - K(i w)| / |Z(w)|: the relative error of a
    one-degree-of-freedom RAO that the fit's error makes (xi = X / Z and Z = C - w^2 (M +
    A_inf) + i w K, so d xi / xi = -i w dK / Z); largest near the resonance, where |Z| is
    the damping alone."""
    kf = evaluate(fit.poles, fit.coef, 1j * omega) + 1j * omega * fit.added_mass_shift
    k = damping + 1j * omega * (added_mass - added_mass_inf)
    return float(np.max(omega * np.abs(kf - k)
                        / _impedance(omega, added_mass, damping, mass, stiffness)))


def _vector_fit_shifted(s, f, order, weight, cap, iterations=40, min_damping=1e-3):
    """vector_fit of f(s) ~ sum_k r_k / (s - p_k) + e s with the rows weighted, e real (a
    shift of A_inf: the BEM's A_inf and a coarse mesh's A(w) near its last frequency need
    not agree with Kramers-Kronig, Perez and Fossen, Ocean Eng. 36, 2009) and the poles
    kept within |p| <= cap (a pole beyond the grid only extrapolates). Returns poles, null
    (columns: coefficients, e last, with K(0) = 0) and y (coefficients = null @ y)."""
    wpos = np.abs(s.imag)[np.abs(s.imag) > 0]
    poles = _initial_poles(order, wpos.min(), wpos.max())
    for _ in range(iterations):
        phi = _basis(s, poles)
        x = _lstsq_real(np.hstack([phi, s[:, None], -f[:, None] * phi]) * weight[:, None],
                        f * weight)
        a, b, c = realisation(poles, x[order + 1:])
        new = _relocate(np.linalg.eigvals(a - np.outer(b, c)), min_damping)
        new = [p * cap / abs(p) if abs(p) > cap else p for p in new]
        if sum(m for _, m in _split_poles(new)) != order:
            break
        poles = new
    g = np.concatenate([_basis(np.array([0.0 + 0.0j]), poles).real[0], [0.0]])
    null = np.linalg.svd(g[None, :])[2][1:].T
    phi = np.hstack([_basis(s, poles), s[:, None]]) @ null
    return poles, null, _lstsq_real(phi * weight[:, None], f * weight)


def _passive_kkt(s, f, poles, null, weight, omega_max, slack=PASSIVE_SLACK, iterations=50):
    """Residue perturbation (Gustavsen and Semlyen, IEEE Trans. Power Syst. 16(1), 2001):
    the weighted least-squares residues of _vector_fit_shifted (same poles) with Re K(i w_m)
    = 0 imposed exactly (Lagrange multipliers) at each local minimum w_m over 0..20
    omega_max where Re K < -slack max |Re f|, the set growing until no minimum is below.
    Returns the coefficients (e last), or None."""
    phi = np.hstack([_basis(s, poles), s[:, None]]) @ null * weight[:, None]
    m = np.vstack([phi.real, phi.imag])
    r = np.concatenate([(f * weight).real, (f * weight).imag])
    w = np.linspace(1e-3, 20.0 * omega_max, 20000)
    scale = np.linalg.norm(m, axis=0)
    scale[scale == 0.0] = 1.0
    m = m / scale
    dense = (np.hstack([_basis(1j * w, poles).real, np.zeros((w.size, 1))]) @ null) / scale
    tol = slack * np.max(np.abs(f.real))
    z = np.linalg.lstsq(m, r, rcond=None)[0]
    active = []
    for _ in range(iterations):
        excess = -tol - dense @ z
        peak = (excess > 0) & (excess >= np.roll(excess, 1)) & (excess >= np.roll(excess, -1))
        new = [k for k in np.nonzero(peak)[0] if k not in active]
        if not new:
            return null @ (z / scale)
        active += new
        g = dense[active]
        kkt = np.block([[m.T @ m, g.T], [g, np.zeros((len(active), len(active)))]])
        z = np.linalg.lstsq(kkt, np.concatenate([m.T @ r, np.zeros(len(active))]),
                            rcond=None)[0][:m.shape[1]]
    return None


def fit_impedance(omega, added_mass, damping, added_mass_inf, mass, stiffness, nmax=12,
                  omega_max=None):
    """A passive fit of a diagonal pair that minimises impedance_error: vector fitting with
    each frequency weighted by w / |Z(w)| (the RAO's sensitivity to K), A_inf shifted by a
    fitted e, the poles within the grid's band, and the residues perturbed to passivity
    (_passive_kkt) where the fit's damping dips below -PASSIVE_SLACK max B over 0..20
    omega_max; of orders 2..nmax the passive one with the least impedance_error. None if
    no order gives a passive fit."""
    omega = np.asarray(omega, float)
    w_top = omega[-1] if omega_max is None else omega_max
    s = np.concatenate([[0.0], omega]) * 1j
    k = np.concatenate([[0.0], damping + 1j * omega * (added_mass - added_mass_inf)])
    scale = np.max(np.abs(k))
    weight = omega / _impedance(omega, added_mass, damping, mass, stiffness)
    weight = np.concatenate([[weight[0]], weight]) / weight.max()
    best = None
    for order in range(2, nmax + 1):
        try:
            poles, null, y = _vector_fit_shifted(s, k / scale, order, weight, omega[-1])
            coef = null @ y
            if _min_fit_damping(poles, coef[:-1], w_top, damping / scale) < -PASSIVE_SLACK:
                coef = _passive_kkt(s, k / scale, poles, null, weight, w_top)
        except np.linalg.LinAlgError:
            continue
        if coef is None:
            continue
        coef = coef * scale
        fit = PairFit(order, *realisation(poles, coef[:-1]), poles, coef[:-1],
                      *fit_errors(poles, coef[:-1], omega, added_mass, damping,
                                  added_mass_inf, coef[-1]), float("nan"),
                      added_mass_shift=float(coef[-1]))
        if _min_fit_damping(poles, fit.coef, w_top, damping) < -PASSIVE_SLACK:
            continue
        fit.error_impedance = impedance_error(fit, omega, added_mass, damping,
                                              added_mass_inf, mass, stiffness)
        if best is None or fit.error_impedance < best.error_impedance:
            best = fit
    return best


def min_damping(fit, omega_max, damping):
    """min over 0..20 omega_max of B_fit(w) / max |B| (negative: the fit makes energy)."""
    return _min_fit_damping(fit.poles, fit.coef, omega_max, damping)


def _with_tail(omega, added_mass, damping, added_mass_inf, tail):
    """The data extended beyond the last frequency w_N to w_N * tail with B_N (w_N/w)^2
    and A_inf + (A_N - A_inf) (w_N/w)^2, the decay of a strictly proper kernel (and the
    tail of the cosine transform in retardation)."""
    wt = omega[-1] * np.asarray(tail, float)
    r2 = (omega[-1] / wt)**2
    return (np.concatenate([omega, wt]),
            np.concatenate([added_mass, added_mass_inf + (added_mass[-1] - added_mass_inf) * r2]),
            np.concatenate([damping, damping[-1] * r2]))


def fit_all(omega, added_mass, damping, added_mass_inf, time, kernel, nmax=12, tol=0.02,
            relative=1e-3, window=30.0, tail=None, zero=None, mass=None, stiffness=None,
            omega_max=None):
    """Fits of every significant pair: dict (i, j) -> PairFit, with the retardation error
    over 0..window s filled in. Pairs that `zero` ((6, 6) bool: symmetry_zero_pairs) marks
    are not fitted. Diagonal pairs are fitted passive (fit_pair).

    With tail (multiples of the last frequency, e.g. (1.25, 1.5, 2, 3, 4, 6)) each pair is
    first fitted to the data extended by _with_tail: without it a fit that must still
    bring A(w) to A_inf past the grid can put a nearly undamped pole just beyond it, whose
    damping there is large and negative (the lifeboat's heave: -7 x max B at 8.4 rad/s).
    Where that fit misses tol on the grid, the plain fit replaces it if it is better and,
    for a diagonal pair, passive (min B_fit >= -PASSIVITY_FLOOR max B): e.g. a damping
    still rising at the grid's end (the lifeboat's roll) does not follow the assumed tail.
    The errors are always those on the grid.

    With mass and stiffness ((6, 6): the rigid-body mass and hydrostatic matrices), a
    diagonal fit that still misses tol is replaced by fit_impedance's if that one's
    impedance_error (the RAO error it makes) is smaller. Passivity is checked over 0..20
    omega_max (default the last frequency: give the database's when omega is the part of
    it that resolved_frequencies keeps)."""
    sig = significant_pairs(kernel, relative)
    w_top = omega[-1] if omega_max is None else omega_max
    if zero is not None:
        sig &= ~np.asarray(zero, bool)
    fits = {}
    for i in range(6):
        for j in range(6):
            if not sig[i, j]:
                continue
            data = (omega, added_mass[:, i, j], damping[:, i, j])
            fit = None
            if tail is not None:
                fit = fit_pair(*_with_tail(*data, added_mass_inf[i, j], tail),
                               added_mass_inf[i, j], nmax=nmax, tol=tol, passive=i == j,
                               omega_max=w_top)
                fit.error_added_mass, fit.error_damping = fit_errors(
                    fit.poles, fit.coef, *data, added_mass_inf[i, j])
                fit.tail = True
            if fit is None or fit.error > tol:
                plain = fit_pair(*data, added_mass_inf[i, j], nmax=nmax, tol=tol,
                                 passive=i == j, omega_max=w_top)
                passive = (i != j or min_damping(plain, w_top, data[2])
                           >= -PASSIVITY_FLOOR)
                if fit is None or (passive and plain.error < fit.error):
                    fit = plain
            if i == j and mass is not None:
                fit = _better_impedance(fit, data, added_mass_inf[i, i], mass[i, i],
                                        stiffness[i, i], nmax, tol, w_top)
            fits[(i, j)] = fit
    fill_errors(fits, time, kernel, damping, w_top, window)
    return fits


def fill_errors(fits, time, kernel, damping, omega_max, window):
    """Each fit's min_damping (over 0..20 omega_max) and K(t) error over 0..window s."""
    mask = time <= window
    for (i, j), fit in fits.items():
        fit.min_damping = min_damping(fit, omega_max, damping[:, i, j])
        kss = impulse_response(fit.poles, fit.coef, time[mask])
        kref = kernel[mask, i, j]
        fit.error_retardation = float(np.linalg.norm(kss - kref) /
                                      max(np.linalg.norm(kref), 1e-300))


def _better_impedance(fit, data, added_mass_inf, mass, stiffness, nmax, tol, omega_max):
    """fit, or fit_impedance's fit of the same data if fit misses tol and that one's
    impedance error is smaller (both with error_impedance filled in)."""
    fit.error_impedance = impedance_error(fit, *data, added_mass_inf, mass, stiffness)
    if fit.error <= tol:
        return fit
    other = fit_impedance(*data, added_mass_inf, mass, stiffness, nmax, omega_max)
    if other is not None and other.error_impedance < fit.error_impedance:
        return other
    return fit


def min_eigen_damping(fits, omega_max, damping, points=4000):
    """min over 0..20 omega_max of the smallest eigenvalue of the symmetric part of the
    fitted damping matrix, scaled by sqrt(max B_ii max B_jj) (>= 0: the radiation memory
    as a whole is passive)."""
    w = np.linspace(1e-3, 20.0 * omega_max, points)
    b = np.zeros((points, 6, 6))
    for (i, j), f in fits.items():
        b[:, i, j] = evaluate(f.poles, f.coef, 1j * w).real
    peak = np.sqrt(np.maximum(np.abs(damping).max(axis=0).diagonal(), 1e-300))
    b = b / np.outer(peak, peak)
    return float(np.min(np.linalg.eigvalsh(0.5 * (b + b.transpose(0, 2, 1)))))


def pack(fits):
    """Zero-padded arrays (order (6, 6) int32, a (6, 6, n, n), b (6, 6, n), c (6, 6, n),
    errors (3, 6, 6): added mass, damping, retardation) of a dict of PairFit."""
    nmax = max([f.order for f in fits.values()] + [1])
    order = np.zeros((6, 6), np.int32)
    a = np.zeros((6, 6, nmax, nmax))
    b = np.zeros((6, 6, nmax))
    c = np.zeros((6, 6, nmax))
    err = np.zeros((3, 6, 6))
    for (i, j), f in fits.items():
        n = f.order
        order[i, j] = n
        a[i, j, :n, :n], b[i, j, :n], c[i, j, :n] = f.a, f.b, f.c
        err[:, i, j] = f.error_added_mass, f.error_damping, f.error_retardation
    return order, a, b, c, err


def transfer(a, b, c, s):
    """C (s I - A)^-1 B of one (zero-padded) realisation at the points s."""
    n = a.shape[0]
    return np.array([c @ np.linalg.solve(si * np.eye(n) - a, b) for si in np.atleast_1d(s)])
