"""The speed-versus-accuracy study tools (postproc/study.py) against analytic results:
the stability functions of RK4 and RODAS3 and the bounce-decay fit."""
import h5py
import numpy as np

from postproc import layout, study


def test_rk4_stability_function_is_the_taylor_polynomial_and_its_limit():
    z = 0.05 + 0.02j
    assert abs(study.stability_function("rk4", z) - np.exp(z)) < abs(z) ** 5 / 100
    # the imaginary-axis limit 2.83 (2 sqrt 2): |R(iy)| = 1 there, < 1 just below
    assert abs(abs(study.stability_function("rk4", 2j * np.sqrt(2))) - 1) < 1e-12
    assert abs(study.stability_function("rk4", 2.8j)) < 1


def test_rodas3_stability_function_order_and_l_stability():
    # order 3: local error ~ z^4, so halving z divides it by ~16
    e1 = abs(study.stability_function("rosenbrock", 0.02) - np.exp(0.02))
    e2 = abs(study.stability_function("rosenbrock", 0.01) - np.exp(0.01))
    assert 14 < e1 / e2 < 18
    # A-stable on the imaginary axis, L-stable: R -> 0 like 8/(3z) (header of rosenbrock.f90)
    y = np.linspace(0, 1e3, 20001)
    assert np.max(np.abs(study.stability_function("rosenbrock", 1j * y))) <= 1 + 1e-12
    z = -1e8
    assert abs(abs(study.stability_function("rosenbrock", z) * z) * 3 / 8 - 1) < 1e-3


def test_bounce_decay_recovers_a_damped_sine_with_drift(tmp_path):
    omega, zeta, dt = 70.0, 0.03, 2e-3
    t = np.arange(0, 3, dt)
    w = 0.1 * np.exp(-zeta * omega * t) * np.sin(omega * np.sqrt(1 - zeta**2) * t)
    w = w - 1e-4 * t
    path = tmp_path / "bounce.h5"
    with h5py.File(path, "w") as f:
        f[layout.TIME] = t
        f[layout.BOAT_VELOCITY] = np.column_stack([0 * t, 0 * t, w])
    om, sigma = study.bounce_decay(path)
    assert abs(om / (omega * np.sqrt(1 - zeta**2)) - 1) < 0.01
    assert abs(sigma / (zeta * omega) - 1) < 0.05
