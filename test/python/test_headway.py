"""The SOLAS 5-knot headway launch on the BEM/MMG ship (input/solas_headway.nml): the whole
launch (boat lowered from 15 m and released, ~83 s, ~2 s of compute each) run by davit in
calm water and in the oblique Level 4 and 5 seas of input/sweep_solas_headway.nml, with the
rudder autopilot holding the heading:

* calm water: the ship keeps its heading (to 1e-9 rad) and makes 5 kn: its CG's travel over
  the run equals 2.57 m/s x the run's duration within 0.1 %;
* Level 4 at 45 and 135 deg and Level 5 at 135 deg (regular Stokes-2, wind along the
  waves as the level's preset): heading error <= 2 deg throughout the launch.

Level 5 at 45 deg (stern-quartering sea and 10 m/s wind from the port quarter) is not held
within 2 deg by this rudder at 5 kn (2.58 deg measured; doc/howto/manoeuvres.md), so it is
not asserted here.
"""
import re

import h5py
import numpy as np
import pytest

from conftest import ROOT

DECK = (ROOT / "input" / "solas_headway.nml").read_text()


def sea_deck(level, angle):
    """The headway deck in a regular Stokes-2 sea of `level` towards `angle` deg, the wind
    the level's preset along the waves (as input/sweep_solas_headway.nml makes it)."""
    text = DECK.replace("&sea\n  wave_type = 'calm'\n/",
                        f"&sea\n  level = {level}\n  wave_type = 'stokes2'\n"
                        f"  direction_deg = {angle}\n/")
    text = re.sub(r"&wind\n  speed = 0.0\n/\n", "", text)
    assert "stokes2" in text and "&wind" not in text
    return text


def run(davit, folder, name, text):
    deck = folder / f"{name}.nml"
    deck.write_text(text)
    out = folder / f"{name}.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out) as h5:
        return h5["time"][()], h5["ship/euler"][()], h5["ship/position"][()]


def test_calm_water_heading_and_speed(davit, tmp_path):
    t, euler, position = run(davit, tmp_path, "calm", DECK)
    assert "model = 'bem'" in DECK and "manoeuvring = 'mmg'" in DECK
    assert np.abs(euler[:, 2]).max() < 1e-9
    travel = position[-1, 0] - position[0, 0]
    assert travel == pytest.approx(2.57 * (t[-1] - t[0]), rel=1e-3)


@pytest.mark.parametrize("level, angle", [(4, 45), (4, 135), (5, 135)])
def test_oblique_sea_heading_held(davit, tmp_path, level, angle):
    t, euler, _ = run(davit, tmp_path, f"l{level}_{angle}", sea_deck(level, angle))
    assert t[-1] > 75.0  # the whole launch: released at ~83 s
    worst = np.degrees(np.abs(euler[:, 2])).max()
    assert worst <= 2.0, f"Level {level}, {angle} deg: heading error {worst:.2f} deg"
    # the sea moves the heading (a test that the waves act at all)
    assert worst > 0.3
