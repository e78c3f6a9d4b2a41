"""The shipped BEM databases' radiation memories are passive as a matrix.

Cummins' memory force absorbs the mean power 1/2 U^H B(w) U over a period of a harmonic
motion U, B(w) the symmetric part of Re K(i w); the memory makes no energy if and only if
B(w) is positive semi-definite at every w. input/ship_bem.nc and input/boat_bem.nc were
built before `bem build` enforced that: their fitted matrices had a smallest eigenvalue of
-0.086 (ship, 2.12 rad/s) and -0.156 (boat, 8.58 rad/s) of the diagonal's scale. Both were
re-fitted with `python -m postproc.bem passive` (postproc.bem_refit); the ship's with its
memory's zero-frequency added mass A_inf(fit) + K'(0) held at Capytaine's A(0) (a re-fit
without that moved heave and sway 3.8 % and 2.7 % from it, beyond what the Munk-moment
test of the headway ship, ship_speed/zero_frequency_munk_moments, allows: 1 % and 2 %).
Everything here is evaluated from the stored realisations (A, B, C of each pair) with
numpy alone, not with postproc.bem_fit or postproc.bem_passive."""
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATABASES = [ROOT / "input" / "ship_bem.nc", ROOT / "input" / "boat_bem.nc"]
# postproc.bem_passive's criterion: no eigenvalue of D^-1 B D^-1 (D = diag sqrt(max_w
# B_ii) of the BEM data) below -1e-3 on a grid that reaches where every pole has died away
TOLERANCE = 1e-3


def _read(path):
    with h5py.File(path, "r") as f:
        return {k: f[k][()] for k in ("davit_ss_order", "davit_ss_a", "davit_ss_b",
                                      "davit_ss_c", "davit_omega", "davit_radiation_damping",
                                      "davit_added_mass", "davit_added_mass_inf",
                                      "davit_mass_matrix", "davit_hydrostatic_stiffness",
                                      "davit_excitation_re", "davit_excitation_im",
                                      "davit_heading")} | {
            "a_fit_inf": f["davit_ss_added_mass_inf"][()]
            if "davit_ss_added_mass_inf" in f else f["davit_added_mass_inf"][()]}


def _kernels(d, s):
    """(ns, 6, 6) K_ij(s) = C (s I - A)^-1 B of each stored pair (zero where not fitted),
    by the eigen-decomposition of A; and every pair's poles."""
    k = np.zeros((s.size, 6, 6), complex)
    poles = []
    for i in range(6):
        for j in range(6):
            n = int(d["davit_ss_order"][i, j])
            if n == 0:
                continue
            lam, v = np.linalg.eig(d["davit_ss_a"][i, j, :n, :n])
            cv = d["davit_ss_c"][i, j, :n] @ v
            vb = np.linalg.solve(v, d["davit_ss_b"][i, j, :n])
            k[:, i, j] = (cv * vb / (s[:, None] - lam[None, :])).sum(axis=1)
            poles.extend(lam)
    return k, np.array(poles)


def _dense_grid(d, poles):
    w_top = max(20.0 * d["davit_omega"][-1], 10.0 * np.max(np.abs(poles)))
    w = [np.linspace(1e-3, w_top, 20000)]
    for p in poles:
        if p.imag > 0:
            w.append(p.imag + abs(p.real) * np.linspace(-4.0, 4.0, 33))
    w = np.unique(np.concatenate(w))
    return w[w > 0]


def smallest_scaled_eigenvalue(path):
    """(min over the dense grid of the smallest eigenvalue of D^-1 sym(Re K(i w)) D^-1, w)."""
    d = _read(path)
    _, poles = _kernels(d, np.array([1j]))
    w = _dense_grid(d, poles)
    k, _ = _kernels(d, 1j * w)
    b = k.real
    b = 0.5 * (b + b.transpose(0, 2, 1))
    scale = np.sqrt(np.abs(d["davit_radiation_damping"]).max(axis=0).diagonal())
    ev = np.linalg.eigvalsh(b / np.outer(scale, scale))[:, 0]
    return float(ev.min()), float(w[np.argmin(ev)])


@pytest.mark.parametrize("path", DATABASES, ids=lambda p: p.name)
def test_shipped_database_memory_is_passive_as_a_matrix(path):
    """The stored fits' damping matrix is positive semi-definite to 1e-3 of the
    diagonal's scale from 0 to where every pole has died away (the old files: -0.086 and
    -0.156); the file says so."""
    low, at = smallest_scaled_eigenvalue(path)
    assert low >= -TOLERANCE, (low, at)
    with h5py.File(path, "r") as f:
        assert int(np.ravel(f.attrs["fit_passive_matrix"])[0]) == 1
        assert float(np.ravel(f.attrs["fit_min_eigen_damping"])[0]) == pytest.approx(
            low, abs=2e-4)


def memory_zero_frequency_added_mass(path):
    """(A_inf(fit) + K'(0) of every pair (6, 6), the fitted-pairs mask, Capytaine's A(0)):
    K(s) = C (s I - A)^-1 B has K'(0) = -C A^-2 B, and the fitted added mass A_inf(fit) +
    Im K(i w)/w tends to A_inf(fit) + K'(0) as w -> 0."""
    d = _read(path)
    a0 = d["a_fit_inf"].copy()
    for i in range(6):
        for j in range(6):
            n = int(d["davit_ss_order"][i, j])
            if n:
                a = d["davit_ss_a"][i, j, :n, :n]
                a0[i, j] -= d["davit_ss_c"][i, j, :n] @ np.linalg.solve(
                    a, np.linalg.solve(a, d["davit_ss_b"][i, j, :n]))
    with h5py.File(path, "r") as f:
        return a0, d["davit_ss_order"] > 0, f["davit_added_mass_zero"][()]


def test_ship_memory_keeps_the_zero_frequency_added_mass():
    """The ship's passive memory reaches Capytaine's A(0) at zero frequency, every fitted
    pair within 1e-3 of sqrt(A_ii(0) A_jj(0)) (the pair's scale): the forward-speed terms'
    Munk moments U^2 A(0) come from it. The database before the re-fit missed sway by
    1.45 %, heave by 0.38 %, the sway-roll couplings by 3.5 % of their own value."""
    a_mem, fitted, a_zero = memory_zero_frequency_added_mass(DATABASES[0])
    scale = np.sqrt(np.outer(np.diag(a_zero), np.diag(a_zero)))
    err = np.abs(a_mem - a_zero) / scale
    assert fitted[2, 2] and fitted[1, 1] and fitted[1, 3]
    assert np.all(err[fitted] < 1e-3), err


def _raos(d, added_mass, damping, zeta=0.05):
    """Heave, roll, pitch amplitudes (nw, 3 headings, 3) of the 6-DOF equations
    [-w^2 (M + A) + i w (B + B_v) + C] xi = X at the database's frequencies, headings 90,
    135, 180 deg; B_v a roll damping of zeta of critical at each frequency's own A44."""
    heading = np.degrees(d["davit_heading"])
    cols = [int(np.argmin(np.abs(heading - h))) for h in (90.0, 135.0, 180.0)]
    x = (d["davit_excitation_re"] + 1j * d["davit_excitation_im"])[:, cols, :]
    m, c = d["davit_mass_matrix"], d["davit_hydrostatic_stiffness"]
    out = np.zeros((d["davit_omega"].size, 3, 3))
    for n, w in enumerate(d["davit_omega"]):
        bv = np.zeros((6, 6))
        bv[3, 3] = zeta * 2.0 * np.sqrt(c[3, 3] * (m[3, 3] + d["davit_added_mass"][n, 3, 3]))
        z = -w**2 * (m + added_mass[n]) + 1j * w * (damping[n] + bv) + c
        out[n] = np.abs(np.linalg.solve(z, x[n].T).T)[:, 2:5]
    return out


@pytest.mark.parametrize("path", DATABASES, ids=lambda p: p.name)
def test_passive_fits_keep_the_raos_of_the_bem_data(path):
    """Passivity costs the fits some accuracy (the roll pair most: its radiation damping is
    small against the sway-roll coupling that makes the matrix indefinite), but the motions
    they give stay the BEM's: the RAOs with the fitted A(w) = A_inf(fit) + Im K(i w)/w and
    B(w) = Re K(i w) differ from those with the database's A(w), B(w) by less than 1 % of
    each RAO's peak (heave, roll, pitch; beam, bow-quartering and head seas)."""
    d = _read(path)
    w = d["davit_omega"]
    k, _ = _kernels(d, 1j * w)
    a_fit = d["a_fit_inf"][None, :, :] + k.imag / w[:, None, None]
    unfitted = d["davit_ss_order"] == 0
    a_fit[:, unfitted] = d["davit_added_mass_inf"][unfitted]
    ref = _raos(d, d["davit_added_mass"], d["davit_radiation_damping"])
    fit = _raos(d, a_fit, k.real)
    peak = ref.max(axis=0)
    err = np.max(np.abs(fit - ref), axis=0) / np.where(peak > 0, peak, 1.0)
    assert np.all(err < 0.01), err


def test_passive_command_refits_a_non_passive_database(tmp_path):
    """`bem passive` on a copy of the ship's database whose sway-roll coupling fits are
    tripled (the matrix then indefinite): exit 0, the result passive by the check above,
    every pair's zero-frequency added mass Capytaine's A(0) (to 1e-6: an equality of the
    least-change problem), every variable but the memory's bit for bit the input's."""
    src = tmp_path / "bad.nc"
    shutil.copy(DATABASES[0], src)
    with h5py.File(src, "r+") as f:
        c = f["davit_ss_c"][()]
        c[1, 3] *= 3.0
        c[3, 1] *= 3.0
        f["davit_ss_c"][...] = c
    assert smallest_scaled_eigenvalue(src)[0] < -0.05
    out = tmp_path / "fixed.nc"
    run = subprocess.run([sys.executable, "-m", "postproc.bem", "passive", str(src), "-o",
                          str(out)], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    assert "smallest eigenvalue" in run.stderr
    assert smallest_scaled_eigenvalue(out)[0] >= -TOLERANCE
    a_mem, fitted, a_zero = memory_zero_frequency_added_mass(out)
    scale = np.sqrt(np.outer(np.diag(a_zero), np.diag(a_zero)))
    assert np.all(np.abs(a_mem - a_zero)[fitted] < 1e-6 * scale[fitted])
    memory = {"davit_ss_order", "davit_ss_a", "davit_ss_b", "davit_ss_c", "davit_ss_fit_error",
              "davit_ss_fit_error_added_mass", "davit_ss_fit_error_damping",
              "davit_ss_fit_error_retardation", "davit_retardation",
              "davit_ss_added_mass_inf", "davit_ss_n", "davit_ss_m"}
    with h5py.File(src, "r") as a, h5py.File(out, "r") as b:
        for name in a:
            if name not in memory:
                assert np.array_equal(np.asarray(a[name][()]), np.asarray(b[name][()])), name
        assert "passive" in b.attrs["refit_command_line"]


def test_passive_command_names_a_missing_file(tmp_path):
    run = subprocess.run([sys.executable, "-m", "postproc.bem", "passive",
                          str(tmp_path / "none.nc")], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 1
    assert "none.nc" in run.stderr
