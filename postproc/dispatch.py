"""`python -m postproc all`: every figure whose inputs exist in an output folder.

Each .h5 file is dispatched by its kind (layout.file_kind: root attribute `scene`, or the
/rao, /cases, /study groups) through KIND_FIGURES, the one table that says which figures a
kind of file gets; then the multi-run figures (paper.FOLDER_FIGURES) run over the folder.
The sweep and study charts live in optional modules (postproc.sweep_figures with
SWEEP_FIGURES = {name: fn(summary, outdir, stem)}, postproc.study_figures with
STUDY_FIGURES = {name: fn(path, outdir)}); without them those files are listed as skipped.
"""
import importlib
import os

from . import figures, layout, paper


def optional_module(name):
    """The module postproc.<name>, or None if it does not exist (other errors propagate:
    a broken module must not pass silently as an absent one)."""
    try:
        return importlib.import_module(f"{__package__}.{name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"{__package__}.{name}":
            return None
        raise


def _stem(path):
    return os.path.splitext(os.path.basename(path))[0]


def run_file_figures(path, outdir):
    """Every single-run figure the file supports (boat runs, sea runs, RAO files)."""
    run = layout.load(path)
    return [figures.RUN_FIGURES[name](run, outdir, _stem(path))
            for name in figures.figures_for(run)]


def sweep_file_figures(path, outdir):
    """Figs. 19-23 from a sweep summary, if postproc.sweep_figures exists."""
    module = optional_module("sweep_figures")
    if module is None or not hasattr(layout, "load_sweep"):
        return None
    summary = layout.load_sweep(path)
    return [fn(summary, outdir, _stem(path)) for fn in module.SWEEP_FIGURES.values()]


def study_file_figures(path, outdir):
    """Work-precision and stability charts, if postproc.study_figures exists."""
    module = optional_module("study_figures")
    if module is None:
        return None
    return [fn(path, outdir) for fn in module.STUDY_FIGURES.values()]


KIND_FIGURES = {"run": run_file_figures, "sea": run_file_figures, "rao": run_file_figures,
                "sweep": sweep_file_figures, "study": study_file_figures}


def _flatten(result):
    if result is None:
        return []
    if isinstance(result, (list, tuple)):
        return [p for item in result for p in _flatten(item)]
    return [result]


def _logged(paths, log):
    for path in paths:
        log(f"postproc: wrote {path}")
    return paths


def make_all(folder, outdir, log=print):
    """Draw every figure whose inputs are in `folder` into `outdir`; returns (written
    paths, error messages). One bad file is reported and the rest still drawn."""
    written, errors = [], []
    names = sorted(n for n in os.listdir(folder) if n.endswith(".h5")) \
        if os.path.isdir(folder) else []
    if not names:
        errors.append(f"{folder}: no .h5 files")
    for name in names:
        path = os.path.join(folder, name)
        try:
            kind = layout.file_kind(path)
            handler = KIND_FIGURES.get(kind)
            if handler is None:
                log(f"postproc: skipped {path} (not a davit output file)")
                continue
            result = handler(path, outdir)
            if result is None:
                log(f"postproc: skipped {path} ({kind}: its figure module is not installed)")
            written += _logged(_flatten(result), log)
        except (OSError, ValueError, KeyError) as exc:
            errors.append(f"{path}: {exc}" if path not in str(exc) else str(exc))
    for name, function in paper.FOLDER_FIGURES.items():
        try:
            written += _logged(_flatten(function(folder, outdir)), log)
        except (OSError, ValueError, KeyError) as exc:
            errors.append(f"{name}: {exc}")
    return written, errors
