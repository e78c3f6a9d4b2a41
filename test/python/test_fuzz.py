"""Property-based tests of davit's readers (issue 24, "Also build"): the deck reader and
the HDF5 readers (the boat's BEM database, sweep summaries given to --resume and --merge).

- random valid decks, written in every form the reader accepts (key case, real forms,
  separators, comments, `/` or `&end`, CRLF, a byte-order mark), round-trip: the run
  stores the deck's very bytes and the values it chose;
- random bytes and mutated decks end in exit 0, 1 or 2, and when not 0 with exactly one
  `davit: error:` line; never a signal, never a hang;
- mutated databases and summaries (h5py: datasets deleted, reshaped, retyped, declared
  huge, filled with NaN; attributes turned into arrays, floats, variable-length text or
  nulls) end in a clean run or a clean refusal, the summary byte-identical and no lock
  or temporary file left.

Hypothesis runs derandomized (a fixed seed: the same examples every run, no example
database written) with a bounded count per test, ~30 s in all. For a release run more:
DAVIT_FUZZ_EXAMPLES=2000 python -m pytest test/python/test_fuzz.py (the README's
"Testing" part)."""
import os
import pathlib
import shutil
import subprocess
import tempfile

import h5py
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from test_hostile_files import SMALL_SWEEP, _stray
from test_sweep import _setup

ROOT = pathlib.Path(__file__).resolve().parents[2]
TIMEOUT = 60
EXAMPLES = os.environ.get("DAVIT_FUZZ_EXAMPLES")


def _settings(default):
    """Derandomized, `default` examples unless DAVIT_FUZZ_EXAMPLES says otherwise."""
    return settings(max_examples=int(EXAMPLES) if EXAMPLES else default, derandomize=True,
                    database=None, deadline=None, suppress_health_check=list(HealthCheck))


def _davit(davit_bin, *args, cwd=None):
    """davit's exit status and stderr (bytes decoded leniently: decks may be any bytes)."""
    done = subprocess.run([davit_bin, *map(str, args)], capture_output=True, cwd=cwd,
                          timeout=TIMEOUT)
    return done.returncode, done.stderr.decode("utf-8", "replace")


def _clean(rc, stderr, codes=(0, 1, 2)):
    """A clean run or a clean refusal: an exit status of `codes` (a signal is negative),
    and a refusal says why on exactly one error line."""
    assert rc in codes, (rc, stderr)
    errors = [line for line in stderr.splitlines() if line.startswith("davit: error:")]
    assert len(errors) == (0 if rc == 0 else 1), stderr
    assert "Backtrace" not in stderr and "Segmentation" not in stderr, stderr


# --- decks -------------------------------------------------------------------------------

def _real_form(draw, value):
    """`value` (a float with a short decimal form) as the deck may spell it."""
    text = repr(value)
    mantissa, _, exponent = f"{value:e}".partition("e")
    forms = [text, f"{value:e}", f"{mantissa.rstrip('0')}d{int(exponent)}",
             f"{mantissa.rstrip('0')}E{int(exponent):+d}"]
    return draw(st.sampled_from(forms))


@st.composite
def valid_decks(draw):
    """(deck text, {attribute: value it must store}) for a short hanging-boat run."""
    dt = draw(st.sampled_from([1e-3, 5e-4, 2e-3, 0.001]))
    steps = draw(st.integers(5, 40))
    t_end = round(steps * dt, 6)
    seed = draw(st.integers(0, 2**31 - 1))
    integrator = draw(st.sampled_from(["rk4", "dopri5", "rosenbrock", "rosw"]))
    simulation = [("t_end", _real_form(draw, t_end)), ("dt", _real_form(draw, dt)),
                  ("seed", str(seed)), ("integrator", f"'{integrator}'"),
                  ("output_interval", _real_form(draw, dt))]
    groups = [("simulation", draw(st.permutations(simulation)))]
    if draw(st.booleans()):
        speed = draw(st.integers(0, 40))
        groups.append(("wind", [("speed", _real_form(draw, float(speed)))]))
    if draw(st.booleans()):
        v = [draw(st.sampled_from([0.0, 0.25, -0.5, 1.0])) for _ in range(3)]
        groups.append(("boat", [("velocity", ", ".join(_real_form(draw, x) for x in v))]))
    groups = draw(st.permutations(groups))
    newline = draw(st.sampled_from(["\n", "\r\n"]))
    text = "\ufeff" if draw(st.booleans()) else ""
    text += draw(st.sampled_from(["", "! a fuzzed deck" + newline]))
    for group, keys in groups:
        name = draw(st.sampled_from([group, group.upper(), group.capitalize()]))
        sep = draw(st.sampled_from([", ", newline + "  ", " ,\t", "," + newline]))
        body = sep.join(f"{draw(st.sampled_from([k, k.upper()]))}"
                        f"{draw(st.sampled_from([' = ', '=', ' =  ', chr(9) + '=' + chr(9)]))}"
                        f"{v}" for k, v in keys)
        comment = draw(st.sampled_from(["", "  ! why" + newline]))
        end = draw(st.sampled_from([" /", newline + "/", newline + "&end"]))
        text += f"&{name}{newline}  {comment}{body}{end}{newline}"
    return text, {"dt": dt, "seed": seed, "integrator": integrator,
                  "steps": steps if integrator == "rk4" else None}


@_settings(60)
@given(deck=valid_decks())
def test_valid_decks_round_trip(davit_bin, deck):
    text, expected = deck
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "deck.nml"
        path.write_bytes(text.encode())
        out = pathlib.Path(folder) / "out.h5"
        rc, stderr = _davit(davit_bin, "run", path, "-o", out)
        assert rc == 0, (text, stderr)
        with h5py.File(out, "r") as f:
            attrs = dict(f.attrs)
        assert attrs["input_namelist"] == text.encode()
        assert attrs["dt"] == expected["dt"] and attrs["seed"] == expected["seed"]
        assert attrs["integrator"].decode() == expected["integrator"]
        if expected["steps"] is not None:
            assert attrs["steps"] == expected["steps"], text


@_settings(100)
@given(data=st.binary(max_size=3000))
def test_random_bytes_are_refused(davit_bin, data):
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "deck.nml"
        path.write_bytes(data)
        rc, stderr = _davit(davit_bin, "run", path, "-o", pathlib.Path(folder) / "out.h5")
        _clean(rc, stderr, codes=(1, 2))
        assert sorted(p.name for p in pathlib.Path(folder).iterdir()) == ["deck.nml"]


# Bytes a mutation inserts: the deck's own syntax, digits, quotes, controls, non-ASCII.
HOSTILE = st.sampled_from(list("&/=,'\"!\n\r\t .eEdD+-0123456789_()*:;") +
                          ["\0", "\x7f", "\xff", "é", "&end", "/\n&simulation",
                           "1e999", "-1e-999", "NaN", "Inf", ".true.", "2147483648"])


@st.composite
def mutated_decks(draw):
    text, _ = draw(valid_decks())
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(text)))
        op = draw(st.sampled_from(["insert", "delete", "duplicate", "truncate"]))
        if op == "insert":
            text = text[:at] + draw(HOSTILE) + text[at:]
        elif op == "delete":
            text = text[:at] + text[at + draw(st.integers(1, 12)):]
        elif op == "duplicate":
            text = text[:at] + text[at:at + draw(st.integers(1, 20))] + text[at:]
        else:
            text = text[:at]
    return text.encode("utf-8", "surrogateescape")


@_settings(150)
@given(deck=mutated_decks())
def test_mutated_decks_end_cleanly(davit_bin, deck):
    """`modes` reads and checks the deck and builds the system without integrating it,
    so a mutation that turns 0.02 s into 1e9 s cannot make the test slow."""
    with tempfile.TemporaryDirectory() as folder:
        path = pathlib.Path(folder) / "deck.nml"
        path.write_bytes(deck)
        rc, stderr = _davit(davit_bin, "modes", path)
        _clean(rc, stderr)


# --- HDF5 inputs ---------------------------------------------------------------------------

def _new_dataset(f, name, data=None, **kw):
    if name in f:
        del f[name]
    f.create_dataset(name, data=data, **kw)


def _small_shape(dataset):
    """The dataset's shape, or (1,) where an earlier edit declared it huge (reading that
    would fill this process's memory)."""
    return dataset.shape if (dataset.size or 0) <= 10**6 else (1,)


@st.composite
def dataset_edits(draw, names):
    """A function editing one dataset of an h5py File, and a description of it."""
    name = draw(st.sampled_from(names))
    op = draw(st.sampled_from(["delete", "reshape", "declare", "retype", "value", "text"]))
    if op == "delete":
        return (lambda f: f.__delitem__(name) if name in f else None), f"delete {name}"
    if op == "reshape":
        shape = tuple(draw(st.lists(st.integers(0, 9), max_size=4)))
        return (lambda f: _new_dataset(f, name, np.ones(shape))), f"{name} {shape}"
    if op == "declare":
        shape = tuple(draw(st.lists(st.sampled_from([1, 6, 2**16, 2**31 - 1, 2**31, 2**40]),
                                    min_size=1, max_size=4)
                           .filter(lambda s: np.prod(s, dtype=object) < 2**60)))
        return ((lambda f: _new_dataset(f, name, shape=shape, dtype="f8",
                                        chunks=(1,) * len(shape))),
                f"{name} declared {shape}")
    if op == "retype":
        dtype = draw(st.sampled_from(["i1", "u8", "f4", "S3", "?", "c16"]))

        def retype(f):
            if name in f:
                _new_dataset(f, name, np.zeros(_small_shape(f[name]), dtype=dtype))
        return retype, f"{name} as {dtype}"
    if op == "text":
        n = draw(st.integers(0, 5))
        return ((lambda f: _new_dataset(f, name, np.array(["t"] * n, dtype=object),
                                        dtype=h5py.string_dtype())),
                f"{name} as {n} variable-length strings")
    value = draw(st.sampled_from([np.nan, np.inf, -np.inf, 1e308, -1e308, 0.0, -1.0, 1e9]))
    where = draw(st.integers(0, 10**6))

    def set_value(f):
        if name not in f or f[name].shape != _small_shape(f[name]) or \
                f[name].dtype.kind not in "iufb":
            return  # numbers only
        data = np.array(f[name][()], dtype=float)
        if data.size:
            data.flat[where % data.size] = value
        _new_dataset(f, name, data)
    return set_value, f"{name}[{where}] = {value}"


BOAT_DB = ROOT / "input" / "boat_bem.nc"
with h5py.File(BOAT_DB, "r") as _f:
    DB_NAMES = sorted(k for k in _f if k.startswith("davit_"))
DB_DECK = ("&simulation t_end = 0.01, dt = 1.0e-3, output_interval = 0.01 /\n"
           "&boat database = 'crafted.nc' /\n")


@_settings(60)
@given(edits=st.lists(dataset_edits(DB_NAMES), min_size=1, max_size=3))
def test_mutated_databases_end_cleanly(davit_bin, edits):
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        shutil.copy(BOAT_DB, folder / "crafted.nc")
        with h5py.File(folder / "crafted.nc", "r+") as f:
            for edit, _ in edits:
                edit(f)
        (folder / "deck.nml").write_text(DB_DECK)
        rc, stderr = _davit(davit_bin, "run", folder / "deck.nml", "-o", folder / "out.h5")
        _clean(rc, stderr, codes=(0, 1))
        assert _stray(folder) == []


@st.composite
def attribute_edits(draw):
    """A function editing one root attribute of a summary, and a description of it."""
    name = draw(st.sampled_from(["ncase", "shard_index", "shard_count", "threads",
                                 "sweep_namelist", "base_namelist", "sweep_file",
                                 "series_dir", "davit_version"]))
    n = draw(st.integers(0, 6))
    value = draw(st.sampled_from([
        np.arange(n, dtype=np.int64), np.array([b"&sweep /"] * n), 2.5, -1, 0, 2**40,
        "variable-length text", h5py.Empty("i8"), np.int8(1), b"fixed text"]))

    def edit(f):
        if name in f.attrs:
            del f.attrs[name]
        f.attrs[name] = value
    return edit, f"{name} = {value!r}"


@pytest.fixture(scope="module")
def shards(davit_bin, tmp_path_factory):
    """(folder, sweep deck, [shard 1/2, shard 2/2]) of the small sweep."""
    folder = tmp_path_factory.mktemp("fuzz_shards")
    deck = _setup(folder, SMALL_SWEEP)
    parts = []
    for k in (1, 2):
        part = folder / f"a{k}.h5"
        rc, stderr = _davit(davit_bin, "sweep", deck, "--shard", f"{k}/2", "-o", part,
                            "--quiet", "--threads", "1")
        assert rc == 0, stderr
        parts.append(part)
    return folder, deck, parts


SUMMARY_NAMES = ["cases/index", "cases/seed", "cases/level", "cases/wave_height",
                 "results/status", "results/message", "results/outcome", "results/steps",
                 "results/min_clearance", "results/wall_time", "results/collided"]


@_settings(60)
@given(edits=st.lists(st.one_of(dataset_edits(SUMMARY_NAMES), attribute_edits()),
                      min_size=1, max_size=3),
       mode=st.sampled_from(["merge", "resume"]))
def test_mutated_summaries_end_cleanly(davit_bin, shards, edits, mode):
    _, _, parts = shards
    with tempfile.TemporaryDirectory() as folder:
        folder = pathlib.Path(folder)
        crafted = folder / "a1.h5"
        shutil.copy(parts[0], crafted)
        with h5py.File(crafted, "r+") as f:
            for edit, _ in edits:
                edit(f)
        before = crafted.read_bytes()
        if mode == "merge":
            rc, stderr = _davit(davit_bin, "sweep", "--merge", folder / "m.h5", crafted,
                                parts[1])
        else:
            deck = _setup(folder, SMALL_SWEEP)
            rc, stderr = _davit(davit_bin, "sweep", deck, "--shard", "1/2", "-o", crafted,
                                "--resume", "--quiet", "--threads", "1")
        _clean(rc, stderr, codes=(0, 1))
        if rc != 0:
            assert crafted.read_bytes() == before, [d for _, d in edits]
        assert _stray(folder) == []
