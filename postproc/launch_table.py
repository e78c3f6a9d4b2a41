"""Peak loads, impacts and limits of launch runs, as a markdown table (README "Loads,
impacts and limits"): `python -m postproc.launch_table out/iiib_*.h5`.

Every number comes from the launch log of the run file (resolved at every step): impacts,
the fastest normal impact speed, the largest CG and filtered seat accelerations, the largest
sling and fall (cable segment) tensions, the first time the safe working load was exceeded
and the outcome."""
import argparse
import os
import sys

import numpy as np

from . import layout


def row(path):
    """The table row of one run file."""
    run = layout.load(path)
    speeds = run.get(layout.IMPACT_SPEED)
    seg = run.get(layout.PEAK_SEGMENT_TENSION)
    swl = run.get(layout.LIMIT_SWL)
    return {
        "run": os.path.basename(path).removesuffix(".h5"),
        "impacts": 0 if speeds is None else len(speeds),
        "v_max": 0.0 if speeds is None or len(speeds) == 0 else float(np.max(speeds)),
        "a_cg": float(run.get(layout.PEAK_CG_ACCELERATION)[0]),
        "a_seat": float(run.get(layout.PEAK_SEAT_ACCELERATION)[0]),
        "sling": float(np.max(run.get(layout.PEAK_SLING_TENSION))) / 1e3,
        "fall": 0.0 if seg is None or len(seg) == 0 else float(np.max(seg)) / 1e3,
        "swl": float(swl[0]),
        "outcome": run.attrs.get(layout.OUTCOME, ""),
    }


def table(paths):
    lines = ["| run | impacts | fastest (m/s) | CG peak (m/s²) | seat, 20 Hz (m/s²) | "
             "sling (kN) | fall (kN) | SWL first exceeded (s) | outcome |",
             "|---|---|---|---|---|---|---|---|---|"]
    for path in paths:
        r = row(path)
        swl = "never" if r["swl"] < 0 else f"{r['swl']:.2f}"
        lines.append(f"| {r['run']} | {r['impacts']} | {r['v_max']:.2f} | {r['a_cg']:.1f} | "
                     f"{r['a_seat']:.1f} | {r['sling']:.1f} | {r['fall']:.1f} | {swl} | "
                     f"{r['outcome']} |")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m postproc.launch_table",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("files", nargs="+", help="run files (davit run) of boat scenes")
    args = parser.parse_args(argv)
    try:
        print(table(args.files))
    except (OSError, ValueError, KeyError, TypeError) as exc:
        print(f"python -m postproc.launch_table: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
