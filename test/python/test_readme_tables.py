"""The documentation's generated tables (launch loads of every III.A/III.B deck in
doc/validation/launch.md, the regression report's deck rows in doc/validation/index.md, the
SOLAS decks in doc/howto/operability.md) against fresh runs of their decks, so that no
number in them goes stale silently. ~43 decks, two at a time: about 1.5 min."""
import pathlib

import h5py
import numpy as np
import pytest

from postproc import layout, readme_tables

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


# The SOLAS calm-water decks (doc/howto/operability.md) against closed forms, independent of
# the code that made the tables: all use reeving A, no sling lumps, drum speed 0.7 m/s, the
# &boat mass 8500 kg and &rigging block_mass 50 kg of the defaults, davit heads at
# (+-4.6, 13.3, -20.55) m in the ship frame (the &rigging defaults), the ship heeled by
# list_deg (starboard down) or trimmed by trim_deg about its origin at the still water.
SOLAS_INCLINATION = {"solas_list_p20": ("list", 20.0), "solas_list_m20": ("list", -20.0),
                     "solas_trim_p10": ("trim", 10.0), "solas_trim_m10": ("trim", -10.0),
                     "solas_headway": ("list", 0.0), "iiib_level5_090": ("list", 0.0)}
HEAD_Y, HEAD_Z = 13.3, -20.55
G = 9.81


def _head_height(kind, degrees):
    """Height of the heads' midpoint above the still water (z down): the ship-frame point
    (0, y, z) turned by the list about x, z' = z cos(a) + y sin(a), or by the trim about y,
    z' = z cos(a)."""
    a = np.radians(degrees)
    if kind == "list":
        return -(HEAD_Z * np.cos(a) + HEAD_Y * np.sin(a))
    return -HEAD_Z * np.cos(a)


@pytest.mark.parametrize("deck", sorted(SOLAS_INCLINATION))
def test_solas_runs_obey_geometry_statics_and_the_lsa_speed_rule(fresh, deck):
    """H is the heads' height from the list or trim alone (14.76 m at +20 deg, 23.86 m at
    -20 deg, 20.24 m at +-10 deg trim); the lowering-speed limit is the LSA Code's
    0.4 + 0.02 H m/s; in calm water with no impact the boat comes down at the drum speed
    over the four parts of reeving A, 0.7/4 = 0.175 m/s; and the peak part tension of a
    calm launch is the static one, T = (W/2 + m_b g)/2 = 21.09 kN, plus at most 5 % (the
    start's 0.175 m/s^2 is 1.8 % of g)."""
    with h5py.File(fresh / f"{deck}.h5") as f:
        height = float(f[layout.ASSESSMENT].attrs["head_height"])
        speed, limit, _ = f[layout.assessment_dataset("lowering_speed")][()]
        fall = float(f[layout.assessment_dataset("fall_swl")][0])
        impacts = len(f[layout.IMPACT_SPEED][()]) if layout.IMPACT_SPEED in f else 0
    assert height == pytest.approx(_head_height(*SOLAS_INCLINATION[deck]), abs=0.02)
    assert limit == pytest.approx(0.4 + 0.02 * height, rel=1e-9)
    if deck == "iiib_level5_090":
        return  # Level 5 waves: only the geometry and the rule apply
    if impacts == 0:
        assert speed == pytest.approx(0.7 / 4, abs=1e-3)
    static = (8500.0 * G / 2 + 50.0 * G) / 2
    assert static <= fall <= 1.05 * static, (fall, static)

