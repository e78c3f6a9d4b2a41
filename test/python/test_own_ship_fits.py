"""The radiation fits behind your own ship's time domain (postproc.bem_fit): unresolved
frequencies left out by their rule, and the impedance-weighted passive fit against a kernel
known in closed form."""
import numpy as np
import pytest

from postproc import bem_fit

# a positive-real kernel in closed form: two parallel resonators
# K(s) = sum b s / (s^2 + 2 zeta w0 s + w0^2), so B(w) = Re K(i w)
# = sum b 2 zeta w0 w^2 / ((w0^2 - w^2)^2 + (2 zeta w0 w)^2) >= 0 and K(0) = 0
RESONATORS = ((100.0, 5.0, 0.3), (50.0, 12.0, 0.5))    # (b, w0, zeta)
A_INF = 30.0                                            # [kg]
MASS = 75.0
STIFFNESS = 7.0**2 * (MASS + 32.0)                      # resonance near 7 rad/s


def _kernel(w):
    s = 1j * w
    return sum(b * s / (s * s + 2 * z * w0 * s + w0 * w0) for b, w0, z in RESONATORS)


def _data(w):
    k = _kernel(w)
    return A_INF + k.imag / w, k.real


def test_frequencies_from_the_first_negative_diagonal_damping_on_are_left_out():
    """B_ii < 0 (no body radiates negative power) marks the first unresolved frequency:
    it and every higher one are dropped, a negative off-diagonal term is no sign; were
    fewer than 4 left, all are kept (the grid is too short to fit without them)."""
    omega = np.arange(1.0, 11.0)
    damping = np.ones((10, 6, 6))
    damping[:, 0, 4] = -1.0                      # a coupling may be negative
    assert bem_fit.resolved_frequencies(omega, damping).all()
    damping[7, 4, 4] = -1e-3                     # pitch at 8 rad/s
    damping[8, 4, 4] = 0.5                       # a later positive value is not trusted
    keep = bem_fit.resolved_frequencies(omega, damping)
    np.testing.assert_array_equal(keep, omega < 8.0)
    damping[3, 2, 2] = -1.0                      # heave at 4 rad/s: 3 would be left
    assert bem_fit.resolved_frequencies(omega, damping).all()


def test_impedance_fit_recovers_a_closed_form_kernel_and_the_shift_of_a_inf():
    """Data of the closed-form kernel with A_inf given 2 kg too high (as a coarse mesh's
    A(inf) can disagree with its A(w)): the fit reproduces K on the grid within 1e-4 of
    the RAO's scale (impedance_error), finds the shift -2 kg, and its damping is >= 0 up to
    20 x the last frequency."""
    omega = np.arange(1.0, 15.01, 0.25)
    added_mass, damping = _data(omega)
    fit = bem_fit.fit_impedance(omega, added_mass, damping, A_INF + 2.0, MASS, STIFFNESS)
    assert fit is not None
    assert fit.added_mass_shift == pytest.approx(-2.0, abs=1e-3)
    assert fit.error_impedance < 1e-4
    wide = np.linspace(1e-3, 20.0 * omega[-1], 20000)
    bfit = bem_fit.evaluate(fit.poles, fit.coef, 1j * wide).real
    assert bfit.min() >= -1e-3 * damping.max()
    np.testing.assert_allclose(bfit, _kernel(wide).real, atol=1e-3 * damping.max())


def test_residue_perturbation_makes_a_non_passive_fit_passive():
    """The kernel minus a resonance of B at 14 rad/s that takes its damping to -0.133 of
    the peak: the unconstrained fit follows it below zero; the perturbed residues
    (Gustavsen and Semlyen 2001) keep B_fit >= 0 (within 1e-3 of the peak) up to 20 x the
    last frequency at every order tried, and no passive B can come closer to the data than
    the dip's depth: theirs is within 5 % of that bound."""
    omega = np.arange(1.0, 15.01, 0.25)
    k = _kernel(omega)
    peak = k.real.max()
    k = k - 0.3 * peak * 0.25 / (0.25 + 1j * (omega - 14.0))
    depth = -k.real.min() / peak
    assert depth > 0.13
    s = np.concatenate([[0.0], omega]) * 1j
    f = np.concatenate([[0.0], k]) / peak
    weight = np.ones(s.size)
    wide = np.linspace(1e-3, 20.0 * omega[-1], 20000)
    for order in (6, 8, 10):
        poles, null, y = bem_fit._vector_fit_shifted(s, f, order, weight, omega[-1])
        plain = bem_fit.evaluate(poles, (null @ y)[:-1], 1j * wide).real
        assert plain.min() < -0.1, order             # the plain fit is not passive
        coef = bem_fit._passive_kkt(s, f, poles, null, weight, omega[-1])
        assert coef is not None, order
        assert bem_fit.evaluate(poles, coef[:-1], 1j * wide).real.min() >= -1e-3, order
        on_grid = bem_fit.evaluate(poles, coef[:-1], 1j * omega).real
        assert np.abs(on_grid - k.real / peak).max() <= 1.05 * depth, order


# a passive 2 x 2 kernel matrix in closed form: K(s) = sum_m P_m h_m(s) with
# h_m(s) = s / (s^2 + 2 zeta_m w0_m s + w0_m^2) (positive real: Re h_m(i w) >= 0) and P_m
# positive definite, so B(w) = sum_m P_m Re h_m(i w) is positive semi-definite at every w;
# the couplings make it nearly singular (det P_1 / P_1[0, 0]^2 = 1 - 0.8^2)
MATRIX_TERMS = ((np.array([[100.0, 80.0], [80.0, 100.0]]), 5.0, 0.3),
                (np.array([[60.0, -30.0], [-30.0, 60.0]]), 12.0, 0.5))
# the perturbed copy's coupling: a resonance beyond the grid (1..15 rad/s), as a fit that
# must bring A(w) to A_inf past its grid can place one (the Wigley hull's surge-pitch)
EXTRA = (40.0, 25.0, 0.1)


def _pole_residue(b, w0, zeta):
    """b h(s) = r / (s - p) + conj(r) / (s - conj(p)): (p, the basis coefficients Re r,
    Im r of postproc.bem_fit's real basis)."""
    p = complex(-zeta * w0, w0 * np.sqrt(1.0 - zeta * zeta))
    r = b * p / (p - np.conj(p))
    return p, [r.real, r.imag]


def _matrix_fits(extra=None):
    """The closed form's exact realisation as pair fits (poles of both terms in every pair),
    with `extra` (b, w0, zeta) added to both couplings."""
    from postproc.bem_fit import PairFit, realisation
    fits = {}
    for i in range(2):
        for j in range(2):
            poles, coef = [], []
            terms = [(p[i, j], w0, z) for p, w0, z in MATRIX_TERMS]
            if extra is not None and i != j:
                terms.append(extra)
            for b, w0, zeta in terms:
                p, c = _pole_residue(b, w0, zeta)
                poles.append(p)
                coef += c
            coef = np.array(coef)
            fits[(i, j)] = PairFit(len(coef), *realisation(poles, coef), poles, coef,
                                   np.nan, np.nan, np.nan)
    return fits


def _as_six(m2):
    """A (nw, 2, 2) matrix in the surge-pitch block of a (nw, 6, 6) one (the rest zero)."""
    out = np.zeros(m2.shape[:1] + (6, 6))
    out[:, 0:2, 0:2] = m2
    return out


def _closed_form(w):
    """(A(w) - A_inf, B(w)) of the closed form, (nw, 2, 2)."""
    k = sum(p[None, :, :] * (1j * w / (-w * w + 2j * z * w0 * w + w0 * w0))[:, None, None]
            for p, w0, z in MATRIX_TERMS)
    return k.imag / w[:, None, None], k.real


def _smallest_eigenvalue(fits, w, scale):
    """min over w of the smallest eigenvalue of the symmetric part of D^-1 B_fit D^-1."""
    b = np.zeros((w.size, 2, 2))
    for (i, j), f in fits.items():
        b[:, i, j] = bem_fit.evaluate(f.poles, f.coef, 1j * w).real / np.sqrt(scale[i] *
                                                                             scale[j])
    return np.linalg.eigvalsh(0.5 * (b + b.transpose(0, 2, 1)))[:, 0].min()


def test_matrix_passivity_restored_with_no_more_change_than_the_defect():
    """The closed form plus a coupling resonance at 25 rad/s: its fitted damping matrix has
    an eigenvalue of -0.17 of the diagonal's scale there. Enforced (postproc.bem_passive),
    the smallest eigenvalue on an independent grid to 400 rad/s (10^5 points and the band
    of the 25 rad/s pole) is >= -1e-3; the change of the fits on the grid, in the enforced
    norm (sum over pairs of |K_fit - K| / max |K_ij| squared), is no larger than removing
    the defect would be (the closed form is passive with the same poles, so the least
    change cannot exceed it; measured: 0.44 of it), and the diagonal dampings stay within
    1 % of the closed form's peak (measured 0.13 %)."""
    pytest.importorskip("scipy")
    from postproc import bem_passive
    omega = np.arange(1.0, 15.01, 0.25)
    da, b2 = _closed_form(omega)
    added_mass, damping = _as_six(da), _as_six(b2)
    a_inf = np.zeros((6, 6))
    check = np.unique(np.concatenate([np.linspace(1e-3, 400.0, 100001),
                                      25.0 + np.linspace(-10.0, 10.0, 2001)]))
    scale = b2.max(axis=0).diagonal()
    exact = _matrix_fits()
    assert _smallest_eigenvalue(exact, check, scale) >= -1e-12       # passive as built
    fits = _matrix_fits(EXTRA)
    before = _smallest_eigenvalue(fits, check, scale)
    assert before < -0.15
    perturbed = {k: f.coef.copy() for k, f in fits.items()}
    result = bem_passive.enforce(fits, omega, added_mass, damping, a_inf)
    assert result.converged
    assert result.min_eigenvalue_before == pytest.approx(before, abs=2e-3)
    assert _smallest_eigenvalue(fits, check, scale) >= -1e-3

    def distance(coefs_a, coefs_b):
        total = 0.0
        for (i, j), f in fits.items():
            kmax = np.abs(b2[:, i, j] + 1j * omega * da[:, i, j]).max()
            d = bem_fit.evaluate(f.poles, coefs_a[(i, j)] - coefs_b[(i, j)], 1j * omega)
            total += np.sum(np.abs(d / kmax)**2)
        return np.sqrt(total)

    after = {k: f.coef for k, f in fits.items()}
    exact_coefs = {k: np.concatenate([exact[k].coef, [0.0, 0.0]]) if k[0] != k[1]
                   else exact[k].coef for k in exact}
    changed, defect = distance(after, perturbed), distance(exact_coefs, perturbed)
    assert 0.0 < changed <= defect * (1.0 + 1e-6)
    for i in range(2):
        bfit = bem_fit.evaluate(fits[(i, i)].poles, fits[(i, i)].coef, 1j * omega).real
        np.testing.assert_allclose(bfit, b2[:, i, i], atol=0.01 * b2[:, i, i].max())


def test_matrix_passivity_leaves_a_passive_fit_alone():
    """The exact realisation of the closed form is passive: enforce changes nothing."""
    pytest.importorskip("scipy")
    from postproc import bem_passive
    omega = np.arange(1.0, 15.01, 0.25)
    da, b2 = _closed_form(omega)
    fits = _matrix_fits()
    coefs = {k: f.coef.copy() for k, f in fits.items()}
    result = bem_passive.enforce(fits, omega, _as_six(da), _as_six(b2), np.zeros((6, 6)))
    assert result.converged and result.iterations == 0
    assert result.min_eigenvalue_before >= 0.0
    for k, f in fits.items():
        np.testing.assert_array_equal(f.coef, coefs[k])


def test_least_norm_under_inequalities_has_its_closed_form():
    """min |z| subject to z_1 >= 1 and z_1 + z_2 >= -5: (1, 0), the second inactive; with
    z_1 - z_2 >= 3 too: its projection (1.5, -1.5), which satisfies the other two."""
    pytest.importorskip("scipy")
    from postproc import bem_passive
    g = np.array([[1.0, 0.0], [1.0, 1.0], [1.0, -1.0]])
    np.testing.assert_allclose(bem_passive._min_norm(g[:2], np.array([1.0, -5.0])),
                               [1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(bem_passive._min_norm(g, np.array([1.0, -5.0, 3.0])),
                               [1.5, -1.5], atol=1e-12)
