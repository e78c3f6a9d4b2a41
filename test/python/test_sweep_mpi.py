"""`davit sweep` across MPI ranks (the MPI build, `bash make.sh mpi`): the coordinator's
summary is the OpenMP sweep's bit for bit (wall times and the thread count aside) on 1 and
3 ranks with 1 and 2 threads per worker; --resume crosses MPI and OpenMP runs; a diverging
case fails and the sweep goes on; a killed worker leaves a valid checkpoint whose unfinished
cases are not run; the serial binary under mpirun runs independent sweeps that the lock
keeps apart; bad arguments are clear errors. Skipped only where Open MPI is missing."""
import os
import pathlib
import shutil
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest

from postproc import layout
from postproc.build_flags import fpm_release
from test_sweep import BASE, SWEEP, _setup
from test_sweep_shards import _assert_bitwise, _attrs

ROOT = pathlib.Path(__file__).resolve().parents[2]
MPI_FLAGS = fpm_release("-DDAVIT_MPI")
# Open MPI refuses root unless told (containers, CI); --oversubscribe: 3 ranks on 2 cores
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
# attributes that legitimately differ between runs
VOLATILE = {"threads"}


def _build_mpi():
    """The MPI binary: DAVIT_MPI_BIN (set by make.sh), else built here with mpifort."""
    if shutil.which("mpirun") is None or shutil.which("mpifort") is None:
        return None
    if os.environ.get("DAVIT_MPI_BIN"):
        return os.environ["DAVIT_MPI_BIN"]
    env = dict(os.environ, FPM_FC="mpifort")
    built = subprocess.run(["fpm", "build", *MPI_FLAGS], cwd=ROOT, env=env,
                           capture_output=True, text=True)
    if built.returncode != 0:
        return None
    out = subprocess.run(["fpm", "run", *MPI_FLAGS, "--runner", "echo"], cwd=ROOT, env=env,
                         capture_output=True, text=True, check=True)
    return str(ROOT / out.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def mpi_bin():
    path = _build_mpi()
    if path is None:
        pytest.skip("no Open MPI (mpirun, mpifort): bash make.sh mpi installs it")
    return path


def _mpirun(binary, nranks, *args, timeout=300):
    return subprocess.run(["mpirun", "--oversubscribe", "--bind-to", "none", "-np",
                           str(nranks), binary, *map(str, args)],
                          capture_output=True, text=True, env=ENV, timeout=timeout)


def _ok(result):
    assert result.returncode == 0, result.stdout + result.stderr
    return result


def _same_attrs(a, b):
    aa, ab = _attrs(a), _attrs(b)
    assert aa.keys() == ab.keys()
    for k in aa.keys() - VOLATILE:
        assert aa[k] == ab[k], k


@pytest.fixture(scope="module")
def reference(davit, tmp_path_factory):
    """The 8-case sweep of test_sweep on one OpenMP thread."""
    folder = tmp_path_factory.mktemp("mpi_ref")
    deck = _setup(folder)
    out = folder / "openmp.h5"
    _ok(davit("sweep", deck, "-o", out, "--threads", "1", "--quiet"))
    return deck, out


@pytest.mark.parametrize("nranks,threads", [(3, 1), (3, 2), (1, 1), (2, 2)])
def test_mpi_summary_is_the_openmp_summary(mpi_bin, reference, tmp_path, nranks, threads):
    deck, ref = reference
    out = tmp_path / "mpi.h5"
    result = _ok(_mpirun(mpi_bin, nranks, "sweep", deck, "-o", out, "--threads", threads))
    _assert_bitwise(ref, out)
    _same_attrs(ref, out)
    assert _attrs(out)["complete"] == 1
    assert not (tmp_path / "mpi.h5.lock").exists()
    # one summary line, from the coordinator only
    assert result.stdout.count("davit: wrote") == 1
    if nranks > 1:
        assert f"{nranks - 1} worker rank(s)" in result.stderr
        assert _attrs(out)["threads"] == (nranks - 1) * threads


@pytest.mark.parametrize("resume_with", ["mpi", "serial"])
def test_resume_after_a_partial_mpi_sweep(mpi_bin, davit, reference, tmp_path, resume_with):
    deck, ref = reference
    out = tmp_path / "partial.h5"
    _ok(_mpirun(mpi_bin, 3, "sweep", deck, "-o", out, "--max-cases", "2", "--quiet"))
    first = layout.load_sweep(out)
    assert (first.status == layout.SWEEP_OK).sum() == 2
    assert (first.status == layout.SWEEP_NOT_RUN).sum() == 6
    if resume_with == "mpi":
        _ok(_mpirun(mpi_bin, 3, "sweep", deck, "-o", out, "--resume", "--threads", "2"))
    else:
        _ok(davit("sweep", deck, "-o", out, "--resume", "--threads", "2"))
    done = layout.load_sweep(out)
    kept = first.status == layout.SWEEP_OK
    np.testing.assert_array_equal(done.wall_time[kept], first.wall_time[kept])
    assert (done.status == layout.SWEEP_OK).all()
    _assert_bitwise(ref, out)


def test_serial_partial_resumed_under_mpi(mpi_bin, davit, reference, tmp_path):
    deck, ref = reference
    out = tmp_path / "partial.h5"
    _ok(davit("sweep", deck, "-o", out, "--max-cases", "3", "--quiet"))
    first = layout.load_sweep(out)
    kept = first.status == layout.SWEEP_OK
    assert kept.sum() == 3
    _ok(_mpirun(mpi_bin, 3, "sweep", deck, "-o", out, "--resume"))
    done = layout.load_sweep(out)
    np.testing.assert_array_equal(done.wall_time[kept], first.wall_time[kept])
    _assert_bitwise(ref, out)


def test_diverging_case_fails_and_the_mpi_sweep_goes_on(mpi_bin, davit, tmp_path):
    """dts = 1e-2 s is beyond RK4's stability limit on the stiff winch mode: those cases
    fail with the divergence message, as in the OpenMP sweep, and the others finish."""
    deck = _setup(tmp_path, SWEEP.replace("realisations = 2", "dts = 2.0e-4, 1.0e-2"))
    ref = tmp_path / "openmp.h5"
    _ok(davit("sweep", deck, "-o", ref, "--threads", "1", "--quiet"))
    out = tmp_path / "mpi.h5"
    result = _ok(_mpirun(mpi_bin, 3, "sweep", deck, "-o", out))
    s = layout.load_sweep(out)
    assert (s.status == layout.SWEEP_FAILED).sum() == 4
    assert (s.status == layout.SWEEP_OK).sum() == 4
    assert all(s.message[i].startswith("run diverged at t = ")
               for i in np.flatnonzero(s.status == layout.SWEEP_FAILED))
    assert "failed: run diverged" in result.stderr
    _assert_bitwise(ref, out)


def test_bad_arguments_are_clear_errors(mpi_bin, reference, tmp_path):
    deck, _ = reference
    bad = _mpirun(mpi_bin, 3, "sweep", deck, "-o", tmp_path / "x.h5", "--threads", "0")
    assert bad.returncode != 0
    assert "option --threads needs an integer >= 1" in bad.stderr
    series = _mpirun(mpi_bin, 3, "sweep", deck, "-o", tmp_path / "y.h5",
                     "--series", tmp_path / "series")
    assert series.returncode != 0
    assert "--series is not available across MPI ranks" in series.stderr
    assert not (tmp_path / "y.h5").exists()
    missing = _mpirun(mpi_bin, 3, "sweep", tmp_path / "nope.nml", "-o", tmp_path / "z.h5")
    assert missing.returncode != 0
    assert "nope.nml" in missing.stderr


def test_serial_binary_under_mpirun_runs_apart(davit, davit_bin, reference, tmp_path):
    """The serial binary knows no MPI: three copies are three OpenMP sweeps of the same
    summary. The lock lets one write, the others stop with a clear message (and mpirun
    then ends the job); the summary left is whole, its finished rows right, and --resume
    completes it (or, where mpirun ended the writer before its first checkpoint, there is
    none, and a plain run makes it)."""
    if shutil.which("mpirun") is None:
        pytest.skip("no mpirun")
    deck, ref = reference
    out = tmp_path / "serial.h5"
    result = _mpirun(davit_bin, 3, "sweep", deck, "-o", out, "--threads", "1")
    assert result.stderr.count("is writing") >= 1, result.stderr
    _wait_lock_owner(out)
    if not out.exists():
        # mpirun ended the job before the lock's owner wrote its first summary: nothing
        # was written, so nothing is lost, and a plain run makes the whole summary
        _ok(davit("sweep", deck, "-o", out, "--quiet"))
        _assert_bitwise(ref, out)
        return
    s, r = layout.load_sweep(out), layout.load_sweep(ref)
    finished = s.status == layout.SWEEP_OK
    assert set(np.unique(s.status)) <= {layout.SWEEP_NOT_RUN, layout.SWEEP_OK}
    np.testing.assert_array_equal(s.min_clearance[finished], r.min_clearance[finished])
    np.testing.assert_array_equal(s.steps[finished], r.steps[finished])
    _ok(davit("sweep", deck, "-o", out, "--resume", "--quiet"))
    _assert_bitwise(ref, out)


def _rank_pids(rank):
    """Process ids of the running davit processes of MPI rank `rank`."""
    pids = []
    for proc in pathlib.Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            env = (proc / "environ").read_bytes().split(b"\0")
            cmd = (proc / "cmdline").read_bytes()
        except OSError:
            continue
        if b"OMPI_COMM_WORLD_RANK=%d" % rank in env and b"sweep" in cmd:
            pids.append(int(proc.name))
    return pids


def _wait_gone(pids, seconds=30):
    """Until processes `pids` have ended (mpirun may return before its ranks are gone)."""
    deadline = time.time() + seconds
    while time.time() < deadline and any(pathlib.Path(f"/proc/{p}").exists() for p in pids):
        time.sleep(0.05)


def _wait_lock_owner(out):
    """Until the process that holds `out`'s lock has ended (mpirun may return before the
    ranks it killed are gone; --resume takes over the lock only from a process gone)."""
    lock = pathlib.Path(str(out) + ".lock")
    try:
        pid = int(lock.read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return
    _wait_gone([pid])


def _statuses(path):
    try:
        with h5py.File(path, "r") as f:
            return f["results/status"][()]
    except (OSError, KeyError):
        return None


def test_killed_worker_leaves_its_cases_not_run(mpi_bin, davit, tmp_path):
    """Cases of ~0.5 s, a checkpoint after every case: a worker killed mid-sweep ends the
    job; the summary on disk is whole, its finished rows are the OpenMP sweep's, the rest
    are not run, and --resume completes it to the OpenMP sweep's summary."""
    base = BASE.replace("t_end = 1.0 ", "t_end = 8.0 ")
    deck = _setup(tmp_path, base=base)
    ref = tmp_path / "openmp.h5"
    _ok(davit("sweep", deck, "-o", ref, "--threads", "1", "--quiet"))
    out = tmp_path / "killed.h5"
    job = subprocess.Popen(["mpirun", "--oversubscribe", "--bind-to", "none", "-np", "3",
                            mpi_bin, "sweep", deck, "-o", out, "--checkpoint", "0",
                            "--quiet"], env=ENV, stdout=subprocess.PIPE,
                           stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.time() + 120
        while time.time() < deadline:
            status = _statuses(out)
            if status is not None and (status == layout.SWEEP_OK).sum() >= 1:
                break
            time.sleep(0.05)
        pids = _rank_pids(1)
        coordinator = _rank_pids(0)
        assert pids, "worker rank 1 not found"
        for pid in pids:
            os.kill(pid, signal.SIGKILL)
        job.communicate(timeout=60)
        _wait_gone(coordinator)
    finally:
        if job.poll() is None:
            job.kill()
            job.communicate()
    assert job.returncode != 0
    s = layout.load_sweep(out)
    assert set(np.unique(s.status)) <= {layout.SWEEP_NOT_RUN, layout.SWEEP_OK}
    assert 1 <= (s.status == layout.SWEEP_OK).sum() < 8
    r = layout.load_sweep(ref)
    finished = s.status == layout.SWEEP_OK
    np.testing.assert_array_equal(s.min_clearance[finished], r.min_clearance[finished])
    _ok(davit("sweep", deck, "-o", out, "--resume", "--threads", "1", "--quiet"))
    _assert_bitwise(ref, out)
