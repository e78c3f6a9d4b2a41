"""`davit-post manoeuvre RUN.h5 [--length L]`: the standard manoeuvre measures of a ship run
with `&ship manoeuvring = 'mmg'` (IMO MSC.137(76) definitions, ITTC 7.5-04-02-01).

Turning circle (rudder held one way): advance (travel of the CG along the approach course
from the rudder execute to 90 deg of heading change), transfer (lateral travel there) and
tactical diameter (lateral travel at 180 deg), in ship lengths L_pp. Zig-zag (the rudder
reverses): the first and second overshoot angles, the heading's excursions beyond the
switching heading (&mmg zigzag_heading_deg of the run's deck) after the first and the second
rudder reversal. The execute is the
moment the rudder leaves amidships (extrapolated back from the first two moving samples).
L_pp is the deck's `&ship length_pp` (the run's stored deck) unless --length is given.
"""
import argparse
import sys

import numpy as np

from . import layout


def load(path):
    """time, CG position (n, 3), yaw (n), rudder (n), L_pp [m] and the zig-zag switching
    heading [deg] of a ship run (&ship length_pp, &mmg zigzag_heading_deg of its deck, or
    the keys' defaults)."""
    run = layout.load(path)
    names = (layout.TIME, layout.SHIP_POSITION, layout.SHIP_EULER, layout.SHIP_RUDDER)
    data = [run.get(name) for name in names]
    for name, value in zip(names, data):
        if value is None:
            raise ValueError(f"{path}: no dataset '{name}' (a 'ship' scene run with "
                             f"&ship manoeuvring = 'mmg' records it)")
    time, position, euler, rudder = (np.asarray(v, dtype=float) for v in data)
    return (time, position, euler[:, 2], rudder, float(run.deck("ship", "length_pp", 126.0)),
            float(run.deck("mmg", "zigzag_heading_deg", 10.0)))


def execute_index(t, rudder):
    """(index of the last sample at rest, execute time)."""
    moving = np.flatnonzero(np.abs(rudder) > 1e-9)
    if moving.size == 0:
        raise ValueError("the rudder never moves: no manoeuvre")
    k = max(moving[0], 1)
    rate = (rudder[k + 1] - rudder[k]) / (t[k + 1] - t[k]) if k + 1 < t.size else 0.0
    t0 = t[k] - rudder[k] / rate if rate != 0.0 else t[k - 1]
    return k - 1, max(t0, t[k - 1])


def _crossing(t, x, level):
    """First time x reaches level (linear interpolation), or None."""
    above = np.flatnonzero(x >= level)
    if above.size == 0:
        return None
    k = above[0]
    if k == 0:
        return t[0]
    return t[k - 1] + (level - x[k - 1]) / (x[k] - x[k - 1]) * (t[k] - t[k - 1])


def turning(t, pos, yaw, rudder, length):
    """Advance, transfer, tactical diameter [L_pp] (None where the turn does not reach
    the heading change)."""
    k0, t0 = execute_index(t, rudder)
    side = np.sign(rudder[np.flatnonzero(np.abs(rudder) > 1e-9)[0]])
    x0 = np.array([np.interp(t0, t, pos[:, i]) for i in range(2)])
    psi0 = np.interp(t0, t, yaw)
    ahead = np.array([np.cos(psi0), np.sin(psi0)])
    beam = side * np.array([-np.sin(psi0), np.cos(psi0)])
    change = side * (yaw - psi0)
    out = {}
    for name, deg in (("advance", 90.0), ("tactical_diameter", 180.0)):
        tc = _crossing(t[k0:], change[k0:], np.radians(deg))
        if tc is None:
            out[name] = None
            if deg == 90.0:
                out["transfer"] = None
            continue
        d = np.array([np.interp(tc, t, pos[:, i]) for i in range(2)]) - x0
        if deg == 90.0:
            out["advance"] = d @ ahead / length
            out["transfer"] = d @ beam / length
        else:
            out["tactical_diameter"] = d @ beam / length
    return out


def overshoots(t, yaw, rudder, switch):
    """First and second overshoot angles [deg] of a zig-zag with the switching heading
    `switch` [deg] (None if not reached): the heading's extreme beyond the switching
    heading between successive zero crossings of the rudder."""
    _, t0 = execute_index(t, rudder)
    psi = np.degrees(yaw - np.interp(t0, t, yaw))
    order = np.sign(np.round(rudder, 9))
    flips = np.flatnonzero(order[1:] * order[:-1] < 0) + 1
    result = []
    for i, k in enumerate(flips[:2]):
        end = flips[i + 1] if i + 1 < flips.size else t.size - 1
        window = psi[k:end + 1]
        j = int(np.argmax(np.abs(window)))
        result.append(None if k + j >= t.size - 1 else abs(window[j]) - switch)
    while len(result) < 2:
        result.append(None)
    return result


def report(path, length=None):
    """The manoeuvre's measures as text lines."""
    t, pos, yaw, rudder, deck_length, switch = load(path)
    length = length or deck_length
    order = np.sign(np.round(rudder, 9))
    reversed_ = np.any(order[1:] * order[:-1] < 0)
    lines = [f"{path}: L_pp = {length:g} m"]
    if not reversed_:
        m = turning(t, pos, yaw, rudder, length)
        for key in ("advance", "transfer", "tactical_diameter"):
            value = m[key]
            lines.append(f"  {key.replace('_', ' ')}: " +
                         ("not reached" if value is None else f"{value:.3f} L"))
    else:
        first, second = overshoots(t, yaw, rudder, switch)
        for name, value in (("first", first), ("second", second)):
            lines.append(f"  {name} overshoot angle: " +
                         ("not reached" if value is None else f"{value:.2f} deg"))
    return lines


def main(argv=None):
    parser = argparse.ArgumentParser(prog="davit-post manoeuvre", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run", help="davit run file (scene 'ship', &ship manoeuvring = 'mmg')")
    parser.add_argument("--length", type=float, default=None,
                        help="ship length L_pp [m] (default: the run's deck)")
    args = parser.parse_args(argv)
    try:
        print("\n".join(report(args.run, args.length)))
    except (OSError, ValueError, KeyError) as exc:
        print(f"davit-post manoeuvre: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
