"""`davit sweep`: thread-count independence, a diverging case, resume, seeds, the summary
layout, progress and the sweep figures, on short launches (1 s of the III.B deck)."""
import pathlib
import re
import shutil

import h5py
import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]

# The III.B launch cut to 1 s, the boat pushed towards the ship at 0.6 m/s: at 0.05 B
# (0.14 m) it hits the side within 0.3 s; at 0.5 B (1.4 m) it cannot reach it (swing
# amplitude v/omega ~ 0.45 m on its ~5.5 m pendulum).
BASE = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
    "t_end = 0.0 ", "t_end = 1.0 ").replace(
    "position = 0.0, 13.3, -15.0", "position = 0.0, 13.3, -15.0\n  velocity = 0.0, -0.6, 0.0")

SWEEP = """&sweep
  base_deck = 'base.nml'
  levels = 4, 5
  angles_deg = 90.0
  clearances_b = 0.05, 0.5
  realisations = 2
  base_seed = 11
/
"""


def _setup(tmp_path, sweep=SWEEP, base=BASE, name="sweep.nml"):
    (tmp_path / "base.nml").write_text(base)
    deck = tmp_path / name
    deck.write_text(sweep)
    return deck


def _sweep(davit, deck, out, *options):
    result = davit("sweep", deck, "-o", out, *options)
    assert result.returncode == 0, result.stderr
    return result


def _datasets(path, skip=("results/wall_time",)):
    data = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: data.__setitem__(name, obj[()])
                     if isinstance(obj, h5py.Dataset) and name not in skip else None)
    return data


def _assert_same(a, b, skip=("results/wall_time",)):
    da, db = _datasets(a, skip), _datasets(b, skip)
    assert da.keys() == db.keys()
    for name in da:
        np.testing.assert_array_equal(da[name], db[name], err_msg=name)


def _splitmix64(seed, n):
    """The n-th SplitMix64 output from `seed` (the documented case-seed derivation)."""
    m = 2 ** 64
    z = (seed + n * 0x9E3779B97F4A7C15) % m
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) % m
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) % m
    return z ^ (z >> 31)


@pytest.fixture(scope="module")
def one_thread(davit, tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep1")
    deck = _setup(folder)
    out = folder / "one.h5"
    result = _sweep(davit, deck, out, "--threads", "1", "--series", folder / "series")
    return deck, out, result


def test_threads_give_bitwise_identical_summaries(davit, one_thread, tmp_path):
    """1 and 2 threads: every dataset identical bit for bit (wall time aside)."""
    deck, one, _ = one_thread
    two = tmp_path / "two.h5"
    _sweep(davit, deck, two, "--threads", "2", "--quiet")
    _assert_same(one, two)
    with h5py.File(two) as f:
        assert f.attrs["threads"] == 2


def test_collisions_follow_the_clearance(one_thread):
    """At 0.05 B the boat swung at the ship hits it, at 0.5 B it cannot; collided is
    min_clearance < 0 and every collision has at least one impact and a first contact."""
    s = layout.load_sweep(one_thread[1])
    assert s.ok.all()
    assert np.array_equal(s.collided == 1, s.min_clearance < 0)
    assert np.array_equal(s.collided == 1, s.impacts >= 1)
    assert (s.collided[s.clearance_b == 0.05] == 1).all()
    assert (s.collided[s.clearance_b == 0.5] == 0).all()
    hit = s.collided == 1
    assert ((s.first_contact_time[hit] > 0) & (s.first_contact_time[hit] < 0.5)).all()
    assert (s.first_contact_time[~hit] == -1).all()
    assert (s.waterborne_time == -1).all()                 # 1 s: still in the air
    assert ((s.min_clearance[~hit] > 0) & (s.min_clearance[~hit] < 1.4)).all()  # it swung in


def test_summary_layout_and_attributes(one_thread):
    """Contract datasets and codes, units and description on every dataset, root
    attributes with both decks' text."""
    deck, out, _ = one_thread
    meta = layout.dataset_metadata(out)
    assert set(layout.SWEEP_FIELDS.values()) <= set(meta)
    assert all(units and description for units, description in meta.values())
    with h5py.File(out) as f:
        for name in layout.SWEEP_FIELDS.values():
            assert f[name].shape == (8,)
        for name in ("cases/index", "cases/level", "cases/wave_type", "results/status",
                     "results/collided", "results/impacts"):
            assert f[name].dtype.kind == "i", name
        assert "2 stokes2" in layout._text(f["cases/wave_type"].attrs["codes"])
        attrs = {k: layout._text(v) for k, v in f.attrs.items()}
    assert set(layout.SWEEP_ROOT_ATTRIBUTES) <= set(attrs)
    assert attrs["sweep_namelist"] == deck.read_text()
    assert attrs["base_namelist"] == BASE and attrs["base_deck"] == "base.nml"
    assert attrs["ncase"] == 8 and attrs["complete"] == 1
    s = layout.load_sweep(out)
    assert s.message == ["ok"] * 8
    assert (s.wave_type == 2).all() and (s.wind == 1).all()
    np.testing.assert_array_equal(s.wind_speed, np.where(s.level == 4, 8.0, 10.0))
    np.testing.assert_array_equal(s.wave_height, np.where(s.level == 4, 2.5, 4.0))


def test_seeds_derive_from_base_seed_and_index(davit, one_thread, tmp_path):
    """Case i's seed is the top 31 bits of SplitMix64(base seed)'s i-th output; two
    realisations of one combination differ (phase and results); a re-run reproduces
    every case exactly."""
    deck, out, _ = one_thread
    s = layout.load_sweep(out)
    assert s.seed.tolist() == [_splitmix64(11, int(i)) >> 33 for i in s.index]
    pairs = s.realisation == 1
    assert (s.phase_deg[pairs] != s.phase_deg[~pairs]).all()
    # the sea moves the boat: its closest approach to the ship differs (the peak tension is
    # the static load at t = 0 in all of these 1 s runs, which start in equilibrium)
    assert (s.min_clearance[pairs] != s.min_clearance[~pairs]).all()
    again = tmp_path / "again.h5"
    _sweep(davit, deck, again, "--threads", "2", "--quiet")
    _assert_same(out, again)


def test_series_files_are_run_files(one_thread):
    """--series writes each case's time series in the run layout."""
    s = layout.load_sweep(one_thread[1])
    for index in s.index:
        run = layout.load(s.series_file(index))
        assert run.complete and run.time[-1] == pytest.approx(1.0)
        assert int(run.attrs["seed"]) == s.seed[index - 1]


def test_progress_on_stderr_and_quiet(davit, one_thread, tmp_path):
    _, _, result = one_thread
    assert "8 of 8 cases to run on 1 thread(s)" in result.stderr
    assert re.search(r"8/8 cases \(0 failed\), [0-9.]+ cases/s", result.stderr)
    quiet = _sweep(davit, one_thread[0], tmp_path / "q.h5", "--quiet", "--threads", "1")
    assert quiet.stderr == ""
    assert "8 cases: 8 ok, 0 failed, 0 not run" in quiet.stdout


def test_diverging_case_fails_and_the_sweep_goes_on(davit, tmp_path):
    """RK4 at dt = 1e-2 s is far beyond the stability limit of the block on its 1 m sling
    (2.83/1500 rad/s = 1.9e-3 s): those cases fail with the divergence message, the others
    finish."""
    deck = _setup(tmp_path, SWEEP.replace("realisations = 2", "dts = 2.0e-4, 1.0e-2"))
    out = tmp_path / "div.h5"
    result = _sweep(davit, deck, out, "--threads", "2")
    s = layout.load_sweep(out)
    bad = s.dt == 1.0e-2
    assert (s.status[bad] == layout.SWEEP_FAILED).all()
    assert (s.status[~bad] == layout.SWEEP_OK).all()
    assert all(re.match(r"run diverged at t = [0-9.]+ s: ", s.message[i])
               for i in np.flatnonzero(bad))
    assert np.isnan(s.min_clearance[bad]).all() and (s.collided[bad] == -1).all()
    assert (s.rhs_evaluations[bad] > 0).all()
    assert "failed: run diverged" in result.stderr
    assert "4 ok, 4 failed" in result.stdout


def test_resume_runs_only_the_unfinished_cases(davit, one_thread, tmp_path):
    """Stopped after 3 cases the summary is whole (3 ok, 5 not run); --resume runs only
    the 5 others: the 3 finished rows keep their wall times and RHS counts bit for bit,
    and the result equals the uninterrupted sweep."""
    deck, full, _ = one_thread
    deck = _setup(tmp_path, deck.read_text())
    out = tmp_path / "part.h5"
    first = _sweep(davit, deck, out, "--threads", "2", "--max-cases", "3")
    assert "3 ok, 0 failed, 5 not run" in first.stdout
    part = layout.load_sweep(out)
    assert (part.status == layout.SWEEP_OK).sum() == 3
    assert part.attrs["complete"] == 0 and np.isnan(part.wall_time[~part.ok]).all()
    second = _sweep(davit, deck, out, "--threads", "2", "--resume")
    assert "5 of 8 cases to run" in second.stderr
    done = layout.load_sweep(out)
    assert done.ok.all()
    np.testing.assert_array_equal(done.wall_time[part.ok], part.wall_time[part.ok])
    np.testing.assert_array_equal(done.rhs_evaluations[part.ok], part.rhs_evaluations[part.ok])
    _assert_same(out, full)


def test_resume_after_a_crash_reruns_only_rows_marked_unfinished(davit, one_thread, tmp_path):
    """A summary whose rows 2 and 7 are reset to status 0 (as a crash between checkpoints
    leaves them): --resume recomputes exactly those two."""
    deck, full, _ = one_thread
    deck = _setup(tmp_path, deck.read_text())
    out = tmp_path / "crash.h5"
    shutil.copy(full, out)
    with h5py.File(out, "r+") as f:
        f["results/status"][[1, 6]] = 0
        f["results/wall_time"][[1, 6]] = np.nan
    result = _sweep(davit, deck, out, "--resume", "--threads", "1")
    assert "2 of 8 cases to run" in result.stderr
    before, after = layout.load_sweep(full), layout.load_sweep(out)
    keep = np.ones(8, bool)
    keep[[1, 6]] = False
    np.testing.assert_array_equal(after.wall_time[keep], before.wall_time[keep])
    assert np.isfinite(after.wall_time).all()
    _assert_same(out, full)


def test_resume_refuses_another_sweep_deck(davit, one_thread, tmp_path):
    deck, full, _ = one_thread
    deck = _setup(tmp_path, deck.read_text().replace("base_seed = 11", "base_seed = 12"))
    out = tmp_path / "other.h5"
    shutil.copy(full, out)
    result = davit("sweep", deck, "-o", out, "--resume")
    assert result.returncode == 1
    assert "cannot resume" in result.stderr and "different sweep deck" in result.stderr


@pytest.mark.parametrize("args", [["sweep"], ["sweep", "x.nml", "--threads", "0"],
                                  ["sweep", "x.nml", "--bogus"], ["sweep", "x.nml", "-o"]])
def test_sweep_usage_errors_exit_2(davit, args):
    assert davit(*args).returncode == 2


@pytest.mark.parametrize("text, message", [
    ("&sweep base_deck = 'base.nml', levels = 4, 6 /",
     "sweep.nml:1: &sweep: levels = 4, 6: out of range; allowed: 3 <= levels <= 5"),
    ("&sweep base_deck = 'base.nml', wave_types = 'stokes3' /",
     "item 1 ('stokes3') is an unknown choice"),
    ("&sweep base_deck = 'base.nml', levels = 4, x /",
     "levels = 4, x: item 2 ('x') is not an integer; allowed: 3 <= levels <= 5 (integers, "
     "1-10 values)"),
    ("&sweep base_deck = 'base.nml', levels = 4, 99999999999 /",
     "levels = 4, 99999999999: out of range; allowed: 3 <= levels <= 5"),
    ("&sweep base_deck = 'base.nml', wind = .true., maybe /",
     "wind = .true., maybe: item 2 ('maybe') is not a logical; allowed: .true. or .false. "
     "(1-2 values)"),
    ("&sweep base_deck = 'missing.nml' /", "base_deck = 'missing.nml': no such file in"),
    ("&sweep levels = 4 /", "base_deck is required"),
    ("&sweep base_deck = 'base.nml', dts = 0.05 /", "must be <= the base deck's"),
    ("&sweep base_deck = 'base.nml' /\n&boat mass = 1.0 /", "unknown namelist group &boat"),
])
def test_bad_sweep_decks_are_rejected(davit, tmp_path, text, message):
    deck = _setup(tmp_path, text)
    out = tmp_path / "bad.h5"
    result = davit("sweep", deck, "-o", out)
    assert result.returncode == 1
    assert message in result.stderr, result.stderr
    assert not out.exists()


@pytest.mark.parametrize("name, ncase", [("sweep_fig19.nml", 80),
                                         ("sweep_fig20_21.nml", 1800),
                                         ("sweep_fig22_23.nml", 1800)])
def test_paper_sweep_decks(davit, name, ncase):
    """The decks of Figs. 19-23 are valid; their base deck hangs the boat 1.5 m off."""
    result = davit("sweep", ROOT / "input" / name, "--dry-run")
    assert result.returncode == 0, result.stderr
    assert f": {ncase} cases on base deck" in result.stdout
    assert "initial clearance 1.4000 m" in result.stdout  # 13.3 - 1.4 - 10.5 (F12)


def test_sweep_figures(one_thread, tmp_path):
    """Both sweep figures, from the summary (with the series: time histories)."""
    _, out, _ = one_thread
    assert cli.main(["sweep", str(out), "-o", str(tmp_path)]) == 0
    names = sorted(p.name for p in tmp_path.glob("*.png"))
    assert names == ["one_fig19.png", "one_min_distance.png"]


def test_load_sweep_names_what_is_missing(short_run, tmp_path):
    with pytest.raises(ValueError, match="not a davit sweep summary .missing cases/index"):
        layout.load_sweep(short_run[1])
    assert cli.main(["sweep", str(short_run[1]), "-o", str(tmp_path)]) == 1
