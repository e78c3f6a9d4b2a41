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
