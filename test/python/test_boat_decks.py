"""The lifeboat decks of input/ run and record their contact and floating physics."""
import math
import re
import pathlib

import numpy as np

from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]
G = 9.81


def _run_deck(davit, tmp_path, name, t_end=None):
    deck = tmp_path / name
    text = (ROOT / "input" / name).read_text()
    if t_end is not None:
        text = "\n".join(f"  t_end = {t_end}" if line.strip().startswith("t_end") else line
                         for line in text.splitlines())
    deck.write_text(text)
    out = tmp_path / (deck.stem + ".h5")
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return layout.load(out)


def test_drop_test_first_contact_and_rebound(davit, tmp_path):
    """The boat swings 0.2 m at 1 m/s onto the side on parallel 3 m slings: it translates
    as a pendulum of length 3 m, x = v0/w sin(w t), so contact at asin(0.2 w/v0)/w; the
    fender force peaks, the clearance dips below zero and the boat rebounds."""
    run = _run_deck(davit, tmp_path, "boat_drop_test.nml", t_end=0.4)
    run.require(layout.CONTACT + (layout.FIRST_CONTACT_TIME,), "contact record")
    w = math.sqrt(G / 3.0)
    expected = math.asin(0.2 * w / 1.0) / w
    first = float(np.ravel(run.get(layout.FIRST_CONTACT_TIME))[0])
    assert abs(first - expected) < 0.01 * expected, (first, expected)
    assert run.get(layout.CONTACT_CLEARANCE).min() < 0.0
    force = run.get(layout.CONTACT_FORCE)
    assert force.shape == (run.time.size, 2)
    assert force.max() > 1e5
    v = run.get(layout.BOAT_VELOCITY)
    assert v[-1, 1] > 0.5          # moving away from the ship after the impact


def test_floating_boat_settles_at_archimedes_draught(davit, tmp_path):
    """Released off equilibrium on calm water with zeta = 0.1: after 30 s the keel sits at
    the draught T = m/(rho A_wp) (A_wp of the 20 strips) and the heel has died out."""
    run = _run_deck(davit, tmp_path, "boat_floating.nml")
    x = -5.75 + (np.arange(20) + 0.5) * 11.5 / 20
    a_wp = np.sum(2.8 * (1 - np.abs(2 * x / 11.5) ** 4.3)) * 11.5 / 20
    draught = 8500.0 / (1025.0 * a_wp)
    z = run.get(layout.BOAT_POSITION)[:, 2]
    assert abs((z[-1] + 1.1) - draught) < 1e-3, (z[-1] + 1.1, draught)
    assert abs(run.get(layout.BOAT_EULER)[-1, 0]) < 1e-3
    assert float(np.ravel(run.get(layout.FIRST_CONTACT_TIME))[0]) < 0.0   # never near the ship


def test_lowering_scene_statics_gearing_and_rigging_record(davit, tmp_path):
    """The boat on the full davit rigging (reeving A, quasi-static sheaves): each hook
    carries W/2 at the equilibrium start (A6), the boat comes down at drum speed / 4 (A7),
    and the rigging datasets are written with their shapes."""
    run = _run_deck(davit, tmp_path, "lowering.nml", t_end=10.0)
    run.require((layout.RIGGING_SEGMENT_TENSION, layout.RIGGING_PAID_OUT), "rigging record")
    t = run.time
    hook = run.get(layout.SLING_TENSION)
    np.testing.assert_allclose(hook[0], [8500.0 * G / 2] * 2, rtol=1e-6)
    z = run.get(layout.BOAT_POSITION)[:, 2]
    i5, i10 = np.searchsorted(t, 5.0), t.size - 1
    speed = (z[i10] - z[i5]) / (t[i10] - t[i5])
    assert abs(speed - 0.7 / 4) < 0.01 * 0.7 / 4, speed
    paid = run.get(layout.RIGGING_PAID_OUT)
    # ramp 1 s to 0.7 m/s: paid out = 0.7 (t - 0.5) after the ramp
    assert abs(paid[-1] - 0.7 * (t[-1] - 0.5)) < 1e-6
    assert run.get(layout.RIGGING_SEGMENT_TENSION).shape[0] == t.size


def test_launch_with_frozen_ship_reproduces_lowering(davit, tmp_path):
    """Coupling regression: the 'launch' scene with the ship frozen at rest is the
    'lowering' scene (same boat trajectory and cable tensions, bitwise)."""
    low = _run_deck(davit, tmp_path, "lowering.nml", t_end=3.0)
    deck = tmp_path / "launch.nml"
    text = (ROOT / "input" / "lowering.nml").read_text()
    text = text.replace("scene = 'lowering'", "scene = 'launch'").replace(
        "t_end = 100.0", "t_end = 3.0") + "&ship\n  frozen = .true.\n/\n"
    deck.write_text(text)
    out = tmp_path / "launch.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    launch = layout.load(out)
    for name in (layout.BOAT_POSITION, layout.RIGGING_SEGMENT_TENSION):
        np.testing.assert_array_equal(launch.get(name), low.get(name))
    assert launch.has(layout.SHIP_POSITION, layout.SHIP_EULER)


def _run_text(davit, tmp_path, name, text):
    deck = tmp_path / name
    deck.write_text(text)
    out = tmp_path / (deck.stem + ".h5")
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return layout.load(out)


def test_integrators_agree_on_impact_and_lowering(davit, tmp_path):
    """RK4 and adaptive dopri5 (rtol 1e-8) agree through a fender impact (rebound velocity
    and peak force); RODAS3 at a 50x larger step reproduces the RK4 lowering (1 mm)."""
    drop = (ROOT / "input" / "boat_drop_test.nml").read_text().replace(
        "t_end = 5.0", "t_end = 0.5")
    rk4 = _run_text(davit, tmp_path, "drop_rk4.nml", drop)
    dp5 = _run_text(davit, tmp_path, "drop_dp5.nml", drop.replace(
        "&simulation\n", "&simulation\n  integrator = 'dopri5'\n  rtol = 1e-8\n"))
    np.testing.assert_allclose(dp5.get(layout.BOAT_VELOCITY)[-1],
                               rk4.get(layout.BOAT_VELOCITY)[-1], atol=1e-6)
    assert abs(dp5.get(layout.CONTACT_FORCE).max() / rk4.get(layout.CONTACT_FORCE).max()
               - 1) < 1e-6
    low = (ROOT / "input" / "lowering.nml").read_text().replace("t_end = 100.0", "t_end = 5.0")
    ref = _run_text(davit, tmp_path, "low_rk4.nml", low)
    ros = _run_text(davit, tmp_path, "low_ros.nml", low.replace(
        "dt = 2.0e-4", "dt = 1.0e-2\n  integrator = 'rosenbrock'\n  rtol = 1e-5"))
    z_ref = ref.get(layout.BOAT_POSITION)
    z_ros = ros.get(layout.BOAT_POSITION)
    np.testing.assert_allclose(z_ros[-1], z_ref[-1], atol=1e-3)
    assert ros.attrs["rhs_evaluations"] < ref.attrs["rhs_evaluations"]


def test_lowering_events_waterborne_and_release(davit, tmp_path):
    """The boat comes down at 0.175 m/s from 15 m (after the 1 s ramp: z = -15 +
    0.175 (t - 0.5)) and is waterborne when its CG reaches the Archimedes floating height
    T - 1.1 m; both hooks open 1 s later (the hold), the boat stays afloat, and the run
    ends 5 s after the release."""
    run = _run_deck(davit, tmp_path, "lowering.nml")
    x = -5.75 + (np.arange(20) + 0.5) * 11.5 / 20
    draught = 8500.0 / (1025.0 * np.sum(2.8 * (1 - np.abs(2 * x / 11.5) ** 4.3)) * 11.5 / 20)
    expected = 0.5 + (15.0 + draught - 1.1) / 0.175
    events = {name: float(np.ravel(run.get("events/" + name))[0])
              for name in ("waterborne_time", "release_time", "lowering_start_time", "end_time")}
    assert abs(events["waterborne_time"] - expected) < 0.2, (events, expected)
    assert abs(events["release_time"] - (events["waterborne_time"] + 1.0)) < 1e-3
    # the run ends &simulation after_release (5 s, review G24) after the hooks open
    assert events["lowering_start_time"] == 0.0
    assert abs(events["end_time"] - (events["release_time"] + 5.0)) < 2e-3
    z = run.get(layout.BOAT_POSITION)[:, 2]
    assert abs(z[-1] - (draught - 1.1)) < 1e-3


def test_f2_tension_settles_on_coupled_model(davit, tmp_path):
    """Paper fact F2 on the coupled 'launch' model (iiib_level5_090, drum held): from
    unstretched falls the cable tension settles to its static value (the equilibrium start,
    W/4 plus block weights over the parts' angle) within 5 % after 3 s."""
    base = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
        "t_end = 0.0 ", "t_end = 5.0 ").replace("drum_speed = 0.7", "drum_speed = 0.0")
    static = _run_text(davit, tmp_path, "f2_eq.nml", base)
    loose = _run_text(davit, tmp_path, "f2_loose.nml",
                      base.replace("reeving = 'a'", "reeving = 'a'\n  initial = 'unstretched'"))
    t = loose.time
    ref = static.get(layout.RIGGING_SEGMENT_TENSION)[0].mean()
    assert abs(ref / (8500.0 * G / 4) - 1) < 0.02        # W/4 plus the block weights
    late = loose.get(layout.RIGGING_SEGMENT_TENSION)[t >= 3.0].mean()
    assert abs(late / ref - 1) < 0.05, (late, ref)
    assert loose.get(layout.RIGGING_SEGMENT_TENSION)[t < 1.0].max() > 1.3 * ref  # the snatch


def test_lowering_divergence_is_caught_with_partial_output(davit, tmp_path):
    """RK4 at dt = 4e-3 s is beyond the stability limit of the block on its sling
    (2.83/1500 rad/s = 1.9e-3 s): the run stops with a message naming the time, the
    subsystem and the quantity, exits 1 and keeps its partial output marked incomplete."""
    text = (ROOT / "input" / "lowering.nml").read_text().replace(
        "t_end = 100.0", "t_end = 5.0").replace("dt = 2.0e-4", "dt = 4.0e-3")
    deck = tmp_path / "diverge.nml"
    deck.write_text(text)
    out = tmp_path / "diverge.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 1
    assert re.search(r"diverged at t = [0-9.]+ s: (boat|rigging state|ship) ", result.stderr), \
        result.stderr
    run = layout.load(out)
    assert not run.complete and 0 < run.time[-1] < 5.0


def test_multirate_divergence_names_the_fast_substep(davit, tmp_path):
    """mri2 at 0.02 s steps with 4 substeps puts the rigging's RK4 substep at 5e-3 s, past
    the block's limit (~2.2e-3 s) while the macro step is not the culprit: the run stops
    with the diagnostic, names the 0.005 s substep as the step that may exceed the limit,
    and keeps its partial output."""
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
        "t_end = 0.0 ", "t_end = 5.0 ").replace(
        "dt = 1.0e-3", "dt = 0.02, integrator = 'mri2', substeps = 4")
    deck = tmp_path / "mri2_diverge.nml"
    deck.write_text(text)
    out = tmp_path / "mri2_diverge.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 1
    assert re.search(r"diverged at t = [0-9.]+ s: .*step size 0\.005 s may exceed the "
                     r"stability limit", result.stderr), result.stderr
    run = layout.load(out)
    assert not run.complete and 0 < run.time[-1] < 5.0


def test_rk4_fourth_order_on_coupled_launch(davit, tmp_path):
    """Self-convergence of RK4 on the coupled launch (iiib_level5_090, first 2 s: ship in
    the ramping waves, boat on the falls, no contact): halving dt divides the change of the
    end state (boat CG, attitude, cable tensions / 1e4 N) by 2^4 = 16 (± 20 %)."""
    base = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
        "t_end = 0.0 ", "t_end = 2.0 ").replace("output_interval = 0.02", "output_interval = 0.4")
    ends = []
    for dt in ("8.0e-4", "4.0e-4", "2.0e-4"):
        run = _run_text(davit, tmp_path, f"order_{dt}.nml", base.replace("dt = 1.0e-3", f"dt = {dt}"))
        ends.append(np.concatenate([run.get(layout.BOAT_POSITION)[-1],
                                    run.get(layout.BOAT_EULER)[-1],
                                    run.get(layout.RIGGING_SEGMENT_TENSION)[-1] / 1e4]))
    ratio = np.abs(ends[0] - ends[1]).max() / np.abs(ends[1] - ends[2]).max()
    assert 12.8 < ratio < 19.2, ratio


def test_contact_step_limiting_locates_onset_and_resolves_impact(davit, tmp_path):
    """With dt = 1e-3 s away from contact and dt_contact = 1e-5 s near and during it, the
    drop test reproduces the run at 1e-5 s throughout: the onset is found within one
    contact step (1e-5 s), the rebound velocity within 1e-4 m/s and the peak fender force
    within 0.5 %, with < 10 % of the steps. Without the limit (dt = 1e-3 s throughout) the
    6 ms impact is not resolved: the peak force is off by more than 5 %."""
    drop = (ROOT / "input" / "boat_drop_test.nml").read_text().replace(
        "t_end = 5.0", "t_end = 0.5")
    fine = _run_text(davit, tmp_path, "fine.nml", drop)
    limited = _run_text(davit, tmp_path, "limited.nml", drop.replace(
        "dt = 1.0e-5", "dt = 1.0e-3\n  dt_contact = 1.0e-5"))
    onset = [float(np.ravel(r.get(layout.FIRST_CONTACT_TIME))[0]) for r in (fine, limited)]
    assert onset[0] > 0 and abs(onset[1] - onset[0]) <= 1.0e-5 + 1e-12, onset
    np.testing.assert_allclose(limited.get(layout.BOAT_VELOCITY)[-1],
                               fine.get(layout.BOAT_VELOCITY)[-1], atol=1e-4)
    peak = [r.get(layout.CONTACT_FORCE).max() for r in (fine, limited)]
    assert abs(peak[1] / peak[0] - 1) < 5e-3, peak
    assert limited.attrs["steps"] < 0.1 * fine.attrs["steps"]


def test_ship_wave_load_slow_clock_is_fourth_order(davit, tmp_path):
    """The ship's Froude-Krylov loads sampled every wave_update and interpolated by cubic
    Hermite: the boat CG error against evaluation at every stage falls as wave_update^4
    (halving it divides the error by 16, +-35 %) on 8 s of the irregular Level 5 launch."""
    base = (ROOT / "input" / "iiib_level5_090_irregular.nml").read_text().replace(
        "t_end = 0.0 ", "t_end = 8.0 ").replace("output_interval = 0.02", "output_interval = 0.1")
    # the irregular decks set wave_update themselves: replace their line
    runs = [_run_text(davit, tmp_path, f"wu{i}.nml",
                      _set_line(base, "wave_update", f"  wave_update = {wu}"))
            for i, wu in enumerate(("0.0", "0.2", "0.1"))]
    x = [r.get(layout.BOAT_POSITION) for r in runs]
    e = [np.linalg.norm(xi - x[0], axis=1).max() for xi in x[1:]]
    assert e[1] > 1e-12, e
    assert 16 / 1.35 < e[0] / e[1] < 16 * 1.35, e


def _set_line(text, key, line):
    """Replace the deck line that sets `key` (exactly one) by `line`."""
    text, n = re.subn(rf"^\s*{key}\s*=.*$", line, text, flags=re.M)
    assert n == 1, (key, n)
    return text


def _launch_text(t_end, dt, output_interval, simulation="", boat=""):
    """iiib_level5_090 (the coupled 'launch' deck) with its window, step and output changed,
    keys added to &simulation and to &boat."""
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text()
    text = _set_line(text, "t_end", f"  t_end = {t_end}")
    text = _set_line(text, "output_interval", f"  output_interval = {output_interval}")
    text = _set_line(text, "dt", f"  dt = {dt}{simulation}")
    return _set_line(text, "position", "  position = 0.0, 13.3, -15.0" + boat)


# Smooth hanging start for the order studies: 0.05 m/s of heave excites the fast modes that
# carry the truncation error (boat bounce 54 rad/s, zeta 0.016; the blocks on their slings,
# 1258 rad/s with zeta 0.09 and 1144 rad/s undamped: eigenvalues of the launch Jacobian),
# while the falls stay taut (bounce amplitude 0.9 mm < 2.4 mm static stretch). The 0.1 rad
# heel keeps 1 m/s of the 10 m/s beam wind on b3: the box-projected wind drag (eq. 15,
# sum A_i |e_i|, review §1.4) is only continuous where a body component of the relative
# wind changes sign, which a level bouncing boat does at every bounce; that alone leaves
# ~1e-11 m of order-2 differences in the CG.
SMOOTH_START = "\n  velocity = 0.0, 0.0, 0.05\n  euler = 0.1, 0.0, 0.0"


def _order_runs(davit, tmp_path, integrator, t_end, dts, output_interval):
    runs = []
    for dt in dts:
        text = _launch_text(t_end, dt, output_interval, boat=SMOOTH_START, simulation=(
            f"\n  integrator = '{integrator}'\n  fixed_step = .true."))
        runs.append(_run_text(davit, tmp_path, f"{integrator}_{dt}.nml", text))
    for run in runs[1:]:
        np.testing.assert_allclose(run.time, runs[0].time, rtol=0, atol=1e-12)
    return runs


def _mean_order(series):
    """Mean observed order over successive halvings of dt: log2 of the first over the last
    successive difference, divided by the number of halvings between them."""
    d = [np.abs(a - b).max() for a, b in zip(series, series[1:])]
    return math.log2(d[0] / d[-1]) / (len(d) - 1), d


def test_dopri5_fifth_order_on_coupled_launch(davit, tmp_path):
    """Dormand-Prince with fixed steps (&simulation fixed_step) on the coupled launch
    (iiib_level5_090: free ship in the Stokes-2 beam sea, wind, boat on the reeving-A falls),
    first 0.5 s of the hanging phase (no contact), SMOOTH_START. dt = 8e-4, 4e-4, 2e-4, 1e-4:
    omega dt <= 1.0 on the 1258 rad/s block mode (inside DOPRI5's region, |R| = 0.9) and
    |R(i omega dt)| - 1 < 1e-6 on the undamped 1144 rad/s one. The error is carried by the
    fast transient, so the measure is the largest difference over the window (sampled every
    8e-4 s): halving dt divides it by 2^5 for the boat CG and the cable tension, mean order
    over the three halvings 5 ± 0.6 (measured 5.20, 5.22). The smallest CG difference
    (3.6e-13 m) is 7x the round-off floor (5e-14 m between dt = 1e-4 and 5e-5)."""
    runs = _order_runs(davit, tmp_path, "dopri5", 0.5, ("8.0e-4", "4.0e-4", "2.0e-4",
                                                         "1.0e-4"), 8.0e-4)
    for name in (layout.BOAT_POSITION, layout.RIGGING_SEGMENT_TENSION):
        order, diffs = _mean_order([run.get(name) for run in runs])
        assert abs(order - 5.0) < 0.6, (name, order, diffs)


def test_rosenbrock_third_order_on_coupled_launch(davit, tmp_path):
    """RODAS3 with fixed steps (&simulation fixed_step) on the same coupled launch and
    SMOOTH_START, dt = 3.2e-3, 1.6e-3, 8e-4, 4e-4 (L-stable: any dt is stable; omega dt = 4
    down to 0.5 on the block modes, which it damps instead of following). Its order 3 is
    that of the smooth solution, so the measure is the largest difference over 0.1-0.512 s,
    after the block transient (decay rate 113/s) has died out (sampled every 3.2e-3 s; one
    end sample alone can sit where the error components cancel): halving dt divides it by
    2^3 for the boat CG and the cable tension, mean order over the three halvings 3 ± 0.6
    (measured 2.93, 2.92)."""
    runs = _order_runs(davit, tmp_path, "rosenbrock", 0.512, ("3.2e-3", "1.6e-3", "8.0e-4",
                                                              "4.0e-4"), 3.2e-3)
    late = runs[0].time >= 0.1
    for name in (layout.BOAT_POSITION, layout.RIGGING_SEGMENT_TENSION):
        order, diffs = _mean_order([run.get(name)[late] for run in runs])
        assert abs(order - 3.0) < 0.6, (name, order, diffs)


def test_integrators_agree_through_fender_impact_on_coupled_launch(davit, tmp_path):
    """RK4 and adaptive dopri5 (rtol 1e-8) on the coupled launch (iiib_level5_090) with a
    fender impact: the ship's side is moved out to 0.2 m from the fenders (&contact side_y =
    11.7 m) and the boat swings onto it at 1 m/s; 0.3 s, both at the macro step dt = 1e-5 s
    (the contact phases advance at macro steps, so both see the same discrete contact law).
    Bound from the tolerance: dopri5 holds each step's error below rtol |y|, i.e. the CG
    (|r| = 20 m from the origin) to rtol |r| = 2e-7 m, and at this macro step it takes one
    internal step per dt, far below what the tolerance asks, so its global error stays
    within that; RK4 at dt = 1e-5 s has omega dt <= 0.013 on the fastest mode (1258 rad/s)
    and resolves the ~6 ms Hertz contact. So the CG tracks agree within rtol |r|, and the
    peak force, f = K delta^1.5, within 1.5 rtol |r| / delta_max (delta_max = 2 mm: 1.5e-4).
    Measured: first contact at 0.206 s, peak 2.35 MN, CG within 1.1e-9 m, peak force 5e-9."""
    rtol = 1.0e-8
    text = _launch_text(0.3, "1.0e-5", "1.0e-4", boat="\n  velocity = 0.0, -1.0, 0.0") + \
        "&contact\n  side_y = 11.7\n  law = 'hertz_elastoplastic'\n/\n"
    rk4 = _run_text(davit, tmp_path, "impact_rk4.nml", text)
    dp5 = _run_text(davit, tmp_path, "impact_dp5.nml", _set_line(
        text, "dt", f"  dt = 1.0e-5\n  integrator = 'dopri5'\n  rtol = {rtol}"))
    for run in (rk4, dp5):
        assert 0.0 <= float(np.ravel(run.get(layout.FIRST_CONTACT_TIME))[0]) < 0.3
        assert run.get(layout.CONTACT_FORCE).max() > 1e5
    r = rk4.get(layout.BOAT_POSITION)
    bound = rtol * np.linalg.norm(r, axis=1).max()
    assert np.abs(dp5.get(layout.BOAT_POSITION) - r).max() < bound
    delta_max = -rk4.get(layout.CONTACT_CLEARANCE).min()
    peak = rk4.get(layout.CONTACT_FORCE).max()
    assert abs(dp5.get(layout.CONTACT_FORCE).max() / peak - 1) < 1.5 * bound / delta_max


def test_iiia_full_scale_lowering_tension_and_release(davit, tmp_path):
    """Paper Section III.A at full scale (iiia_model_scale_1, first 46 s): winch mode 'boat'
    lowers the boat at 1.1 m/s; paper fact F2 (Fig. 13 is this experiment): the cable
    tension in air is (W + 2 m_block g)/4 within 2 % (review F2) for the Froude-scaled
    W = 11820 g; the boat meets the 4 m waves, is waterborne, the hooks open 1 s later and
    from then on carry nothing."""
    run = _run_deck(davit, tmp_path, "iiia_model_scale_1.nml", t_end=46.0)
    t = run.time
    z = run.get(layout.BOAT_POSITION)[:, 2]
    i5, i25 = np.searchsorted(t, 5.0), np.searchsorted(t, 25.0)
    speed = (z[i25] - z[i5]) / (t[i25] - t[i5])
    assert abs(speed / 1.1 - 1) < 0.01, speed
    tension = run.get(layout.RIGGING_SEGMENT_TENSION)[(t >= 3.0) & (t <= 8.0)].mean()
    assert abs(tension / ((11820.0 + 2 * 50.0) * G / 4) - 1) < 0.02, tension
    events = {name: float(np.ravel(run.get("events/" + name))[0])
              for name in ("waterborne_time", "release_time")}
    assert 0.0 < events["waterborne_time"] < 45.0, events
    assert abs(events["release_time"] - (events["waterborne_time"] + 1.0)) < 1e-3
    released = t > events["release_time"]
    assert released.any() and not run.get(layout.SLING_TENSION)[released].any()


def test_energy_after_release_counts_the_falls_where_they_were_left(davit, tmp_path):
    """After the hooks let go (iiib_level5_090, regular 4 m waves), /diagnostics/energy is
    the boat's kinetic and potential energy plus the falls' frozen elastic energy: it can
    change by at most what the boat's motion on the waves gives, m g (H + 1 m) ~ 4e5 J,
    not by the stretch of the released slings to wherever the boat drifts (9e8 J before)."""
    run = _run_deck(davit, tmp_path, "iiib_level5_090.nml")
    t = run.get(layout.TIME)
    e = run.get(layout.ENERGY)
    release = float(np.ravel(run.get("events/release_time"))[0])
    assert release > 0
    after = t > release
    at_release = e[np.searchsorted(t, release) - 1]
    assert np.max(np.abs(e[after] - at_release)) < 8500.0 * 9.81 * (4.0 + 1.0)


# ISO 17357-1 generic pneumatic fender curve (reaction / rated at 0, 5, ..., 60 % of D) and
# the 1000 x 1500 fender at 50 kPa (D 1 m, 182 kN): the source's numbers, not the code's.
FENDER_TABLE = [0.0, 0.03, 0.06, 0.10, 0.14, 0.19, 0.25, 0.32, 0.40, 0.51, 0.66, 0.82, 1.0]


def test_fender_swing_at_lsa_speed_matches_energy_estimate(davit, tmp_path):
    """input/fender_test.nml at the LSA Code's 3.5 m/s: each fender takes half the boat's
    kinetic energy, so its deflection is where the table's work reaches m v^2 / 4 and its
    peak force the table's reaction there; the boat's peak acceleration is 2 F / m (the 30 m
    slings add g/L x deflection, 0.5 %), and it rebounds at e_r = 0.8."""
    from postproc import fender_test
    deck = tmp_path / "fender_test_35.nml"
    deck.write_text(fender_test.deck_text("rubber_fender", 3.5))
    out = tmp_path / "fender_test_35.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    m = fender_test.impact_metrics(layout.load(out), 3.5)
    d = np.linspace(0.0, 0.6, 13)
    r = 182e3 * np.array(FENDER_TABLE)
    work = np.concatenate(([0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * 0.05)))
    delta = np.interp(0.25 * 8490.0 * 3.5**2, work, d)
    force = np.interp(delta, d, r)
    assert abs(m["deflection"] / delta - 1) < 0.01, (m["deflection"], delta)
    assert abs(m["force"] / force - 1) < 0.01, (m["force"], force)
    assert abs(m["accel"] / (2 * force / 8490.0) - 1) < 0.02, (m["accel"], force)
    assert abs(m["rebound"] - 0.8) < 0.01, m["rebound"]
