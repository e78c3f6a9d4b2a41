"""Every run deck in input/ is accepted and its scene runs a few steps to a complete file
(the sweep decks, &sweep, are checked in test_sweep.py)."""
import pathlib
import re

import pytest

from postproc import layout

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUN_DECKS = sorted(p for p in (ROOT / "input").glob("*.nml")
                   if "&rao" not in p.read_text() and "&sweep" not in p.read_text())


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
