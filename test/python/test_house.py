"""The house rule on file size: no Fortran or C source in src/, app/ or test/ is longer
than 600 lines (the project's code standards: short routines, files <= 600 lines). A file
that grows past it is split by responsibility into modules of its own, not cut at line 600."""
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MAX_LINES = 600
FOLDERS = ("src", "app", "test")
SUFFIXES = {".f90", ".F90", ".c", ".h"}
# Files over the limit that another change is splitting, each with why; a file here that
# is no longer over the limit fails test_exceptions_still_needed, so the list cannot rot.
KNOWN_OVER = {}


def line_count(path):
    with open(path, "rb") as f:
        return sum(1 for _ in f)


def sources(root):
    for folder in FOLDERS:
        for path in sorted((root / folder).rglob("*")):
            if path.is_file() and path.suffix in SUFFIXES:
                yield path


def over_limit(root):
    """{relative path: lines} of every source over MAX_LINES below root."""
    return {p.relative_to(root).as_posix(): n for p in sources(root)
            if (n := line_count(p)) > MAX_LINES}


def test_no_source_over_600_lines():
    over = {p: n for p, n in over_limit(ROOT).items() if p not in KNOWN_OVER}
    assert not over, "files over %d lines (split them by responsibility): %s" % (
        MAX_LINES, ", ".join(f"{p} ({n})" for p, n in sorted(over.items())))


def test_exceptions_still_needed():
    over = over_limit(ROOT)
    stale = [p for p in KNOWN_OVER if p not in over]
    assert not stale, f"no longer over {MAX_LINES} lines: remove from KNOWN_OVER: {stale}"


@pytest.mark.parametrize("lines, caught", [(600, False), (601, True)])
def test_the_count_catches_a_long_file(tmp_path, lines, caught):
    """The check itself: a 601-line file in any of the folders is named, 600 lines is not;
    C and Fortran count, other files do not."""
    for folder in FOLDERS:
        (tmp_path / folder / "sub").mkdir(parents=True)
    (tmp_path / "test" / "sub" / "long.F90").write_text("x\n" * lines)
    (tmp_path / "app" / "long.c").write_text("x\n" * lines)
    (tmp_path / "src" / "notes.md").write_text("x\n" * 5000)
    expected = {"test/sub/long.F90": lines, "app/long.c": lines} if caught else {}
    assert over_limit(tmp_path) == expected
