"""Every kind of file davit writes opens with xarray (engine h5netcdf): named dimensions
(HDF5 dimension scales, no phony_dim_*), units and long_name as text, and the same values
h5py reads. Each file is small: a short run, the 'sea' fixture, a one-frequency RAO, a
two-case sweep, a short launch with lumps and rotating sheaves, the ship alone, a quick
bench, and the Python-written study and bench-reference layouts."""
import pathlib

import h5py
import numpy as np
import pytest

from postproc import layout
from test_hostile_files import SMALL_SWEEP as SWEEP

xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

ROOT = pathlib.Path(__file__).resolve().parents[2]
# The III.B launch cut short (0.2 s); the sweep's base deck and, with two lumps per sling
# and rotating sheaves (a smaller step), the run that writes every rigging dataset.
LAUNCH = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
    "t_end = 0.0 ", "t_end = 0.2 ")
RIGGED = LAUNCH.replace("lumps = 0", "lumps = 2").replace(
    "sheaves = 'quasi_static'", "sheaves = 'rotating'").replace(
    "dt = 1.0e-3 ", "dt = 5.0e-5 ").replace("t_end = 0.2 ", "t_end = 0.1 ")
RAO = """&rao omegas = 0.6, headings_deg = 90.0, 180.0, settle_time = 20.0,
     measure_periods = 1 /
"""
SHIP = "&simulation scene = 'ship', t_end = 5.0 /\n"


def _groups(path):
    """'' (the root) and every group of the file."""
    names = [""]
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: names.append(name)
                     if isinstance(obj, h5py.Group) else None)
    return names


def _check(path, units=True):
    """Open every group with xarray and compare it with h5py; {group: xarray.Dataset
    (closed)} for further checks."""
    opened = {}
    with h5py.File(path, "r") as f:
        for group in _groups(path):
            with xr.open_dataset(path, engine="h5netcdf", group=group or None) as ds:
                ds.load()
            where = f[group] if group else f
            phony = [d for d in ds.dims if str(d).startswith("phony_dim")]
            assert not phony, f"{path.name}:/{group}: unnamed dimensions {phony}"
            datasets = {name for name, obj in where.items() if isinstance(obj, h5py.Dataset)
                        and not _dimension_only(obj)}
            assert set(ds.variables) == datasets, f"{path.name}:/{group}"
            for name in datasets:
                var, raw = ds[name], where[name]
                assert var.shape == raw.shape, f"/{group}/{name}"
                expected = raw[()]
                if expected.dtype.kind == "S":
                    expected = expected.astype(var.dtype) if var.dtype.kind == "S" else \
                        np.char.decode(expected, "utf-8")
                elif expected.dtype.kind == "O":  # variable-length text: h5py gives bytes
                    expected = np.array([layout._text(v) for v in expected.ravel()],
                                        dtype=object).reshape(expected.shape)
                np.testing.assert_array_equal(var.values, expected, err_msg=f"/{group}/{name}")
                if units:
                    for key in (layout.UNITS, layout.LONG_NAME):
                        assert isinstance(var.attrs.get(key), str), f"/{group}/{name}@{key}"
                    assert var.attrs[layout.LONG_NAME] == var.attrs[layout.DESCRIPTION]
            opened[group] = ds
    return opened


def _dimension_only(obj):
    name = obj.attrs.get("NAME", b"")
    return isinstance(name, bytes) and name.startswith(layout.DIMENSION_ONLY.encode())


def _run(davit, folder, command, deck_text, name, *options):
    folder.mkdir(exist_ok=True)
    deck = folder / f"{name}.nml"
    deck.write_text(deck_text)
    out = folder / f"{name}.h5"
    result = davit(command, deck, "-o", out, *options)
    assert result.returncode == 0, result.stderr
    return out


def test_run_file_time_series_are_time_by_component(short_run):
    _, out = short_run
    groups = _check(out)
    assert groups[""]["time"].attrs[layout.UNITS] == "s"
    boat = groups["boat"]
    for name in ("position", "velocity", "acceleration", "angular_velocity"):
        assert boat[name].dims == ("time", "component")
    assert boat["euler"].dims == ("time", "angle")
    assert boat["position"].attrs[layout.UNITS] == "m"
    assert groups["slings"]["tension"].dims == ("time", "sling")
    assert groups["contact"]["force"].dims == ("time", "fender")
    assert groups["seat"]["acceleration"].dims == ("seat_sample", "component")
    assert groups["events/impacts"]["speed"].dims == ("impact",)
    assert groups["peaks"]["sling_tension"].dims == ("sling",)
    # the scale of a group's shared dimension is one dataset, its time the root's /time
    with h5py.File(out, "r") as f:
        scales = {d[0].name for name in ("position", "velocity", "acceleration")
                  for d in f["boat"][name].dims}
        assert scales == {"/time", "/boat/component"}


def test_netcdf_c_reads_the_same_dimensions(short_run, davit, tmp_path):
    """engine='netcdf4' (the netCDF-C library; skipped where netCDF4 is not installed)."""
    pytest.importorskip("netCDF4")
    _, out = short_run
    rao = _run(davit, tmp_path, "rao", RAO, "rao")
    for path, group, name, dims in ((out, "boat", "position", ("time", "component")),
                                    (rao, "rao", "amplitude", ("heading", "omega", "dof"))):
        with xr.open_dataset(path, engine="netcdf4", group=group) as ds:
            assert not [d for d in ds.dims if str(d).startswith("phony_dim")]
            assert ds[name].dims == dims


def test_the_tree_inherits_the_time_coordinate(short_run):
    """open_datatree: every group's time series sees /time as its coordinate."""
    _, out = short_run
    with xr.open_datatree(out, engine="h5netcdf") as tree:
        position = tree["boat"].to_dataset()["position"]
        with h5py.File(out, "r") as f:
            np.testing.assert_array_equal(position["time"].values, f[layout.TIME][()])
            np.testing.assert_array_equal(position.sel(time=position["time"][-1]).values,
                                          f[layout.BOAT_POSITION][-1])


def test_rigging_and_lump_datasets(davit, tmp_path):
    out = _run(davit, tmp_path, "run", RIGGED, "rigged")
    groups = _check(out)
    assert groups["rigging"]["segment_tension"].dims == ("time", "segment")
    assert groups["rigging"]["pulley_angle"].dims == ("time", "sheave")
    assert groups["slings"]["lump_position"].dims == ("time", "lump", "component")
    assert groups["peaks"]["segment_tension"].dims == ("segment",)
    assert groups["assessment"]["fall_swl"].dims == ("value_limit_margin",)
    assert groups["ship"]["position"].dims == ("time", "component")


def test_sea_file(sea_run):
    _, out = sea_run
    groups = _check(out)
    assert groups["sea"]["elevation"].dims == ("time", "probe")
    assert groups["sea"]["probe_position"].dims == ("probe", "component")
    assert groups["sea/components"]["omega"].dims == ("wave_component",)


def test_ship_scene_file(davit, tmp_path):
    groups = _check(_run(davit, tmp_path, "run", SHIP, "ship"))
    assert groups["ship"]["velocity"].dims == ("time", "component")


def test_rao_file_has_its_coordinates(davit, tmp_path):
    out = _run(davit, tmp_path, "rao", RAO, "rao")
    rao = _check(out)["rao"]
    assert rao["amplitude"].dims == ("heading", "omega", "dof")
    for name in ("omega", "heading", "dof"):
        assert name in rao.coords
    np.testing.assert_allclose(np.degrees(rao["heading"].values), [90.0, 180.0])


def test_sweep_summary(davit, tmp_path):
    (tmp_path / "base.nml").write_text(LAUNCH)
    groups = _check(_run(davit, tmp_path, "sweep", SWEEP, "sweep", "--quiet"))
    assert groups["cases"]["seed"].dims == ("case",)
    assert groups["results"]["message"].dims == ("case",)
    assert groups["results"].sizes["case"] == 2


def test_python_writers_name_their_dimensions(tmp_path):
    """The Python-written files: a study file (layout.write_study) and a bench reference's
    group as postproc.bench_reference writes it (its runs take minutes)."""
    study = tmp_path / "study.h5"
    layout.write_study(study, {"kind": "stability"}, ["a", "b", "c"], [True, True, False],
                       {"dt": [1e-3, 2e-3, 4e-3], "error": [1e-6, 4e-6, np.nan]})
    ds = _check(study, units=False)[layout.STUDY_GROUP]
    assert ds["dt"].dims == (layout.STUDY_RUN,)
    assert sorted(layout.load_study(study)) == ["attrs", "dt", "error", "label", "ok"]
    reference = tmp_path / "reference.h5"
    with h5py.File(reference, "w") as f:
        g = f.create_group("regular")
        values = (np.arange(4.0), np.ones((4, 3)), np.array([-1.0]), np.ones(2), np.ones(7))
        for name, value, dims in zip(layout.BENCH_REFERENCE_DATASETS, values,
                                     layout.BENCH_REFERENCE_DIMS):
            g[name] = value
            layout.name_dimensions(g[name], dims)
    ds = _check(reference, units=False)["regular"]
    assert ds["position"].dims == ("time", "component")
    assert "time" in ds.coords


def test_bench_file(davit, tmp_path):
    """`davit bench --quick` (about 10 s on two cores)."""
    out = tmp_path / "bench.h5"
    result = davit("bench", "--quick", "-o", out, "--decks", ROOT / "input")
    assert result.returncode == 0, result.stderr
    groups = _check(out)
    assert groups["bench/runs"]["wall_time"].dims == ("run",)
    assert groups["bench/sea"]["unit"].dims == ("sea_timing",)
