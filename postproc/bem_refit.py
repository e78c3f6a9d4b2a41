"""Re-fit the radiation memory of an existing BEM database (python -m postproc.bem passive).

A database built before `bem build` made the fitted damping matrix positive semi-definite
(postproc.bem_passive) can have a memory that makes energy: the shipped input/ship_bem.nc
has a smallest scaled eigenvalue of -0.086 at 2.12 rad/s, input/boat_bem.nc had -0.156 at
8.58 rad/s. refit_file runs the build's own fitting stage
(postproc.bem_build.fit_memory: the same resolved frequencies, retardation grid, fit tail,
pair selection, passive diagonal fits, impedance fits and matrix enforcement)
on the database's stored frequency-domain data, so the result is what `bem build` would
write for the same mesh and grid today, without solving the BEM problem again (the ship's
solve took 146 s, the lifeboat's 675 s). Everything but the memory variables (davit_ss_*,
davit_retardation*, davit_ss_added_mass_inf) and the fit attributes stays as it was, bit
for bit; the pairs the database did not fit stay unfitted. Unlike the build, the re-fit
holds every fitted pair's zero-frequency added mass A_inf(fit) + K'(0) at the database's
A(0) (davit_added_mass_zero; hold_zero_frequency=False: not), which the forward-speed
terms' Munk moments come from (postproc.bem_passive.enforce's added_mass_zero): the
ship's re-fit without it moved heave and sway 3.8 % and 2.7 % from Capytaine's A(0).
"""
import os

import numpy as np

from . import bem_db as db


def _retardation(attrs):
    from . import bem_build
    if db.ATTR_RETARDATION_GRID in attrs:
        return tuple(float(v) for v in np.ravel(attrs[db.ATTR_RETARDATION_GRID]))
    return (bem_build.RETARDATION_DT, bem_build.RETARDATION_END, bem_build.FIT_WINDOW)


def _write(source, path, memory, attrs):
    """source's dataset with the memory variables replaced (and created where it lacks
    them) and attrs set, written to path (netCDF4/HDF5 as the build writes it; the other
    variables read and written back raw, decode_cf off)."""
    import xarray as xr
    from . import bem_build, layout
    with xr.open_dataset(source, engine="h5netcdf", decode_cf=False) as ds:
        ds = ds.load()
    ds = ds.drop_vars([n for n in memory if n in ds.variables])
    for name, value in memory.items():
        dims, units, description = db.VARIABLES.get(name) or bem_build.FIT_VARIABLES[name]
        value = np.asarray(value, np.int32 if name == db.SS_ORDER else np.float64)
        ds[name] = xr.DataArray(value, dims=dims,
                                attrs={layout.UNITS: units, layout.DESCRIPTION: description})
    ds.attrs.update(attrs)
    ds.to_netcdf(path, engine="h5netcdf", invalid_netcdf=False)


def refit_file(source, target, nmax=12, tol=0.02, command="", progress=False,
               hold_zero_frequency=True):
    """Database `source` with its radiation memory re-fitted passive (see the module doc),
    written to `target` (may be `source`: written to a temporary name and renamed when
    complete). nmax, tol: the build's --nmax, --fit-tol. Returns the hydro dict of
    postproc.bem_build.fit_memory (min_eigen_damping, min_eigen_damping_unenforced,
    passive_result: postproc.bem_passive.Result)."""
    from . import bem_build
    base = db.Database(source)
    tail = base.attrs.get(db.ATTR_FIT_TAIL)
    tail = None if tail is None else tuple(float(v) for v in np.ravel(tail))
    hydro = {}
    a_zero = np.asarray(base[db.ADDED_MASS_ZERO]) if hold_zero_frequency else None
    memory = bem_build.fit_memory(base.omega, base.added_mass, base.damping,
                                  base.added_mass_inf, base.mass, base.stiffness,
                                  np.asarray(base[db.SS_ORDER]) == 0,
                                  _retardation(base.attrs), tail, nmax, tol, True, progress,
                                  hydro, a_zero=a_zero)
    attrs = {db.ATTR_FIT_MIN_EIGEN: hydro["min_eigen_damping"],
             db.ATTR_FIT_MIN_EIGEN_UNENFORCED: hydro["min_eigen_damping_unenforced"],
             db.ATTR_FIT_PASSIVE_MATRIX: np.int32(1),
             "fit_last_omega": hydro["fit_last_omega"]}
    if command:
        attrs["refit_command_line"] = command
    tmp = f"{target}.tmp{os.getpid()}"
    try:
        _write(source, tmp, memory, attrs)
        os.replace(tmp, target)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return hydro
