"""davit as a library: a launch stepped, controlled and read from Python.

A thin ctypes layer over the C ABI of build/libdavit.so (include/davit.h); no compiler is
needed at import. The library is looked for in $DAVIT_LIB, then in the build/ folder of the
checkout this package lies in (bash make.sh demo builds it there and makes this package
importable). Arrays come out as numpy arrays. Calls into the library release the GIL, so
threads may each step their own Launch. Guide: doc/howto/library.md.

    import davit
    with davit.Launch.from_file("input/iiib_level5_090.nml") as run:
        run.advance_to(30.0)
        print(run.time, run.boat_pose()["position"], run.sling_tensions())
"""
import ctypes
import os
import pathlib

import numpy as np

__all__ = ["Launch", "DavitError", "OK", "E_INPUT", "E_RUN", "E_ARG", "E_SNAPSHOT",
           "library_path"]

OK, E_INPUT, E_RUN, E_ARG, E_SNAPSHOT = 0, 1, 2, 3, 4
_CODE_NAMES = {E_INPUT: "input", E_RUN: "run", E_ARG: "argument", E_SNAPSHOT: "snapshot"}


class DavitError(RuntimeError):
    """A failed library call: `code` (E_INPUT, E_RUN, E_ARG, E_SNAPSHOT) and the message."""

    def __init__(self, code, message):
        super().__init__(f"davit {_CODE_NAMES.get(code, code)} error ({code}): {message}")
        self.code = code
        self.message = message


def library_path():
    """Where libdavit.so is taken from: $DAVIT_LIB, else <checkout>/build/libdavit.so."""
    env = os.environ.get("DAVIT_LIB")
    if env:
        return pathlib.Path(env)
    return pathlib.Path(__file__).resolve().parents[2] / "build" / "libdavit.so"


_lib = None


def _load():
    global _lib
    if _lib is not None:
        return _lib
    path = library_path()
    if not path.exists():
        raise OSError(f"{path} not found: build it with `bash make.sh setup` (or demo), "
                      "or point DAVIT_LIB at a libdavit.so")
    lib = ctypes.CDLL(str(path))
    h, i, d, s = ctypes.c_void_p, ctypes.c_int, ctypes.c_double, ctypes.c_size_t
    dp = ctypes.POINTER(ctypes.c_double)
    sig = {
        "davit_create_file": (i, [ctypes.c_char_p, ctypes.POINTER(h)]),
        "davit_create_text": (i, [ctypes.c_char_p, ctypes.c_char_p, ctypes.POINTER(h)]),
        "davit_destroy": (None, [h]),
        "davit_error_code": (i, [h]),
        "davit_error_message": (s, [h, ctypes.c_char_p, s]),
        "davit_advance_to": (i, [h, d]),
        "davit_advance": (i, [h, d]),
        "davit_time": (d, [h]),
        "davit_finished": (i, [h]),
        "davit_set_winch_speed": (i, [h, d, d]),
        "davit_brake": (i, [h, d]),
        "davit_release": (i, [h]),
        "davit_set_heading": (i, [h, d]),
        "davit_sizes": (i, [h, ctypes.POINTER(ctypes.c_int)]),
        "davit_state": (i, [h, dp, i]),
        "davit_boat_pose": (i, [h, dp]),
        "davit_ship_pose": (i, [h, dp]),
        "davit_blocks": (i, [h, dp]),
        "davit_hooks": (i, [h, dp]),
        "davit_sling_tensions": (i, [h, dp]),
        "davit_fall_tensions": (i, [h, dp, i]),
        "davit_fender_forces": (i, [h, dp, i]),
        "davit_events": (i, [h, dp]),
        "davit_impacts": (i, [h, dp, i]),
        "davit_rule_checks": (i, [h, dp, dp, dp, i]),
        "davit_check_name": (i, [i, ctypes.c_char_p, s]),
        "davit_save_size": (s, [h]),
        "davit_save": (i, [h, ctypes.c_char_p, s]),
        "davit_restore": (i, [h, ctypes.c_char_p, s]),
    }
    for name, (res, args) in sig.items():
        f = getattr(lib, name)
        f.restype = res
        f.argtypes = args
    _lib = lib
    return lib


def _ptr(a):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


class Launch:
    """One launch run step by step (a handle of the C ABI)."""

    def __init__(self, handle):
        self._h = handle

    @classmethod
    def from_file(cls, path):
        """The run of deck file `path` at t = 0; DavitError (E_INPUT) for a bad deck."""
        return cls._create(lambda lib, out: lib.davit_create_file(os.fsencode(path), out))

    @classmethod
    def from_text(cls, text, name="<deck text>"):
        """The run of deck `text` (named `name` in messages) at t = 0."""
        return cls._create(lambda lib, out: lib.davit_create_text(
            name.encode(), text.encode(), out))

    @classmethod
    def _create(cls, make):
        lib = _load()
        out = ctypes.c_void_p()
        code = make(lib, ctypes.byref(out))
        run = cls(out.value)
        if code != OK:
            err = run._error(code)
            run.close()
            raise err
        return run

    def close(self):
        if self._h:
            _load().davit_destroy(self._h)
            self._h = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown
            pass

    def _error(self, code):
        lib = _load()
        n = lib.davit_error_message(self._h, None, 0)
        buf = ctypes.create_string_buffer(n + 1)
        lib.davit_error_message(self._h, buf, n + 1)
        return DavitError(code, buf.value.decode(errors="replace"))

    def _check(self, code):
        if code != OK:
            raise self._error(code)

    # stepping
    def advance_to(self, t):
        """Step to the first step end at or after t (s); the run's own steps, never cut."""
        self._check(_load().davit_advance_to(self._h, float(t)))
        return self.time

    def advance(self, dt):
        self._check(_load().davit_advance(self._h, float(dt)))
        return self.time

    @property
    def time(self):
        return _load().davit_time(self._h)

    @property
    def finished(self):
        return bool(_load().davit_finished(self._h))

    # controls
    def set_winch_speed(self, drum_speed, ramp=1.0):
        """Drum pay-out speed set-point (m/s, > 0 lowers), reached linearly over ramp s."""
        self._check(_load().davit_set_winch_speed(self._h, float(drum_speed), float(ramp)))

    def brake(self, time_to_rest=0.5):
        self._check(_load().davit_brake(self._h, float(time_to_rest)))

    def release(self):
        self._check(_load().davit_release(self._h))

    def set_heading(self, heading):
        """The ship's heading set-point (rad); a moving ship that keeps a heading."""
        self._check(_load().davit_set_heading(self._h, float(heading)))

    # getters
    def sizes(self):
        """(state components, fall segments, fenders, rule checks)."""
        n = (ctypes.c_int * 4)()
        self._check(_load().davit_sizes(self._h, n))
        return tuple(n)

    def _array(self, fn, n, shape=None):
        a = np.empty(n)
        self._check(fn(self._h, _ptr(a)))
        return a if shape is None else a.reshape(shape)

    def _sized(self, fn, n):
        a = np.empty(n)
        self._check(fn(self._h, _ptr(a), n))
        return a

    def state(self):
        return self._sized(_load().davit_state, self.sizes()[0])

    def boat_pose(self):
        """dict of position, euler, velocity (inertial), angular_velocity (boat axes)."""
        a = self._array(_load().davit_boat_pose, 12)
        return {"position": a[0:3], "euler": a[3:6], "velocity": a[6:9],
                "angular_velocity": a[9:12]}

    def ship_pose(self):
        a = self._array(_load().davit_ship_pose, 6)
        return {"position": a[0:3], "euler": a[3:6]}

    def blocks(self):
        """(2, 3): the movable blocks' positions."""
        return self._array(_load().davit_blocks, 6, (2, 3))

    def hooks(self):
        """(2, 3): the hooks' positions."""
        return self._array(_load().davit_hooks, 6, (2, 3))

    def sling_tensions(self):
        return self._array(_load().davit_sling_tensions, 2)

    def fall_tensions(self):
        return self._sized(_load().davit_fall_tensions, self.sizes()[1])

    def fender_forces(self):
        return self._sized(_load().davit_fender_forces, self.sizes()[2])

    def events(self):
        """dict of first_contact, waterborne, release times (None: not yet) and impacts."""
        a = self._array(_load().davit_events, 4)
        n = int(a[3])
        imp = np.empty(4 * n)
        if n:
            self._check(_load().davit_impacts(self._h, _ptr(imp), 4 * n))
        names = ("first_contact", "waterborne", "release")
        out = {k: (None if v < 0 else float(v)) for k, v in zip(names, a[:3])}
        out["impacts"] = imp.reshape(n, 4)
        return out

    def rule_checks(self):
        """{check id: (value, limit, margin)} so far (NaN: not applicable yet)."""
        lib = _load()
        n = self.sizes()[3]
        v, lim, m = np.empty(n), np.empty(n), np.empty(n)
        self._check(lib.davit_rule_checks(self._h, _ptr(v), _ptr(lim), _ptr(m), n))
        out = {}
        for i in range(n):
            buf = ctypes.create_string_buffer(64)
            lib.davit_check_name(i + 1, buf, 64)
            out[buf.value.decode()] = (v[i], lim[i], m[i])
        return out

    # snapshots
    def save(self):
        """The run's whole state as bytes (restore() takes them back)."""
        lib = _load()
        n = lib.davit_save_size(self._h)
        buf = ctypes.create_string_buffer(n)
        self._check(lib.davit_save(self._h, buf, n))
        return buf.raw

    def restore(self, data):
        self._check(_load().davit_restore(self._h, bytes(data), len(data)))
