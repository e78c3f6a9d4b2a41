"""Long runs, diverging trial stages and huge case lists (issue 35, defects 1, 2 and 7).

Each process runs under a stack limit (the default 8 MiB, or smaller where a smaller one is
the cheap proof), a virtual-memory limit and a timeout, so a regression shows up as a
failure, never as a machine eaten:

* a run of t_end = 2000 s (a 2e6-sample seat trace, 16 MB a component) segfaulted after
  the simulation: array temporaries of the trace on the stack (-fstack-arrays);
* a sweep of 1e5 cases segfaulted under a 256 KiB stack writing its summary (1e6 cases
  under the default 8 MiB): temporaries of the case list;
* a diverging dopri5 run segfaulted in the rubber fender's table (a NaN or huge trial-stage
  deflection) instead of stopping with the divergence message;
* 256 x 256 x 65537 cases were counted as 65536 (a 32-bit product) and 10^9 cases ended in
  an allocation error with a backtrace.
"""
import pathlib
import resource
import subprocess

import h5py
import pytest

VMEM_LIMIT = 6 * 1024**3
DEFAULT_STACK = 8 * 1024**2
SMALL_STACK = 256 * 1024
TIMEOUT = 120
ROOT = pathlib.Path(__file__).resolve().parents[2]


def run_davit(davit_bin, *args, cwd, stack=DEFAULT_STACK):
    def limits():
        resource.setrlimit(resource.RLIMIT_AS, (VMEM_LIMIT, VMEM_LIMIT))
        resource.setrlimit(resource.RLIMIT_STACK, (stack, stack))
    return subprocess.run([davit_bin, *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=TIMEOUT, preexec_fn=limits)


def error_lines(stderr):
    return [line for line in stderr.splitlines() if line.startswith("davit: error:")]


def listing(folder):
    return sorted(p.name for p in pathlib.Path(folder).iterdir())


def hanging_deck(**simulation):
    """input/hanging_boat.nml with its &simulation keys replaced."""
    text = (ROOT / "input" / "hanging_boat.nml").read_text()
    lines = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        if key in simulation:
            line = f"  {key} = {simulation.pop(key)}"
        lines.append(line)
    assert not simulation, f"keys not in the deck: {simulation}"
    return "\n".join(lines) + "\n"


# RK4 at 0.01 s is stable on the slings (bounce 70 rad/s, pitch 130 rad/s) and runs 2000 s
# in ~3 s; the seat trace is 1 kHz whatever the step.
LONG = {"t_end": "2000.0", "dt": "0.01"}


@pytest.mark.parametrize("output_interval,stack", [
    ("1.0", DEFAULT_STACK),   # the case: the default stack, the seat trace's size
    ("0.05", SMALL_STACK),    # 40 000 samples (320 kB a channel) past a 256 KiB stack
], ids=["default_stack", "samples_small_stack"])
def test_long_run_keeps_its_arrays_off_the_stack(davit_bin, tmp_path, output_interval, stack):
    (tmp_path / "deck.nml").write_text(hanging_deck(**LONG, output_interval=output_interval))
    result = run_davit(davit_bin, "run", "deck.nml", "-o", "out.h5", cwd=tmp_path, stack=stack)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr[-2000:]}"
    assert error_lines(result.stderr) == []
    assert listing(tmp_path) == ["deck.nml", "out.h5"]
    with h5py.File(tmp_path / "out.h5") as f:
        assert f["time"][-1] == pytest.approx(2000.0)
        assert max(f["seat/acceleration"].shape) > 1_990_000


def test_long_sweep_case_runs(davit_bin, tmp_path):
    """Each case of a sweep goes through the same launch log (its seat peaks)."""
    (tmp_path / "base.nml").write_text(hanging_deck(**LONG, output_interval="1.0"))
    (tmp_path / "sweep.nml").write_text("&sweep\n  base_deck = 'base.nml'\n"
                                        "  angles_deg = 0.0, 90.0\n/\n")
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "sweep.h5", "--threads", "1",
                       "--quiet", cwd=tmp_path)
    assert result.returncode == 0, f"{result.returncode}\n{result.stderr[-2000:]}"
    with h5py.File(tmp_path / "sweep.h5") as f:
        assert list(f["results/status"][:]) == [1, 1]
    assert listing(tmp_path) == ["base.nml", "sweep.h5", "sweep.nml"]


def tiny_base(tmp_path):
    (tmp_path / "base.nml").write_text(hanging_deck(t_end="0.05", dt="0.01",
                                                    output_interval="0.01"))


def test_large_case_list_keeps_its_arrays_off_the_stack(davit_bin, tmp_path):
    """1e5 cases (800 kB a summary column) under a 256 KiB stack: one case, a resume, two
    shards and their merge."""
    tiny_base(tmp_path)
    (tmp_path / "sweep.nml").write_text("&sweep\n  base_deck = 'base.nml'\n"
                                        "  realisations = 100000\n/\n")
    steps = [("sweep.nml", "-o", "a.h5", "--max-cases", "1"),
             ("sweep.nml", "-o", "a.h5", "--max-cases", "1", "--resume"),
             ("sweep.nml", "-o", "s1.h5", "--max-cases", "1", "--shard", "1/2"),
             ("sweep.nml", "-o", "s2.h5", "--max-cases", "1", "--shard", "2/2"),
             ("--merge", "m.h5", "s1.h5", "s2.h5")]
    for args in steps:
        result = run_davit(davit_bin, "sweep", *args, "--threads", "1", "--quiet",
                           cwd=tmp_path, stack=SMALL_STACK) if args[0] != "--merge" else \
            run_davit(davit_bin, "sweep", *args, cwd=tmp_path, stack=SMALL_STACK)
        assert result.returncode == 0, f"{args}: {result.returncode}\n{result.stderr[-2000:]}"
    with h5py.File(tmp_path / "a.h5") as f:
        status = f["results/status"][:]
        assert len(status) == 100000 and (status == 1).sum() == 2
    with h5py.File(tmp_path / "m.h5") as f:
        assert (f["results/status"][:] == 1).sum() == 2
    assert listing(tmp_path) == ["a.h5", "base.nml", "m.h5", "s1.h5", "s2.h5", "sweep.nml"]


@pytest.mark.parametrize("keys", ["  rtol = 1.0\n  atol = 1.0", "  fixed_step = .true."],
                         ids=["tolerance_1", "fixed_step"])
def test_diverging_dopri5_stops_with_its_message(davit_bin, tmp_path, keys):
    deck = hanging_deck(dt="0.05", output_interval="0.1", integrator="'dopri5'")
    deck = deck.replace("  integrator = 'dopri5'", "  integrator = 'dopri5'\n" + keys)
    (tmp_path / "deck.nml").write_text(deck)
    result = run_davit(davit_bin, "run", "deck.nml", "-o", "out.h5", cwd=tmp_path)
    assert result.returncode == 1, f"{result.returncode}\n{result.stderr[-2000:]}"
    errors = error_lines(result.stderr)
    assert len(errors) == 1, result.stderr[-2000:]
    assert "run diverged at t = " in errors[0] and "partial output kept in 'out.h5'" in errors[0]
    assert "Backtrace" not in result.stderr
    assert listing(tmp_path) == ["deck.nml", "out.h5"]
    with h5py.File(tmp_path / "out.h5") as f:
        assert f.attrs["complete"] == 0
        assert len(f["time"]) >= 2


def values(start, step, n):
    return ", ".join(f"{start + k * step:.4f}" for k in range(n))


# (id, &sweep lists, the count and the factors the error line must give)
HUGE_SWEEPS = [
    ("2^32_plus", f"  heights = {values(1.0, 0.01, 256)}\n"
     f"  periods = {values(5.0, 0.05, 256)}\n  realisations = 65537\n",
     "4295032832 cases (256 heights x 256 periods x 65537 realisations)"),
    ("1e9", f"  heights = {values(1.0, 0.01, 1000)}\n"
     f"  periods = {values(5.0, 0.02, 1000)}\n  angles_deg = {values(0.0, 0.3, 1000)}\n",
     "1000000000 cases (1000 heights x 1000 periods x 1000 angles)"),
]


@pytest.mark.parametrize("lists,count", [r[1:] for r in HUGE_SWEEPS],
                         ids=[r[0] for r in HUGE_SWEEPS])
@pytest.mark.parametrize("dry_run", [False, True], ids=["run", "dry_run"])
def test_huge_case_list_is_refused_with_its_count(davit_bin, tmp_path, lists, count, dry_run):
    tiny_base(tmp_path)
    (tmp_path / "sweep.nml").write_text("&sweep\n  base_deck = 'base.nml'\n" + lists + "/\n")
    args = ["sweep", "sweep.nml", "-o", "out.h5"] + (["--dry-run"] if dry_run else [])
    result = run_davit(davit_bin, *args, cwd=tmp_path)
    assert result.returncode == 1, f"{result.returncode}\n{result.stderr[-2000:]}"
    errors = error_lines(result.stderr)
    assert len(errors) == 1, result.stderr[-2000:]
    assert "sweep.nml:3: &sweep: " + count in errors[0]
    assert "exceed the cap of 1000000 cases" in errors[0]
    assert listing(tmp_path) == ["base.nml", "sweep.nml"]


def test_case_list_beyond_max_memory_is_refused(davit_bin, tmp_path):
    """1e6 cases (~1 GB) against a base deck's max_memory of 0.25 GiB."""
    (tmp_path / "base.nml").write_text(hanging_deck(t_end="0.05", dt="0.01",
                                                    output_interval="0.01")
                                       .replace("  seed = 12345", "  seed = 12345\n"
                                                "  max_memory = 0.25"))
    (tmp_path / "sweep.nml").write_text("&sweep\n  base_deck = 'base.nml'\n"
                                        f"  angles_deg = {values(0.0, 10.0, 10)}\n"
                                        "  realisations = 100000\n/\n")
    result = run_davit(davit_bin, "sweep", "sweep.nml", "-o", "out.h5", cwd=tmp_path)
    assert result.returncode == 1, f"{result.returncode}\n{result.stderr[-2000:]}"
    errors = error_lines(result.stderr)
    assert len(errors) == 1, result.stderr[-2000:]
    assert "sweep.nml:3: &sweep: 1000000 cases (10 angles x 100000 realisations) would hold" in errors[0]
    assert "max_memory" in errors[0]
    assert listing(tmp_path) == ["base.nml", "sweep.nml"]
