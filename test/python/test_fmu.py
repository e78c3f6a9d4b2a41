"""The FMI 2.0 co-simulation FMU (`python3 -m davit.fmu`) stepped by FMPy, a co-simulation
master from PyPI that shares no code with davit: it validates against the standard, and its
outputs equal the Python package's stepping of the same deck with the same controls, bit
for bit (the same library underneath, the same steps)."""
import os
import pathlib
import shutil

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DECK = ROOT / "input" / "iiib_level5_090.nml"
fmpy = pytest.importorskip("fmpy")


@pytest.fixture(scope="module")
def fmu(tmp_path_factory):
    from davit import fmu as davit_fmu
    if shutil.which("cc") is None:
        pytest.skip("no C compiler")
    if not (ROOT / "build" / "libdavit.so").is_file():
        pytest.skip("no build/libdavit.so (bash make.sh demo builds it)")
    return str(davit_fmu.build(DECK, tmp_path_factory.mktemp("fmu") / "davit.fmu"))


def test_fmu_passes_fmpys_validation(fmu):
    from fmpy.validation import validate_fmu
    assert validate_fmu(fmu) == []
    md = fmpy.read_model_description(fmu, validate=True)
    assert md.fmiVersion == "2.0" and md.coSimulation.modelIdentifier == "davit"


def launch_reference(stop, stop_winch_at=None, release_at=None):
    """The same deck through the Python package, stepped at 0.02 s with the controls at
    the same communication points: (time, boat z, fore sling tension)."""
    import davit
    out = []
    with davit.Launch.from_file(str(DECK)) as run:
        for k in range(round(stop / 0.02) + 1):
            t = k * 0.02
            if k:
                run.advance_to(t)
            out.append((t, run.boat_pose()["position"][2], run.sling_tensions()[0]))
            if stop_winch_at is not None and abs(t - stop_winch_at) < 1e-9:
                run.set_winch_speed(0.0, ramp=0.0)
            if release_at is not None and abs(t - release_at) < 1e-9:
                run.release()
    return out


def test_fmu_steps_like_the_library_with_its_inputs(fmu):
    """20 s of the default launch with the winch stopped at 5 s by the FMU's input and the
    hooks released at 15 s: boat z and the fore sling tension at every 0.02 s
    communication point equal the package's stepping bit for bit; the release time is
    reported; and the boat's height holds after the stop (it lowered before)."""
    dtype = [("time", np.float64), ("winch_speed", np.float64), ("release", np.bool_)]
    signals = np.array([(0.0, -1.0, False), (4.99, -1.0, False), (5.0, 0.0, False),
                        (14.99, 0.0, False), (15.0, 0.0, True), (20.0, 0.0, True)], dtype=dtype)
    r = fmpy.simulate_fmu(fmu, stop_time=20.0, step_size=0.02, output_interval=0.02,
                          input=signals, output=["boat_z", "sling_tension_fore", "release_time"])
    ref = launch_reference(20.0, stop_winch_at=5.0, release_at=15.0)
    n = min(len(r), len(ref))
    assert n >= 1000
    np.testing.assert_allclose(r["time"][:n], [x[0] for x in ref[:n]], rtol=0, atol=1e-9)
    assert np.array_equal(r["boat_z"][:n], [x[1] for x in ref[:n]])
    assert np.array_equal(r["sling_tension_fore"][:n], [x[2] for x in ref[:n]])
    assert r["boat_z"][250] > r["boat_z"][0] + 0.5          # lowered (z down) before 5 s
    assert abs(r["release_time"][-1] - 15.0) < 0.03
    assert r["release_time"][700] == -1.0                 # not released at 14 s


def test_fmu_state_get_set_and_serialize(fmu, tmp_path):
    """FMI's state handling through FMPy's FMU2Slave: save at 10 s and step to 12 s;
    restore and step again: the same boat z and sling tension bit for bit; restore, stop
    the winch through the input and step: a different (higher) boat; the state serialized
    to bytes and read back restores the first path again, the input with it."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    md = read_model_description(fmu)
    unzipped = extract(fmu, unzipdir=str(tmp_path / "fmu"))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    slave = FMU2Slave(guid=md.guid, unzipDirectory=unzipped,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="d")
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()

    def run_to(t0, t1):
        t = t0
        while t < t1 - 1e-9:
            slave.doStep(currentCommunicationPoint=t, communicationStepSize=0.02)
            t = round(t + 0.02, 10)
        return slave.getReal([vr["boat_z"], vr["sling_tension_fore"]])

    run_to(0.0, 10.0)
    saved = slave.getFMUstate()
    a = run_to(10.0, 12.0)
    slave.setFMUstate(saved)
    assert run_to(10.0, 12.0) == a
    slave.setFMUstate(saved)
    slave.setReal([vr["winch_speed"]], [0.0])
    stopped = run_to(10.0, 12.0)
    assert stopped[0] < a[0] - 0.1            # z down: the stopped boat hangs higher
    data = slave.serializeFMUstate(saved)
    restored = slave.deSerializeFMUstate(bytes(data))
    slave.setFMUstate(restored)               # the input back to the deck's profile too
    assert run_to(10.0, 12.0) == a
    slave.freeFMUstate(saved)
    slave.freeFMUstate(restored)
    slave.terminate()
    slave.freeInstance()


def test_fmu_with_a_bad_deck_fails_with_the_message(tmp_path, capfd):
    """An FMU whose deck has an out-of-range key: instantiation succeeds, initialisation
    fails with fmi2Error, and the logger receives davit's message naming the key."""
    from davit import fmu as davit_fmu
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave
    if shutil.which("cc") is None or not (ROOT / "build" / "libdavit.so").is_file():
        pytest.skip("no C compiler or no build/libdavit.so")
    bad = tmp_path / "bad.nml"
    bad.write_text(DECK.read_text().replace("output_interval = 0.02", "output_interval = -1.0"))
    path = davit_fmu.build(bad, tmp_path / "bad.fmu")
    md = read_model_description(str(path))
    slave = FMU2Slave(guid=md.guid, unzipDirectory=extract(str(path), str(tmp_path / "x")),
                      modelIdentifier="davit", instanceName="bad")
    slave.instantiate(loggingOn=True)
    slave.setupExperiment(startTime=0.0)
    with pytest.raises(Exception):
        slave.enterInitializationMode()
    slave.freeInstance()
    logged = capfd.readouterr()
    assert "output_interval" in logged.out + logged.err, logged
