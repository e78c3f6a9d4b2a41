"""Hostile inputs, memory and time grid (issue 19, classes 1, 3, 4's time grid, 8's
--threads): large but valid seas, runs that cannot fit or cannot finish, absurd thread
counts. Each case asserts the exit code, exactly one `davit: error:` line naming what
applies (file, line, group, key, the estimate or the allowed range), no stray files, and a
pre-existing good output left byte-identical where one is given.

A reviewer extends it by adding a row to REFUSED (decks that must be refused before the
run) or to RUNS (decks that must run): each row is (id, deck text, expected fragments of
the error line). Every process runs under a virtual-memory limit and a timeout, so a
regression shows up as a failure, never as a machine eaten."""
import pathlib
import resource
import subprocess

import pytest

# Every case runs under this address-space limit: the large seas need ~1 GiB.
VMEM_LIMIT = 6 * 1024**3
TIMEOUT = 60


def _limits(stack=None):
    def apply():
        resource.setrlimit(resource.RLIMIT_AS, (VMEM_LIMIT, VMEM_LIMIT))
        if stack:
            resource.setrlimit(resource.RLIMIT_STACK, (stack, stack))
    return apply


def run_davit(davit_bin, *args, cwd=None, timeout=TIMEOUT, stack=None):
    return subprocess.run([davit_bin, *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=timeout, preexec_fn=_limits(stack))


def error_lines(stderr):
    return [line for line in stderr.splitlines() if line.startswith("davit: error:")]


def listing(folder):
    return sorted(p.name for p in pathlib.Path(folder).iterdir())


SWING = "&boat velocity = 0.0, 0.5, 0.0 /\n&wind speed = 0.0 /\n"

# (id, deck, fragments every one of which the single error line must hold)
REFUSED = [
    # class 4: a step that can never finish
    ("dt_1e-300", "&simulation\n  t_end = 1.0\n  dt = 1.0e-300\n  output_interval = 0.5\n/\n"
     + SWING, ["deck.nml:3:", "&simulation", "dt = ", "steps", "allowed: dt >="]),
    ("dt_tiny_long", "&simulation\n  t_end = 1.0e5\n  dt = 1.0e-6\n  output_interval = 10.0\n/\n"
     + SWING, ["deck.nml:3:", "&simulation: dt", "t_end/dt = 1e11 steps", "allowed"]),
    ("dt_contact_tiny", "&simulation\n  t_end = 10.0\n  dt = 1.0e-3\n  dt_contact = 1.0e-300\n"
     "  output_interval = 0.5\n/\n" + SWING,
     ["deck.nml:4:", "&simulation: dt_contact", "allowed: 0 or dt_contact >="]),
    ("wave_update_tiny", "&simulation\n  t_end = 10.0\n  wave_update = 1.0e-300\n"
     "  output_interval = 0.5\n/\n" + SWING,
     ["deck.nml:3:", "&simulation: wave_update", "allowed: 0 or wave_update >="]),
    # class 3: 1e10 samples (34 GB with a 32-bit wrapped count before the fix)
    ("samples_1e10", "&simulation\n  t_end = 1.0e5\n  dt = 1.0e-5\n  output_interval = 1.0e-5\n/\n"
     + SWING, ["deck.nml:4:", "&simulation: output_interval", "samples", "allowed"]),
    ("memory_records", "&simulation\n  t_end = 1.0e5\n  dt = 1.0e-3\n  output_interval = 1.0e-3\n"
     "  max_memory = 1.0\n/\n" + SWING,
     ["deck.nml:4:", "output_interval", "GiB", "t_end = ", "max_memory"]),
    ("memory_seat_trace", "&simulation\n  scene = 'launch'\n  t_end = 1.0e5\n"
     "  output_interval = 100.0\n  max_memory = 1.0\n/\n&ship\n  model = 'bem'\n/\n",
     ["deck.nml:3:", "&simulation: t_end", "seat trace", "GiB"]),
    ("sea_samples", "&simulation\n  scene = 'sea'\n  t_end = 5.0e4\n  output_interval = 1.0e-5\n"
     "  dt = 1.0e-5\n/\n"
     "&sea\n  level = 5\n  wave_type = 'irregular'\n/\n",
     ["deck.nml:4:", "output_interval", "allowed"]),
    # class 1 (the part that cannot fit): components beyond max_memory
    ("sea_components_memory", "&simulation\n  scene = 'launch'\n  t_end = 0.01\n"
     "  max_memory = 0.5\n/\n&sea\n  level = 5\n  wave_type = 'irregular'\n"
     "  n_frequencies = 5000\n  n_directions = 361\n/\n&ship\n  model = 'bem'\n/\n",
     ["deck.nml:9:", "&sea: n_frequencies", "wave components", "GiB", "max_memory"]),
]


@pytest.mark.parametrize("case_id,deck,fragments", REFUSED, ids=[r[0] for r in REFUSED])
def test_refused_before_the_run(davit_bin, tmp_path, case_id, deck, fragments):
    (tmp_path / "deck.nml").write_text(deck)
    good = tmp_path / "out.h5"
    good.write_bytes(b"a good earlier result\n")
    before = listing(tmp_path)
    result = run_davit(davit_bin, "run", "deck.nml", "-o", "out.h5", cwd=tmp_path,
                       timeout=20)
    assert result.returncode != 0, result.stdout
    assert result.returncode < 128, f"crashed: {result.returncode}\n{result.stderr}"
    errors = error_lines(result.stderr)
    assert len(errors) == 1, result.stderr
    for fragment in fragments:
        assert fragment in errors[0], (fragment, errors[0])
    assert "Traceback" not in result.stderr and "backtrace" not in result.stderr.lower()
    assert listing(tmp_path) == before, "stray files"
    assert good.read_bytes() == b"a good earlier result\n"


def floating(water_model, nf, nd):
    """A boat floating in a short-crested sea: the strips, pressure and BEM water loads
    evaluate every component at every section."""
    return ("&simulation\n  t_end = 0.004\n  dt = 2.0e-3\n  output_interval = 0.002\n/\n"
            f"&boat\n  position = 0.0, 20.0, -0.9\n  water_model = '{water_model}'\n/\n"
            "&slings\n  attached = .false.\n/\n&wind\n  speed = 0.0\n/\n"
            f"&sea\n  level = 5\n  wave_type = 'irregular'\n  n_frequencies = {nf}\n"
            f"  n_directions = {nd}\n/\n")


# (id, deck, timeout [s], stack limit [bytes] or None): large but valid seas must run
# (allocation proven by t_end tiny). The 256 KiB stack rows are the cheap proof for the
# slow water models: 26 000 components overflowed such a stack before the fix (exit 139,
# 4 to 5 scratch arrays of the sea's size), as 300 000 overflowed the default 8 MiB.
RUNS = [
    ("sea_5000x361", "&simulation\n  scene = 'sea'\n  t_end = 1.0\n  output_interval = 0.5\n/\n"
     "&sea\n  level = 5\n  wave_type = 'irregular'\n  n_frequencies = 5000\n"
     "  n_directions = 361\n/\n", 60, None),
    ("ship_5000x361", "&simulation\n  scene = 'ship'\n  t_end = 0.01\n  dt = 0.005\n"
     "  output_interval = 0.005\n/\n&sea\n  level = 5\n  wave_type = 'irregular'\n"
     "  n_frequencies = 5000\n  n_directions = 361\n/\n&ship\n  model = 'bem'\n/\n", 60, None),
    ("launch_5000x60", "&simulation\n  scene = 'launch'\n  t_end = 0.004\n"
     "  output_interval = 0.002\n  wave_update = 0.05\n/\n&rigging\n  reeving = 'a'\n/\n"
     "&sea\n  level = 5\n  wave_type = 'irregular'\n  n_frequencies = 5000\n"
     "  n_directions = 60\n/\n&ship\n  model = 'bem'\n/\n", 60, None),
    ("floating_paper_5000x60", floating("paper", 5000, 60), 60, None),
    ("floating_paper_small_stack", floating("paper", 2000, 13), 60, 256 * 1024),
    ("floating_pressure_small_stack", floating("pressure", 2000, 13), 60, 256 * 1024),
    ("floating_bem_small_stack", floating("bem", 2000, 13), 60, 256 * 1024),
]


@pytest.mark.parametrize("case_id,deck,timeout,stack", RUNS, ids=[r[0] for r in RUNS])
def test_large_valid_seas_run(davit_bin, tmp_path, case_id, deck, timeout, stack):
    (tmp_path / "deck.nml").write_text(deck)
    result = run_davit(davit_bin, "run", "deck.nml", "-o", "out.h5", cwd=tmp_path,
                       timeout=timeout, stack=stack)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr}"
    assert error_lines(result.stderr) == []
    assert listing(tmp_path) == ["deck.nml", "out.h5"]


SWEEP = """&sweep
  base_deck = 'base.nml'
  angles_deg = 0.0, 90.0
/
"""

BASE = """&simulation
  scene = 'launch'
  t_end = 0.05
  dt = 1.0e-3
  output_interval = 0.01
/
&ship
  model = 'bem'
/
"""


@pytest.mark.parametrize("threads", ["100000", "2147483647"])
def test_absurd_thread_count_is_clamped(davit_bin, tmp_path, threads):
    (tmp_path / "base.nml").write_text(BASE)
    (tmp_path / "sweep.nml").write_text(SWEEP)
    check = run_davit(davit_bin, "sweep", "sweep.nml", "--dry-run", cwd=tmp_path)
    if check.returncode != 0:
        pytest.skip(f"sweep deck not accepted here: {check.stderr.strip()}")
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "s.h5", "--threads", threads,
                       cwd=tmp_path, timeout=120)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr}"
    assert "davit sweep: note: --threads " + threads in result.stderr
    assert error_lines(result.stderr) == []
    assert not [n for n in listing(tmp_path) if n.endswith(".tmp")]


@pytest.mark.parametrize("threads", ["0", "-3", "1e9", "99999999999999999999", "many"])
def test_bad_thread_count_is_refused(davit_bin, tmp_path, threads):
    (tmp_path / "base.nml").write_text(BASE)
    (tmp_path / "sweep.nml").write_text(SWEEP)
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "s.h5", "--threads", threads,
                       cwd=tmp_path)
    assert 0 < result.returncode < 128, f"{result.returncode}\n{result.stderr}"
    errors = error_lines(result.stderr)
    assert len(errors) == 1 and "--threads" in errors[0], result.stderr
    assert listing(tmp_path) == ["base.nml", "sweep.nml"]


def test_omp_num_threads_absurd_is_clamped(davit_bin, tmp_path, monkeypatch):
    (tmp_path / "base.nml").write_text(BASE)
    (tmp_path / "sweep.nml").write_text(SWEEP)
    monkeypatch.setenv("OMP_NUM_THREADS", "100000")
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "s.h5", cwd=tmp_path,
                       timeout=120)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr}"
    assert "davit sweep: note: OMP_NUM_THREADS=100000" in result.stderr
    assert listing(tmp_path) == ["base.nml", "s.h5", "sweep.nml"]


def test_threads_limited_by_memory(davit_bin, tmp_path):
    """Three threads of ~0.2 GiB cases within max_memory = 0.45 GiB: two threads."""
    (tmp_path / "base.nml").write_text(BASE.replace("  output_interval = 0.01\n",
                                                    "  output_interval = 0.01\n"
                                                    "  max_memory = 0.45\n"))
    (tmp_path / "sweep.nml").write_text(SWEEP.replace("0.0, 90.0", "0.0, 90.0, 45.0"))
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "s.h5", "--threads", "3",
                       cwd=tmp_path, timeout=120)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr}"
    assert "would hold more than &simulation max_memory" in result.stderr
    assert "on 2 thread(s)" in result.stderr
    assert error_lines(result.stderr) == []


def test_sweep_case_that_cannot_finish_fails_alone(davit_bin, tmp_path):
    """A sweep's dts = 1e-300 (in the key's range) makes one case that cannot finish: that
    case fails with the time-grid message (naming the sweep case, not a base-deck line),
    the other runs, and the summary is written."""
    (tmp_path / "base.nml").write_text(BASE)
    (tmp_path / "sweep.nml").write_text("&sweep\n  base_deck = 'base.nml'\n"
                                        "  dts = 1.0e-3, 1.0e-300\n/\n")
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "s.h5", cwd=tmp_path,
                       timeout=60)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr}"
    assert "1 ok, 1 failed" in result.stdout
    failed = [line for line in result.stderr.splitlines() if "case 2 failed" in line]
    assert len(failed) == 1, result.stderr
    assert "(this sweep case): &simulation: dt = 1.0000E-300" in failed[0]
    assert "allowed: dt >=" in failed[0]
    assert listing(tmp_path) == ["base.nml", "s.h5", "sweep.nml"]
