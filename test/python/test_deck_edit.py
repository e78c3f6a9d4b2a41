"""postproc.deck_edit: a key set in its namelist group, not in a comment that names it."""
from postproc.deck_edit import override

DECK = """! a comment that names the group: (&sea summation = 'single' is the level)
&simulation
  dt = 1e-2
/
&sea
  level = 5
  summation = 'single_equal_energy'     ! one direction per frequency
/
"""


def test_override_edits_the_group_not_a_comment_naming_it():
    out = override(DECK, "sea", "level", 4)
    assert out.splitlines()[0] == DECK.splitlines()[0]
    assert "  level = 4" in out and "level = 5" not in out
    assert out.count("&sea") == 2


def test_override_adds_a_missing_key_inside_its_group():
    out = override(DECK, "sea", "direction_deg", 45.0)
    group = out[out.index("\n&sea"):]
    assert "direction_deg = 45.0" in group.split("\n/")[0]
    assert "direction_deg" not in out.splitlines()[0]
