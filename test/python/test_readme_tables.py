"""The README's generated tables (launch loads of every III.A/III.B deck, the regression
report's deck rows, the SOLAS decks) against fresh runs of their decks, so that no number
in them goes stale silently (issue 17). ~43 decks, two at a time: about 1.5 min."""
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
    text = (ROOT / "README.md").read_text()
    copy = readme_tables.readme_copy(text, name)
    assert copy is not None, f"README.md has no table '{name}'"
    made = readme_tables.make(str(fresh), [name])[name]
    assert copy == made, (f"README table '{name}' is stale: "
                          "davit-post readme-tables out --run --write")


def test_replace_and_check_round_trip():
    text = "a\n<!-- table:x -->\nold\n<!-- /table:x -->\nb\n"
    new = readme_tables.replace(text, "x", "| new |")
    assert readme_tables.readme_copy(new, "x") == "| new |"
    assert new.startswith("a\n") and new.endswith("\nb\n")
    assert readme_tables.stale({"x": "| new |"}, new) == []
    assert readme_tables.stale({"x": "| other |"}, new) == ["x"]
    assert readme_tables.stale({"y": "| y |"}, new) == ["y"]
