"""Every run deck in input/ is accepted and its scene runs a few steps to a complete file
(the sweep decks, &sweep, are checked in test_sweep.py)."""
import pathlib
import re

import pytest

from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUN_DECKS = sorted(p for p in (ROOT / "input").glob("*.nml")
                   if not any(group in p.read_text() for group in ("&rao", "&study", "&sweep")))


@pytest.mark.parametrize("path", RUN_DECKS, ids=lambda p: p.stem)
def test_deck_runs_a_few_steps(davit, tmp_path, path):
    text = path.read_text()
    dt = float(re.search(r"^\s*dt\s*=\s*([0-9.eE+-]+)", text, re.M).group(1)) \
        if re.search(r"^\s*dt\s*=", text, re.M) else 1e-3
    t_end = 20 * dt
    text = re.sub(r"^(\s*)t_end\s*=\s*[0-9.eE+-]+", rf"\g<1>t_end = {t_end!r}", text,
                  flags=re.M)
    text = re.sub(r"^(\s*)output_interval\s*=\s*[0-9.eE+-]+", rf"\g<1>output_interval = {dt!r}",
                  text, flags=re.M)
    deck = tmp_path / path.name
    deck.write_text(text)
    out = tmp_path / (path.stem + ".h5")
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    assert layout.load(out).complete


STUDY_DECKS = sorted(p for p in (ROOT / "input").glob("*.nml") if "&study" in p.read_text())


@pytest.mark.parametrize("path", STUDY_DECKS, ids=lambda p: p.stem)
def test_study_deck_variants_are_valid_decks(davit, tmp_path, path):
    """Every run of a study deck (python -m postproc.study) is a deck davit accepts: each
    variant runs 20 steps to a complete file."""
    from postproc import deck_edit, study
    spec = study.parse_study(path)
    base = (ROOT / spec["base"]).read_text()
    for i, run in enumerate(spec["runs"] + [spec.get("reference", spec["runs"][0])]):
        words = run.split()
        # stability runs have their step bisected by the study: probe them at 1e-5 s
        dt = next((float(w.split("=")[1]) for w in words if w.startswith("dt=")), 1e-5)
        text = deck_edit.override(deck_edit.variant(base, run, 20 * dt), "simulation", "dt", dt)
        text = deck_edit.override(text, "simulation", "output_interval", dt)
        deck = tmp_path / f"v{i}.nml"
        deck.write_text(text)
        result = davit("run", deck, "-o", tmp_path / f"v{i}.h5")
        assert result.returncode == 0, (run, result.stderr)
