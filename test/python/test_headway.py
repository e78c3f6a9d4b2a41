"""The SOLAS 5-knot headway launch on the BEM/MMG ship (input/solas_headway.nml): the whole
launch (boat lowered from 15 m and released, ~83 s, ~2 s of compute each) run by davit in
calm water and in the oblique Level 4 and 5 seas of input/sweep_solas_headway.nml, with the
rudder autopilot holding the heading:

* calm water: the ship keeps its heading (to 1e-9 rad) and makes 5 kn: its CG's travel over
  the run equals 2.57 m/s x the run's duration within 0.1 %;
* Level 4 and 5 at 45 and 135 deg (regular Stokes-2, wind along the waves as the level's
  preset): heading error <= 2 deg throughout the launch;

and the ship alone:

* the same four seas for 600 s (seven launches long): heading error <= 2 deg, no larger in
  the last 200 s than in the first 200 s (no slow oscillation growing), the rudder within
  its rate limit (2.32 deg/s) in >= 95 % of the samples after the first 100 s; without
  the autopilot's notch at the encounter period the same gains lose the heading in the
  Level 5 sea at 45 deg (the rudder chases the wave-frequency yaw at its rate limit);

* the deck's linear hull derivatives are Kijima et al. 1990's regressions from Table 1's
  L_pp, B, d, C_b and the database's mass and A11(inf) (computed here);
* a steady 20 deg turn in calm water (no windage) equals the steady state of Yasukawa &
  Yoshimura 2015's eq. 4 (3 DOF, written here from the paper's formulas, scipy fsolve)
  with the BEM ship's added masses m_x = A11(inf), m_y = A22(inf) in its Kirchhoff terms,
  within 0.5 % (without them u is 6 % off, with the two swapped v 12 %).

Level 5 at 45 deg (stern-quartering sea and 10 m/s wind from the port quarter) was not
held within 2 deg (3.09 deg) by the PID behind a single 4 s low-pass filter; the notch at
the encounter period holds it (doc/howto/manoeuvres.md).
"""
import re

import h5py
import numpy as np
import pytest
from scipy.optimize import brentq, fsolve

from conftest import ROOT

DECK = (ROOT / "input" / "solas_headway.nml").read_text()
RHO = 1025.0
# Table 1 of the paper (input/iiib_level5_090.nml's &ship defaults)
LPP, BEAM, DRAUGHT, CB = 126.0, 20.8, 4.4, 0.68


def mmg_keys():
    """The deck's &mmg numbers as {key: value}."""
    group = DECK.split("&mmg", 1)[1].split("\n/", 1)[0]
    group = re.sub(r"!.*", "", group)
    return {k: float(v) for k, v in re.findall(r"(\w+)\s*=\s*([-+0-9.eE]+)", group)}


def database():
    """Mass, A11(inf), A22(inf) of the shipped database."""
    with h5py.File(ROOT / "input" / "ship_bem.nc") as h5:
        return (float(h5["davit_mass_matrix"][0, 0]), float(h5["davit_added_mass_inf"][0, 0]),
                float(h5["davit_added_mass_inf"][1, 1]))


def sea_deck(level, angle):
    """The headway deck in a regular Stokes-2 sea of `level` towards `angle` deg, the wind
    the level's preset along the waves (as input/sweep_solas_headway.nml makes it)."""
    text = DECK.replace("&sea\n  wave_type = 'calm'\n/",
                        f"&sea\n  level = {level}\n  wave_type = 'stokes2'\n"
                        f"  direction_deg = {angle}\n/")
    text = re.sub(r"&wind\n  speed = 0.0\n/\n", "", text)
    assert "stokes2" in text and "&wind" not in text
    return text


def run_deck(davit, folder, name, text):
    """Write the deck `text` as folder/name.nml, run it, return its record's path."""
    deck = folder / f"{name}.nml"
    deck.write_text(text)
    out = folder / f"{name}.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return out


def run(davit, folder, name, text):
    with h5py.File(run_deck(davit, folder, name, text)) as h5:
        return h5["time"][()], h5["ship/euler"][()], h5["ship/position"][()]


def test_calm_water_heading_and_speed(davit, tmp_path):
    t, euler, position = run(davit, tmp_path, "calm", DECK)
    assert "model = 'bem'" in DECK and "manoeuvring = 'mmg'" in DECK
    assert np.abs(euler[:, 2]).max() < 1e-9
    travel = position[-1, 0] - position[0, 0]
    assert travel == pytest.approx(2.57 * (t[-1] - t[0]), rel=1e-3)


@pytest.mark.parametrize("level, angle", [(4, 45), (4, 135), (5, 45), (5, 135)])
def test_oblique_sea_heading_held(davit, tmp_path, level, angle):
    t, euler, _ = run(davit, tmp_path, f"l{level}_{angle}", sea_deck(level, angle))
    assert t[-1] > 75.0  # the whole launch: released at ~83 s
    worst = np.degrees(np.abs(euler[:, 2])).max()
    assert worst <= 2.0, f"Level {level}, {angle} deg: heading error {worst:.2f} deg"
    # the sea moves the heading (a test that the waves act at all)
    assert worst > 0.3


def ship_alone(davit, folder, name, text, t_end):
    """Time, heading error [deg], rudder [deg] of the deck `text` as the ship alone."""
    text = re.sub(r"&simulation.*?\n/\n", f"&simulation\n  scene = 'ship'\n  t_end = {t_end}\n"
                  "  dt = 0.01\n  output_interval = 0.1\n/\n", text, flags=re.S)
    with h5py.File(run_deck(davit, folder, name, text)) as h5:
        return (h5["time"][()], np.degrees(h5["ship/euler"][:, 2]),
                np.degrees(h5["ship/rudder"][()]).ravel())


@pytest.mark.parametrize("level, angle", [(4, 45), (4, 135), (5, 45), (5, 135)])
def test_ship_alone_600s_heading_held_rudder_off_its_rate_limit(davit, tmp_path, level, angle):
    t, yaw, rudder = ship_alone(davit, tmp_path, f"s{level}_{angle}", sea_deck(level, angle),
                                600.0)
    assert t[-1] == pytest.approx(600.0)
    err = np.abs(yaw)
    assert err.max() <= 2.0, f"Level {level}, {angle} deg: {err.max():.2f} deg"
    assert err[t > 400.0].max() <= err[t < 200.0].max()
    rate = np.abs(np.gradient(rudder, t))[t > 100.0]
    assert np.mean(rate > 2.3) < 0.05


def test_without_notch_the_same_gains_lose_the_heading(davit, tmp_path):
    text = sea_deck(5, 45).replace("autopilot_notch = 'encounter'", "autopilot_notch = 'off'")
    assert "'off'" in text
    t, yaw, rudder = ship_alone(davit, tmp_path, "no_notch", text, 600.0)
    assert np.abs(yaw).max() > 4.0
    rate = np.abs(np.gradient(rudder, t))[t > 100.0]
    assert np.mean(rate > 2.3) > 0.3


def test_container_ship_linear_derivatives_are_kijima():
    k = mmg_keys()
    mass, a11, _ = database()
    q = 0.5 * RHO * LPP ** 2 * DRAUGHT
    kk, cbl = 2 * DRAUGHT / LPP, CB * BEAM / LPP
    assert k["y_v"] == pytest.approx(-(0.5 * np.pi * kk + 1.4 * cbl), abs=1e-5)
    assert k["y_r"] == pytest.approx(mass / q + a11 / q - 1.5 * cbl, abs=1e-5)
    assert k["n_v"] == pytest.approx(-kk, abs=1e-5)
    assert k["n_r"] == pytest.approx(-0.54 * kk + kk ** 2, abs=1e-5)
    assert k["m_x"] == pytest.approx(a11 / q, abs=1e-4)


def mmg_forces(k, u, vm, r, delta, n):
    """X, Y, N about midship of Yasukawa & Yoshimura 2015 (eqs. 5-27) for the &mmg set k."""
    sp = np.hypot(u, vm)
    v, rp, beta = vm / sp, r * LPP / sp, np.arctan2(-vm, u)
    q = 0.5 * RHO * LPP * DRAUGHT * sp ** 2
    xh = q * (-k["r0"] + k["x_vv"] * v ** 2 + k["x_vr"] * v * rp + k["x_rr"] * rp ** 2
              + k["x_vvvv"] * v ** 4)
    yh = q * (k["y_v"] * v + k["y_r"] * rp + k["y_vvv"] * v ** 3 + k["y_vvr"] * v ** 2 * rp
              + k["y_vrr"] * v * rp ** 2 + k["y_rrr"] * rp ** 3)
    nh = q * LPP * (k["n_v"] * v + k["n_r"] * rp + k["n_vvv"] * v ** 3
                    + k["n_vvr"] * v ** 2 * rp + k["n_vrr"] * v * rp ** 2 + k["n_rrr"] * rp ** 3)
    bp = beta - k["x_p"] * rp
    c2 = k["c2_plus"] if bp > 0 else k["c2_minus"]
    wake = (1 - k["w_p0"]) * (1 + (1 - np.exp(-k["c1"] * abs(bp))) * (c2 - 1))
    dp = k["propeller_diameter"]
    j = u * wake / (n * dp)
    kt = k["k0"] + k["k1"] * j + k["k2"] * j ** 2
    xp = (1 - k["t_p"]) * RHO * n ** 2 * dp ** 4 * kt
    eta = dp / k["rudder_span"]
    ur = k["epsilon"] * u * wake * np.sqrt(
        eta * (1 + k["kappa"] * (np.sqrt(1 + 8 * kt / (np.pi * j ** 2)) - 1)) ** 2 + 1 - eta)
    br = beta - k["l_r"] * rp
    vr = sp * (k["gamma_plus"] if br > 0 else k["gamma_minus"]) * br
    fn = (0.5 * RHO * k["rudder_area"] * (ur ** 2 + vr ** 2) * k["f_alpha"]
          * np.sin(delta - np.arctan2(vr, ur)))
    lever = (k["x_r"] + k["a_h"] * k["x_h"]) * LPP
    return np.array([xh + xp - (1 - k["t_r"]) * fn * np.sin(delta),
                     yh - (1 + k["a_h"]) * fn * np.cos(delta), nh - lever * fn * np.cos(delta)])


def steady_turn(k, delta, mx, my, mass):
    """(u, v, r) of the steady turn of eq. 4 (x_G = 0) at the self-propulsion rps of 5 kn."""
    n = brentq(lambda n: mmg_forces(k, 2.57, 0.0, 0.0, 0.0, n)[0], 0.3, 10.0, xtol=1e-14)

    def residual(x):
        u, vm, r = x
        f = mmg_forces(k, u, vm, r, delta, n)
        return [(f[0] + (mass + my) * vm * r) / 1e5, (f[1] - (mass + mx) * u * r) / 1e5,
                f[2] / 1e7]
    return fsolve(residual, [2.0, -0.3, 0.005], xtol=1e-13)


def test_steady_turn_with_bem_added_masses(davit, tmp_path):
    text = re.sub(r"&simulation.*?\n/\n", "&simulation\n  scene = 'ship'\n  t_end = 3000.0\n"
                  "  dt = 0.02\n  output_interval = 10.0\n/\n", DECK, flags=re.S)
    text = text.replace("  manoeuvring = 'mmg'\n",
                        "  manoeuvring = 'mmg'\n  area_front = 0.0, area_lateral = 0.0\n")
    text = text.replace("rudder_mode = 'autopilot'", "rudder_mode = 'fixed', rudder_deg = 20.0")
    deck = tmp_path / "turn.nml"
    deck.write_text(text)
    out = tmp_path / "turn.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out) as h5:
        v = h5["ship/velocity"][-1]
        r = h5["ship/angular_velocity"][-1, 2]
        psi = h5["ship/euler"][-1, 2]
    u_g = np.cos(psi) * v[0] + np.sin(psi) * v[1]
    v_g = -np.sin(psi) * v[0] + np.cos(psi) * v[1]
    mass, a11, a22 = database()
    ref = steady_turn(mmg_keys(), np.radians(20.0), a11, a22, mass)
    assert u_g == pytest.approx(ref[0], rel=5e-3)
    assert v_g == pytest.approx(ref[1], rel=5e-3)
    assert r == pytest.approx(ref[2], rel=5e-3)
    # the check discriminates: without the added masses u is 6 % off, swapped v 12 %
    assert abs(steady_turn(mmg_keys(), np.radians(20.0), 0.0, 0.0, mass)[0] / ref[0] - 1) > 0.03
    assert abs(steady_turn(mmg_keys(), np.radians(20.0), a22, a11, mass)[1] / ref[1] - 1) > 0.03
