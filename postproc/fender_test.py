"""Fender impact test: input/fender_test.nml at 0.5, 1, 2 and 3.5 m/s with the rubber
fender and the paper's Hertz law, as a markdown table (README "### Fenders").

  python -m postproc.fender_test [--davit PATH] [--keep DIR]

Each case writes its deck to a temporary folder (or DIR), runs it and reads the HDF5 output:
peak force per fender, deepest deflection, contact duration (force > 0), peak horizontal
acceleration of the boat's CG (/boat/acceleration), energy absorbed 1/2 m (v_in^2 - v_out^2),
the loop area (the work of the fender force over the contact, which the slings do not
enter), and the rebound ratio v_out / v_in at separation.
"""
import argparse
import os
import pathlib
import subprocess
import tempfile

import numpy as np

from . import layout

ROOT = pathlib.Path(__file__).resolve().parents[1]
BASE = ROOT / "input" / "fender_test.nml"
SPEEDS = (0.5, 1.0, 2.0, 3.5)
MASS = 8490.0
# law: (deck key, step and output interval [s], simulated time [s])
LAWS = {"rubber_fender": (1.0e-4, 1.2), "hertz_elastoplastic": (1.0e-5, 0.05)}


def deck_text(law, speed):
    """The base deck at approach speed `speed` [m/s] with contact law `law`."""
    dt, t_end = LAWS[law]
    out = []
    for line in BASE.read_text().splitlines():
        key = line.strip().split("=")[0].strip()
        if key == "velocity":
            line = f"  velocity = 0.0, {-speed}, 0.0"
        elif key == "law":
            line = f"  law = '{law}'"
        elif key in ("dt", "output_interval"):
            line = f"  {key} = {dt}"
        elif key == "t_end":
            line = f"  t_end = {t_end}"
        out.append(line)
    return "\n".join(out) + "\n"


def impact_metrics(run, speed):
    """The impact's numbers from a loaded run (layout.Run)."""
    t = run.time
    force = run.get(layout.CONTACT_FORCE)
    deflection = -run.get(layout.CONTACT_CLEARANCE)
    vy = run.get(layout.BOAT_VELOCITY)[:, 1]
    ay = run.get(layout.BOAT_ACCELERATION)[:, 1]
    on = np.flatnonzero(force.max(axis=1) > 0.0)
    first, last = on[0], on[-1]
    v_out = vy[min(last + 1, t.size - 1)]
    f = force[first - 1:last + 2, 0]
    d = np.clip(deflection[first - 1:last + 2], 0.0, None)
    loop = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(d)))
    return {"speed": speed, "force": force.max(), "deflection": deflection.max(),
            "duration": t[last] - t[first], "accel": np.abs(ay).max(),
            "absorbed": 0.5 * MASS * (speed**2 - v_out**2), "loop": 2.0 * loop,
            "kinetic": 0.5 * MASS * speed**2, "rebound": v_out / speed}


def run_case(davit, folder, law, speed):
    deck = pathlib.Path(folder) / f"fender_test_{law}_{speed:g}.nml"
    deck.write_text(deck_text(law, speed))
    out = deck.with_suffix(".h5")
    res = subprocess.run([davit, "run", str(deck), "-o", str(out)], capture_output=True,
                         text=True)
    if res.returncode != 0:
        raise RuntimeError(f"{deck}: {res.stderr}")
    return impact_metrics(layout.load(out), speed)


def table(rows):
    head = ("| law | v (m/s) | peak force per fender (kN) | deflection (mm) | contact (ms) | "
            "peak a (m/s², g) | KE (kJ) | absorbed (kJ) | loop area (kJ) | rebound v_out/v_in |")
    lines = [head, "|" + "---|" * 10]
    for law, m in rows:
        lines.append(f"| {law} | {m['speed']:g} | {m['force'] / 1e3:.1f} | "
                     f"{m['deflection'] * 1e3:.1f} | {m['duration'] * 1e3:.0f} | "
                     f"{m['accel']:.1f} ({m['accel'] / 9.81:.2f} g) | {m['kinetic'] / 1e3:.2f} | "
                     f"{m['absorbed'] / 1e3:.2f} | {m['loop'] / 1e3:.2f} | {m['rebound']:.3f} |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--davit", default=os.environ.get("DAVIT", "davit"),
                        help="davit executable (default: $DAVIT or davit on PATH)")
    parser.add_argument("--keep", help="folder for the decks and outputs (default: temporary)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.keep or tmp
        pathlib.Path(folder).mkdir(parents=True, exist_ok=True)
        rows = [(law, run_case(args.davit, folder, law, v)) for law in LAWS for v in SPEEDS]
    print(table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
