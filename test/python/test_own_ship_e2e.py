"""Your own ship end to end: a Wigley hull (L = 3 m, the Wigley III model's main dimensions)
whose mesh this test writes -> `bem build --mesh` -> `bem rao` (frequency domain) and
`davit rao` (time domain, Cummins' equation with the fitted radiation memory) from a deck
that names the database and nothing else of the paper's ship."""
import pathlib
import subprocess
import sys

import h5py
import numpy as np
import pytest

from postproc import bem_db as db
from postproc import bem_fit, bem_rao

import wigley

pytest.importorskip("capytaine")

ROOT = pathlib.Path(__file__).resolve().parents[2]
L, B, T = 3.0, 0.3, 0.1875
CG_Z = -0.06                       # KG 0.1275 m: GM_T 0.031 m
# heave and pitch resonate at 7.6 and 7.2 rad/s; at 16 rad/s the 288 panels no longer
# resolve the wave (B_55 < 0), and the fits leave it out (bem_fit.resolved_frequencies)
OMEGAS = np.concatenate([np.arange(1.0, 4.0, 0.5), np.arange(4.0, 9.0, 0.25),
                         np.arange(9.0, 16.01, 1.0)])
COMPARE = [3.0, 4.0, 5.0, 6.0]     # rad/s: head seas (the restraint, the empirical loads)
# head seas, time domain against frequency domain, heave and pitch within 1 %: through both
# resonances (the fits without impedance weighting were 1.2-1.8 % off at 7-8 rad/s)
E2E_OMEGAS = [3.0, 4.0, 5.0, 6.0, 7.0, 8.0]
DECK = """&ship model = 'bem', database = 'wigley_bem.nc', empirical_loads = '{loads}',
      zeta_roll = 0.05{extra} /
&rao omegas = {omegas}, headings_deg = {heading}, amplitude = 0.005,
     settle_time = 30.0, measure_periods = 10, dt = 0.005 /
"""


@pytest.fixture(scope="module")
def wigley_db(tmp_path_factory):
    folder = tmp_path_factory.mktemp("wigley")
    mesh = folder / "wigley.obj"
    wigley.write_obj(mesh, *wigley.wigley_faces(L, B, T, 24, 6))
    out = folder / "wigley_bem.nc"
    cmd = [sys.executable, "-m", "postproc.bem", "build", "--mesh", str(mesh), "--cg", "0",
           "0", str(CG_Z), "--omegas", *[f"{w:.3f}" for w in OMEGAS], "--headings-deg", "0",
           "90", "180", "-o", str(out)]
    result = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    assert "radiation pairs zero by the hull's symmetry" in result.stderr
    assert "B_ii < 0 at 16 rad/s" in result.stderr
    return folder, db.Database(out), result.stderr


def _davit_rao(davit, folder, name, omegas, heading, extra="", loads="off"):
    deck = folder / f"{name}.nml"
    deck.write_text(DECK.format(extra=extra, omegas=", ".join(f"{w:g}" for w in omegas),
                                heading=heading, loads=loads))
    out = folder / f"{name}.h5"
    result = davit("rao", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        assert f.attrs["complete"] == 1
        return f["rao/amplitude"][()][0]          # (omega, dof) of the one heading


def test_symmetry_zero_pairs_are_not_fitted_and_diagonal_fits_are_passive(wigley_db):
    """Port-starboard and fore-aft symmetric about the CG: only surge-pitch and sway-roll
    couple (zero data, order 0 for the rest), and every diagonal fit's damping is >= 0
    (within 1e-3 of its peak) up to 20 x the last frequency."""
    _, base, _ = wigley_db
    order = base[db.SS_ORDER]
    coupled = {(0, 4), (4, 0), (1, 3), (3, 1)}
    for i in range(6):
        for j in range(6):
            if i != j and (i, j) not in coupled:
                assert order[i, j] == 0, (i, j)
                assert np.all(base.damping[:, i, j] == 0.0), (i, j)
    wide = np.linspace(1e-3, 20.0 * base.omega[-1], 20000)
    for i in range(6):
        n = order[i, i]
        assert n > 0
        bfit = bem_fit.transfer(base[db.SS_A][i, i, :n, :n], base[db.SS_B][i, i, :n],
                                base[db.SS_C][i, i, :n], 1j * wide).real
        assert bfit.min() >= -1.001e-3 * np.abs(base.damping[:, i, i]).max(), db.DOFS[i]


def test_fitted_damping_matrix_is_passive_up_to_where_its_poles_die_away(wigley_db):
    """The symmetric part of the stored fits' damping matrix, D^-1 B_fit(w) D^-1 with
    D = diag(sqrt(max B_ii)), has no eigenvalue below -1.001e-3 (the enforcement's
    tolerance) from 0 to 10 x the largest pole modulus (2 x 10^5 points): the radiation
    memory as a whole makes no energy. The pair-by-pair fits before the residue
    perturbation had -0.42 at 17.4 rad/s (surge-pitch, beyond the 15 rad/s grid), which
    the build keeps as fit_min_eigen_damping_unenforced: a database built with
    --no-passive-matrix fails the first assertion by that much."""
    folder, base, log = wigley_db
    order, a, b, c = (base[k] for k in (db.SS_ORDER, db.SS_A, db.SS_B, db.SS_C))
    top = max(np.abs(np.linalg.eigvals(a[i, j, :n, :n])).max()
              for (i, j), n in np.ndenumerate(order) if n > 0)
    w = np.linspace(1e-3, 10.0 * top, 200001)
    bfit = np.zeros((w.size, 6, 6))
    for (i, j), n in np.ndenumerate(order):
        if n > 0:
            bfit[:, i, j] = bem_fit.transfer(a[i, j, :n, :n], b[i, j, :n], c[i, j, :n],
                                             1j * w).real
    d = np.sqrt(np.abs(base.damping).max(axis=0).diagonal())
    bfit = bfit / np.outer(d, d)
    smallest = np.linalg.eigvalsh(0.5 * (bfit + bfit.transpose(0, 2, 1)))[:, 0]
    assert smallest.min() >= -1.001e-3, w[np.argmin(smallest)]
    with h5py.File(folder / "wigley_bem.nc", "r") as f:
        assert f.attrs["fit_min_eigen_damping_unenforced"] < -0.3
        assert f.attrs["fit_passive_matrix"] == 1
    assert "smallest eigenvalue up to where the poles die away: -0.42" in log


def test_heave_and_pitch_memory_reproduces_the_impedance_through_resonance(wigley_db):
    """The fitted model of heave and pitch (Cummins' A_inf from davit_ss_added_mass_inf,
    the state-space memory K_fit) against the BEM's own A(w), B(w): the relative error of
    the one-DOF impedance, w |K_fit - K| / |C - w^2 (M + A) + i w B|, is below 2 % at every
    grid frequency the fits use (<= 15 rad/s), 1 % at 3..8 rad/s; the shift is on the
    heave and pitch diagonals only (their impedance fits), below 3 % of A_inf."""
    folder, base, _ = wigley_db
    with h5py.File(folder / "wigley_bem.nc", "r") as f:
        a_inf = f["davit_ss_added_mass_inf"][()]
        assert f.attrs["fit_last_omega"] == pytest.approx(15.0)
    shift = a_inf - base.added_mass_inf
    assert np.count_nonzero(shift) == 2 and shift[2, 2] != 0 and shift[4, 4] != 0
    assert np.all(np.abs(np.diag(shift)) < 0.03 * np.diag(base.added_mass_inf))
    w = base.omega[base.omega <= 15.0]
    band = (w >= 3.0) & (w <= 8.0)
    for i in (2, 4):
        n = base[db.SS_ORDER][i, i]
        kfit = bem_fit.transfer(base[db.SS_A][i, i, :n, :n], base[db.SS_B][i, i, :n],
                                base[db.SS_C][i, i, :n], 1j * w)
        a = base.added_mass[:w.size, i, i]
        b = base.damping[:w.size, i, i]
        model = 1j * w * kfit - w**2 * a_inf[i, i]
        bem = 1j * w * b - w**2 * a
        z = base.stiffness[i, i] - w**2 * (base.mass[i, i] + a) + 1j * w * b
        err = np.abs(model - bem) / np.abs(z)
        assert err.max() < 0.02, db.DOFS[i]
        assert err[band].max() < 0.01, db.DOFS[i]


def test_time_domain_heave_and_pitch_equal_the_frequency_domain(wigley_db, davit):
    """davit rao (Cummins' equation, the fitted memory) against bem rao (the database's
    A(w), B(w) themselves) at 3..8 rad/s, through the heave and pitch resonances."""
    folder, base, _ = wigley_db
    td = _davit_rao(davit, folder, "head", E2E_OMEGAS, 180.0)
    xi, _ = bem_rao.raos(base, np.array(E2E_OMEGAS), np.array([np.pi]), 0.05)
    fd = np.abs(xi[:, 0, :])
    np.testing.assert_allclose(td[:, 2], fd[:, 2], rtol=0.01)     # heave [m/m]
    np.testing.assert_allclose(td[:, 4], fd[:, 4], rtol=0.01)     # pitch [rad/m]


def test_roll_stays_bounded_in_beam_seas_at_its_resonance(wigley_db, davit):
    """zeta_roll = 0.05 at the undamped roll frequency (4.33 rad/s) and either side: the
    runs complete (a non-passive memory made the roll grow without bound) and the roll
    peaks where the frequency domain puts it."""
    folder, base, _ = wigley_db
    w_roll = 2 * np.pi / bem_rao.natural_periods(base)[3]
    omegas = [0.8 * w_roll, w_roll, 1.25 * w_roll]
    td = _davit_rao(davit, folder, "beam", omegas, 90.0)
    assert np.all(np.isfinite(td))
    assert td[1, 3] > td[0, 3] and td[1, 3] > td[2, 3]
    xi, _ = bem_rao.raos(base, np.array(omegas), np.array([0.5 * np.pi]), 0.05)
    np.testing.assert_allclose(td[:, 3], np.abs(xi[:, 0, 3]), rtol=0.03)


def test_restrained_heave_gives_the_five_dof_frequency_domain_pitch(wigley_db, davit):
    """&ship restrain = 'heave' (a tank test's heave post locked): no heave, and pitch as
    the frequency-domain 6 x 6 system with the heave row and column struck out."""
    folder, base, _ = wigley_db
    omegas = np.array(COMPARE)
    td = _davit_rao(davit, folder, "noheave", omegas, 180.0, ", restrain = 'heave'")
    free = _davit_rao(davit, folder, "free", omegas, 180.0)
    # the body-axis heave is held; the CG's inertial z moves only at second order (the
    # pitch times the surge): 0.05-0.2 % of the free heave
    assert np.all(td[:, 2] < 0.005 * free[:, 2])
    keep = [0, 1, 3, 4, 5]
    x = (base.excitation[:, np.argmin(np.abs(base.heading - np.pi)), :])
    for n, w in enumerate(omegas):
        k = int(np.argmin(np.abs(base.omega - w)))
        assert base.omega[k] == pytest.approx(w)
        z = (-w**2 * (base.mass + base.added_mass[k]) + 1j * w * base.damping[k]
             + base.stiffness)
        bv = np.zeros(6)
        bv[3] = bem_rao.roll_damping(base, 0.05)
        z += 1j * w * np.diag(bv)
        xi = np.linalg.solve(z[np.ix_(keep, keep)], x[k, keep])
        assert td[n, 4] == pytest.approx(abs(xi[3]), rel=0.01), w


def test_the_paper_ships_drag_on_the_model_fails_loudly(wigley_db, davit):
    """The same deck with the paper's empirical loads (cross-flow drag on L_pp = 126 m,
    d = 4.4 m, 1,600 m^2 of windage) on the 77 kg model: the runs blow up within seconds,
    and davit rao says which and why and exits 1 instead of writing them as results."""
    folder, _, _ = wigley_db
    deck = folder / "paper_drag.nml"
    deck.write_text(DECK.format(extra="", omegas="4.0, 6.0", heading=180.0, loads="deck"))
    result = davit("rao", deck, "-o", folder / "paper_drag.h5")
    assert result.returncode == 1
    assert "2 of 2 runs failed" in result.stderr
    assert "omega 4 rad/s, heading 180 deg: " in result.stderr


def test_the_models_own_drag_and_windage_admitted_and_small(wigley_db, davit):
    """The deck's empirical loads sized for the model itself (the ranges admit it): the
    runs complete, and at a 5 mm wave the quadratic drag moves heave and pitch by < 2 %."""
    folder, _, _ = wigley_db
    own = (", length_overall = 3.0, length_waterline = 3.0,"
           " length_pp = 3.0, beam = 0.3, draught = 0.1875, depth = 0.3,"
           " displacement = 75.8, block_coefficient = 0.444, area_front = 0.03,"
           " area_lateral = 0.3, wind_height = 0.1")
    td = _davit_rao(davit, folder, "own_drag", [4.0, 6.0], 180.0, own, loads="deck")
    free = _davit_rao(davit, folder, "no_drag", [4.0, 6.0], 180.0)
    np.testing.assert_allclose(td[:, [2, 4]], free[:, [2, 4]], rtol=0.02)


def test_one_heading_database_is_refused_by_the_run_and_answered_at_its_heading(wigley_db,
                                                                                 davit):
    """The database cut to its 180 deg heading: `bem rao` answers at 180 deg (the full
    database's answer) and refuses 90 deg; `davit rao` refuses it, naming why."""
    import shutil
    folder, base, _ = wigley_db
    one = folder / "one" / "wigley_bem.nc"
    one.parent.mkdir()
    shutil.copy(folder / "wigley_bem.nc", one)
    k = int(np.argmin(np.abs(base.heading - np.pi)))
    with h5py.File(one, "r+") as f:
        for name in (db.HEADING, db.EXCITATION_RE, db.EXCITATION_IM, db.FROUDE_KRYLOV_RE,
                     db.FROUDE_KRYLOV_IM):
            data, attrs = f[name][()], dict(f[name].attrs)
            data = data[k:k + 1] if name == db.HEADING else data[:, k:k + 1]
            for dim in ("DIMENSION_LIST", "REFERENCE_LIST", "CLASS", "NAME"):
                attrs.pop(dim, None)
            del f[name]
            f.create_dataset(name, data=data)
            f[name].attrs.update(attrs)
    single = db.Database(one)
    xi, _ = bem_rao.raos(single, np.array([5.0]), np.array([np.pi]))
    ref, _ = bem_rao.raos(base, np.array([5.0]), np.array([np.pi]))
    np.testing.assert_allclose(xi, ref, rtol=1e-12)
    with pytest.raises(ValueError, match="covers the one heading 180 deg only"):
        bem_rao.raos(single, np.array([5.0]), np.array([0.5 * np.pi]))
    deck = one.parent / "one.nml"
    deck.write_text(DECK.format(extra="", omegas="5.0", heading=180.0, loads="off"))
    result = davit("rao", deck, "-o", one.parent / "one.h5")
    assert result.returncode == 1
    assert "holds one heading only" in result.stderr
    assert not (one.parent / "one.h5").exists()
