"""Hostile files and faults around davit's outputs (issue 13, classes 2, 6 and 8): full
disks, outputs that are inputs or folders, a diverging run over a good file, concurrent
runs on one output, stale locks of killed runs, sweeps whose set-up fails after a finished
summary, and crafted summaries given to --resume.

Every case asserts the exit status, exactly one `davit: error:` line, no stray files
(temporary files, locks) and that a good file that was there before is byte-identical.
Extend by adding rows to the CRAFTED table (a summary edit and the words of the refusal)
or a function using `_expect_error`. Full-disk cases mount a small tmpfs; where that is
not allowed (not root, no mount) they are skipped with the reason."""
import os
import pathlib
import shutil
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest

from test_sweep import BASE, _setup

SMALL_SWEEP = """&sweep
  base_deck = 'base.nml'
  levels = 4
  angles_deg = 90.0
  clearances_b = 0.5
  realisations = 2
  base_seed = 11
/
"""

SHORT = "&simulation t_end = 0.2, dt = 1.0e-3, output_interval = 0.01 /\n"
DIVERGE = "&simulation t_end = 50, dt = 0.1, output_interval = 0.1 /\n"


def _error_lines(result):
    return [line for line in result.stderr.splitlines() if line.startswith("davit: error:")]


def _expect_error(result, *words, code=1):
    assert result.returncode == code, (result.returncode, result.stderr)
    lines = _error_lines(result)
    assert len(lines) == 1, result.stderr
    for word in words:
        assert word in lines[0], lines[0]
    assert "Segmentation" not in result.stderr and "Backtrace" not in result.stderr
    return lines[0]


def _stray(folder):
    """Temporary files and locks davit must not leave behind."""
    return sorted(p.name for p in pathlib.Path(folder).rglob("*")
                  if ".tmp" in p.name or p.name.endswith(".lock"))


def _good_output(davit, folder, name="good.h5"):
    deck = folder / "good.nml"
    deck.write_text(SHORT)
    out = folder / name
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return out, out.read_bytes()


@pytest.fixture(scope="module")
def sweep_summary(davit, tmp_path_factory):
    """(folder, sweep deck, finished 2-case summary) of a small sweep."""
    folder = tmp_path_factory.mktemp("hostile_sweep")
    deck = _setup(folder, SMALL_SWEEP)
    out = folder / "done.h5"
    result = davit("sweep", deck, "-o", out, "--threads", "1", "--quiet")
    assert result.returncode == 0, result.stderr
    return folder, deck, out


# --- outputs that are inputs or folders (class 6, class 8) -----------------------------

def test_output_equal_to_the_deck_is_refused(davit, tmp_path):
    deck = tmp_path / "deck.nml"
    deck.write_text(SHORT)
    result = davit("run", deck, "-o", deck)
    _expect_error(result, "refusing to overwrite", "deck.nml", "not a davit output")
    assert deck.read_text() == SHORT
    assert _stray(tmp_path) == []


def test_output_equal_to_a_database_is_refused(davit, tmp_path):
    db = tmp_path / "hull.nc"
    with h5py.File(db, "w") as f:
        f["added_mass"] = np.arange(6.0)
    before = db.read_bytes()
    deck = tmp_path / "deck.nml"
    deck.write_text(SHORT)
    _expect_error(davit("run", deck, "-o", db), "refusing to overwrite", "hull.nc")
    assert db.read_bytes() == before
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("which", ["sweep.nml", "base.nml"])
def test_sweep_output_equal_to_its_decks_is_refused(davit, tmp_path, which):
    deck = _setup(tmp_path, SMALL_SWEEP)
    before = (tmp_path / which).read_bytes()
    _expect_error(davit("sweep", deck, "-o", tmp_path / which), "refusing to overwrite")
    assert (tmp_path / which).read_bytes() == before
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("command", ["run", "sweep"])
def test_output_that_is_a_folder_is_refused(davit, tmp_path, command):
    folder = tmp_path / "outdir"
    folder.mkdir()
    if command == "run":
        deck = tmp_path / "deck.nml"
        deck.write_text(SHORT)
    else:
        deck = _setup(tmp_path, SMALL_SWEEP)
    _expect_error(davit(command, deck, "-o", folder), "is a folder")
    assert list(folder.iterdir()) == []
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("args", [["run", "d.nml", "-o", ""], ["sweep", "s.nml", "-o", ""],
                                  ["sweep", "s.nml", "--series", " "]])
def test_empty_output_names_are_usage_errors(davit, tmp_path, args):
    (tmp_path / "d.nml").write_text(SHORT)
    _setup(tmp_path, SMALL_SWEEP, name="s.nml")
    _expect_error(davit(*args, cwd=tmp_path), "needs a name", code=2)
    assert not (tmp_path / "out").exists()


# --- a diverging run over a good output (class 6) -------------------------------------

def test_diverging_run_keeps_the_good_file_and_puts_the_partial_record_beside(davit, tmp_path):
    out, before = _good_output(davit, tmp_path, "run.h5")
    deck = tmp_path / "diverge.nml"
    deck.write_text(DIVERGE)
    line = _expect_error(davit("run", deck, "-o", out), "run diverged", "run.partial.h5",
                         "left as it was")
    assert out.read_bytes() == before
    with h5py.File(tmp_path / "run.partial.h5", "r") as f:
        assert f.attrs["complete"] == 0
    assert "diverged" in line
    assert _stray(tmp_path) == []


def test_diverging_run_never_replaces_a_foreign_partial_name(davit, tmp_path):
    out, before = _good_output(davit, tmp_path, "run.h5")
    foreign = tmp_path / "run.partial.h5"
    foreign.write_text("someone's notes\n")
    deck = tmp_path / "diverge.nml"
    deck.write_text(DIVERGE)
    _expect_error(davit("run", deck, "-o", out), "run diverged", "partial record not kept")
    assert out.read_bytes() == before
    assert foreign.read_text() == "someone's notes\n"
    assert _stray(tmp_path) == []


# --- concurrent runs and locks (class 6) ----------------------------------------------

def test_a_live_lock_refuses_a_second_run(davit, tmp_path):
    out, before = _good_output(davit, tmp_path)
    lock = tmp_path / "good.h5.lock"
    lock.write_text(f"{os.getpid()}\n")  # this test process: alive
    deck = tmp_path / "good.nml"
    _expect_error(davit("run", deck, "-o", out), "another davit run", str(os.getpid()))
    assert out.read_bytes() == before
    assert lock.read_text() == f"{os.getpid()}\n"
    lock.unlink()


def test_a_stale_lock_of_a_killed_run_is_taken_over(davit, tmp_path):
    out, _ = _good_output(davit, tmp_path)
    dead = subprocess.Popen(["true"])
    dead.wait()
    tmp = tmp_path / f"good.h5.tmp.{dead.pid}.1"
    tmp.write_bytes(b"half a file")
    (tmp_path / "good.h5.lock").write_text(f"{dead.pid}\n{tmp}\n")
    result = davit("run", tmp_path / "good.nml", "-o", out)
    assert result.returncode == 0, result.stderr
    assert _stray(tmp_path) == []


def test_two_runs_on_one_output_never_mislabel_it(davit_bin, tmp_path):
    """Without HDF5's own file locking (NFS, Lustre) two runs on one output either run
    one after the other or the second is refused; the file always holds the deck of a
    run that reported success."""
    decks = []
    for k, t_end in enumerate((0.3, 0.4)):
        deck = tmp_path / f"d{k}.nml"
        deck.write_text(SHORT.replace("t_end = 0.2", f"t_end = {t_end}"))
        decks.append(deck)
    out = tmp_path / "shared.h5"
    env = dict(os.environ, HDF5_USE_FILE_LOCKING="FALSE")
    procs = [subprocess.Popen([davit_bin, "run", str(d), "-o", str(out)], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for d in decks]
    results = [(p.wait(timeout=120), p.stderr.read()) for p in procs]
    ok = [decks[k].read_text() for k, (rc, _) in enumerate(results) if rc == 0]
    for rc, err in results:
        assert rc in (0, 1), err
        if rc == 1:
            assert "another davit run" in err, err
    assert ok, results
    with h5py.File(out, "r") as f:
        assert f.attrs["input_namelist"].decode() in ok
        assert f.attrs["complete"] == 1
    assert _stray(tmp_path) == []


def test_kill_leaves_no_file_that_looks_whole_and_the_next_run_goes_on(davit, davit_bin,
                                                                       tmp_path):
    out, before = _good_output(davit, tmp_path)
    deck = tmp_path / "long.nml"
    deck.write_text("&simulation t_end = 600.0, dt = 1.0e-4, output_interval = 0.1 /\n")
    proc = subprocess.Popen([davit_bin, "run", str(deck), "-o", str(out)],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    assert proc.poll() is None, "the long run ended before it could be killed"
    assert (tmp_path / "good.h5.lock").exists()
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert out.read_bytes() == before
    result = davit("run", tmp_path / "good.nml", "-o", out)
    assert result.returncode == 0, result.stderr
    assert _stray(tmp_path) == []


# --- full disks (class 2) --------------------------------------------------------------

@pytest.fixture
def full_disk(tmp_path):
    """A 64 KiB tmpfs (too small for a run's file); skipped where mounting is refused."""
    mnt = tmp_path / "full"
    mnt.mkdir()
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("full-disk case needs root to mount a small tmpfs")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(mnt)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs: {done.stderr.strip()}")
    yield mnt
    subprocess.run(["umount", str(mnt)], check=False)


def test_disk_full_fails_cleanly_and_keeps_the_earlier_file(davit_bin, tmp_path, full_disk):
    good = full_disk / "run.h5"
    with h5py.File(good, "w") as f:  # a small earlier davit output on the full disk
        f.attrs["davit_version"] = "0"
        f["time"] = np.arange(10.0)
    before = good.read_bytes()
    deck = tmp_path / "deck.nml"
    deck.write_text(SHORT.replace("t_end = 0.2", "t_end = 2.0").replace("0.01", "0.002"))
    errfile = tmp_path / "stderr.txt"
    with open(errfile, "w") as err:  # stderr in a file: the error line must get there
        rc = subprocess.run([davit_bin, "run", str(deck), "-o", str(good)], stderr=err,
                            stdout=subprocess.DEVNULL).returncode
    result = subprocess.CompletedProcess([], rc, "", errfile.read_text())
    _expect_error(result, "disk full", "left as it was")
    assert good.read_bytes() == before
    assert _stray(full_disk) == []


def test_sweep_summary_on_a_full_disk_fails_cleanly(davit, tmp_path, full_disk):
    deck = _setup(tmp_path, SMALL_SWEEP.replace("realisations = 2", "realisations = 400"))
    out = full_disk / "summary.h5"
    _expect_error(davit("sweep", deck, "-o", out, "--quiet", "--max-cases", "1"),
                  "disk full")
    assert not out.exists()
    assert _stray(full_disk) == [] and _stray(tmp_path) == []


def test_sweep_series_on_a_full_disk_fails_cleanly(davit, tmp_path, full_disk):
    deck = _setup(tmp_path, SMALL_SWEEP)
    out = tmp_path / "summary.h5"
    result = davit("sweep", deck, "-o", out, "--series", full_disk / "series", "--quiet",
                   "--threads", "1")
    _expect_error(result, "disk full")
    with h5py.File(out, "r") as f:  # the summary itself is whole
        assert list(f["results/status"][()]) == [1, 1]
    assert _stray(full_disk) == [] and _stray(tmp_path) == []


# --- sweeps: the summary untouched until the set-up is valid (class 6) ------------------

def test_a_locked_summary_refuses_a_second_sweep(davit, sweep_summary, tmp_path):
    _, _, done = sweep_summary
    out = tmp_path / "busy.h5"
    shutil.copy(done, out)
    before = out.read_bytes()
    (tmp_path / "busy.h5.lock").write_text(f"{os.getpid()}\n")
    deck = _setup(tmp_path, SMALL_SWEEP)
    _expect_error(davit("sweep", deck, "-o", out, "--resume"), "another davit run")
    assert out.read_bytes() == before
    (tmp_path / "busy.h5.lock").unlink()


def test_series_folder_equal_to_the_summary_is_refused(davit, tmp_path):
    deck = _setup(tmp_path, SMALL_SWEEP)
    out = tmp_path / "s.h5"
    _expect_error(davit("sweep", deck, "-o", out, "--series", out), "two different paths")
    assert not out.exists() and _stray(tmp_path) == []


def test_bad_series_folder_leaves_a_finished_summary_alone(davit, sweep_summary, tmp_path):
    folder, deck, done = sweep_summary
    out = tmp_path / "keep.h5"
    shutil.copy(done, out)
    before = out.read_bytes()
    blocker = tmp_path / "plainfile"
    blocker.write_text("x")
    deck2 = _setup(tmp_path, SMALL_SWEEP)
    _expect_error(davit("sweep", deck2, "-o", out, "--series", blocker / "sub"),
                  "series folder")
    assert out.read_bytes() == before
    assert _stray(tmp_path) == []


# --- crafted summaries given to --resume (class 5 of the issue, resume part) -----------

def _resize(name, n):
    def edit(f):
        data = f[name][()]
        del f[name]
        f[name] = np.resize(data, n)
    return edit


def _set(name, index, value):
    def edit(f):
        f[name][index] = value
    return edit


def _delete(name):
    def edit(f):
        del f[name]
    return edit


def _retype(name, dtype):
    def edit(f):
        data = f[name][()]
        del f[name]
        f[name] = data.astype(dtype) if dtype != "numbers" else np.arange(len(data))
    return edit


def _to_2d(name):
    def edit(f):
        data = f[name][()]
        del f[name]
        f[name] = np.stack([data, data])
    return edit


CRAFTED = [
    ("status_short", _resize("results/status", 1), "rows"),
    ("status_long", _resize("results/status", 5), "rows"),
    ("status_7", _set("results/status", 0, 7), "out of range"),
    ("status_minus_3", _set("results/status", 1, -3), "out of range"),
    ("status_missing", _delete("results/status"), "no dataset /results/status"),
    ("status_2d", _to_2d("results/status"), "not 1-D"),
    ("collided_5", _set("results/collided", 0, 5), "out of range"),
    ("steps_negative", _set("results/steps", 0, -1), "out of range"),
    ("message_short", _resize("results/message", 1), "rows"),
    ("outcome_long", _resize("results/outcome", 4), "rows"),
    ("clearance_short", _resize("results/min_clearance", 1), "rows"),
    ("wall_time_missing", _delete("results/wall_time"), "no dataset /results/wall_time"),
    ("wall_time_nan_ok", _set("results/wall_time", 0, np.nan), "wall_time"),
    ("index_long", _resize("cases/index", 3), "rows"),
    ("tension_long", _resize("results/peak_fall_tension", 9), "rows"),
    ("status_as_reals", _retype("results/status", np.float64), "not of integers"),
    ("message_as_numbers", _retype("results/message", "numbers"), "cannot read"),
    ("ncase_attr_3", lambda f: f.attrs.__setitem__("ncase", 3), "different number of cases"),
    ("no_version", lambda f: f.attrs.__delitem__("davit_version"), "not a davit output"),
]


@pytest.mark.parametrize("name, edit, words", CRAFTED, ids=[c[0] for c in CRAFTED])
def test_resume_refuses_crafted_summaries(davit, sweep_summary, tmp_path, name, edit, words):
    folder, _, done = sweep_summary
    deck = _setup(tmp_path, SMALL_SWEEP)
    out = tmp_path / "crafted.h5"
    shutil.copy(done, out)
    with h5py.File(out, "r+") as f:
        edit(f)
    before = out.read_bytes()
    _expect_error(davit("sweep", deck, "-o", out, "--resume", "--quiet"), words)
    assert out.read_bytes() == before
    assert _stray(tmp_path) == []
