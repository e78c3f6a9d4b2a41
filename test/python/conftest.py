"""Shared fixtures: the davit binary (DAVIT_BIN, set by make.sh, or found through fpm) and a
short run file written by the Fortran code during the test session."""
import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
from postproc.build_flags import fpm_release  # noqa: E402
# Decks copied to temporary folders still find their data files (the BEM database of
# &ship model = 'bem') in the project's input/ (davit searches DAVIT_PATH after the
# deck's own folder).
os.environ.setdefault("DAVIT_PATH", str(ROOT / "input"))

SHORT_DECK = """! short swing for the Python tests
&simulation t_end = 2.0, dt = 1.0e-3, output_interval = 0.002 /
&boat velocity = 0.0, 0.5, 0.0 /
&wind speed = 0.0 /
"""


def _find_binary():
    env = os.environ.get("DAVIT_BIN")
    if env:
        return env
    out = subprocess.run(["fpm", "run", *fpm_release(), "--runner", "echo"],
                         cwd=ROOT, capture_output=True, text=True, check=True)
    return str(ROOT / out.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="session")
def davit_bin():
    return _find_binary()


@pytest.fixture(scope="session")
def davit(davit_bin):
    """Run davit with arguments; returns the CompletedProcess."""
    def run(*args, cwd=None):
        return subprocess.run([davit_bin, *map(str, args)], capture_output=True, text=True,
                              cwd=cwd, timeout=300)
    return run


@pytest.fixture(scope="session")
def short_run(davit, tmp_path_factory):
    """(deck path, h5 path) of a 2 s swing written by the Fortran code."""
    folder = tmp_path_factory.mktemp("short")
    deck = folder / "short.nml"
    deck.write_text(SHORT_DECK)
    out = folder / "short.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return deck, out


SEA_DECK = """&simulation scene = 'sea', t_end = 300.0, output_interval = 0.5, seed = 7 /
&sea level = 4, wave_type = 'irregular', direction_deg = 45.0,
     probes_x = 0.0, 120.0, -40.0, probes_y = 0.0, 30.0, 75.0 /
"""


@pytest.fixture(scope="session")
def sea_run(davit, tmp_path_factory):
    """(deck path, h5 path) of a 300 s Level 4 irregular sea at three probes."""
    folder = tmp_path_factory.mktemp("sea")
    deck = folder / "sea.nml"
    deck.write_text(SEA_DECK)
    out = folder / "sea.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return deck, out


@pytest.fixture(scope="module")
def launch(davit, tmp_path_factory):
    """A 2 s launch of input/iiib_level5_090.nml (the deck's text with t_end = 2)."""
    folder = tmp_path_factory.mktemp("launch")
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text()
    deck = folder / "launch.nml"
    deck.write_text(text.replace("t_end = 0.0", "t_end = 2.0", 1))
    out = folder / "launch.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return out
