"""The KVLCC2 manoeuvre decks against the SIMMAN 2008 free-running model tests (the L = 7 m
KVLCC2 model at Fn 0.142, rudder rate 15.68 deg/s: the decks' condition, case 1.2).

Source: the MARIN and HSVA free-running time series of the SIMMAN 2008 workshop as
redistributed in github.com/martinlarsalbert/System-identification-of-Vessel-Manoeuvring-
Models (commit 4b7ce53f0cc8ac159126fdda7d45e30c540be2d8), data/01_raw/kvlcc2/
MARIN_FREE_KVLCC2_{tc_-35,zz_-10,zz_-20}_m.dat (MARIN, the workshop's primary data) and
data/01_raw/kvlcc2_hsva/raw_data/HSVA_CPMC_KVLCC2_Z_10_10_S.dat (HSVA; its report, "05
SIMMAN model test report _KVLCC1 and 2 free_ HSVA.pdf" beside it, Cura Hochbaum 2006,
gives the conventions: heading positive turning to starboard, rudder angle positive
steering to port, so the files named -35, -10 and -20 are the starboard turn and the
zig-zags whose first rudder is to starboard, as the decks'; yaw gyradius 0.25 L_pp as
davit's; full scale, L_pp = 320 m). The numbers below were measured from those series
with postproc.manoeuvre's own turning() and overshoots() (heading change from the heading
at the rudder's execute, the rudder angle's sign flipped, its offset before the execute
removed); they are not davit's output. HSVA repeated its 10/10 tests three times: the
first overshoots differed by 0.2 deg (starboard) at most (its report).

MARIN 35 deg starboard turn: advance 3.10 L, transfer 1.36 L, tactical diameter 3.33 L.
MARIN 10/10 zig-zag: overshoots 8.11 and 21.99 deg (HSVA: 9.69 and 20.54 deg).
MARIN 20/20 zig-zag: overshoots 12.58 and 16.02 deg (HSVA tested no 20/20).

davit's MMG model (Yasukawa & Yoshimura 2015's coefficients; it agrees with the 3-DOF
reference solver of test_manoeuvre.py within 0.15 deg) meets the turning circle and the
20/20 second overshoot within 10 %, but its 10/10 overshoots are 39 % below the model
tests' and its 20/20 first overshoot 16 % below: those comparisons are strict xfails
(they fail the suite the day they pass, so that the table in doc/howto/manoeuvres.md is
then brought up to date). A second audit (doc/howto/manoeuvres.md, "A second audit") found
davit's model and coefficients the same as Yasukawa & Yoshimura's and two more open-source
transcriptions (ShipMMG.jl, VesselManoeuvringModels), and the tank's own condition (MARIN's
propeller rate of 10.32 1/s with a skin-friction tow force, its approach speed) moves the
10/10 first overshoot by 0.3 deg at most (5.26 deg): the gap is the model with these
coefficients, not a slip, and the xfails stay. Two implementations by other groups,
ShipMMG and mmgdynamics, run with the deck's values and the paper's equations, give
davit's overshoots within 0.08 deg (4.96/13.59 and 4.95/13.61 deg at 10/10;
doc/howto/manoeuvres.md, "Independent implementations"). No published *simulation* of this model
(Yasukawa & Yoshimura's coefficients) stating its zig-zag overshoots was found to compare
with instead; the sources checked are listed in doc/howto/manoeuvres.md ("Published
simulations of this model").
"""
import pytest

from conftest import ROOT
from postproc import manoeuvre

TOLERANCE = 0.10          # the issue's: within 10 % of the published value
TURN = {"advance": 3.10, "transfer": 1.36, "tactical_diameter": 3.33}
OVERSHOOTS = {10: (8.11, 21.99), 20: (12.58, 16.02)}


@pytest.fixture(scope="module")
def runs(davit, tmp_path_factory):
    folder = tmp_path_factory.mktemp("published")
    out = {}
    for name in ("kvlcc2_turning_35", "kvlcc2_zigzag_10", "kvlcc2_zigzag_20"):
        path = folder / f"{name}.h5"
        result = davit("run", ROOT / "input" / f"{name}.nml", "-o", path)
        assert result.returncode == 0, result.stderr
        out[name] = path
    return out


def _overshoots(runs, angle):
    t, _, yaw, rudder, _, switch = manoeuvre.load(runs[f"kvlcc2_zigzag_{angle}"])
    assert switch == angle
    got = manoeuvre.overshoots(t, yaw, rudder, switch)
    assert None not in got
    return got


@pytest.mark.parametrize("key", ["advance", "transfer", "tactical_diameter"])
def test_turning_circle_against_marin_free_running(runs, key):
    t, pos, yaw, rudder, length, _ = manoeuvre.load(runs["kvlcc2_turning_35"])
    got = manoeuvre.turning(t, pos, yaw, rudder, length)
    assert got[key] == pytest.approx(TURN[key], rel=TOLERANCE)


def test_zigzag_20_second_overshoot_against_marin_free_running(runs):
    assert _overshoots(runs, 20)[1] == pytest.approx(OVERSHOOTS[20][1], rel=TOLERANCE)


@pytest.mark.xfail(strict=True, reason="davit's MMG KVLCC2 gives 4.96 and 13.67 deg at "
                   "10/10 and 10.51 deg first at 20/20, 39 % and 16 % below MARIN's")
@pytest.mark.parametrize("angle,which", [(10, 0), (10, 1), (20, 0)])
def test_zigzag_overshoots_against_marin_free_running(runs, angle, which):
    assert _overshoots(runs, angle)[which] == pytest.approx(OVERSHOOTS[angle][which],
                                                            rel=TOLERANCE)

