"""davit as a library (include/davit.h, python/davit): a launch stepped in pieces equals
`davit run` to rounding (the same objects: make.sh links build/libdavit.so from the archive
fpm links the binary from; each link optimises them on its own, -flto, so their inlining and
hence their last bits may differ), a save / restore pair reproduces the run it left, handles on
several threads equal their serial runs, the controls act as their physics says, and bad
input is refused with the code and a message naming file, line, group and key."""
import concurrent.futures
import os
import pathlib
import subprocess
import sys

import h5py
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python"))
import davit  # noqa: E402

DEFAULT_DECK = ROOT / "input" / "iiib_level5_090.nml"


@pytest.fixture(scope="module")
def default_run(davit, tmp_path_factory):
    """`davit run` of the default deck: (time, /boat/position, /slings/tension), the
    arrays (component, time)."""
    out = tmp_path_factory.mktemp("lib") / "default.h5"
    result = davit("run", DEFAULT_DECK, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        return f["time"][:], f["boat/position"][:].T, f["slings/tension"][:].T


def stepped(run, piece, t_stop=None):
    """Step `run` in pieces of `piece` s to its end (or t_stop): times, positions, tensions."""
    times, pos, ten = [run.time], [run.boat_pose()["position"]], [run.sling_tensions()]
    while not run.finished and (t_stop is None or run.time < t_stop - 1e-9):
        run.advance(piece)
        times.append(run.time)
        pos.append(run.boat_pose()["position"])
        ten.append(run.sling_tensions())
    return np.array(times), np.array(pos).T, np.array(ten).T


def test_stepped_launch_equals_davit_run(default_run):
    """The default launch (lowering, contacts, waterborne, release, 5 s after) in 0.02 s
    pieces: the same samples, every /boat/position within 1e-9 m and /slings/tension within
    1e-9 of its peak of `davit run`'s (the two links' rounding: 3e-13 m and 4.5e-11 measured;
    a wrong step, piece or event would move them by millimetres)."""
    time, position, tension = default_run
    with davit.Launch.from_file(DEFAULT_DECK) as run:
        t, p, s = stepped(run, 0.02)
        events = run.events()
    assert events["release"] is not None and events["waterborne"] is not None
    assert t.shape == time.shape, (t[-3:], time[-3:])
    assert np.array_equal(t, time)
    assert np.abs(p - position).max() <= 1e-9
    assert np.abs(s - tension).max() <= 1e-9*np.abs(tension).max()


def test_pieces_of_other_lengths_reach_the_same_state():
    """0.02 s pieces and 0.37 s pieces (not a multiple of the output interval: the time
    reached is the first step end after each target) leave the same state at 12 s."""
    with davit.Launch.from_file(DEFAULT_DECK) as a, davit.Launch.from_file(DEFAULT_DECK) as b:
        stepped(a, 0.02, 12.0)
        while b.time < 12.0 - 1e-9:
            b.advance(min(0.37, 12.0 - b.time))
        assert a.time == b.time == pytest.approx(12.0, abs=1e-12)
        assert np.array_equal(a.state(), b.state())


def test_save_restore_reproduces_the_run():
    """A winch set-point at 20 s, save at 30 s, brake at 35 s, run to 40 s; restore (into
    this handle and into a new one), brake again at 35 s, run to 40 s: state, poses,
    tensions, events and rule checks identical."""
    def finish(run):
        run.advance_to(35.0)
        run.brake(0.5)
        run.advance_to(40.0)
        return (run.time, run.state(), run.boat_pose()["position"], run.sling_tensions(),
                run.fall_tensions(), run.events(), run.rule_checks())

    def same(x, y):
        assert x[0] == y[0]
        for a, b in zip(x[1:5], y[1:5]):
            assert np.array_equal(a, b)
        assert x[5]["release"] == y[5]["release"]
        assert np.array_equal(x[5]["impacts"], y[5]["impacts"])
        for key in x[6]:
            assert np.array_equal(np.array(x[6][key]), np.array(y[6][key]), equal_nan=True)

    with davit.Launch.from_file(DEFAULT_DECK) as run:
        run.advance_to(20.0)
        run.set_winch_speed(1.0, ramp=1.0)
        run.advance_to(30.0)
        snapshot = run.save()
        first = finish(run)
        run.restore(snapshot)
        assert run.time == pytest.approx(30.0, abs=1e-12)
        same(first, finish(run))
    with davit.Launch.from_text("&simulation /\n", "other.nml") as other:
        other.restore(snapshot)
        same(first, finish(other))


def test_restore_refuses_corrupt_bytes_and_keeps_the_run():
    with davit.Launch.from_file(DEFAULT_DECK) as run:
        run.advance_to(1.0)
        snapshot = bytearray(run.save())
        y = run.state()
        snapshot[-1] ^= 0x40  # a bit of the check (the state vector's last component)
        with pytest.raises(davit.DavitError) as err:
            run.restore(bytes(snapshot))
        assert err.value.code == davit.E_SNAPSHOT
        assert "did not reach the saved state" in err.value.message
        with pytest.raises(davit.DavitError) as err:
            run.restore(b"not a snapshot at all, longer than the header is")
        assert err.value.code == davit.E_SNAPSHOT
        assert np.array_equal(run.state(), y)


VARIANT = """&simulation scene = 'launch', t_end = 12.0, dt = 1.0e-3, output_interval = 0.02 /
&boat position = 0.0, 13.3, -15.0 /
&rigging reeving = 'a', sheaves = 'quasi_static', lumps = 0, drum_speed = 0.7 /
&sea level = {level}, wave_type = 'stokes2', direction_deg = {direction}, ramp_periods = 2.0 /
"""


def test_eight_handles_on_two_threads_equal_their_serial_runs():
    """Eight different launches, each stepped in 0.02 s pieces to 6 s alone, then all
    eight at once on two threads (ctypes releases the GIL, so the steps interleave)."""
    decks = [VARIANT.format(level=3 + i % 3, direction=30.0 * i) for i in range(8)]

    def one(deck):
        with davit.Launch.from_text(deck, "variant.nml") as run:
            stepped(run, 0.02, 6.0)
            return run.time, run.state()

    serial = [one(d) for d in decks]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        threaded = list(pool.map(one, decks))
    for (t1, y1), (t2, y2) in zip(serial, threaded):
        assert t1 == t2
        assert np.array_equal(y1, y2)
    # the launches do differ (the check would be empty otherwise)
    assert not np.array_equal(serial[0][1], serial[1][1])


CALM = """&simulation scene = 'launch', t_end = 40.0, dt = 1.0e-3, output_interval = 0.02 /
&boat position = 0.0, 13.3, -15.0 /
&rigging reeving = 'a', sheaves = 'quasi_static', lumps = 0, drum_speed = 0.7, ramp_time = 1.0 /
&wind speed = 0.0 /
"""


def boat_z(run):
    return run.boat_pose()["position"][2]


def test_winch_set_point_lowers_the_boat_at_drum_speed_over_the_gear():
    """Calm water, no wind. Reeving A pays out 4 parts per fall (gear 4): the deck's drum
    speed 0.7 m/s lowers the boat at 0.175 m/s (z down), a set-point of 1.2 m/s at 0.3 m/s."""
    with davit.Launch.from_text(CALM, "calm.nml") as run:
        run.advance_to(6.0)
        z0 = boat_z(run)
        run.advance_to(16.0)
        assert (boat_z(run) - z0) / 10.0 == pytest.approx(0.7 / 4, rel=0.03)
        run.set_winch_speed(1.2, ramp=1.0)
        run.advance_to(18.0)
        z1 = boat_z(run)
        run.advance_to(28.0)
        assert (boat_z(run) - z1) / 10.0 == pytest.approx(1.2 / 4, rel=0.03)


def test_brake_stops_the_lowering():
    """Calm water: the drum braked to rest over 0.5 s at 10 s: the boat's mean height over
    12-17 s and over 17-22 s differ by less than 2 cm (0.875 m at the deck's speed)."""
    with davit.Launch.from_text(CALM, "calm.nml") as run:
        run.advance_to(10.0)
        run.brake(0.5)
        run.advance_to(12.0)
        z = []
        while run.time < 22.0 - 1e-9:
            run.advance(0.02)
            z.append(boat_z(run))
        assert abs(np.mean(z[:250]) - np.mean(z[250:])) < 0.02


def test_release_drops_the_boat():
    """Calm water, no wind: hooks opened by hand at 5 s (the boat 15 m up): the release
    time is noted, the slings carry nothing, and 1 s later the boat has fallen
    v0 t + g t^2 / 2 = 5.08 m (v0 = 0.175 m/s, the lowering speed; to 1 %: the air's drag
    is small over 1 s)."""
    with davit.Launch.from_text(CALM, "calm.nml") as run:
        run.advance_to(5.0)
        t0, z0, v0 = run.time, boat_z(run), run.boat_pose()["velocity"][2]
        assert v0 == pytest.approx(0.175, rel=0.02)
        run.release()
        run.advance_to(6.0)
        assert run.events()["release"] == t0
        assert np.all(run.sling_tensions() == 0.0)
        t = run.time - t0
        assert boat_z(run) - z0 == pytest.approx(v0 * t + 0.5 * 9.81 * t**2, rel=0.01)


def test_heading_set_point_turns_the_ship():
    """Calm water, drum at rest: the ship's heading keeping (a spring of period 30 s, the
    &ship heading_period default, with damping and an integral term) turned 0.05 rad to
    starboard at 1 s: the yaw moves towards the set-point only, is within 20 % of the step
    after one period and within 10 % after two; a deck on foundation slings (no moving
    ship) refuses the set-point."""
    deck = CALM.replace("drum_speed = 0.7", "drum_speed = 0.0").replace(
        "t_end = 40.0", "t_end = 70.0")
    with davit.Launch.from_text(deck, "calm.nml") as run:
        run.advance_to(1.0)
        yaw0 = run.ship_pose()["euler"][2]
        run.set_heading(yaw0 + 0.05)
        turned = []
        while run.time < 61.0 - 1e-9:
            run.advance(0.5)
            turned.append(run.ship_pose()["euler"][2] - yaw0)
        assert min(turned) >= 0.0
        assert turned[59] == pytest.approx(0.05, rel=0.2)   # 31 s
        assert turned[-1] == pytest.approx(0.05, rel=0.1)   # 61 s
    with davit.Launch.from_text("&simulation scene = 'hanging_boat', t_end = 1.0 /\n", "h.nml") as run:
        with pytest.raises(davit.DavitError) as err:
            run.set_heading(0.1)
        assert err.value.code == davit.E_ARG and "heading" in err.value.message


def test_bad_deck_gives_code_and_message():
    deck = "! a deck\n&simulation\n  dt = 1.0e-3\n  t_end = -5.0\n/\n"
    with pytest.raises(davit.DavitError) as err:
        davit.Launch.from_text(deck, "trainee.nml")
    assert err.value.code == davit.E_INPUT
    m = err.value.message
    assert "trainee.nml" in m and ":4" in m and "&simulation" in m and "t_end" in m


def test_missing_file_and_boatless_scene_are_refused(tmp_path):
    with pytest.raises(davit.DavitError) as err:
        davit.Launch.from_file(tmp_path / "nowhere.nml")
    assert err.value.code == davit.E_INPUT and "nowhere.nml" in err.value.message
    with pytest.raises(davit.DavitError) as err:
        davit.Launch.from_text("&simulation scene = 'sea', t_end = 10.0 /\n", "sea.nml")
    assert err.value.code == davit.E_INPUT and "scene" in err.value.message


def test_bad_controls_are_refused_and_the_run_goes_on():
    with davit.Launch.from_file(DEFAULT_DECK) as run:
        run.advance_to(1.0)
        with pytest.raises(davit.DavitError) as err:
            run.set_winch_speed(50.0)
        assert err.value.code == davit.E_ARG and "[-10, 10]" in err.value.message
        with pytest.raises(davit.DavitError) as err:
            run.brake(float("nan"))
        assert err.value.code == davit.E_ARG
        run.advance_to(2.0)
        assert run.time == pytest.approx(2.0, abs=1e-12)



def test_bad_steps_are_refused_and_the_run_goes_on():
    """A negative or non-finite step and a non-finite target time are refused (E_ARG, the
    message naming the call) before the run moves; the handle stays usable."""
    with davit.Launch.from_file(DEFAULT_DECK) as run:
        run.advance_to(0.5)
        t = run.time
        for call, value, text in ((run.advance, -0.1, "advance: dt must be a finite number"),
                                  (run.advance, float("inf"), "advance: dt must be a finite"),
                                  (run.advance_to, float("nan"), "advance_to: the time is not")):
            with pytest.raises(davit.DavitError) as err:
                call(value)
            assert err.value.code == davit.E_ARG and text in err.value.message
            assert run.time == t
        run.advance(0.5)
        assert run.time == pytest.approx(t + 0.5, abs=1e-12)

def test_c_header_compiles_and_runs(tmp_path):
    """A C program against include/davit.h and build/libdavit.so: 1 s of the default
    launch, its sling tension equal to the Python package's."""
    src = tmp_path / "probe.c"
    src.write_text(r"""
#include <stdio.h>
#include "davit.h"
int main(int argc, char **argv) {
  davit_handle h;
  double ten[2];
  if (davit_create_file(argv[1], &h) != DAVIT_OK) { davit_destroy(h); return 2; }
  if (davit_advance_to(h, 1.0) != DAVIT_OK) return 3;
  davit_sling_tensions(h, ten);
  printf("%.17g %.17g %.17g\n", davit_time(h), ten[0], ten[1]);
  davit_destroy(h);
  return 0;
}
""")
    lib = davit.library_path()
    exe = tmp_path / "probe"
    subprocess.run(["gcc", "-o", exe, src, "-I", ROOT / "include", lib,
                    f"-Wl,-rpath,{lib.parent}"], check=True)
    out = subprocess.run([exe, DEFAULT_DECK], capture_output=True, text=True, check=True,
                         env={**os.environ})
    t, t1, t2 = map(float, out.stdout.split())
    with davit.Launch.from_file(DEFAULT_DECK) as run:
        run.advance_to(1.0)
        assert t == run.time
        assert [t1, t2] == list(run.sling_tensions())
