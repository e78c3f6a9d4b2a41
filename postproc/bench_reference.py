"""The converged references of `davit bench`'s scenes (its accuracy column, issue 14).

    python -m postproc.bench_reference [--decks input] [-o input/bench_reference.h5]
                                       [--davit PATH]

Runs each bench scene's deck with classical RK4 at a step well inside its converged range
(the default level of detail at 1e-4 s, 10x below the paper's 1e-3 s: its own error is
below 1e-9 m before contact, study_speed; the paper-literal scene at 0.02/1024 s, 4x below
its stability-limited bench step; the irregular seas' slow clock of the water at 0.01 s,
5x below the decks' 0.05 s, where it is converged: a 0.02 s window moves the peaks by
0.005 % in the double-summation sea), and keeps what the bench compares: the sample times,
the boat's CG positions, the first contact time and the launch log's resolved peak sling
and segment tensions. Group per scene: /regular, /irregular, /paper_literal. The scenes
and spans are those of src/bench/suite.f90 (the paper-literal one 20 s).
"""
import argparse
import os
import sys
import tempfile

import h5py
import numpy as np

from . import layout
from .deck_edit import run_davit, variant

SCENES = (("regular", "iiib_level5_090.nml", 0.0, "rk4 dt=1e-4"),
          ("irregular", "iiib_level5_090_irregular.nml", 0.0, "rk4 dt=1e-4 wave_update=0.01"),
          ("paper_literal", "iiib_level5_090_literal.nml", 20.0, "rk4 dt=1.953125e-5"),
          ("irregular_single", "iiib_level5_090_irregular_single.nml", 0.0,
           "rk4 dt=1e-4 wave_update=0.01"))


def _keep(old, g):
    """Copy a scene's reference group as written (values, attributes, named dimensions:
    h5py's copy would carry the dimension scales' references into the old file)."""
    for key, value in old.attrs.items():
        g.attrs[key] = value
    for dataset, dims in zip(layout.BENCH_REFERENCE_DATASETS, layout.BENCH_REFERENCE_DIMS):
        g[dataset] = old[dataset][...]
        layout.name_dimensions(g[dataset], dims)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m postproc.bench_reference",
                                     description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--decks", default="input")
    parser.add_argument("-o", "--output", default=None,
                        help="default: DECKS/bench_reference.h5")
    parser.add_argument("--davit", default=os.environ.get("DAVIT", "davit"))
    parser.add_argument("--only", action="append", choices=[s[0] for s in SCENES],
                        help="run this scene only (repeatable); the file's other groups "
                             "are kept")
    args = parser.parse_args(argv)
    out = args.output or os.path.join(args.decks, "bench_reference.h5")
    os.environ["DAVIT_PATH"] = os.pathsep.join(
        p for p in (os.path.abspath(args.decks), os.environ.get("DAVIT_PATH", "")) if p)
    with tempfile.TemporaryDirectory() as work, h5py.File(out + ".tmp", "w") as f:
        attr = layout.BENCH_REFERENCE_ATTRS
        f.attrs[attr["description"]] = ("Converged references of davit bench's scenes "
                                        "(python -m postproc.bench_reference)")
        if args.only and os.path.exists(out):
            with h5py.File(out, "r") as old:
                for name in old:
                    if name not in args.only:
                        _keep(old[name], f.create_group(name))
        for name, deck, t_end, spec in SCENES:
            if args.only and name not in args.only:
                continue
            text = variant(open(os.path.join(args.decks, deck)).read(), spec, t_end)
            path, ok, msg = run_davit(args.davit, text, work, name)
            if not ok:
                print(f"postproc.bench_reference: {name}: {msg}", file=sys.stderr)
                return 1
            with h5py.File(path, "r") as r:
                g = f.create_group(name)
                wall = float(r.attrs[layout.WALL_TIME])
                g.attrs[attr["deck"]] = deck
                g.attrs[attr["settings"]] = spec
                g.attrs[attr["wall_time"]] = wall
                contact = (float(np.ravel(r[layout.FIRST_CONTACT_TIME])[0])
                           if layout.FIRST_CONTACT_TIME in r else -1.0)
                values = (r[layout.TIME][:], r[layout.BOAT_POSITION][:], np.array([contact]),
                          r[layout.PEAK_SLING_TENSION][:], r[layout.PEAK_SEGMENT_TENSION][:])
                for dataset, value, dims in zip(layout.BENCH_REFERENCE_DATASETS, values,
                                                layout.BENCH_REFERENCE_DIMS):
                    g[dataset] = value
                    layout.name_dimensions(g[dataset], dims)
            print(f"postproc.bench_reference: {name}: {spec}, {wall:.1f} s", flush=True)
    os.replace(out + ".tmp", out)
    print(f"postproc.bench_reference: wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
