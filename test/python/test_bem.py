"""The ship's BEM database (postproc.bem): the shipped input/ship_bem.nc against closed
forms (Froude-Krylov forces and hydrostatics of the box), long-wave limits of its RAOs,
its state-space memory fits; and a tiny build with Capytaine."""
import pathlib
import subprocess
import sys

import h5py
import numpy as np
import pytest

from postproc import bem_db as db
from postproc import bem_fit, bem_rao

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATABASE = ROOT / "input" / "ship_bem.nc"
RHO, G = 1025.0, 9.81
# FK forces: the mesh's panel-centroid quadrature against the exact integrals
FK_TOLERANCE = 0.01
# hydrostatics: capytaine's waterplane integrals use panel centroids (BM 0.4 % low at 16
# panels across the beam)
HYDROSTATIC_TOLERANCE = 0.01
# the state-space fits are built to 2 % (bem --fit-tol), but the shipped file's were then
# made passive as a matrix with the zero-frequency added mass held (`bem passive`,
# input/ship_bem.md): that trades pair-wise accuracy for a memory that makes no energy
# (surge A 4.6 %, roll A 3.9 % and B 4.2 %, the others <= 2.6 %; before, not passive:
# <= 1.9 %). The motions they give are held to 1 % of each RAO's peak by
# test_bem_passive_default.py; here each diagonal fit within 5 %.
FIT_TOLERANCE = 0.05


@pytest.fixture(scope="module")
def base():
    return db.Database(DATABASE)


def _box(base):
    return base.attrs[db.ATTR_LENGTH], base.attrs[db.ATTR_BEAM], base.attrs[db.ATTR_DRAUGHT]


def _scalar(value):
    return float(np.asarray(value).reshape(-1)[0])


def test_database_is_the_default_box(base):
    assert base.attrs[db.ATTR_HULL_KIND] == "box"
    l, b, d = (_scalar(v) for v in _box(base))
    assert l == pytest.approx(np.sqrt(0.68) * 130.55, rel=1e-6)
    assert (b, d) == (20.8, 4.4)
    assert 1000 <= _scalar(base.attrs[db.ATTR_PANELS]) <= 2500
    assert np.allclose(base[db.CG], 0.0)
    assert base.omega.size >= 40 and base.omega[0] == pytest.approx(0.1)
    assert base.omega[-1] == pytest.approx(2.0)
    assert np.degrees(base.heading[-1]) == pytest.approx(360.0)
    x = base.excitation
    assert np.allclose(x[:, -1], x[:, 0], rtol=1e-12, atol=0.0)


def test_long_wave_limits(base):
    """At the lowest frequency (wave length 6 km) the ship follows the surface: heave
    displacement = -eta (z down), pitch = d eta/dx (bow up), roll = -d eta/dy (starboard
    down), i.e. xi_3 -> -1, xi_5 -> -i k cos(beta), xi_4 -> +i k sin(beta)."""
    w = base.omega[0]
    k = w**2 / G
    betas = np.radians([0.0, 45.0, 90.0, 135.0, 180.0, 270.0])
    xi, _ = bem_rao.raos(base, [w], betas, zeta=0.05)
    for n, beta in enumerate(betas):
        heave, roll, pitch = xi[0, n, 2], xi[0, n, 3], xi[0, n, 4]
        assert abs(heave - (-1.0)) < 0.02, (np.degrees(beta), heave)
        # resonance amplification (w / w_n)^2 ~ 1.5 % (pitch) and 1.6 % (roll) at 0.1 rad/s
        assert abs(pitch - (-1j * k * np.cos(beta))) < 0.04 * k, (np.degrees(beta), pitch / k)
        assert abs(roll - (1j * k * np.sin(beta))) < 0.04 * k, (np.degrees(beta), roll / k)


def _fk_quadrature(l, b, d, k, beta, n=(400, 100, 40)):
    """Froude-Krylov force and moment (about the origin at midship on the waterline) on the
    box by midpoint quadrature in davit's frame (x forward, y starboard, z down), per unit
    amplitude, for eta = Re[exp(i (w t - k (x cos beta + y sin beta)))]: the dynamic pressure
    is rho g exp(-k z) exp(-i k (x cos beta + y sin beta)), the load -int p n dS."""
    nx, ny, nz = n
    xs = (np.arange(nx) + 0.5) / nx * l - l / 2
    ys = (np.arange(ny) + 0.5) / ny * b - b / 2
    zs = (np.arange(nz) + 0.5) / nz * d
    dx, dy, dz = l / nx, b / ny, d / nz
    panels = []
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    panels.append((X, Y, np.full_like(X, d), (0.0, 0.0, 1.0), dx * dy))       # bottom
    for side in (-1.0, 1.0):
        X, Z = np.meshgrid(xs, zs, indexing="ij")
        panels.append((X, np.full_like(X, side * b / 2), Z, (0.0, side, 0.0), dx * dz))
        Y, Z = np.meshgrid(ys, zs, indexing="ij")
        panels.append((np.full_like(Y, side * l / 2), Y, Z, (side, 0.0, 0.0), dy * dz))
    load = np.zeros(6, complex)
    for x, y, z, normal, area in panels:
        p = RHO * G * np.exp(-k * z) * np.exp(-1j * k * (x * np.cos(beta) + y * np.sin(beta)))
        nvec = np.array(normal)
        f = -(p * area)[..., None] * nvec
        r = np.stack([x, y, z], axis=-1)
        load[:3] += f.reshape(-1, 3).sum(axis=0)
        load[3:] += np.cross(r, f).reshape(-1, 3).sum(axis=0)
    return load


@pytest.mark.parametrize("omega", [0.5, 1.0])
@pytest.mark.parametrize("beta_deg", [45.0, 180.0])
def test_froude_krylov_matches_closed_form(base, omega, beta_deg):
    l, b, d = (_scalar(v) for v in _box(base))
    iw = int(np.argmin(abs(base.omega - omega)))
    ib = int(np.argmin(abs(np.degrees(base.heading) - beta_deg)))
    assert base.omega[iw] == pytest.approx(omega) and np.degrees(base.heading[ib]) == beta_deg
    k, beta = omega**2 / G, np.radians(beta_deg)
    fk = base.froude_krylov[iw, ib]
    # heave in closed form: -rho g exp(-k d) int_bottom exp(-i k.x) dA (z down)
    heave = (-RHO * G * np.exp(-k * d) * l * b * np.sinc(k * l * np.cos(beta) / 2 / np.pi)
             * np.sinc(k * b * np.sin(beta) / 2 / np.pi))
    assert abs(fk[2] - heave) < FK_TOLERANCE * abs(heave)
    # all six components against quadrature, relative to the force / moment scale
    ref = _fk_quadrature(l, b, d, k, beta)
    assert abs(ref[2] - heave) < 1e-3 * abs(heave)
    f_scale, m_scale = np.max(np.abs(ref[:3])), np.max(np.abs(ref[3:]))
    assert np.max(np.abs(fk[:3] - ref[:3])) < FK_TOLERANCE * f_scale, (fk[:3], ref[:3])
    assert np.max(np.abs(fk[3:] - ref[3:])) < FK_TOLERANCE * m_scale, (fk[3:], ref[3:])


def test_hydrostatics_match_the_box(base):
    l, b, d = (_scalar(v) for v in _box(base))
    volume = l * b * d
    kg = d                                 # CG on the waterline
    gm_t = d / 2 + b**2 / (12 * d) - kg
    gm_l = d / 2 + l**2 / (12 * d) - kg
    c = base.stiffness
    tol = HYDROSTATIC_TOLERANCE
    assert _scalar(base[db.VOLUME]) == pytest.approx(volume, rel=1e-6)
    assert _scalar(base[db.WATERPLANE_AREA]) == pytest.approx(l * b, rel=1e-6)
    assert c[2, 2] == pytest.approx(RHO * G * l * b, rel=tol)
    assert c[3, 3] == pytest.approx(RHO * G * volume * gm_t, rel=tol)
    assert c[4, 4] == pytest.approx(RHO * G * volume * gm_l, rel=tol)
    # centre of buoyancy d/2 below the CG: +d/2 in davit's z down
    assert np.allclose(base[db.BUOYANCY_CENTRE], [0.0, 0.0, d / 2], atol=1e-9)
    assert base.mass[0, 0] == pytest.approx(RHO * volume, rel=1e-6)


@pytest.mark.parametrize("dof", [0, 1, 2, 3, 4])
def test_state_space_fit_reproduces_added_mass_and_damping(base, dof):
    n = base[db.SS_ORDER][dof, dof]
    assert n > 0
    a = base[db.SS_A][dof, dof, :n, :n]
    b = base[db.SS_B][dof, dof, :n]
    c = base[db.SS_C][dof, dof, :n]
    w = base.omega
    k = bem_fit.transfer(a, b, c, 1j * w)
    # Cummins' A(inf) of the fits (an impedance fit shifts it: davit_ss_added_mass_inf)
    with h5py.File(DATABASE, "r") as f:
        a_inf = f["davit_ss_added_mass_inf"][dof, dof]
    a_fit = a_inf + k.imag / w
    b_fit = k.real
    am, bd = base.added_mass[:, dof, dof], base.damping[:, dof, dof]
    a_err = np.max(np.abs(a_fit - am)) / np.max(np.abs(am - base.added_mass_inf[dof, dof]))
    b_err = np.max(np.abs(b_fit - bd)) / np.max(np.abs(bd))
    assert a_err < FIT_TOLERANCE and b_err < FIT_TOLERANCE, (a_err, b_err)
    assert a_err == pytest.approx(base[db.SS_FIT_ERROR_ADDED_MASS][dof, dof], rel=1e-6)
    # no memory at zero frequency: K(0) = -C A^-1 B = 0
    assert abs(c @ np.linalg.solve(a, b)) < 1e-6 * np.max(np.abs(bd))


def test_all_fitted_poles_are_stable(base):
    order = base[db.SS_ORDER]
    assert order.dtype == np.int32
    for i in range(6):
        for j in range(6):
            n = order[i, j]
            if n:
                assert np.all(np.linalg.eigvals(base[db.SS_A][i, j, :n, :n]).real < 0)
            assert not np.any(base[db.SS_A][i, j, n:, :]) and not np.any(base[db.SS_C][i, j, n:])


def test_rao_peaks_at_the_natural_frequencies(base):
    for dof in bem_rao.RESTORED:
        w = bem_rao.natural_frequency(base, dof)
        a = bem_rao.added_mass_at(base, dof, w)
        assert w == pytest.approx(np.sqrt(base.stiffness[dof, dof] / (base.mass[dof, dof] + a)),
                                  rel=1e-8)
        assert base.omega[0] < w < base.omega[-1]
    xi, _ = bem_rao.raos(base, None, np.radians([90.0]), zeta=0.05)
    w = base.omega
    # beam seas: heave (heavily damped) and roll (lightly damped) peak inside the grid, near
    # their undamped natural frequencies. (Pitch has no peak: at its 0.92 rad/s the wave is
    # 73 m long on a 108 m hull, and the pitch moment nearly cancels.)
    for dof, tol in ((2, 0.05), (3, 0.03)):
        amp = np.abs(xi[:, 0, dof])
        if dof == 2:
            amp = np.where(w > 0.5, amp, 0.0)   # skip the long-wave plateau |xi_3| -> 1
        else:
            amp = amp / w**2                     # per unit wave slope
        peak = int(np.argmax(amp))
        assert 0 < peak < len(w) - 1
        assert w[peak] == pytest.approx(bem_rao.natural_frequency(base, dof), rel=tol)


def test_rao_command_writes_h5_and_csv(tmp_path):
    out = tmp_path / "rao.h5"
    cmd = [sys.executable, "-m", "postproc.bem", "rao", str(DATABASE), "--headings-deg",
           "90", "180", "--omegas", "0.5", "0.8", "-o"]
    result = subprocess.run(cmd + [str(out)], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "natural period  roll" in result.stdout
    with h5py.File(out) as f:
        assert f[bem_rao.RAO_RE].shape == (2, 2, 6)
        assert f[bem_rao.NATURAL_PERIOD].shape == (6,)
    csv = tmp_path / "rao.csv"
    result = subprocess.run(cmd + [str(csv)], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert len(csv.read_text().splitlines()) == 1 + 2 * 2 * 6


def test_tiny_build_writes_every_davit_variable(tmp_path):
    """A ~200-panel box, 3 frequencies, 2 headings, the CG 10 m forward of midship: every
    davit variable with its shape, and the excitation phase referred to the CG."""
    pytest.importorskip("capytaine")
    out = tmp_path / "tiny.nc"
    cmd = [sys.executable, "-m", "postproc.bem", "build", "--panels", "200", "--omegas",
           "0.5", "0.8", "1.2", "--headings-deg", "0", "135", "--cg", "10", "0", "0", "-q",
           "-o", str(out)]
    result = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    tiny = db.Database(out)
    nw, nb = 3, 2
    nmax = int(tiny[db.SS_ORDER].max())
    shapes = {db.OMEGA: (nw,), db.HEADING: (nb,), db.WAVENUMBER: (nw,),
              db.ADDED_MASS: (nw, 6, 6), db.DAMPING: (nw, 6, 6),
              db.ADDED_MASS_INF: (6, 6), db.ADDED_MASS_ZERO: (6, 6),
              db.EXCITATION_RE: (nw, nb, 6), db.EXCITATION_IM: (nw, nb, 6),
              db.FROUDE_KRYLOV_RE: (nw, nb, 6), db.FROUDE_KRYLOV_IM: (nw, nb, 6),
              db.STIFFNESS: (6, 6), db.MASS: (6, 6), db.VOLUME: (),
              db.WATERPLANE_AREA: (), db.BUOYANCY_CENTRE: (3,), db.CG: (3,),
              db.SS_ORDER: (6, 6), db.SS_A: (6, 6, nmax, nmax), db.SS_B: (6, 6, nmax),
              db.SS_C: (6, 6, nmax), db.SS_FIT_ERROR: (6, 6),
              db.SS_FIT_ERROR_ADDED_MASS: (6, 6), db.SS_FIT_ERROR_DAMPING: (6, 6),
              db.SS_FIT_ERROR_RETARDATION: (6, 6)}
    assert set(shapes) | {db.RETARDATION_TIME, db.RETARDATION} == set(db.VARIABLES)
    for name, shape in shapes.items():
        assert tiny[name].shape == shape, name
    assert tiny.drift.shape == (nw, nb, 3)
    assert tiny[db.DRIFT_ENERGY_DEFECT].shape == (nw, nb)
    nt = tiny[db.RETARDATION_TIME].size
    assert tiny[db.RETARDATION].shape == (nt, 6, 6)
    with h5py.File(out) as f:
        for name in list(db.VARIABLES) + list(db.DRIFT_VARIABLES):
            assert f[name].dtype == (np.int32 if name == db.SS_ORDER else np.float64), name
            assert f[name].attrs["units"] and f[name].attrs["description"], name
        assert "added_mass" in f and "excitation_force" in f     # Capytaine's own dataset
    assert np.allclose(tiny[db.CG], [10.0, 0.0, 0.0])
    assert np.allclose(np.degrees(tiny.heading), [0.0, 135.0])
    # heave FK of the box referred to the CG at x_G = 10 m: the bottom integral of
    # exp(-i k ((x - x_G) cos b + y sin b)) puts a phase exp(+i k x_G cos b) on a real value
    l, b, d = (_scalar(v) for v in _box(tiny))
    for iw, w in enumerate(tiny.omega):
        k = w**2 / G
        for ib, beta in enumerate(tiny.heading):
            expected = (-RHO * G * np.exp(-k * d) * l * b
                        * np.sinc(k * l * np.cos(beta) / 2 / np.pi)
                        * np.sinc(k * b * np.sin(beta) / 2 / np.pi)
                        * np.exp(1j * k * 10.0 * np.cos(beta)))
            ratio = tiny.froude_krylov[iw, ib, 2] / expected
            assert abs(np.angle(ratio)) < 0.01, (w, beta, ratio)
            # 16 panels along 107 m: k h ~ 1 at 1.2 rad/s (7 % off there)
            if w <= 0.8:
                assert abs(abs(ratio) - 1) < 0.03, (w, beta, ratio)
