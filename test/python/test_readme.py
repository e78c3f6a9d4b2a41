"""The README starts with the two commands and CI runs the test command; the deck keys and
the command line it points to are checked against the code in test_docs.py."""
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_starts_with_the_two_commands():
    readme = (ROOT / "README.md").read_text()
    head = readme[: readme.index("## Quick start")]
    block = head[head.index("```sh\n") + 6:]
    lines = block.splitlines()
    assert lines[0].startswith("bash make.sh demo") and lines[1].startswith("bash make.sh test")
    ci = (ROOT / ".ci" / "run").read_text()
    assert "make.sh test" in ci


def test_license_is_mit_as_fpm_toml_says():
    assert 'license = "MIT"' in (ROOT / "fpm.toml").read_text()
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("MIT License") and "Copyright (c) 2026 davit developers" in text
