"""Sensitivity of the collision pattern (review F7) to what the paper does not give.

    python -m postproc.sensitivity SUMMARY.h5 [SUMMARY.h5 ...]

prints, for each `davit sweep` summary (the decks of input/sensitivity/), how many of the
launches of each sea state (wave height and period) and encounter angle collided, as one
Markdown table: a row per summary, a column per (H, T, angle). Exit status 1 on an
unreadable or incomplete summary.
"""
import os
import sys

import numpy as np

from . import layout


def pattern(path):
    """{(H, T, angle): (collided, finished)} of one summary."""
    c = layout.load_sweep_columns(path, layout.SENSITIVITY_FIELDS)
    ok = c["status"] == layout.SWEEP_OK
    out = {}
    for key in sorted({(h, t, a) for h, t, a in
                       zip(c["wave_height"][ok], c["wave_period"][ok], c["angle_deg"][ok])}):
        rows = ok & (c["wave_height"] == key[0]) & (c["wave_period"] == key[1]) \
            & (c["angle_deg"] == key[2])
        out[key] = (int(np.sum(c["collided"][rows] == 1)), int(np.sum(rows)))
    return out


def table(paths):
    """Markdown table of the patterns of the summaries `paths`."""
    patterns = {os.path.splitext(os.path.basename(p))[0]: pattern(p) for p in paths}
    columns = sorted({k for p in patterns.values() for k in p})
    head = "| sweep | " + " | ".join(f"H {h:g} m, T {t:.3g} s, {a:g} deg" for h, t, a in columns)
    lines = [head + " |", "|---" * (len(columns) + 1) + "|"]
    for name, p in patterns.items():
        cells = [f"{p[k][0]}/{p[k][1]}" if k in p else "-" for k in columns]
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    if not args:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        print(table(args))
    except (OSError, ValueError) as exc:
        print(f"postproc.sensitivity: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
