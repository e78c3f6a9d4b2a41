"""`bash make.sh install PREFIX`: PREFIX/bin/davit runs a deck copied away from input/ (its
BEM databases come from the installed data, not DAVIT_PATH or the deck's folder), and
PREFIX/bin/davit-post runs python -m postproc from any folder without the project's
environment on PATH."""
import os
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def bare_env(home):
    """A login-like environment: no venv, no DAVIT_PATH, no PYTHONPATH."""
    return {"PATH": "/usr/bin:/bin", "HOME": str(home)}


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    """A prefix installed into by make.sh (setup installs nothing that is there already)."""
    prefix = tmp_path_factory.mktemp("prefix")
    result = subprocess.run(["bash", str(ROOT / "make.sh"), "install", str(prefix)],
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    assert f"installed {prefix}/bin/davit " in result.stderr
    # a temporary prefix is not on PATH: make.sh names the line for ~/.bashrc
    assert f'export PATH="{prefix}/bin:$PATH"' in result.stderr
    return prefix


def test_commands_installed(prefix):
    for name in ("davit", "davit-post"):
        path = prefix / "bin" / name
        assert path.is_file() and os.access(path, os.X_OK), path


def test_davit_version_from_elsewhere(prefix, tmp_path):
    result = subprocess.run([str(prefix / "bin" / "davit"), "--version"], cwd=tmp_path,
                            env=bare_env(tmp_path), capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("davit ")


def test_davit_runs_copied_bem_deck(prefix, tmp_path):
    """The default deck (&ship model = 'bem', the boat's BEM water model) cut to 1 s, in a
    folder without the databases."""
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text()
    text, n = re.subn(r"(?m)^(\s*t_end\s*=\s*)[0-9.eE+-]+", r"\g<1>1.0", text)
    assert n == 1
    (tmp_path / "deck.nml").write_text(text)
    assert not list(tmp_path.glob("*.nc"))
    result = subprocess.run([str(prefix / "bin" / "davit"), "run", "deck.nml", "-o", "d.h5"],
                            cwd=tmp_path, env=bare_env(tmp_path), capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "d.h5").is_file()


def test_davit_keeps_working_after_the_build_goes(prefix):
    """The installed binary is a copy, not a link into build/."""
    binary = prefix / "libexec" / "davit" / "davit"
    assert binary.is_file() and not binary.is_symlink()


def test_davit_post_help_without_venv(prefix, tmp_path):
    result = subprocess.run([str(prefix / "bin" / "davit-post"), "--help"], cwd=tmp_path,
                            env=bare_env(tmp_path), capture_output=True, text=True,
                            timeout=120)
    assert result.returncode == 0, result.stderr
    assert "usage" in result.stdout.lower()


@pytest.mark.parametrize("tool, module", [("study", "postproc.study"),
                                          ("launch-table", "postproc.launch_table"),
                                          ("readme-tables", "readme-tables")])
def test_davit_post_runs_the_tools(prefix, tmp_path, tool, module):
    """`davit-post TOOL` is `python -m postproc.MODULE`: one name for every command the
    README shows, from any folder, without the venv on PATH."""
    result = subprocess.run([str(prefix / "bin" / "davit-post"), tool, "--help"],
                            cwd=tmp_path, env=bare_env(tmp_path), capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert module in result.stdout
