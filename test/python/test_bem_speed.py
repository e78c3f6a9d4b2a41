"""Forward-speed corrections of the radiation coefficients (postproc.bem_speed): Salvesen,
Tuck and Faltinsen's speed terms against the form they come from, the potentials of a body
making way, and the Timman-Newman relations."""
import numpy as np
import pytest

from postproc import bem_speed

RNG = np.random.default_rng(7)
# the couplings a port-starboard symmetric hull has (surge-heave-pitch and sway-roll-yaw);
# strip theory has no surge couplings either
COUPLED = np.zeros((6, 6), bool)
for group in ((2, 4), (1, 3, 5)):
    COUPLED[np.ix_(group, group)] = True
COUPLED[0, 0] = True


def _symmetric(n):
    m = RNG.normal(size=(n, 6, 6))
    return (m + m.transpose(0, 2, 1)) * COUPLED


def test_speed_terms_are_those_of_the_potentials_of_a_body_making_way():
    """With phi_5 = -x phi_3 + (U / (i w)) phi_3 and phi_6 = x phi_2 - (U / (i w)) phi_2
    (STF 1970, eqs. 22-23), the force coefficients T = -w^2 A + i w B become
    T(U) = T + (U / (i w)) (T E - E^T T) + (U / w)^2 E^T T E with E[3, 5] = 1,
    E[2, 6] = -1 (the speed part of the pitch and yaw potentials; the moment's -U d/dx
    term the transposed one): the table's A and B at three frequencies and speeds,
    both signs of U, to rounding."""
    omega = np.array([0.3, 0.8, 1.7])
    a0, b0 = 1e6 * _symmetric(3), 1e5 * _symmetric(3)
    e = np.zeros((6, 6))
    e[2, 4], e[1, 5] = 1.0, -1.0
    for speed in (2.57, -4.0, 7.5):
        a, b = bem_speed.stf_coefficients(omega, a0, b0, speed)
        for n, w in enumerate(omega):
            t0 = -w**2 * a0[n] + 1j * w * b0[n]
            s = speed / (1j * w)
            t = t0 + s * (t0 @ e - e.T @ t0) + (speed / w)**2 * e.T @ t0 @ e
            np.testing.assert_allclose(-w**2 * a[n] + 1j * w * b[n], t,
                                       rtol=1e-12, atol=1e-9 * np.abs(t0).max())


def test_speed_terms_obey_timman_newman():
    """A_ij(U) = A_ji(-U) and B_ij(U) = B_ji(-U) (Timman and Newman 1962) for symmetric
    zero-speed coefficients; at U = 0 nothing changes; the heave-pitch terms are the
    published ones, A35 = A35' - U B33 / w^2, B35 = B35' + U A33 (one case by hand)."""
    omega = np.array([0.5, 1.1])
    a0, b0 = 1e6 * _symmetric(2), 1e5 * _symmetric(2)
    ap, bp = bem_speed.stf_coefficients(omega, a0, b0, 3.0)
    am, bm = bem_speed.stf_coefficients(omega, a0, b0, -3.0)
    np.testing.assert_allclose(ap, am.transpose(0, 2, 1), rtol=1e-13)
    np.testing.assert_allclose(bp, bm.transpose(0, 2, 1), rtol=1e-13)
    assert not np.allclose(ap, ap.transpose(0, 2, 1))
    a, b = bem_speed.stf_coefficients(omega, a0, b0, 0.0)
    np.testing.assert_array_equal(a, a0)
    np.testing.assert_array_equal(b, b0)
    assert ap[1, 2, 4] == pytest.approx(a0[1, 2, 4] - 3.0 * b0[1, 2, 2] / 1.1**2)
    assert bp[1, 2, 4] == pytest.approx(b0[1, 2, 4] + 3.0 * a0[1, 2, 2])
    assert ap[1, 4, 4] == pytest.approx(a0[1, 4, 4] + 9.0 * a0[1, 2, 2] / 1.1**2)


def test_encounter_frequency():
    """w_e = w - k U cos(beta): head seas (180 deg) raise it by k U, following lower it,
    beam seas leave it (a 12.72 s wave at 5 kn: k U = 0.0639 rad/s)."""
    w = 2 * np.pi / 12.72
    ku = w * w / 9.81 * 2.57
    assert ku == pytest.approx(0.0639, abs=1e-4)
    assert bem_speed.encounter_frequency(w, np.pi, 2.57) == pytest.approx(w + ku)
    assert bem_speed.encounter_frequency(w, 0.0, 2.57) == pytest.approx(w - ku)
    assert bem_speed.encounter_frequency(w, 0.5 * np.pi, 2.57) == pytest.approx(w)
