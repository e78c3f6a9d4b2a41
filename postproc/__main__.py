"""Command line:

  python -m postproc FIGURE RUN.h5 [-o OUTDIR]    one run's figure: trajectory, tension,
                                                   acceleration, segment_tension (Fig. 13),
                                                   contact (boat runs); surface (Fig. 6),
                                                   spectrum (sea runs); rao (davit rao);
                                                   run = every figure the file supports
  python -m postproc FIGURE [FOLDER] [-o OUTDIR]  multi-run figures over the paper decks'
                                                   outputs in FOLDER (default out/):
                                                   trajectories (Figs. 15-18), collisions
                                                   (Fig. 19)
  python -m postproc all [FOLDER] [-o OUTDIR]     every figure whose inputs are in FOLDER
  python -m postproc sweep SUMMARY.h5 [-o OUTDIR] the Figs. 19-23 style charts of a
                                                   `davit sweep` summary
  python -m postproc operability SUMMARY.h5 [-o OUTDIR] [--risk 0.05] [--by sea,angle,...]
                                                   operability table of a sweep summary:
                                                   collision and rule-check failure shares
                                                   with Wilson intervals, Gumbel maxima,
                                                   verdict per cell (postproc.operability)
  python -m postproc regress [FOLDER] [--strict]  the paper's stated facts vs the outputs
                                                   in FOLDER, as a table
  python -m postproc readme-tables [FOLDER] [--run] [--write|--check]
                                                   the documentation's tables made from the
                                                   runs in FOLDER (postproc.readme_tables)
  python -m postproc doc-blocks [--write|--check] [--site [OUTDIR]]
                                                   the documentation's blocks made from the
                                                   code (deck keys, command line) and the
                                                   FORD site (postproc.doc_blocks)
  python -m postproc manoeuvre RUN.h5 [--length L]
                                                   advance, transfer, tactical diameter
                                                   or zig-zag overshoot angles of an MMG
                                                   ship run (postproc.manoeuvre)
  python -m postproc study|bem|bench-reference|boat-rao|fender-test|launch-table|sensitivity|compare-sweeps ...
                                                   the tool postproc.study, .bem, ...
                                                   (their own --help)
  (`davit-post ...` = `python -m postproc ...` in the project's environment, from any folder)
  python -m postproc scene RUN.h5 [-o OUTDIR] [--every N]
                                                   the launch as a ParaView time series:
                                                   .vtu frames, .pvd index, state .py
                                                   (postproc.scene)
  python -m postproc animate RUN.h5 [-o OUT.mp4|OUT.gif|OUTDIR] [--fps 20] [--every N]
                                  [--frame T -o OUT.png|.jpg|...]
                                                   the launch as a movie (end and side
                                                   views, tension and acceleration), or
                                                   one still at time T (postproc.animate)

Exit status: 0 success, 1 an unreadable or incomplete input (the message names the file and
the missing dataset); regress exits 1 on a FAIL only with --strict.
"""
import argparse
import importlib
import os
import sys

from . import dispatch, figures, layout, operability, paper, readme_tables, regress, sweep_figures

MOVIE_COMMANDS = ("scene", "animate")

FOLDER_COMMANDS = ("all", "regress")


def _parser():
    parser = argparse.ArgumentParser(prog="python -m postproc", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    choices = (sorted(figures.RUN_FIGURES) + ["run"] + sorted(paper.FOLDER_FIGURES)
               + list(FOLDER_COMMANDS) + ["sweep", "operability"] + list(MOVIE_COMMANDS))
    parser.add_argument("figure", choices=choices, metavar="FIGURE",
                        help="one of: " + ", ".join(choices))
    parser.add_argument("input", nargs="?", default=None,
                        help="davit HDF5 file (single-run figures) or folder (default out)")
    parser.add_argument("-o", "--outdir", default="out",
                        help="folder for PNG files (animate: also the .mp4, .gif or, with "
                             "--frame, .png file)")
    parser.add_argument("--every", type=int, default=None,
                        help="scene, animate: draw every N-th sample (default: scene 5, "
                             "animate about 400 frames)")
    parser.add_argument("--fps", type=float, default=20.0,
                        help="animate: frames per second (default %(default)s)")
    parser.add_argument("--frame", type=float, default=None, metavar="T",
                        help="animate: write only the still at time T [s] (PNG, or the "
                             "image format of the -o name: .jpg, .webp, .tif, ...)")
    parser.add_argument("--strict", action="store_true",
                        help="regress: exit 1 if any fact fails")
    parser.add_argument("--risk", type=float, default=operability.RISK,
                        help="operability: the acceptable failure probability r "
                             "(default %(default)s)")
    parser.add_argument("--by", default=",".join(operability.DIMENSIONS),
                        help="operability: the cell keys, comma-separated, of "
                             + ", ".join(operability.DIMENSIONS) + " (default all; the "
                             "others are pooled)")
    return parser


def _error(message):
    print(f"postproc: error: {message}", file=sys.stderr)
    return 1


def _single_run(args):
    if args.input is None:
        return _error(f"'{args.figure}' needs a davit HDF5 file")
    try:
        run = layout.load(args.input)
    except (OSError, ValueError) as exc:
        return _error(exc)
    stem = os.path.splitext(os.path.basename(args.input))[0]
    names = figures.figures_for(run) if args.figure == "run" else [args.figure]
    for name in names:
        try:
            path = figures.RUN_FIGURES[name](run, args.outdir, stem)
        except ValueError as exc:
            return _error(exc)
        if path:
            print(f"postproc: wrote {path}")
    return 0


def _folder(args):
    folder = args.input or "out"
    if not os.path.isdir(folder):
        return _error(f"{folder}: not a folder")
    if args.figure == "regress":
        try:
            verdicts = regress.report(folder)
        except (OSError, ValueError) as exc:
            return _error(exc)
        print(regress.format_table(verdicts))
        failed = any(v.result == regress.FAIL for v in verdicts)
        return 1 if args.strict and failed else 0
    if args.figure == "all":
        _, errors = dispatch.make_all(folder, args.outdir)
    else:
        errors = []
        try:
            written = [p for p in paper.FOLDER_FIGURES[args.figure](folder, args.outdir) if p]
        except (OSError, ValueError) as exc:
            errors, written = [str(exc)], []
        for path in written:
            print(f"postproc: wrote {path}")
        if not written and not errors:
            print(f"postproc: no figure: no paper-deck runs for '{args.figure}' in {folder}")
    for message in errors:
        _error(message)
    return 1 if errors else 0


def _sweep(args):
    """Every sweep figure of a `davit sweep` summary."""
    if args.input is None:
        return _error("'sweep' needs a davit sweep summary file")
    stem = os.path.splitext(os.path.basename(args.input))[0]
    try:
        summary = layout.load_sweep(args.input)
        for plot in sweep_figures.SWEEP_FIGURES.values():
            print(f"postproc: wrote {plot(summary, args.outdir, stem)}")
    except (OSError, ValueError) as exc:
        return _error(exc)
    return 0


def _operability(args):
    """The operability table of a `davit sweep` summary, then (the paper's own sweeps only)
    the paper's conclusion."""
    if args.input is None:
        return _error("'operability' needs a davit sweep summary file")
    by = [d.strip() for d in args.by.split(",") if d.strip()]
    unknown = [d for d in by if d not in operability.DIMENSIONS]
    if unknown or not 0 < args.risk < 1:
        return _error(f"operability: --by takes {', '.join(operability.DIMENSIONS)} and "
                      f"--risk a probability in (0, 1) (got --by {args.by} --risk {args.risk})")
    try:
        paths, _, text = operability.write(args.input, args.outdir, args.risk, by)
    except (OSError, ValueError) as exc:
        return _error(exc)
    print(text)
    for path in paths:
        print(f"postproc: wrote {path}")
    return 0


def _movie(args):
    """The ParaView scene or the animation of one run."""
    if args.input is None:
        return _error(f"'{args.figure}' needs a davit run file")
    from . import animate, scene
    try:
        if args.figure == "scene":
            pvd, state, frames = scene.write(args.input, args.outdir, args.every or 5)
            print(f"postproc: wrote {pvd} ({frames} frames) and {state}")
        elif args.frame is not None:
            print(f"postproc: wrote {animate.still(args.input, args.outdir, args.frame)}")
        else:
            path, frames = animate.movie(args.input, args.outdir, args.fps, args.every)
            print(f"postproc: wrote {path} ({frames} frames)")
    except (OSError, ValueError) as exc:
        return _error(exc)
    return 0


# The tools with a command line of their own: `davit-post TOOL ...` is
# `python -m postproc.MODULE ...` (one name for every post-processing command).
TOOLS = {"readme-tables": "readme_tables", "doc-blocks": "doc_blocks", "study": "study", "bem": "bem",
         "bench-reference": "bench_reference", "boat-rao": "boat_rao",
         "fender-test": "fender_test", "launch-table": "launch_table",
         "sensitivity": "sensitivity", "summation-compare": "summation_compare",
         "compare-sweeps": "summation_compare",
         "manoeuvre": "manoeuvre"}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] and argv[0] in TOOLS:
        module = importlib.import_module(f"{__package__}.{TOOLS[argv[0]]}")
        return module.main(argv[1:])
    args = _parser().parse_args(argv)
    if args.figure in MOVIE_COMMANDS:
        return _movie(args)
    if args.figure in figures.RUN_FIGURES or args.figure == "run":
        return _single_run(args)
    if args.figure == "sweep":
        return _sweep(args)
    if args.figure == "operability":
        return _operability(args)
    return _folder(args)


if __name__ == "__main__":
    sys.exit(main())
