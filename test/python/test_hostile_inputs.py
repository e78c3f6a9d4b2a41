"""Hostile files, part 2 (issue 24, defects 3-6 and 8): a disk full before the lock is
written, stale locks that name no process, crafted HDF5 inputs (extents beyond 2^31,
attributes stored as arrays), decks that are pipes, devices or FIFOs, FIFOs as outputs,
output names near NAME_MAX, one output spelled two ways, and a merge whose output is an
input under another spelling.

In the style of test_hostile_files: every refusal has the exit status, exactly one
`davit: error:` line with the words of its cause, no stray lock or temporary file, and
earlier files byte-identical. Every davit call here has a short timeout: a FIFO that
blocks davit fails the test instead of hanging the suite."""
import os
import pathlib
import shutil
import subprocess

import h5py
import numpy as np
import pytest

from test_hostile_files import SHORT, SMALL_SWEEP, _expect_error, _good_output, _stray
from test_sweep import _setup

ROOT = pathlib.Path(__file__).resolve().parents[2]
TIMEOUT = 60


def _run(davit_bin, *args, cwd=None, stdin=None):
    return subprocess.run([davit_bin, *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, input=stdin, timeout=TIMEOUT)


def _shell(command, cwd):
    """A bash command line (process substitution), with davit's exit status."""
    return subprocess.run(["bash", "-c", command], capture_output=True, text=True, cwd=cwd,
                          timeout=TIMEOUT)


def _stored_deck(path):
    with h5py.File(path, "r") as f:
        return f.attrs["input_namelist"].decode()


# --- defect 3: a full disk, stale locks that name no process ------------------------------

@pytest.fixture
def small_disk(tmp_path):
    """A 1 MiB tmpfs (room for a short run or a small sweep once emptied); skipped where
    mounting is refused."""
    mnt = tmp_path / "disk"
    mnt.mkdir()
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("full-disk case needs root to mount a small tmpfs")
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(mnt)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs: {done.stderr.strip()}")
    yield mnt
    subprocess.run(["umount", str(mnt)], check=False)


def _fill(folder):
    """Fill the file system of `folder` to the last byte."""
    with open(folder / "filler", "wb", buffering=0) as f:
        try:
            while True:
                f.write(b"\0" * 4096)
        except OSError:
            pass


@pytest.mark.parametrize("command", ["run", "sweep"])
def test_full_disk_leaves_no_lock_and_names_the_cause(davit_bin, tmp_path, small_disk,
                                                      command):
    if command == "run":
        deck = tmp_path / "deck.nml"
        deck.write_text(SHORT)
        args = ["run", deck]
    else:
        deck = _setup(tmp_path, SMALL_SWEEP)
        args = ["sweep", deck, "--quiet", "--threads", "1"]
    out = small_disk / "out.h5"
    _fill(small_disk)
    _expect_error(_run(davit_bin, *args, "-o", out), "No space left on device")
    assert _stray(small_disk) == [] and not out.exists()
    (small_disk / "filler").unlink()  # space again: the same output is not blocked
    result = _run(davit_bin, *args, "-o", out)
    assert result.returncode == 0, result.stderr
    assert _stray(small_disk) == []


@pytest.mark.parametrize("text", ["", "\n", "not a pid\n", "-5\n"],
                         ids=["empty", "blank", "words", "negative"])
def test_a_lock_naming_no_process_is_taken_over_with_a_note(davit_bin, tmp_path, text):
    out, _ = _good_output(lambda *a: _run(davit_bin, *a), tmp_path)
    (tmp_path / "good.h5.lock").write_text(text)
    result = _run(davit_bin, "run", tmp_path / "good.nml", "-o", out)
    assert result.returncode == 0, result.stderr
    assert "taking over the stale lock" in result.stderr
    assert _stray(tmp_path) == []


def test_a_lock_that_is_a_fifo_is_refused_without_blocking(davit_bin, tmp_path):
    out, before = _good_output(lambda *a: _run(davit_bin, *a), tmp_path)
    os.mkfifo(tmp_path / "good.h5.lock")
    _expect_error(_run(davit_bin, "run", tmp_path / "good.nml", "-o", out),
                  "good.h5.lock", "FIFO", "not a davit lock")
    assert out.read_bytes() == before


# --- defect 4: crafted HDF5 inputs --------------------------------------------------------

def _database(tmp_path, edit):
    """A run deck on a copy of the boat's database changed by `edit` (an h5py File)."""
    db = tmp_path / "crafted.nc"
    shutil.copy(ROOT / "input" / "boat_bem.nc", db)
    with h5py.File(db, "r+") as f:
        edit(f)
    deck = tmp_path / "deck.nml"
    deck.write_text(SHORT + "&boat database = 'crafted.nc' /\n")
    return deck, db


def _declare(name, shape):
    """Replace dataset `name` by one declaring `shape` (chunked: no data is stored)."""
    def edit(f):
        del f[name]
        chunks = (1,) * len(shape) if all(shape) else None
        f.create_dataset(name, shape=shape, dtype="f8", chunks=chunks)
    return edit


DATABASES = [
    ("omega_beyond_2_31", _declare("davit_omega", (2**31 + 7,)), ["davit_omega", "2^31"]),
    ("omega_beyond_2_32", _declare("davit_omega", (2**32 + 1,)), ["davit_omega", "2^31"]),
    ("added_mass_huge", _declare("davit_added_mass", (2**29, 6, 6)),
     ["davit_added_mass", "more than"]),
    ("ss_a_huge", _declare("davit_ss_a", (6, 6, 2**20, 2**20)), ["davit_ss_a", "more than"]),
    ("volume_empty", _declare("davit_displaced_volume", (0,)), ["davit_displaced_volume"]),
    ("omega_as_text", lambda f: (f.__delitem__("davit_omega"),
                                 f.create_dataset("davit_omega", data=np.array([b"a"] * 87))),
     ["davit_omega", "numbers"]),
]


@pytest.mark.parametrize("name, edit, words", DATABASES, ids=[d[0] for d in DATABASES])
def test_crafted_database_is_refused(davit_bin, tmp_path, name, edit, words):
    deck, _ = _database(tmp_path, edit)
    _expect_error(_run(davit_bin, "run", deck, "-o", tmp_path / "out.h5"), *words)
    assert _stray(tmp_path) == [] and not (tmp_path / "out.h5").exists()


@pytest.fixture(scope="module")
def shard_pair(davit_bin, tmp_path_factory):
    """(folder, sweep deck, shard 1/2 summary, shard 2/2 summary) of the small sweep."""
    folder = tmp_path_factory.mktemp("hostile_shards")
    deck = _setup(folder, SMALL_SWEEP)
    parts = []
    for k in (1, 2):
        part = folder / f"a{k}.h5"
        result = _run(davit_bin, "sweep", deck, "--shard", f"{k}/2", "-o", part, "--quiet",
                      "--threads", "1")
        assert result.returncode == 0, result.stderr
        parts.append(part)
    return folder, deck, parts


ARRAY_ATTRIBUTES = [
    ("ncase", np.array([2, 2, 2], dtype=np.int64)),
    ("shard_index", np.array([1, 1, 1, 1], dtype=np.int64)),
    ("shard_count", np.arange(1, 65, dtype=np.int64)),
    ("sweep_namelist", np.array([b"&sweep /" * 8] * 16)),
]


@pytest.mark.parametrize("attr, value", ARRAY_ATTRIBUTES, ids=[a[0] for a in ARRAY_ATTRIBUTES])
@pytest.mark.parametrize("mode", ["resume", "merge"])
def test_summary_attribute_stored_as_an_array_is_refused(davit_bin, shard_pair, tmp_path,
                                                         attr, value, mode):
    folder, _, parts = shard_pair
    crafted = tmp_path / "a1.h5"
    shutil.copy(parts[0], crafted)
    with h5py.File(crafted, "r+") as f:
        f.attrs[attr] = value
    before = crafted.read_bytes()
    if mode == "resume":
        deck = _setup(tmp_path, SMALL_SWEEP)
        result = _run(davit_bin, "sweep", deck, "--shard", "1/2", "-o", crafted, "--resume",
                      "--quiet", "--threads", "1")
    else:
        result = _run(davit_bin, "sweep", "--merge", tmp_path / "merged.h5", crafted,
                      parts[1])
    _expect_error(result, attr, "values, not one")
    assert crafted.read_bytes() == before
    assert _stray(tmp_path) == [] and not (tmp_path / "merged.h5").exists()


@pytest.mark.parametrize("attr, value, words", [
    ("ncase", 2.5, "not an integer"),
    ("sweep_file", "variable-length text (h5py's default)", "variable-length"),
])
def test_summary_attribute_of_the_wrong_type_is_refused(davit_bin, shard_pair, tmp_path,
                                                        attr, value, words):
    _, _, parts = shard_pair
    crafted = tmp_path / "a1.h5"
    shutil.copy(parts[0], crafted)
    with h5py.File(crafted, "r+") as f:
        f.attrs[attr] = value
    _expect_error(_run(davit_bin, "sweep", "--merge", tmp_path / "m.h5", crafted, parts[1]),
                  attr, words)
    assert _stray(tmp_path) == [] and not (tmp_path / "m.h5").exists()


# --- defect 5: decks that are not regular files --------------------------------------------

def test_deck_from_process_substitution_runs_that_deck(davit_bin, tmp_path):
    deck = tmp_path / "d.nml"
    deck.write_text(SHORT)
    result = _shell(f"'{davit_bin}' run <(cat d.nml) -o sub.h5", tmp_path)
    assert result.returncode == 0, result.stderr
    assert _stored_deck(tmp_path / "sub.h5") == SHORT


def test_deck_from_a_pipe_on_stdin_runs_that_deck(davit_bin, tmp_path):
    result = _run(davit_bin, "run", "/dev/stdin", "-o", tmp_path / "in.h5", stdin=SHORT)
    assert result.returncode == 0, result.stderr
    assert _stored_deck(tmp_path / "in.h5") == SHORT


@pytest.mark.parametrize("source, words", [
    ("/dev/zero", ["/dev/zero", "larger than 64 MiB"]),
    ("/dev/null", ["/dev/null", "is empty"]),
])
def test_device_as_deck_is_refused(davit_bin, tmp_path, source, words):
    _expect_error(_run(davit_bin, "run", source, "-o", tmp_path / "x.h5"), *words)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("text", ["", "\n\n", "! only a comment\n"],
                         ids=["nothing", "blank", "comment"])
def test_empty_deck_is_refused(davit_bin, tmp_path, text):
    _expect_error(_run(davit_bin, "run", "/dev/stdin", "-o", tmp_path / "x.h5", stdin=text),
                  "is empty", "nothing came through the pipe")
    deck = tmp_path / "empty.nml"
    deck.write_text(text)
    _expect_error(_run(davit_bin, "run", deck, "-o", tmp_path / "x.h5"), "is empty")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty.nml"]


# --- defect 6: FIFOs ------------------------------------------------------------------------

@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "fifo"
    os.mkfifo(path)
    return path


def test_fifo_deck_without_a_writer_is_refused(davit_bin, tmp_path, fifo):
    _expect_error(_run(davit_bin, "run", fifo, "-o", tmp_path / "x.h5"), "fifo", "is empty")


def test_fifo_deck_with_a_writer_runs(davit_bin, tmp_path, fifo):
    writer = subprocess.Popen(["bash", "-c", f"printf '%s' '{SHORT}' > '{fifo}'"])
    try:
        result = subprocess.run(["bash", "-c", f"sleep 0.2; '{davit_bin}' run '{fifo}' -o "
                                 f"'{tmp_path / 'f.h5'}'"], capture_output=True, text=True,
                                timeout=TIMEOUT)
    finally:
        writer.wait(timeout=TIMEOUT)
    assert result.returncode == 0, result.stderr
    assert _stored_deck(tmp_path / "f.h5") == SHORT


def test_fifo_base_deck_is_refused(davit_bin, tmp_path, fifo):
    deck = _setup(tmp_path, SMALL_SWEEP.replace("base.nml", "fifo"))
    _expect_error(_run(davit_bin, "sweep", deck, "-o", tmp_path / "s.h5", "--quiet"), "fifo",
                  "is empty")
    assert not (tmp_path / "s.h5").exists()


@pytest.mark.parametrize("command", ["run", "rao", "sweep", "merge"])
def test_fifo_output_is_refused(davit_bin, tmp_path, fifo, shard_pair, command):
    deck = tmp_path / "d.nml"
    deck.write_text(SHORT)
    if command == "sweep":
        args = ["sweep", _setup(tmp_path, SMALL_SWEEP), "--quiet", "-o", fifo]
    elif command == "merge":
        args = ["sweep", "--merge", fifo, *shard_pair[2]]
    else:
        args = [command, deck, "-o", fifo]
    _expect_error(_run(davit_bin, *args), "fifo", "not a regular file")
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("which", ["database", "shard"])
def test_fifo_hdf5_input_is_refused(davit_bin, tmp_path, fifo, shard_pair, which):
    if which == "database":
        deck = tmp_path / "d.nml"
        deck.write_text(SHORT + "&boat database = 'fifo' /\n")
        result = _run(davit_bin, "run", deck, "-o", tmp_path / "x.h5")
    else:
        result = _run(davit_bin, "sweep", "--merge", tmp_path / "m.h5", fifo,
                      shard_pair[2][1])
    _expect_error(result, "fifo", "not a regular file")
    assert _stray(tmp_path) == []


# --- defect 8: long names, one output spelled two ways, a merge onto an input ------------

@pytest.mark.parametrize("length", [237, 240, 252, 255])
def test_output_name_too_long_for_its_temporary_is_refused_with_that_cause(davit_bin,
                                                                          tmp_path, length):
    deck = tmp_path / "d.nml"
    deck.write_text(SHORT)
    name = "x" * (length - 3) + ".h5"
    _expect_error(_run(davit_bin, "run", deck, "-o", tmp_path / name), "bytes per name",
                  "at most 236 bytes")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.nml"]


def test_output_name_of_236_bytes_runs(davit_bin, tmp_path):
    deck = tmp_path / "d.nml"
    deck.write_text(SHORT)
    out = tmp_path / ("x" * 233 + ".h5")
    result = _run(davit_bin, "run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("noted, given", [("absolute", "relative"), ("relative", "absolute"),
                                          ("dotted", "relative")])
def test_killed_runs_temporary_is_removed_however_the_output_is_spelled(davit_bin, tmp_path,
                                                                        noted, given):
    out, _ = _good_output(lambda *a: _run(davit_bin, *a), tmp_path)
    dead = subprocess.Popen(["true"])
    dead.wait()
    tmp = f"good.h5.tmp.{dead.pid}.1"
    (tmp_path / tmp).write_bytes(b"half a file")
    spelled = {"absolute": str(tmp_path / tmp), "relative": tmp, "dotted": f"./{tmp}"}
    (tmp_path / "good.h5.lock").write_text(f"{dead.pid}\n{spelled[noted]}\n")
    output = str(out) if given == "absolute" else "good.h5"
    result = _run(davit_bin, "run", "good.nml", "-o", output, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert _stray(tmp_path) == []


@pytest.mark.parametrize("spelling", ["./a1.h5", "{folder}/a1.h5", "link.h5"])
def test_merge_onto_an_input_spelled_otherwise_is_refused(davit_bin, shard_pair, tmp_path,
                                                          spelling):
    _, _, parts = shard_pair
    for part in parts:
        shutil.copy(part, tmp_path / part.name)
    (tmp_path / "link.h5").symlink_to(tmp_path / "a1.h5")
    before = (tmp_path / "a1.h5").read_bytes()
    out = spelling.format(folder=tmp_path)
    _expect_error(_run(davit_bin, "sweep", "--merge", out, "a1.h5", "a2.h5", cwd=tmp_path),
                  "is also an input")
    assert (tmp_path / "a1.h5").read_bytes() == before
    assert _stray(tmp_path) == []
