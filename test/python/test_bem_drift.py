"""Mean wave drift from the far field (postproc.bem_drift) on a coarse box, and the database's
drift coefficients as davit reads them (old databases without them, and the messages)."""
import pathlib
import shutil
import sys

import h5py
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from postproc import bem_db as db  # noqa: E402
from postproc import bem_drift as bd  # noqa: E402

RHO, G = 1025.0, 9.81
OMEGAS = (0.8, 1.2, 2.0)
DIRECTIONS = np.radians([0.0, 45.0, 90.0])   # Capytaine's: towards x, ..., towards y (port)


@pytest.fixture(scope="module")
def coarse():
    """The default box (107.65 x 20.8 x 4.4 m) on ~400 panels and a lid, solved at three
    frequencies: {omega: (results, body)} (6 radiation, 3 diffraction problems each)."""
    cpt = pytest.importorskip("capytaine")
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    from postproc import bem_build, bem_mesh
    hull = bem_mesh.box_hull(panels=400, omega_max=2.0)
    body, _, _ = bem_build.make_body(hull, (0.0, 0.0, 0.0))
    solver = cpt.BEMSolver()
    out = {}
    for w in OMEGAS:
        problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=w, rho=RHO, g=G)
                    for d in body.dofs]
        problems += [cpt.DiffractionProblem(body=body, wave_direction=b, omega=w, rho=RHO, g=G)
                     for b in DIRECTIONS]
        out[w] = solver.solve_all(problems, progress_bar=False)
        bem_build._clear_capytaine_cache()
    return out, body, hull


def _free(results, body, theta, zeta=0.0):
    """H_tot, H_tot' of the free box (no viscous damping), and the fixed box's i H_diff."""
    import capytaine as cpt
    h, hp = bd.kochin(results, body, theta)
    ds = cpt.assemble_dataset(results, hydrostatics=True)
    xi = cpt.post_pro.rao(ds).sel(radiating_dof=list(body.dofs)).transpose(
        "omega", "wave_direction", "radiating_dof").values[0]
    free = bd.total_kochin(h[6:], hp[6:], h[:6], hp[:6], xi)
    return free, (1j * h[6:], 1j * hp[6:])


def test_kochin_matches_capytaine_and_its_derivative(coarse):
    """bd.kochin is Capytaine's compute_kochin (to rounding), about any reference point, and
    H' its theta derivative (central differences, step 1e-5: 1e-6)."""
    from capytaine.post_pro.kochin import compute_kochin
    results, body, _ = coarse[0][1.2], coarse[1], coarse[2]
    theta = bd.theta_grid(72)
    ref = (3.0, -1.0)
    h, hp = bd.kochin(results, body, theta, ref)
    for n in (1, 7):
        expected = compute_kochin(results[n], theta, ref_point=ref)
        assert np.max(np.abs(h[n] - expected)) < 1e-12 * np.max(np.abs(expected))
        step = 1e-5
        fd = (compute_kochin(results[n], theta + step, ref_point=ref)
              - compute_kochin(results[n], theta - step, ref_point=ref)) / (2 * step)
        assert np.max(np.abs(hp[n] - fd)) < 1e-6 * np.max(np.abs(fd))


def test_energy_conservation_fixed_and_free(coarse):
    """A body that absorbs nothing scatters only what it takes from the incident wave (the
    optical theorem): omega Im H(beta) = -k^2 int |H|^2, for the fixed box (diffraction
    alone) and the freely floating one without viscous damping, within 5 % on 400 panels.
    This ties the scale of the two terms of the drift formula to each other."""
    (out, body, _), theta = coarse, bd.theta_grid()
    for w, results in out.items():
        k = w * w / G
        free, fixed = _free(results, body, theta)
        for h, what in ((fixed[0], "fixed"), (free[0], "free")):
            defect = bd.energy_defect(h, theta, DIRECTIONS, w, k)
            assert np.all(np.abs(defect) < 0.05), (w, what, defect)


def test_beam_seas_down_wave_and_the_wall_limit(coarse):
    """Beam seas push the box down-wave (waves towards +y: F_y > 0), more as the waves
    shorten, and short waves (2 rad/s: 15 m, k d = 1.8) are reflected whole by its side:
    F_y -> 1/2 rho g a^2 l, the vertical wall's drift per unit length (Faltinsen 1990, Sea
    loads on ships and offshore structures, eq. 5.47), here within 10 % below (the ends
    diffract); head-on alike on the 20.8 m end. The free box's drift is the fixed box's
    where it hardly moves (2 rad/s: 5 %) and smaller where it follows the wave."""
    (out, body, hull), theta = coarse, bd.theta_grid()
    wall = 0.5 * RHO * G * hull.length
    beam = []
    for w, results in out.items():
        k = w * w / G
        free, fixed = _free(results, body, theta)
        f_fixed = bd.mean_drift(*fixed, theta, DIRECTIONS, w, k, RHO)
        f_free = bd.mean_drift(*free, theta, DIRECTIONS, w, k, RHO)
        assert f_fixed[2, 1] > 0 and f_free[2, 1] > 0 and f_fixed[0, 0] > 0
        # symmetric hull in beam and head seas: no surge, no yaw moment; sway alike
        assert abs(f_fixed[2, 0]) < 1e-6 * wall and abs(f_fixed[0, 1]) < 1e-6 * wall
        assert abs(f_free[2, 2]) < 1e-6 * wall * hull.length
        beam.append(f_free[2, 1])
    assert beam[0] < beam[1] < beam[2] * 1.1
    w = 2.0
    free, fixed = _free(out[w], body, theta)
    f_fixed = bd.mean_drift(*fixed, theta, DIRECTIONS, w, w * w / G, RHO)
    f_free = bd.mean_drift(*free, theta, DIRECTIONS, w, w * w / G, RHO)
    assert 0.9 < f_fixed[2, 1] / wall < 1.0
    assert 0.9 < f_fixed[0, 0] / (0.5 * RHO * G * hull.beam) < 1.0
    assert abs(f_free[2, 1] / f_fixed[2, 1] - 1) < 0.05


def test_matches_capytaine_mean_drift_force(coarse):
    """The diagonal of Capytaine's own far_field_mean_drift_force (xarray interpolation and
    finite-difference theta derivative on its grid) agrees with bd.mean_drift (Fourier
    interpolation, analytic derivative) on the free box: surge and sway within 1 % of the
    largest, yaw within 2 %."""
    import capytaine as cpt
    from capytaine.io.xarray import kochin_data_array
    from capytaine.post_pro.mean_drift_force import far_field_mean_drift_force
    (out, body, hull) = coarse
    w = 1.2
    results = out[w]
    ds = cpt.assemble_dataset(results, hydrostatics=True)
    theta_c = np.linspace(-0.1, 2 * np.pi + 0.1, 2000)
    import xarray as xr
    far = kochin_data_array(results, xr.DataArray(theta_c, dims="theta",
                                                  coords={"theta": theta_c}))
    for name in ("wavenumber", "water_depth", "rho", "g"):
        far[name] = ds[name]
    xi = cpt.post_pro.rao(ds)
    xi = xi.assign_coords(radiating_dof=[str(d) for d in xi.radiating_dof.values])
    # its theta grid must hold every direction strictly inside: 45 and 90 deg
    keep = dict(wave_direction=DIRECTIONS[1:])
    theirs = far_field_mean_drift_force(xi.sel(**keep), far.sel(**keep))
    theta = bd.theta_grid()
    free, _ = _free(results, body, theta)
    mine = bd.mean_drift(*free, theta, DIRECTIONS, w, w * w / G, RHO)
    for n, beta in enumerate(DIRECTIONS[1:], start=1):
        sel = dict(omega=w, wave_direction_k=beta, wave_direction_l=beta)
        fx = float(theirs.drift_force_surge.sel(**sel).real)
        fy = float(theirs.drift_force_sway.sel(**sel).real)
        mz = float(theirs.drift_force_yaw.sel(**sel).real)
        scale = max(abs(mine[n, 0]), abs(mine[n, 1]))
        assert abs(fx - mine[n, 0]) < 0.01 * scale, (beta, fx, mine[n])
        assert abs(fy - mine[n, 1]) < 0.01 * scale, (beta, fy, mine[n])
        assert abs(mz - mine[n, 2]) < 0.02 * max(abs(mine[n, 2]), 1e-3 * scale * hull.length)


def _havelock(ka, nmax=None):
    """Mean drift force / (rho g A^2 a) on a fixed vertical circular cylinder through the whole
    (deep) water depth, the exact solution: the potential is exp(k z) times the 2-D scattering
    by a hard circle (Havelock 1940, Proc. R. Soc. A 175, 409-421; MacCamy and Fuchs 1954),
    whose far field gives the scattering width sigma(theta) = 2/(pi k) |sum_n eps_n B_n
    cos(n theta)|^2, B_n = -J_n'(ka)/H_n'(ka), and the drift is the momentum flux of deep-
    water waves (E c_g / c = rho g A^2 / 4 per unit width) times int sigma (1 - cos theta):
        F / (rho g A^2 a) = 1/(4 a) int sigma(theta) (1 - cos theta) dtheta."""
    from scipy.special import h1vp, jvp
    n = np.arange(nmax or int(2 * ka + 30))
    th = np.linspace(0.0, 2 * np.pi, 4001)[:-1]
    amp = (np.where(n == 0, 1.0, 2.0) * -jvp(n, ka) / h1vp(n, ka)) @ np.cos(np.outer(n, th))
    sigma = 2.0 / (np.pi * ka) * np.abs(amp) ** 2           # a = 1
    return float(np.sum(sigma * (1 - np.cos(th))) * (th[1] - th[0]) / 4)


def test_vertical_cylinder_against_havelock():
    """A fixed vertical cylinder (a = 1 m, draught 4 m: exp(-2 k T) <= 3e-4 of the flow left
    at the bottom for ka >= 1; ~1,100 panels, finer in the top 1.5 m; below the first
    irregular frequency, ka = 2.4) against the exact full-depth solution (_havelock): within
    4 % at ka = 1 and 2. The reference itself tends to the published short-wave limit
    2/3 rho g A^2 a (Faltinsen 1990, eq. 5.47 on a circle) within 1 % at ka = 30."""
    cpt = pytest.importorskip("capytaine")
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    assert abs(_havelock(30.0) / (2.0 / 3.0) - 1) < 0.01
    a, draught, nth = 1.0, 4.0, 40
    top = cpt.mesh_vertical_cylinder(length=1.5, radius=a, center=(0, 0, -0.75),
                                     resolution=(0, nth, 12))
    low = cpt.mesh_vertical_cylinder(length=draught - 1.5, radius=a,
                                     center=(0, 0, -(1.5 + draught) / 2), resolution=(0, nth, 8))
    bottom = cpt.mesh_disk(radius=a, center=(0, 0, -draught), normal=(0, 0, -1),
                           resolution=(6, nth))
    body = cpt.FloatingBody(mesh=top.join_meshes(low, bottom), dofs=cpt.rigid_body_dofs())
    solver, theta = cpt.BEMSolver(), bd.theta_grid()
    for ka in (1.0, 2.0):
        k = ka / a
        w = np.sqrt(G * k)
        result = solver.solve(cpt.DiffractionProblem(body=body, wave_direction=0.0, omega=w,
                                                     rho=RHO, g=G))
        h, hp = bd.kochin([result], body, theta)
        f = bd.mean_drift(1j * h, 1j * hp, theta, np.array([0.0]), w, k, RHO)
        ratio = f[0, 0] / (RHO * G * a) / _havelock(ka)
        assert abs(ratio - 1) < 0.04, (ka, ratio)


def test_shipped_database_drift_in_davit_frame():
    """input/ship_bem.nc's davit_drift: (omega, heading, surge/sway/yaw), waves travelling to
    starboard (davit heading 90 deg) push to starboard (+), to port (270) to port, head seas
    (180) aft; mirror symmetric to 1 %; energy conserved at 2 rad/s where the roll damping
    absorbs little (5 %)."""
    base = db.Database(ROOT / "input" / "ship_bem.nc")
    d = base.drift
    assert d.shape == (base.omega.size, base.heading.size, 3)
    deg = np.round(np.degrees(base.heading)).astype(int)
    i90, i180, i270 = (int(np.flatnonzero(deg == a)[0]) for a in (90, 180, 270))
    high = base.omega >= 0.6
    assert np.all(d[high, i90, 1] > 0) and np.all(d[high, i270, 1] < 0)
    assert np.all(d[high, i180, 0] < 0)
    assert np.allclose(d[:, i270, 1], -d[:, i90, 1], rtol=0.01, atol=1e-6 * d[:, i90, 1].max())
    defect = base[db.DRIFT_ENERGY_DEFECT]
    assert np.all(np.abs(defect[-1, [i90, i180]]) < 0.05)


def _deck(folder, database, drift="mean", model="bem"):
    deck = folder / "drift.nml"
    deck.write_text(f"&simulation scene = 'ship', t_end = 1.0 /\n"
                    f"&ship model = '{model}', database = '{database}', drift = '{drift}' /\n")
    return deck


def test_old_database_without_drift(davit, tmp_path):
    """A database written before the drift coefficients still reads (Python: drift None;
    davit: runs with drift = 'none'), and asking it for drift stops with a message naming
    the deck, the group, the key and the database, and a non-zero exit; so does drift on
    the box ship, which has no database."""
    old = tmp_path / "old.nc"
    shutil.copy(ROOT / "input" / "ship_bem.nc", old)
    with h5py.File(old, "a") as f:
        for name in db.DRIFT_VARIABLES:
            del f[name]
    assert db.Database(old).drift is None
    result = davit("run", _deck(tmp_path, old, "none"), "-o", tmp_path / "none.h5")
    assert result.returncode == 0, result.stderr
    deck = _deck(tmp_path, old, "newman")
    result = davit("run", deck, "-o", tmp_path / "x.h5")
    assert result.returncode != 0
    for word in ("drift.nml", "&ship", "drift = 'newman'", "old.nc", "davit_drift"):
        assert word in result.stderr, (word, result.stderr)
    result = davit("run", _deck(tmp_path, old, "mean", "fk_box"), "-o", tmp_path / "y.h5")
    assert result.returncode != 0
    for word in ("drift.nml", "&ship", "model = 'bem'", "'none'"):
        assert word in result.stderr, (word, result.stderr)
    result = davit("run", _deck(tmp_path, old, "sometimes"), "-o", tmp_path / "z.h5")
    assert result.returncode != 0 and "drift" in result.stderr
