"""The davit command line: usage errors, input errors and what they leave on disk."""
import re

import h5py
import pytest

BAD_DECKS = [
    ("&simulation\n  dtt = 0.001\n/\n", r"bad\.nml:2: &simulation: unknown key 'dtt'"),
    ("&simulation dt = -1 /\n", r"bad\.nml:1: &simulation: dt = -1: out of range; "
                                r"allowed: 0 < dt <= 1 \[s\]"),
    ("&boat mass = heavy /\n", r"bad\.nml:1: &boat: mass = heavy: not a real number"),
    ("&seastate height = 4 /\n", r"bad\.nml:1: unknown namelist group &seastate"),
    ("&simulation t_end = 5\n", r"bad\.nml:1: group &simulation is not closed"),
    ("&sea\n  kinematics = 'grids' /\n", r"bad\.nml:2: &sea: kinematics = 'grids': unknown "
                                          r"choice; allowed: one of 'sum' 'grid'"),
    ("&sea grid_spacing = 0.0 /\n", r"bad\.nml:1: &sea: grid_spacing = 0\.0: out of range; "
                                    r"allowed: 0 < grid_spacing <= 10 \[m\]"),
]


def test_help_and_version(davit):
    result = davit("--help")
    assert result.returncode == 0
    assert "davit run DECK.nml [-o OUT.h5]" in result.stdout
    result = davit("--version")
    assert result.returncode == 0
    assert re.fullmatch(r"davit \d+\.\d+\.\d+\n", result.stdout)


@pytest.mark.parametrize("args", [[], ["frobnicate"], ["--frob"], ["run"],
                                  ["run", "a.nml", "--bogus"], ["run", "a.nml", "-o"],
                                  ["run", "a.nml", "b.nml"], ["keys", "extra"]])
def test_usage_errors_exit_2(davit, args):
    result = davit(*args)
    assert result.returncode == 2
    assert "usage: davit run" in result.stderr


@pytest.mark.parametrize("text,message", BAD_DECKS)
def test_bad_deck_is_rejected_without_output(davit, tmp_path, text, message):
    deck = tmp_path / "bad.nml"
    deck.write_text(text)
    out = tmp_path / "result.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 1
    assert re.search(message, result.stderr), result.stderr
    assert list(tmp_path.iterdir()) == [deck], "a rejected deck must not leave any file"


def test_bad_deck_keeps_existing_output(davit, short_run, tmp_path):
    """A failed run must not destroy a good file already at the output path."""
    _, good = short_run
    target = tmp_path / "keep.h5"
    target.write_bytes(good.read_bytes())
    deck = tmp_path / "bad.nml"
    deck.write_text("&simulation dt = 0 /\n")
    assert davit("run", deck, "-o", target).returncode == 1
    assert target.read_bytes() == good.read_bytes()


def test_missing_deck(davit, tmp_path):
    result = davit("run", tmp_path / "nope.nml")
    assert result.returncode == 1
    assert "cannot open input deck" in result.stderr and "no such file" in result.stderr


def test_unwritable_output(davit, short_run, tmp_path):
    deck, _ = short_run
    result = davit("run", deck, "-o", tmp_path / "missing_dir" / "x.h5")
    assert result.returncode == 1
    assert "cannot create output file" in result.stderr
    assert not (tmp_path / "missing_dir").exists()


def test_diverging_run_keeps_partial_output(davit, tmp_path):
    """RK4 at dt = 0.1 s is far beyond the sling bounce (70 rad/s) and pitch (130 rad/s)
    stability limit omega dt < 2.8: the run must stop with a diagnostic and keep a file
    marked incomplete."""
    deck = tmp_path / "diverge.nml"
    deck.write_text("&simulation t_end = 50, dt = 0.1, output_interval = 0.1 /\n")
    out = tmp_path / "diverge.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 1
    assert re.search(r"run diverged at t = [0-9.]+ s: boat \w+ = \S+ is not finite or beyond 1000", result.stderr)
    with h5py.File(out, "r") as f:
        assert f.attrs["complete"] == 0
        assert "diverged" in f.attrs["status"].decode()
        assert 0 < f["time"].shape[0] < 501
    assert not (tmp_path / "diverge.h5.tmp").exists()


@pytest.mark.parametrize("sub", ["run", "rao", "sweep", "keys", "modes", "bench"])
def test_subcommand_help(davit, sub):
    """`davit SUB --help` prints that subcommand's usage on stdout and exits 0 (it used to
    be refused as an unknown option)."""
    result = davit(sub, "--help")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith(f"usage: davit {sub}")
    assert result.stderr == ""
