"""Command line: python -m postproc FIGURE RUN.h5 [-o OUTDIR]

FIGURE is one of: trajectory, tension, acceleration (boat runs), surface (the paper's
Fig. 6), spectrum (sea runs), rao (davit rao files), or run (every figure the file
supports); or sweep, with a `davit sweep` summary (Figs. 19-23 style).
"""
import argparse
import os
import sys

from . import figures, layout, sweep_figures


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m postproc", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("figure", choices=sorted(figures.RUN_FIGURES) + ["run", "sweep"])
    parser.add_argument("input", help="davit HDF5 output file")
    parser.add_argument("-o", "--outdir", default="out", help="folder for PNG files")
    args = parser.parse_args(argv)
    if args.figure == "sweep":
        return _sweep(args)
    try:
        run = layout.load(args.input)
    except (OSError, ValueError) as exc:
        print(f"postproc: error: {exc}", file=sys.stderr)
        return 1
    stem = os.path.splitext(os.path.basename(args.input))[0]
    names = figures.figures_for(run) if args.figure == "run" else [args.figure]
    for name in names:
        try:
            path = figures.RUN_FIGURES[name](run, args.outdir, stem)
        except ValueError as exc:
            print(f"postproc: error: {exc}", file=sys.stderr)
            return 1
        if path:
            print(f"postproc: wrote {path}")
    return 0


def _sweep(args):
    """Every sweep figure of a `davit sweep` summary."""
    stem = os.path.splitext(os.path.basename(args.input))[0]
    try:
        summary = layout.load_sweep(args.input)
        for plot in sweep_figures.SWEEP_FIGURES.values():
            print(f"postproc: wrote {plot(summary, args.outdir, stem)}")
    except (OSError, ValueError) as exc:
        print(f"postproc: error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
