"""Regular-wave RAOs of the floating lifeboat (&boat water_model = 'bem') against the
frequency-domain solution of its database (postproc.boat_rao; issue 18).

The long-wave check runs always. The full comparison (heave, roll, pitch at 90 and 180
deg over 0.5-6 rad/s within 10 %) waits for the strips' pressure-averaged Froude-Krylov
load and wave roll moment (issue 18, strip work): the strips still apply rho g b eta on
each section without the pressure's decay with depth (heave 1.5x at 2.9 rad/s) and no
roll moment from the wave slope (beam-sea roll -65 % at 1.4 rad/s). Enable it with
DAVIT_BOAT_RAO=1 once that work is merged.
"""
import os
import pathlib

import numpy as np
import pytest

from postproc import boat_rao

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATABASE = ROOT / "input" / "boat_bem.nc"


def test_long_waves_heave_and_pitch_follow_the_surface(davit_bin):
    """At 0.5 rad/s (a 250 m wave on the 11.5 m boat) heave follows the surface (RAO 1) and
    head-sea pitch the slope (k cos beta): davit within 2 % (heave) and 5 % (pitch) of the
    frequency-domain solution."""
    td, ref = boat_rao.compare(davit_bin, DATABASE, [0.5], [90.0, 180.0])
    assert np.allclose(td["heave"], ref["heave"], rtol=0.02), (td, ref)
    assert abs(td["pitch"][0, 1] / ref["pitch"][0, 1] - 1) < 0.05, (td, ref)


@pytest.mark.skipif(os.environ.get("DAVIT_BOAT_RAO") != "1",
                    reason="needs the strips' pressure-averaged Froude-Krylov and wave roll "
                           "moment (issue 18 strip work); set DAVIT_BOAT_RAO=1")
@pytest.mark.parametrize("dof,heading", [("heave", 90.0), ("roll", 90.0), ("heave", 180.0),
                                         ("pitch", 180.0)])
def test_rao_within_10_percent(davit_bin, dof, heading):
    omegas = [0.5, 1.0, 1.4, 2.0, 2.5, 2.9, 3.2, 4.0, 5.0, 6.0]
    td, ref = boat_rao.compare(davit_bin, DATABASE, omegas, [heading])
    r, d = ref[dof][:, 0], td[dof][:, 0]
    keep = r > 0.02 * r.max()                 # where the response is not negligible
    err = np.abs(d[keep] / r[keep] - 1)
    assert err.max() < 0.10, dict(zip(np.asarray(omegas)[keep], err.round(3)))
