"""Issue 14's methods on the coupled launch: the first 20 s of the default III.B scene
(Level 5 regular sea, BEM ship, the boat hanging and lowering in 10 m/s wind) against the
same deck at RK4 1e-4 s (the converged reference of the work-precision study, README
Speed), within the tolerances its table states for each method: the default (RK4 1e-3 s,
switches located) to 1e-8 m and 1e-6 of the resolved peak tensions, the Rosenbrock-W
method (rtol 1e-4, the rigging implicit, one accepted step at a time up to 0.02 s) to
2e-4 m and 0.2 %, and the fast level of detail (quasi-static blocks, RK4 1e-2 s) to its
model error, 1 cm and 1 %."""
import subprocess

import h5py
import numpy as np
import pytest

from postproc import layout
from postproc.deck_edit import variant

from conftest import ROOT

DECK = ROOT / "input" / "iiib_level5_090.nml"
FAST = ROOT / "input" / "iiib_level5_090_fast.nml"
T_END = 20.0


def _run(davit_bin, tmp_path, deck, spec, name):
    path = tmp_path / f"{name}.nml"
    path.write_text(variant(deck.read_text(), spec, T_END))
    out = tmp_path / f"{name}.h5"
    result = subprocess.run([davit_bin, "run", str(path), "-o", str(out)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        return {"time": f[layout.TIME][:], "x": f[layout.BOAT_POSITION][:],
                "sling": f[layout.PEAK_SLING_TENSION][:],
                "segment": f[layout.PEAK_SEGMENT_TENSION][:],
                "steps": int(f.attrs[layout.STEPS])}


@pytest.fixture(scope="module")
def reference(davit_bin, tmp_path_factory):
    return _run(davit_bin, tmp_path_factory.mktemp("speed"), DECK, "rk4 dt=1e-4", "ref")


@pytest.mark.parametrize("deck, spec, cg_tol, peak_tol", [
    (DECK, "rk4 dt=1e-3", 1e-8, 1e-6),
    (DECK, "rosw dt=0.02 rtol=1e-4 atol=1e-5", 2e-4, 2e-3),
    (FAST, "rk4", 1e-2, 1e-2)], ids=["default", "rosw", "fast"])
def test_method_agrees_with_the_converged_reference(davit_bin, tmp_path, reference, deck,
                                                    spec, cg_tol, peak_tol):
    run = _run(davit_bin, tmp_path, deck, spec, "run")
    np.testing.assert_allclose(run["time"], reference["time"], rtol=0, atol=1e-9)
    assert np.max(np.linalg.norm(run["x"] - reference["x"], axis=1)) < cg_tol
    assert np.max(np.abs(run["sling"] / reference["sling"] - 1)) < peak_tol
    assert np.max(np.abs(run["segment"] / reference["segment"] - 1)) < peak_tol
    # and each is cheaper than the reference by at least its step ratio
    assert run["steps"] < reference["steps"] / 9
