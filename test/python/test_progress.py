"""`davit run` draws its progress on stderr when that is a terminal (here a pseudo-terminal)
and stays quiet when stderr is a pipe; stdout is the same either way."""
import os
import pathlib
import pty
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
# the default scenario: ~90 s simulated, 1-3 s of wall time, several redraws (every 0.5 s)
DECK = ROOT / "input" / "iiib_level5_090.nml"


def run_at_terminal(davit_bin, out):
    """stderr at a pseudo-terminal: (return code, stdout, what the terminal showed)."""
    master, slave = pty.openpty()
    proc = subprocess.Popen([davit_bin, "run", str(DECK), "-o", str(out)],
                            stdout=subprocess.PIPE, stderr=slave)
    os.close(slave)
    shown = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        shown += chunk
    os.close(master)
    stdout = proc.stdout.read().decode()
    proc.stdout.close()
    return proc.wait(timeout=300), stdout, shown.decode()


def test_progress_at_terminal(davit_bin, tmp_path):
    rc, stdout, shown = run_at_terminal(davit_bin, tmp_path / "a.h5")
    assert rc == 0, shown
    assert "davit: wrote" in stdout
    assert "davit: t = " in shown and "x real time, ETA" in shown
    # one line redrawn in place, closed by a newline (the terminal shows \r\n)
    assert shown.startswith("\r") and shown.rstrip(" ").endswith("\n")
    assert shown.count("\n") == 1
    assert "real time" not in stdout


def test_no_progress_when_piped(davit_bin, tmp_path):
    result = subprocess.run([davit_bin, "run", str(DECK), "-o", str(tmp_path / "b.h5")],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    assert "davit: wrote" in result.stdout
