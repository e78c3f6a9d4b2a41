"""netCDF's own tools read every kind of file davit writes: `ncdump` (the whole file, data
included, not only -h) and `nccopy` exit 0 on a run, a sea run, a sweep summary, a shard, a
merged summary, an RAO file, a quick benchmark and a study file. netCDF-C 4.9 crashes
(exit 139) on fixed-length string arrays and shows their entries after the first as NIL,
so davit writes text datasets as variable-length UTF-8 strings; the text must come back
whole. ncdump and nccopy come from Debian's netcdf-bin (bash make.sh test installs it)."""
import pathlib
import shutil
import subprocess

import h5py
import numpy as np
import pytest

from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]

pytestmark = pytest.mark.skipif(
    shutil.which("ncdump") is None or shutil.which("nccopy") is None,
    reason="ncdump/nccopy not installed (apt-get install netcdf-bin; bash make.sh test "
           "installs it)")

# The III.B launch cut to 1 s (still lowering at its end: every case has an outcome text).
BASE = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
    "t_end = 0.0 ", "t_end = 1.0 ")
SWEEP = """&sweep
  base_deck = 'base.nml'
  levels = 4, 5
  angles_deg = 90.0
  clearances_b = 0.05, 0.5
/
"""


def _ok(davit, *args):
    result = davit(*args)
    assert result.returncode == 0, result.stderr
    return result


@pytest.fixture(scope="module")
def files(davit, short_run, sea_run, tmp_path_factory):
    """{kind: path} of one file of every kind davit writes."""
    folder = tmp_path_factory.mktemp("netcdf")
    (folder / "base.nml").write_text(BASE)
    sweep = folder / "sweep.nml"
    sweep.write_text(SWEEP)
    out = {"run": short_run[1], "sea": sea_run[1]}
    out["summary"] = folder / "summary.h5"
    _ok(davit, "sweep", sweep, "-o", out["summary"], "--threads", "1", "--quiet")
    out["shard"] = folder / "shard1.h5"
    _ok(davit, "sweep", sweep, "-o", out["shard"], "--shard", "1/2", "--quiet")
    _ok(davit, "sweep", sweep, "-o", folder / "shard2.h5", "--shard", "2/2", "--quiet")
    out["merged"] = folder / "merged.h5"
    _ok(davit, "sweep", "--merge", out["merged"], out["shard"], folder / "shard2.h5")
    out["rao"] = folder / "rao.h5"
    _ok(davit, "rao", ROOT / "input" / "ship_rao.nml", "-o", out["rao"])
    out["bench"] = folder / "bench.h5"
    _ok(davit, "bench", "--quick", "-o", out["bench"], "--decks", ROOT / "input")
    out["study"] = folder / "study.h5"
    layout.write_study(out["study"], {"kind": "work_precision", "base": "base.nml"},
                       ["rk4 dt=1e-3", "rosenbrock dt=0.01 dt_contact=1e-4"], [1, 0],
                       {"wall_time": [1.0, 2.0]})
    return out


KINDS = ["run", "sea", "summary", "shard", "merged", "rao", "bench", "study"]


@pytest.mark.parametrize("kind", KINDS)
def test_ncdump_reads_the_whole_file(files, kind):
    result = subprocess.run(["ncdump", str(files[kind])], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, (result.returncode, result.stderr[-2000:])
    assert "data:" in result.stdout


@pytest.mark.parametrize("kind", KINDS)
def test_nccopy_copies_the_file(files, kind, tmp_path):
    copy = tmp_path / "copy.nc"
    result = subprocess.run(["nccopy", str(files[kind]), str(copy)], capture_output=True,
                            text=True, timeout=300)
    assert result.returncode == 0, (result.returncode, result.stderr[-2000:])
    assert copy.stat().st_size > 0


@pytest.mark.parametrize("kind, name", [("summary", "results/outcome"),
                                        ("summary", "results/message"),
                                        ("merged", "results/outcome"),
                                        ("bench", "bench/runs/deck"),
                                        ("study", "study/label")])
def test_text_datasets_are_variable_length_utf8(files, kind, name):
    with h5py.File(files[kind], "r") as f:
        info = h5py.check_string_dtype(f[name].dtype)
    assert info is not None and info.length is None and info.encoding == "utf-8"


def test_ncdump_shows_every_entry_of_a_text_array(files):
    """Each study label and each case's outcome appears in ncdump's data section (a
    fixed-length array showed NIL after the first entry)."""
    study = subprocess.run(["ncdump", "-v", "label", str(files["study"])],
                           capture_output=True, text=True, check=True).stdout
    assert '"rk4 dt=1e-3", "rosenbrock dt=0.01 dt_contact=1e-4"' in study
    summary = subprocess.run(["ncdump", "-v", "outcome", str(files["summary"])],
                             capture_output=True, text=True, check=True).stdout
    # the base deck stops at t = 1 s while the boat still hangs: every case says so
    assert summary.count('"not waterborne by t = 1.000 s') == 4


def test_resume_reads_fixed_length_text_of_older_summaries(davit, files, tmp_path):
    """A summary written before text became variable-length (fixed-length, blank-padded
    ASCII, as h5py writes bytes) still resumes: its 4 cases are done, none is rerun."""
    old = tmp_path / "old.h5"
    shutil.copy(files["summary"], old)
    with h5py.File(old, "r+") as f:
        for name in ("results/message", "results/outcome"):
            text = [layout._text(s) for s in f[name][()]]
            del f[name]
            width = max(1, max(len(s) for s in text))
            f[name] = np.array([s.ljust(width).encode() for s in text], dtype=f"S{width}")
    sweep = pathlib.Path(files["summary"]).parent / "sweep.nml"
    result = davit("sweep", sweep, "-o", old, "--resume")
    assert result.returncode == 0, result.stderr
    assert "0 of 4 cases to run" in result.stderr
