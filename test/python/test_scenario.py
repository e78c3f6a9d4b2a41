"""No silent traps: every run prints its scenario at the start and stores it under
/scenario; the wind says where it came from (the deck or the level's preset); the shipped
decks leave preset values to the presets, so a copied deck with another `level` gets that
level's wind. Expected values: the sea-state presets of the paper (review G19: Level 4 =
H 2.5 m, wind 8 m/s; Level 5 = H 4 m, wind 10 m/s) and the direction convention
(travelled towards, from N1 towards N2; the ship heads along N1, N2 is starboard)."""
import pathlib
import re

import h5py
import pytest

from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]
PRESET_WIND = {3: 5.5, 4: 8.0, 5: 10.0}
PRESET_HEIGHT = {3: 1.25, 4: 2.5, 5: 4.0}


def _deck(level=None, direction=None, wind=None, t_end=0.2):
    """input/iiib_level5_090.nml as a user edits it (t_end cut: the scenario is the point)."""
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text()
    text = text.replace("t_end = 0.0 ", f"t_end = {t_end} ")
    if level is not None:
        text = re.sub(r"(?m)^(\s*level\s*=\s*)5", rf"\g<1>{level}", text)
    if direction is not None:
        text = re.sub(r"(?m)^(\s*direction_deg\s*=\s*)90\.0", rf"\g<1>{direction}", text)
    if wind is not None:
        text += f"&wind speed = {wind} /\n"
    return text


def _run(davit, tmp_path, text):
    deck = tmp_path / "user.nml"
    deck.write_text(text)
    out = tmp_path / "user.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        attrs = {k: layout._text(v) for k, v in f["scenario"].attrs.items()}
    return result.stdout, attrs


def _line(stdout, head):
    return next(line for line in stdout.splitlines() if line.startswith(head))


def test_the_issues_trap_prints_and_stores_level_4s_wind(davit, tmp_path):
    """The issue's trap: the Level 5 deck copied with level = 4, direction_deg = 135 runs
    Level 4's sea and wind (8 m/s, from the preset), and says so before the run."""
    stdout, attrs = _run(davit, tmp_path, _deck(level=4, direction=135.0))
    lines = stdout.splitlines()
    assert lines[0].startswith("scenario of ")  # printed first, before the run's report
    assert "level 4" in _line(stdout, "sea:") and "H = 2.500 m (level 4 preset)" in stdout
    wind = _line(stdout, "wind:")
    assert "8.00 m/s (level 4 preset)" in wind and "towards 135.0 deg" in wind
    assert attrs["sea_level"] == 4
    assert attrs["wind_speed_m_s"] == PRESET_WIND[4]
    assert attrs["wind_speed_source"] == "level 4 preset"
    assert attrs["wave_height_m"] == PRESET_HEIGHT[4]
    assert attrs["wave_direction_deg"] == 135.0
    # travelling towards 135 deg (aft and to starboard) they come from ahead on the port side
    assert attrs["waves_from"] == "from the port bow"
    assert "from the port bow" in _line(stdout, "waves:")
    assert "starboard side" in _line(stdout, "waves:")
    assert attrs["summary"] == "\n".join(lines[:len(attrs["summary"].splitlines())])


def test_an_explicit_wind_says_deck(davit, tmp_path):
    stdout, attrs = _run(davit, tmp_path, _deck(level=4, wind=12.0))
    assert "12.00 m/s (deck)" in _line(stdout, "wind:")
    assert attrs["wind_speed_m_s"] == 12.0 and attrs["wind_speed_source"] == "deck"


@pytest.mark.parametrize("direction, words", [(0.0, "from astern (following seas)"),
                                              (90.0, "from port (on the beam)"),
                                              (180.0, "from ahead (head seas)"),
                                              (270.0, "from starboard (on the beam)"),
                                              (45.0, "from the port quarter")])
def test_wave_direction_in_words(davit, tmp_path, direction, words):
    """direction_deg is travelled towards, from N1 (the bow) towards N2 (starboard)."""
    _, attrs = _run(davit, tmp_path, _deck(direction=direction, t_end=0.02))
    assert attrs["waves_from"] == words
    assert attrs["wind_from"] == words  # the wind blows along the waves by default


def _groups(text):
    """{group: {key: value text}} of a deck (values up to a comment or the line's end)."""
    groups = {}
    for m in re.finditer(r"(?ms)^\s*&(\w+)(.*?)^\s*/", text):
        body = re.sub(r"!.*", "", m.group(2))
        groups[m.group(1).lower()] = dict(re.findall(r"(\w+)\s*=\s*([^\n,]+)", body))
    return groups


def test_shipped_decks_do_not_pin_the_level_wind():
    """No shipped deck sets &wind speed to its level's preset: such a pin keeps the old
    level's wind when a user changes `level` (the issue's trap)."""
    pinned = []
    for deck in sorted((ROOT / "input").rglob("*.nml")):
        g = _groups(deck.read_text())
        if "speed" not in g.get("wind", {}):
            continue
        level = int(g.get("sea", {}).get("level", "5").strip())
        if float(g["wind"]["speed"]) == PRESET_WIND[level]:
            pinned.append(deck.relative_to(ROOT).as_posix())
    assert not pinned, f"decks pinning the level's preset wind: {pinned}"


def test_sweep_series_files_store_each_cases_scenario(davit, tmp_path):
    """A case's series file states the case's level and its preset wind, from the sweep."""
    (tmp_path / "base.nml").write_text(_deck(t_end=0.2))
    sweep = tmp_path / "sweep.nml"
    sweep.write_text("&sweep base_deck = 'base.nml', levels = 4, 5 /\n")
    result = davit("sweep", sweep, "-o", tmp_path / "s.h5", "--series", tmp_path / "series",
                   "--quiet")
    assert result.returncode == 0, result.stderr
    for case, level in ((1, 4), (2, 5)):
        with h5py.File(tmp_path / "series" / f"case_{case:06d}.h5", "r") as f:
            attrs = {k: layout._text(v) for k, v in f["scenario"].attrs.items()}
        assert attrs["sea_level"] == level
        assert attrs["wind_speed_m_s"] == PRESET_WIND[level]
        assert attrs["wind_speed_source"] == f"sweep: level {level} preset"
