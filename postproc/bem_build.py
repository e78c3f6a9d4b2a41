"""Solve a hull with Capytaine and write the BEM database (see postproc.bem_db).

The frequencies are solved one at a time (6 radiation problems and one diffraction problem
per heading share one factorised matrix), and Capytaine's per-matrix LRU cache of the
symmetric-mesh blocks is cleared after each, so memory stays flat (~0.3 GB for 2,000
panels); omega = 0 and omega = inf are solved for radiation only.
"""
import os
import sys
import time as _time

import numpy as np

from . import bem_db as db
from . import bem_checks, bem_drift, bem_fit, bem_passive, bem_rao, layout

RHO = 1025.0
G = 9.81
ROLL_GYRADIUS_FACTOR = 0.38      # k_xx = 0.38 B (review G9)
PITCH_GYRADIUS = 32.6375         # k_yy = k_zz = 0.25 L_wl [m]
# viscous roll damping of the motions behind the drift coefficients (davit's zeta_roll default)
DRIFT_ROLL_DAMPING = 0.05
RETARDATION_DT = 0.1             # [s]
RETARDATION_END = 60.0           # [s]
FIT_WINDOW = 30.0                # [s] of the K(t) error
# the lifeboat's kernels (frequencies up to 8 rad/s, natural periods ~2-4.5 s) die out
# within ~10 s: a finer, shorter grid (dt, end, K(t) error window) [s]
LIFEBOAT_RETARDATION = (0.02, 20.0, 10.0)
# and its fits see the data extended past 8 rad/s (postproc.bem_fit.fit_all, tail)
LIFEBOAT_FIT_TAIL = (1.25, 1.5, 2.0, 3.0, 4.0, 6.0)
SS_ADDED_MASS_INF = db.SS_ADDED_MASS_INF
FIT_VARIABLES = {
    SS_ADDED_MASS_INF: ((db.DIM_I, db.DIM_J), db._UNITS_6x6,
                        "A_inf of the fitted memory model (Cummins' mass M + A_inf): "
                        "davit_added_mass_inf plus the diagonal shift e_ii of impedance fits "
                        "(A_fit(w) = A_inf + e + Im K_fit(i w) / w)"),
}


def default_omegas():
    """55 frequencies in 0.1..2.0 rad/s: every 0.05 below 0.5, 0.025 over 0.5..1.2 and
    0.0125 over 0.7..0.95, where the default box's roll (undamped natural frequency 0.80
    rad/s), heave and pitch (0.92 rad/s) respond; every 0.1 above 1.2."""
    w = np.concatenate([np.arange(0.1, 0.5, 0.05), np.arange(0.5, 1.2, 0.025),
                        np.arange(0.7, 0.95, 0.0125), np.arange(1.2, 2.0001, 0.1)])
    return np.unique(np.round(w, 6))


def lifeboat_omegas():
    """87 frequencies in 0.3..8 rad/s for the lifeboat (postproc.bem_mesh.lifeboat_hull):
    every 0.1 below 1.2, 0.025 over 1.2..1.7 around its roll (undamped natural frequency
    ~1.4 rad/s with the hull's GM_T, ~1.6 rad/s with the paper's h_m = 2 m), 0.1 up to
    2.4, 0.05 over 2.4..3.6 around heave and pitch (~2.9, ~3.2 rad/s), 0.1 up to 5 and
    0.25 up to 8 rad/s (a 0.96 m wave: the panels, ~0.15 m, still resolve it)."""
    w = np.concatenate([np.arange(0.3, 1.2, 0.1), np.arange(1.2, 1.7, 0.025),
                        np.arange(1.7, 2.4, 0.1), np.arange(2.4, 3.6, 0.05),
                        np.arange(3.6, 5.0, 0.1), np.arange(5.0, 8.0001, 0.25)])
    return np.unique(np.round(w, 6))


def default_headings_deg():
    """0..360 deg every 15 deg (360 is a copy of 0, for interpolation without wrapping)."""
    return np.arange(0.0, 360.0001, 15.0)


def default_gyradii(hull, given=(None, None, None), paper_box=False):
    """Radii of gyration (roll, pitch, yaw) [m] and where each comes from: those given,
    else 0.38 B (roll; review G9's 0.38 B, within the usual 0.35-0.40 B of ships) and
    0.25 L (pitch, yaw) of this hull, the paper's 0.25 L_wl = 32.6375 m for the default
    box (paper_box)."""
    pitch = PITCH_GYRADIUS if paper_box else 0.25 * hull.length
    pitch_source = "0.25 L_wl of the paper's ship" if paper_box else "0.25 L of the hull"
    defaults = ((ROLL_GYRADIUS_FACTOR * hull.beam, f"{ROLL_GYRADIUS_FACTOR:g} B of the hull"),
                (pitch, pitch_source), (pitch, pitch_source))
    radii, sources = [], []
    for value, (fallback, source) in zip(given, defaults):
        radii.append(float(fallback if value is None else value))
        sources.append(source if value is None else "given")
    return tuple(radii), tuple(sources)


def mass_matrix(mass, gyradii):
    """Diagonal 6x6 rigid-body mass matrix about the CG (the same in both frames)."""
    return np.diag([mass, mass, mass] + [mass * r**2 for r in gyradii])


def _clear_capytaine_cache():
    from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix
    clear = getattr(NestedBlockCirculantMatrix.to_BlockCirculantMatrix, "cache_clear", None)
    if clear is not None:
        clear()


def _sign_matrix(m):
    return db.DOF_SIGN[:, None] * m * db.DOF_SIGN[None, :]


def _ordered(da, dofs):
    return da.sel(influenced_dof=list(dofs), radiating_dof=list(dofs))


def make_body(hull, cg, mass=None, gyradii=None, rho=RHO, g=G):
    """Capytaine FloatingBody with 6 rigid DOFs about cg, the mass matrix, and Capytaine's
    hydrostatic stiffness; returns (body, mass matrix, hydrostatics dict)."""
    import capytaine as cpt
    import xarray as xr
    cg = np.asarray(cg, float)
    body = cpt.FloatingBody(mesh=hull.mesh, lid_mesh=hull.lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=cg), center_of_mass=cg,
                            name=hull.kind)
    volume = float(body.disp_volume)
    if mass is None:
        mass = rho * volume
    body.mass = mass
    if gyradii is None:
        gyradii = default_gyradii(hull, paper_box=hull.kind == "box")[0]
    m6 = mass_matrix(mass, gyradii)
    dofs = list(body.dofs)
    body.inertia_matrix = xr.DataArray(m6, dims=["influenced_dof", "radiating_dof"],
                                       coords={"influenced_dof": dofs, "radiating_dof": dofs})
    body.hydrostatic_stiffness = body.compute_hydrostatic_stiffness(rho=rho, g=g)
    checked = bem_checks.hydrostatics(hull.mesh, cg)
    bem_checks.check_stability(checked)
    hydro = {"volume": volume, "waterplane_area": float(body.waterplane_area),
             "centre_of_buoyancy": np.asarray(body.center_of_buoyancy, float),
             "gm_t": float(body.transversal_metacentric_height),
             "gm_l": float(body.longitudinal_metacentric_height),
             "mass": float(mass), "gyradii": np.asarray(gyradii, float)}
    return body, m6, hydro


def solve(body, omegas, headings_deg, rho=RHO, g=G, progress=True):
    """Radiation + diffraction over omegas x headings (davit's relative headings, deg),
    frequency by frequency; then radiation at omega = 0 and inf. Returns
    (dataset of the finite frequencies, dataset of 0 and inf, solve time [s], far field):
    the far field holds each frequency's Kochin functions H, H' about the CG's vertical
    (postproc.bem_drift) of the 6 radiation problems and of the diffraction problems, in
    Capytaine's wave directions (the sources are dropped once they are taken)."""
    import capytaine as cpt
    solver = cpt.BEMSolver()
    directions = np.unique(np.mod(-np.radians(headings_deg), 2 * np.pi).round(12))
    theta = bem_drift.theta_grid()
    ref = np.asarray(body.center_of_mass, float)[:2]
    far = {"theta": theta, "directions": directions, "radiation": [], "diffraction": []}
    results, t0 = [], _time.time()
    for n, w in enumerate(omegas):
        t = _time.time()
        problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=w, rho=rho, g=g)
                    for d in body.dofs]
        problems += [cpt.DiffractionProblem(body=body, wave_direction=b, omega=w, rho=rho, g=g)
                     for b in directions]
        solved = solver.solve_all(problems, progress_bar=False)
        _clear_capytaine_cache()
        h, hp = bem_drift.kochin(solved, body, theta, ref)
        nr = len(body.dofs)
        hd, hpd = bem_drift.shift_phase(h[nr:], hp[nr:], directions, solved[0].wavenumber,
                                        ref)
        far["radiation"].append((h[:nr], hp[:nr]))
        far["diffraction"].append((hd, hpd))
        for r in solved:
            r.sources = None
            r.potential = None
        results += solved
        if progress:
            print(f"bem: omega {w:.4f} rad/s ({n + 1}/{len(omegas)}) {_time.time() - t:.1f} s",
                  file=sys.stderr, flush=True)
    special = []
    for w in (0.0, np.inf):
        special += solver.solve_all([cpt.RadiationProblem(body=body, radiating_dof=d, omega=w,
                                                          rho=rho, g=g) for d in body.dofs],
                                    progress_bar=False)
        _clear_capytaine_cache()
    elapsed = _time.time() - t0
    ds = cpt.assemble_dataset(results, hydrostatics=True)
    ds_special = cpt.assemble_dataset(special, hydrostatics=False)
    return ds, ds_special, elapsed, far


def davit_variables(ds, ds_special, body, m6, hydro, headings_deg, g=G, nmax=12, tol=0.02,
                    progress=True, retardation=(RETARDATION_DT, RETARDATION_END, FIT_WINDOW),
                    tail=None, passive_matrix=True):
    """The davit_ variables (name -> numpy array) from Capytaine's datasets. passive_matrix:
    the fitted damping matrix made positive semi-definite (postproc.bem_passive.enforce)."""
    dofs = list(body.dofs)
    cg = np.asarray(body.center_of_mass, float)
    omega = ds.omega.values
    k = omega**2 / g
    a_c = _ordered(ds.added_mass, dofs).transpose("omega", "influenced_dof", "radiating_dof")
    b_c = _ordered(ds.radiation_damping, dofs).transpose("omega", "influenced_dof",
                                                         "radiating_dof")
    added_mass = _sign_matrix(a_c.values)
    damping = _sign_matrix(b_c.values)
    a_sp = _ordered(ds_special.added_mass, dofs)
    a_zero = _sign_matrix(a_sp.sel(omega=0.0).values)
    a_inf = _sign_matrix(a_sp.sel(omega=np.inf).values)
    # the pairs the hull's symmetries make zero are zero (not the solver's round-off, whose
    # fits had negative damping) and are not fitted
    zero = bem_fit.symmetry_zero_pairs(body.mesh.vertices, cg)
    for m in (added_mass, damping):
        m[:, zero] = 0.0
    a_zero[zero] = 0.0
    a_inf[zero] = 0.0
    if progress and zero.any():
        print(f"bem: {int(zero.sum()) // 2} radiation pairs zero by the hull's symmetry, "
              f"not fitted", file=sys.stderr)

    beta = np.radians(headings_deg)
    beta_c = np.mod(-beta, 2 * np.pi)
    dirs = ds.wave_direction.values
    index = [int(np.argmin(np.abs(np.angle(np.exp(1j * (dirs - b)))))) for b in beta_c]

    def convert(force):
        f = force.sel(influenced_dof=dofs).transpose("omega", "wave_direction",
                                                     "influenced_dof").values[:, index, :]
        # Capytaine: F = Re[X e^{-i w t}] for eta = Re[e^{i (k.x - w t)}] at the origin;
        # davit: F = Re[X e^{i (w t - k.x_G)}], so X_davit = S conj(X_cpt) e^{+i k.x_G}
        shift = np.exp(1j * np.outer(k, cg[0] * np.cos(beta_c) + cg[1] * np.sin(beta_c)))
        return np.conj(f) * shift[:, :, None] * db.DOF_SIGN[None, None, :]

    excitation = convert(ds.excitation_force)
    froude_krylov = convert(ds.Froude_Krylov_force)
    stiffness = _sign_matrix(_ordered(ds.hydrostatic_stiffness.squeeze(drop=True),
                                      dofs).values)

    memory = fit_memory(omega, added_mass, damping, a_inf, m6, stiffness, zero, retardation,
                        tail, nmax, tol, passive_matrix, progress, hydro)
    return {
        db.OMEGA: omega, db.HEADING: beta, db.WAVENUMBER: k,
        db.ADDED_MASS: added_mass, db.DAMPING: damping,
        db.ADDED_MASS_INF: a_inf, db.ADDED_MASS_ZERO: a_zero,
        db.EXCITATION_RE: excitation.real, db.EXCITATION_IM: excitation.imag,
        db.FROUDE_KRYLOV_RE: froude_krylov.real, db.FROUDE_KRYLOV_IM: froude_krylov.imag,
        db.STIFFNESS: stiffness, db.MASS: m6,
        db.VOLUME: np.float64(hydro["volume"]),
        db.WATERPLANE_AREA: np.float64(hydro["waterplane_area"]),
        db.BUOYANCY_CENTRE: db.VECTOR_SIGN * (hydro["centre_of_buoyancy"] - cg),
        db.CG: cg, **memory,
    }


def fit_memory(omega, added_mass, damping, a_inf, m6, stiffness, zero, retardation,
               tail=None, nmax=12, tol=0.02, passive_matrix=True, progress=True, hydro=None,
               a_zero=None):
    """The radiation memory's state-space fits from the frequency-domain data (davit's
    frame): the frequencies the mesh resolves (bem_fit.resolved_frequencies), K(t) on the
    retardation (dt, end, window) grid, the pairs fit_all finds significant and `zero`
    ((6, 6) bool) does not exclude, the diagonal ones passive, the matrix made positive
    semi-definite if passive_matrix (postproc.bem_passive: augment, then enforce with
    rao_weights). The build's fitting stage, and `bem passive`'s re-fit of a stored
    database. Returns the davit variables SS_*, RETARDATION_TIME, RETARDATION and
    SS_ADDED_MASS_INF; fills hydro (min_eigen_damping(_unenforced), fit_last_omega) and
    the last enforcement's Result (passive_result: None if not enforced). a_zero: (6, 6)
    A(0) of the data, or None; given (and passive_matrix), the enforcement holds every
    fitted pair's zero-frequency added mass A_inf(fit) + K'(0) at it (the Munk moments of
    the forward-speed terms, davit_ship_bem_loads' bem_speed_load, come from it)."""
    hydro = {} if hydro is None else hydro
    dt, end, window = retardation
    time = np.arange(0.0, end + 0.5 * dt, dt)
    # the fits (and K(t)) see the frequencies the mesh resolves (bem_fit.resolved_frequencies)
    keep = bem_fit.resolved_frequencies(omega, damping)
    if progress and not keep.all():
        print(f"bem: radiation damping B_ii < 0 at {omega[~keep][0]:g} rad/s (the mesh does not "
              f"resolve that wave): the fits use {keep.sum()} frequencies up to "
              f"{omega[keep][-1]:g} rad/s", file=sys.stderr)
    kernel = bem_fit.retardation(omega[keep], damping[keep], time)
    fits = bem_fit.fit_all(omega[keep], added_mass[keep], damping[keep], a_inf, time, kernel,
                           nmax=nmax, tol=tol, window=window, tail=tail, zero=zero, mass=m6,
                           stiffness=stiffness, omega_max=omega[-1])
    hydro["min_eigen_damping_unenforced"] = bem_passive.min_eigenvalue(fits, omega[-1],
                                                                       damping)[0]
    if passive_matrix:
        # a pole pair beyond the grid for the DOFs of the violation, then the least change
        # in the RAO error (postproc.bem_passive.augment, rao_weights)
        augmented = bem_passive.augment(fits, omega[-1], damping)
        weights = bem_passive.rao_weights(omega[keep], added_mass[keep], damping[keep],
                                          m6, stiffness, fits)
        passive = bem_passive.enforce(fits, omega[keep], added_mass[keep], damping[keep],
                                      a_inf, omega_max=omega[-1], weights=weights,
                                      added_mass_zero=a_zero)
        if progress and augmented:
            print("bem: passivity: a pole pair at " f"{bem_passive.AUGMENT_FACTOR:g} x the "
                  "last frequency given to the diagonal fits of "
                  + ", ".join(db.DOFS[i] for i in augmented), file=sys.stderr)
        bem_fit.fill_errors(fits, time, kernel, damping[keep], omega[-1], window)
        for i in range(6):
            if (i, i) in fits and np.isfinite(fits[(i, i)].error_impedance):
                fits[(i, i)].error_impedance = bem_fit.impedance_error(
                    fits[(i, i)], omega[keep], added_mass[keep, i, i], damping[keep, i, i],
                    a_inf[i, i], m6[i, i], stiffness[i, i])
    order, ss_a, ss_b, ss_c, err = bem_fit.pack(fits)
    # Cummins' mass: A_inf plus the shifts that impedance fits took (bem_fit.fit_impedance)
    a_inf_fit = a_inf + np.diag([fits[(i, i)].added_mass_shift if (i, i) in fits else 0.0
                                 for i in range(6)])
    hydro["min_eigen_damping"] = bem_passive.min_eigenvalue(fits, omega[-1], damping)[0]
    hydro["fit_last_omega"] = float(omega[keep][-1])
    if progress:
        print_fit_report(fits)
        if passive_matrix:
            print_passive_report(passive)
        else:
            print(f"bem: fitted damping matrix, smallest eigenvalue (scaled by sqrt(max B_ii "
                  f"max B_jj)): {hydro['min_eigen_damping']:.3g}, not enforced "
                  f"(--no-passive-matrix)", file=sys.stderr)
    hydro["passive_result"] = passive if passive_matrix else None
    return {
        db.SS_ORDER: order, db.SS_A: ss_a, db.SS_B: ss_b, db.SS_C: ss_c,
        db.SS_FIT_ERROR: np.maximum(err[0], err[1]),
        db.SS_FIT_ERROR_ADDED_MASS: err[0], db.SS_FIT_ERROR_DAMPING: err[1],
        db.SS_FIT_ERROR_RETARDATION: err[2],
        db.RETARDATION_TIME: time, db.RETARDATION: kernel,
        SS_ADDED_MASS_INF: a_inf_fit,
    }


def drift_variables(ds, far, body, variables, zeta_roll=DRIFT_ROLL_DAMPING, rho=RHO):
    """The mean drift coefficients (postproc.bem_drift) of the freely floating body in davit's
    frame and headings: motions from Capytaine's RAOs with a viscous roll damping zeta_roll of
    critical at the roll resonance (postproc.bem_rao.roll_damping, as davit's `zeta_roll`).
    Returns the davit variables DRIFT and DRIFT_ENERGY_DEFECT and B44_visc."""
    import types
    import capytaine as cpt
    import xarray as xr
    dofs = list(body.dofs)
    base = types.SimpleNamespace(omega=variables[db.OMEGA], added_mass=variables[db.ADDED_MASS],
                                 added_mass_inf=variables[db.ADDED_MASS_INF],
                                 stiffness=variables[db.STIFFNESS], mass=variables[db.MASS])
    b44 = bem_rao.roll_damping(base, zeta_roll) if zeta_roll > 0 else 0.0
    bv = np.zeros((6, 6))
    bv[3, 3] = b44
    bv = xr.DataArray(bv, dims=["influenced_dof", "radiating_dof"],
                      coords={"influenced_dof": dofs, "radiating_dof": dofs})
    xi = cpt.post_pro.rao(ds, dissipation=bv).sel(radiating_dof=dofs).transpose(
        "omega", "wave_direction", "radiating_dof").values
    theta, directions = far["theta"], far["directions"]
    omega = ds.omega.values
    drift = np.empty((omega.size, directions.size, 3))
    defect = np.empty((omega.size, directions.size))
    for n, w in enumerate(omega):
        k = w * w / G
        h, hp = bem_drift.total_kochin(*far["diffraction"][n], *far["radiation"][n], xi[n])
        drift[n] = bem_drift.mean_drift(h, hp, theta, directions, w, k, rho)
        defect[n] = bem_drift.energy_defect(h, theta, directions, w, k)
    beta_c = np.mod(-variables[db.HEADING], 2 * np.pi)
    index = [int(np.argmin(np.abs(np.angle(np.exp(1j * (directions - b)))))) for b in beta_c]
    # Capytaine's (x, y port, z up) to davit's (x, y starboard, z down): sway and yaw flip
    sign = np.array([1.0, -1.0, -1.0])
    return {db.DRIFT: drift[:, index, :] * sign, db.DRIFT_ENERGY_DEFECT: defect[:, index]}, b44


def print_passive_report(result, file=sys.stderr):
    """The matrix passivity enforcement's smallest eigenvalue before and after and each
    pair's weighted RMS fit error before and after (postproc.bem_passive)."""
    print(f"bem: fitted damping matrix (symmetric part, scaled by sqrt(max B_ii max B_jj)), "
          f"smallest eigenvalue up to where the poles die away: "
          f"{result.min_eigenvalue_before:.3g} at {result.omega_at_min_before:.4g} rad/s "
          f"before, {result.min_eigenvalue_after:.3g} after the residue perturbation "
          f"({result.iterations} iterations)", file=file)
    if result.iterations:
        print("bem: passivity's cost, RMS over the grid of each fit's RAO error "
              "w |K_fit - K| / sqrt(|Z_ii Z_jj|) (before -> after):", file=file)
        for (i, j) in sorted(result.rms_before):
            print(f"bem:   {db.DOFS[i]:>5s}-{db.DOFS[j]:<5s} {result.rms_before[(i, j)]:7.3%}"
                  f" -> {result.rms_after[(i, j)]:7.3%}", file=file)


def print_fit_report(fits, file=sys.stderr):
    print("bem: state-space fits (pair i,j: order, max err A, max err B, L2 err K(t) over "
          "the window)", file=file)
    for (i, j), f in sorted(fits.items()):
        print(f"bem:   {db.DOFS[i]:>5s}-{db.DOFS[j]:<5s} n={f.order:2d}  "
              f"A {f.error_added_mass:7.2%}  B {f.error_damping:7.2%}  "
              f"K(t) {f.error_retardation:7.2%}  max Re(pole) "
              f"{max(p.real for p in f.poles):.3g}  min B_fit/max B {f.min_damping:.3f}"
              f"{'  (tail)' if f.tail else ''}"
              + (f"  RAO err {f.error_impedance:.2%}" if np.isfinite(f.error_impedance) else "")
              + (f"  A_inf {f.added_mass_shift:+.4g} (impedance fit)"
                 if f.added_mass_shift else ""), file=file)


def write(path, ds, variables, attrs):
    """Capytaine's dataset (complex values split) plus the davit variables, netCDF4/HDF5,
    written to a temporary name and renamed when complete."""
    import xarray as xr
    from capytaine.io.xarray import separate_complex_values
    out = separate_complex_values(ds)
    out["radiating_dof"] = out["radiating_dof"].astype(str)
    out["influenced_dof"] = out["influenced_dof"].astype(str)
    for name, value in variables.items():
        dims, units, description = (db.VARIABLES.get(name) or db.DRIFT_VARIABLES.get(name)
                                    or FIT_VARIABLES[name])
        value = np.asarray(value)
        if name == db.SS_ORDER:
            value = value.astype(np.int32)
        else:
            value = value.astype(np.float64)
        out[name] = xr.DataArray(value, dims=dims,
                                 attrs={layout.UNITS: units, layout.DESCRIPTION: description})
    out.attrs = {k: v for k, v in out.attrs.items()}
    out.attrs.update(attrs)
    tmp = f"{path}.tmp{os.getpid()}"
    out.to_netcdf(tmp, engine="h5netcdf", invalid_netcdf=False)
    os.replace(tmp, path)


def build(hull, out, cg=(0.0, 0.0, 0.0), mass=None, gyradii=None, omegas=None,
          headings_deg=None, rho=RHO, g=G, nmax=12, tol=0.02, command="", progress=True,
          retardation=None, drift_roll_damping=DRIFT_ROLL_DAMPING, passive_matrix=True):
    """Mesh -> BEM solve -> davit variables -> database file. Returns (variables, attrs).
    The lifeboat hull gets its own frequency grid and retardation grid by default."""
    import capytaine as cpt
    lifeboat = hull.kind == "lifeboat"
    if omegas is None:
        omegas = lifeboat_omegas() if lifeboat else default_omegas()
    omegas = np.sort(np.asarray(omegas, float))
    if retardation is None:
        retardation = (LIFEBOAT_RETARDATION if lifeboat
                       else (RETARDATION_DT, RETARDATION_END, FIT_WINDOW))
    headings_deg = (default_headings_deg() if headings_deg is None
                    else np.asarray(headings_deg, float))
    body, m6, hydro = make_body(hull, cg, mass, gyradii, rho, g)
    if progress:
        for line in bem_checks.report(bem_checks.hydrostatics(hull.mesh, cg)):
            print(f"bem: {line}", file=sys.stderr)
        print(f"bem: {hull.kind} hull {hull.length:.2f} x {hull.beam:.2f} x {hull.draught:.2f} m, "
              f"{hull.panels} panels + {hull.lid_panels} lid panels (z = {hull.lid_z:.2f} m), "
              f"{len(omegas)} frequencies x {len(headings_deg)} headings", file=sys.stderr)
    ds, ds_special, elapsed, far = solve(body, omegas, headings_deg, rho, g, progress)
    variables = davit_variables(ds, ds_special, body, m6, hydro, headings_deg, g, nmax, tol,
                                progress, retardation,
                                LIFEBOAT_FIT_TAIL if lifeboat else None, passive_matrix)
    drift, b44 = drift_variables(ds, far, body, variables, drift_roll_damping, rho)
    variables.update(drift)
    attrs = {
        "title": (f"davit {'lifeboat' if lifeboat else 'ship'} hydrodynamics "
                  "(Capytaine BEM database)"),
        db.ATTR_HULL_KIND: hull.kind, db.ATTR_LENGTH: hull.length, db.ATTR_BEAM: hull.beam,
        db.ATTR_DRAUGHT: hull.draught, db.ATTR_PANELS: np.int32(hull.panels),
        db.ATTR_LID_PANELS: np.int32(hull.lid_panels), "lid": np.int32(hull.lid is not None),
        "lid_z": hull.lid_z, "rho": rho, "g": g, "mass": hydro["mass"],
        "gyradii": hydro["gyradii"], "gm_transverse": hydro["gm_t"],
        "gm_longitudinal": hydro["gm_l"], "capytaine_version": cpt.__version__,
        db.ATTR_FIT_MIN_EIGEN: hydro["min_eigen_damping"],
        db.ATTR_FIT_MIN_EIGEN_UNENFORCED: hydro["min_eigen_damping_unenforced"],
        db.ATTR_FIT_PASSIVE_MATRIX: np.int32(passive_matrix),
        "fit_last_omega": hydro["fit_last_omega"],
        "retardation_dt_end_window": np.asarray(retardation, float),
        db.ATTR_DRIFT_ROLL_DAMPING: drift_roll_damping, "drift_roll_damping_visc": b44,
        "drift_theta_points": np.int32(bem_drift.N_THETA),
        db.ATTR_COMMAND_LINE: command, db.ATTR_SOLVE_TIME: elapsed,
        db.ATTR_CONVENTIONS: db.__doc__.strip(),
        "frame_of_capytaine_variables": "Capytaine's (x forward, y port, z up; e^{-i w t}; "
                                        "wave_direction from x towards y, port)",
    }
    if lifeboat:
        attrs["fit_tail"] = np.asarray(LIFEBOAT_FIT_TAIL, float)
    for key, value in hull.extra.items():
        attrs[key] = value
    write(out, ds, variables, attrs)
    if progress:
        size = os.path.getsize(out) / 1e6
        print(f"bem: wrote {out} ({size:.1f} MB), solve {elapsed:.0f} s", file=sys.stderr)
    return variables, attrs
