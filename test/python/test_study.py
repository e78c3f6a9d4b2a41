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


def _run(time, x, contact=-1.0, sling=(100.0, 100.0), segment=(50.0,), impact=0.0):
    return {"time": np.asarray(time), "x": np.asarray(x), "a": np.zeros((len(time), 3)),
            "tension": np.zeros(len(time)), "contact": contact,
            "peak_sling": max(sling), "peak_segment": max(segment), "peak_impact": impact}


def test_compare_splits_at_first_contact_and_drops_an_off_grid_last_sample():
    t = np.arange(0.0, 1.0001, 0.02)
    ref_x = np.zeros((len(t), 3))
    ref = _run(t, ref_x, contact=0.5, sling=(100.0, 80.0), impact=20.0)
    ref["release"] = 0.3           # hooks let go at 0.3 s: on the falls only the 1 mm
    x = ref_x.copy()
    x[t < 0.5, 0] += 1e-3           # 1 mm before the reference's first contact
    x[t >= 0.5, 1] += 2e-2          # 2 cm after it
    # the run ended between samples (launch log): its last time is off the grid
    tr = np.append(t[:-1], 0.9713)
    x[-1] = [5.0, 5.0, 5.0]         # ... and that sample must not count
    run = _run(tr, x, sling=(110.0, 70.0), segment=(49.0,), impact=15.0)
    e = study.compare(run, ref)
    assert abs(e["err_smooth"] - 1e-3) < 1e-12
    assert abs(e["err_contact"] - 2e-2) < 1e-12
    assert abs(e["sling_err"] - 0.10) < 1e-12      # resolved peak 110 vs 100
    assert abs(e["segment_err"] - 0.02) < 1e-12
    assert abs(e["impact_err"] - 0.25) < 1e-12
    assert abs(e["err_falls"] - 1e-3) < 1e-12
    # no contact in either: every sample is "before contact", none after
    e = study.compare(_run(t, x[:len(t)] * 0), _run(t, ref_x))
    assert e["err_contact"] == 0.0 and e["impact_err"] == 0.0
