"""Every module of src/ has a direct Fortran test (a file of test/ that uses it) or a line in
the tests page's "Modules tested through others" table naming where it is tested; a line for
a module that has a direct test is stale and fails too, as does a line naming a test file
that does not exist."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "doc" / "validation" / "tests.md"
HEADING = "## Modules tested through others"


def modules():
    found = {}
    for path in sorted((ROOT / "src").rglob("*.[fF]90")):
        for line in path.read_text().splitlines():
            m = re.match(r"\s*module\s+(\w+)\s*$", line, re.IGNORECASE)
            if m:
                found[m.group(1).lower()] = path
    return found


def used_by_tests():
    used = set()
    for path in (ROOT / "test").glob("*.[fF]90"):
        for line in path.read_text().splitlines():
            m = re.match(r"\s*use\s*(?:,\s*\w+\s*::)?\s*(\w+)", line, re.IGNORECASE)
            if m:
                used.add(m.group(1).lower())
    return used


def index_lines():
    text = PAGE.read_text()
    assert HEADING in text, f"{PAGE} lacks the section '{HEADING}'"
    section = text.split(HEADING, 1)[1].split("\n## ", 1)[0]
    rows = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 2 and cells[0].startswith("davit_"):
            rows[cells[0]] = cells[1]
    return rows


def test_every_module_has_a_direct_test_or_a_reason():
    missing = sorted(set(modules()) - used_by_tests() - set(index_lines()))
    assert not missing, f"modules with no direct test and no line in {PAGE.name}: {missing}"


def test_no_stale_or_unknown_lines():
    rows, mods, used = index_lines(), modules(), used_by_tests()
    assert not sorted(set(rows) - set(mods)), "lines for modules that do not exist"
    assert not sorted(set(rows) & used), "lines for modules that now have a direct test"


def test_reasons_name_tests_that_exist():
    tests = {p.name for p in (ROOT / "test").rglob("test_*")}
    for module, reason in index_lines().items():
        named = re.findall(r"test_\w+\.(?:py|f90)", reason)
        assert named or "no numbers of its own" in reason, (module, reason)
        for name in named:
            assert name in tests, (module, name)


def test_the_check_sees_a_module_without_a_test(tmp_path):
    """The scan itself: a made-up module is neither used by a test nor listed."""
    assert "davit_made_up_module" not in used_by_tests() | set(index_lines())
    assert "davit_core_kane" in used_by_tests()


def test_no_doc_comment_starts_as_ford_metadata():
    """FORD reads `word: text` on the first line of a doc comment block as metadata and
    drops it from the page; such a first line must be worded otherwise."""
    bad = []
    for path in sorted((ROOT / "src").rglob("*.[fF]90")) + sorted((ROOT / "app").rglob("*.[fF]90")):
        lines = path.read_text().splitlines()
        for i, line in enumerate(lines):
            if re.match(r"\s*!>\s*[A-Za-z0-9_-]+:", line) and (
                    i == 0 or not re.match(r"\s*!>", lines[i - 1])):
                bad.append(f"{path.relative_to(ROOT)}:{i + 1}")
    assert not bad, bad
