"""`davit sweep` with adaptive realisations (&sweep target_halfwidth > 0, issue 16): each
cell gets realisations until the 95 % Wilson half-width of its collision probability is at
most the target or it has max_realisations. On cells whose outcome is forced (0.05 B: every
launch hits the ship; 0.5 B: none does) the half-width after n realisations is known in
closed form, z^2 / (2 (n + z^2)), so the round at which each cell stops is computed here by
hand. Also: the cap, 1 vs 2 threads bit for bit, --resume after an interruption or lost
rows, status 3 rows and their message, the keys' documentation and range errors, and the
refusal of --shard and MPI. Launches are cut to 0.4 s (a few hundredths of a second each)."""
import math
import re

import h5py
import numpy as np
import pytest

from postproc import layout
from test_sweep import BASE, _assert_same, _setup, _sweep

Z = 1.959963984540054
SHORT = BASE.replace("t_end = 1.0 ", "t_end = 0.4 ")
assert SHORT != BASE

# first round 4, batches of 4 (the default: realisations), at most 40
ADAPTIVE = """&sweep
  base_deck = 'base.nml'
  clearances_b = 0.05, 0.5
  realisations = 4
  target_halfwidth = 0.1
  max_realisations = 40
  base_seed = 11
/
"""
CAP = 40


def _wilson(k, n, z=Z):
    """(lower, upper) of the Wilson score interval, no continuity correction."""
    if n == 0:
        return 0.0, 1.0
    centre = 2 * k + z * z
    spread = z * math.sqrt(z * z + 4 * k * (n - k) / n)
    return (max(0.0, (centre - spread) / (2 * (n + z * z))),
            min(1.0, (centre + spread) / (2 * (n + z * z))))


def _halfwidth(k, n):
    lower, upper = _wilson(k, n)
    return (upper - lower) / 2


def _stop_at(first, batch, cap, target, collided_fraction):
    """Realisations a cell whose launches all (fraction 1) or never (0) collide runs: the
    first round size n in first, first + batch, ... (capped) with z^2/(2(n + z^2)) <= target
    (the closed form of the Wilson half-width for k = 0 or k = n)."""
    assert collided_fraction in (0, 1)
    n = first
    while n < cap and Z * Z / (2 * (n + Z * Z)) > target:
        n = min(n + batch, cap)
    return n


def _replay(collided, status, first, batch, cap, target):
    """The rounds of one cell replayed from its stored rows: realisations it must have run."""
    n = first
    while True:
        run = status[:n]
        assert ((run == layout.SWEEP_OK) | (run == layout.SWEEP_FAILED)).all()
        ok = run == layout.SWEEP_OK
        if n >= cap or _halfwidth(int((collided[:n][ok] == 1).sum()), int(ok.sum())) <= target:
            return n
        n = min(n + batch, cap)


def _cells(s, cap):
    return s.status.reshape(-1, cap), s.collided.reshape(-1, cap)


@pytest.fixture(scope="module")
def adaptive_run(davit, tmp_path_factory):
    folder = tmp_path_factory.mktemp("adaptive")
    deck = _setup(folder, ADAPTIVE, SHORT)
    out = folder / "one.h5"
    result = _sweep(davit, deck, out, "--threads", "1")
    return deck, out, result


def test_closed_form_matches_the_wilson_formula():
    """The hand rule used below is the Wilson half-width for k = 0 and k = n."""
    for n in (1, 4, 15, 16, 40):
        assert _halfwidth(0, n) == pytest.approx(Z * Z / (2 * (n + Z * Z)), rel=1e-12)
        assert _halfwidth(n, n) == pytest.approx(Z * Z / (2 * (n + Z * Z)), rel=1e-12)


def test_cells_stop_where_the_rule_says(adaptive_run):
    """Target 0.1: n >= 4 z^2 = 15.4, so rounds 4, 8, 12 stay open (12: 0.121) and both
    forced cells stop after the fourth round, at 16; the other 24 slots are not needed."""
    _, out, result = adaptive_run
    assert _stop_at(4, 4, CAP, 0.1, 0) == 16
    assert _halfwidth(0, 12) > 0.1 >= _halfwidth(0, 16)
    s = layout.load_sweep(out)
    status, collided = _cells(s, CAP)
    assert status.shape == (2, CAP)
    assert (collided[0, :16] == 1).all() and (collided[1, :16] == 0).all()   # forced
    for cell in range(2):
        assert (status[cell, :16] == layout.SWEEP_OK).all()
        assert (status[cell, 16:] == layout.SWEEP_NOT_NEEDED).all()
        assert _replay(collided[cell], status[cell], 4, 4, CAP, 0.1) == 16
    assert "32 ok, 0 failed, 0 not run, 48 not needed" in result.stdout
    rounds = re.findall(r"davit sweep: round (\d+): (\d+) of 2 cells stopped", result.stderr)
    assert rounds == [("1", "0"), ("2", "0"), ("3", "0"), ("4", "2")]
    assert "adaptive realisations, 2 cells of up to 40 realisations" in result.stderr


def test_not_needed_rows_say_why(adaptive_run):
    """Status 3 rows carry the cell's half-width, the target and the realisations run; their
    results are undefined like those of unrun cases; the summary is complete."""
    s = layout.load_sweep(adaptive_run[1])
    spare = s.status == layout.SWEEP_NOT_NEEDED
    width = f"{_halfwidth(0, 16):.4f}"
    assert width == "0.0968"
    assert all(s.message[i].startswith(f"not needed: cell's 95 % half-width {width} <= "
                                       "0.1000 after 16 realisations")
               for i in np.flatnonzero(spare))
    assert (s.collided[spare] == -1).all() and np.isnan(s.min_clearance[spare]).all()
    assert s.attrs["complete"] == 1
    with h5py.File(adaptive_run[1]) as f:
        assert "3 not needed" in layout._text(f["results/status"].attrs["description"])
        assert f.attrs["target_halfwidth"] == pytest.approx(0.1)
        assert f.attrs["max_realisations"] == CAP and f.attrs["realisation_batch"] == 4


def test_seeds_fixed_by_cell_and_realisation(adaptive_run):
    """Cases are laid out cells x max_realisations: case i's seed is that of index i."""
    from test_sweep import _splitmix64
    s = layout.load_sweep(adaptive_run[1])
    assert s.ncase == 2 * CAP
    assert s.seed.tolist() == [_splitmix64(11, int(i)) >> 33 for i in s.index]
    assert s.realisation.tolist() == list(range(1, CAP + 1)) * 2


def test_threads_give_bitwise_identical_summaries(davit, adaptive_run, tmp_path):
    deck, one, _ = adaptive_run
    two = tmp_path / "two.h5"
    _sweep(davit, deck, two, "--threads", "2", "--quiet")
    _assert_same(one, two)


def test_the_cap_is_respected(davit, tmp_path):
    """Target 0.05 needs n >= 9 z^2 = 34.6, beyond the cap 20: rounds 5, 12, 19 and the
    last 1 to reach 20; every slot runs, none is 'not needed'."""
    deck = _setup(tmp_path, ADAPTIVE.replace("\n  realisations = 4\n", "\n  realisations = 5\n"
                                             "  realisation_batch = 7\n").replace(
        "target_halfwidth = 0.1", "target_halfwidth = 0.05").replace(
        "max_realisations = 40", "max_realisations = 20"), SHORT)
    assert _stop_at(5, 7, 20, 0.05, 1) == 20
    out = tmp_path / "cap.h5"
    result = _sweep(davit, deck, out, "--threads", "2")
    s = layout.load_sweep(out)
    assert s.ncase == 40 and s.ok.all()
    assert "round 4: 2 of 2 cells stopped (0 at 95 % half-width <= 0.0500, 2 at " \
           "max_realisations 20)" in result.stderr
    assert "round 5" not in result.stderr


def test_a_batch_that_overshoots_the_target(davit, tmp_path):
    """First 5, batches of 7, target 0.1: 5, 12 stay open, 19 >= 15.4 stops."""
    deck = _setup(tmp_path, ADAPTIVE.replace("\n  realisations = 4\n", "\n  realisations = 5\n"
                                             "  realisation_batch = 7\n"), SHORT)
    out = tmp_path / "batch.h5"
    _sweep(davit, deck, out, "--threads", "2", "--quiet")
    status, collided = _cells(layout.load_sweep(out), CAP)
    assert _stop_at(5, 7, CAP, 0.1, 0) == 19
    for cell in range(2):
        assert (status[cell, :19] == layout.SWEEP_OK).all()
        assert (status[cell, 19:] == layout.SWEEP_NOT_NEEDED).all()
        assert _replay(collided[cell], status[cell], 5, 7, CAP, 0.1) == 19


def test_resume_after_an_interruption(davit, adaptive_run, tmp_path):
    """Stopped after 10 cases (inside round 2) the summary has no status 3 yet and is not
    complete; --resume replays the rounds from the stored rows and ends with the
    uninterrupted summary; the 10 rows it kept keep their wall times."""
    deck = _setup(tmp_path, ADAPTIVE, SHORT)
    out = tmp_path / "part.h5"
    first = _sweep(davit, deck, out, "--threads", "2", "--max-cases", "10")
    assert "10 ok, 0 failed, 70 not run" in first.stdout
    part = layout.load_sweep(out)
    assert part.attrs["complete"] == 0
    assert not (part.status == layout.SWEEP_NOT_NEEDED).any()
    _sweep(davit, deck, out, "--threads", "2", "--resume", "--quiet")
    done = layout.load_sweep(out)
    np.testing.assert_array_equal(done.wall_time[part.ok], part.wall_time[part.ok])
    _assert_same(out, adaptive_run[1])


def test_resume_after_lost_rows(davit, adaptive_run, tmp_path):
    """Rows reset to status 0 (a crash between checkpoints), in the first round, the last
    round and among the not-needed slots: --resume reruns only the lost ok rows and gives
    the same summary; a resume of a complete summary runs nothing."""
    deck = _setup(tmp_path, ADAPTIVE, SHORT)
    out = tmp_path / "lost.h5"
    out.write_bytes(adaptive_run[1].read_bytes())
    with h5py.File(out, "r+") as f:
        status = f["results/status"][()]
        status[[1, 14, 30, 55]] = layout.SWEEP_NOT_RUN
        f["results/status"][...] = status
    result = _sweep(davit, deck, out, "--threads", "2", "--resume")
    assert re.search(r"davit sweep: 3/3 cases", result.stderr)
    _assert_same(out, adaptive_run[1])
    again = _sweep(davit, deck, out, "--threads", "2", "--resume")
    assert "32 ok, 0 failed, 0 not run, 48 not needed" in again.stdout
    _assert_same(out, adaptive_run[1])


def test_keys_documented_and_range_checked(davit, tmp_path):
    keys = davit("keys").stdout
    for key in ("target_halfwidth", "max_realisations", "realisation_batch"):
        assert f"| `{key}` |" in keys
    bad = davit("sweep", _setup(tmp_path, ADAPTIVE.replace("= 0.1", "= 0.7"), SHORT),
                "--dry-run")
    assert bad.returncode != 0
    assert "target_halfwidth" in bad.stderr and "0 <= target_halfwidth <= 0.5" in bad.stderr
    low = davit("sweep", _setup(tmp_path, ADAPTIVE.replace("= 40", "= 3"), SHORT), "--dry-run")
    assert low.returncode != 0
    assert "max_realisations = 3 must be >= realisations = 4" in low.stderr


def test_shards_refused(davit, tmp_path):
    deck = _setup(tmp_path, ADAPTIVE, SHORT)
    result = davit("sweep", deck, "-o", tmp_path / "s1.h5", "--shard", "1/2")
    assert result.returncode != 0
    assert "target_halfwidth > 0 (adaptive realisations) cannot run across shards" \
        in result.stderr
    assert not (tmp_path / "s1.h5").exists()


def test_mpi_refused(tmp_path):
    """Across MPI ranks the coordinator refuses before any case runs."""
    from test_sweep_mpi import _build_mpi, _mpirun
    binary = _build_mpi()
    if binary is None:
        pytest.skip("no Open MPI (mpirun, mpifort): bash make.sh mpi installs it")
    deck = _setup(tmp_path, ADAPTIVE, SHORT)
    result = _mpirun(binary, 2, "sweep", deck, "-o", tmp_path / "m.h5")
    assert result.returncode != 0
    assert "cannot run across MPI ranks" in result.stderr and "target_halfwidth" in result.stderr
