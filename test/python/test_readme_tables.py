"""The documentation's generated tables (launch loads of every III.A/III.B deck in
doc/validation/launch.md, the regression report's deck rows in doc/validation/index.md, the
SOLAS decks in doc/howto/operability.md) against fresh runs of their decks, so that no
number in them goes stale silently. ~43 decks, two at a time: about 1.5 min."""
import pathlib

import pytest

from postproc import readme_tables

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def fresh(davit_bin, tmp_path_factory):
    folder = tmp_path_factory.mktemp("readme_runs")
    decks = sorted({d for decks, _ in readme_tables.TABLES.values() for d in decks})
    readme_tables.run_decks(str(folder), decks, davit_bin)
    return folder


@pytest.mark.parametrize("name", sorted(readme_tables.TABLES))
def test_readme_table_is_what_the_runs_give(fresh, name):
    page = pathlib.Path(readme_tables.page_path(name))
    copy = readme_tables.readme_copy(page.read_text(), name)
    assert copy is not None, f"{page} has no table '{name}'"
    made = readme_tables.make(str(fresh), [name])[name]
    found = readme_tables.differences(copy, made)
    assert not found, (f"table '{name}' in {page} is stale "
                       "(davit-post readme-tables out --run --write):\n" + "\n".join(found))


def test_replace_and_check_round_trip():
    text = "a\n<!-- table:x -->\nold\n<!-- /table:x -->\nb\n"
    new = readme_tables.replace(text, "x", "| new |")
    assert readme_tables.readme_copy(new, "x") == "| new |"
    assert new.startswith("a\n") and new.endswith("\nb\n")
    assert readme_tables.stale({"x": "| new |"}, new) == []
    assert readme_tables.stale({"x": "| other |"}, new) == ["x"]
    assert readme_tables.stale({"y": "| y |"}, new) == ["y"]


def test_numbers_compare_at_their_printed_precision():
    """Another CPU's last bits pass (a located event 3e-8 s later, a rounding that flips the
    last printed digit); a changed count, a changed text or a number moved by 1 % do not."""
    old = "| r | 3 | 0.42 | 21107 N | released at t = 82.780 s |"
    same = ["| r | 3 | 0.42 | 21107 N | released at t = 82.780 s |",
            "| r | 3 | 0.43 | 21110 N | released at t = 82.781 s |"]
    changed = ["| r | 4 | 0.42 | 21107 N | released at t = 82.780 s |",
               "| r | 3 | 0.45 | 21107 N | released at t = 82.780 s |",
               "| r | 3 | 0.42 | 21318 N | released at t = 82.780 s |",
               "| r | 3 | 0.42 | 21107 N | waterborne at t = 82.780 s |",
               "| r | 3 | 0.42 | 21107 N | released at t = 83.611 s |",
               "| r | 3 | 0.42 | 21107 N |"]
    for line in same:
        assert readme_tables.differences(old, line) == [], line
    for line in changed:
        assert readme_tables.differences(old, line), line
    assert readme_tables.differences(old, old + "\n| extra |")


def test_every_table_sits_in_its_page_once():
    """Each generated table is in the page PAGES names, once, and nowhere else in doc/ or
    the README (a copy left behind would go stale unchecked)."""
    for name in readme_tables.TABLES:
        start = f"<!-- table:{name} -->"
        holders = [p for p in [ROOT / "README.md", *sorted((ROOT / "doc").rglob("*.md"))]
                   if start in p.read_text()]
        assert holders == [pathlib.Path(readme_tables.page_path(name))], (name, holders)
        assert pathlib.Path(readme_tables.page_path(name)).read_text().count(start) == 1
