"""The post-processing a user meets first (issue "The user's path, part 2"): each test
failed before its fix. A one-period sweep's heat map has one panel per sea state; the
paper's conclusion is tested only on the paper's own sweeps; no title reaches past its
figure (Fig. 19 was clipped); a missing base deck names the sweep deck's line and the
folders searched; `davit bench` runs outside the checkout; `--frame T -o still.jpg` writes
a JPEG; titles keep the digits of small accelerations; only the paper's deck gets the
"Fig. 13" title; the start-up transient has the causes the README gives."""
import pathlib
import re

import h5py
import matplotlib.figure
from matplotlib.backends.backend_agg import FigureCanvasAgg
import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import figures, layout, operability, paper, sweep_figures
from test_operability import _known_cells, _write

ROOT = pathlib.Path(__file__).resolve().parents[2]
GRAVITY = 9.81


@pytest.fixture
def saved(monkeypatch):
    """Every figure postproc saves, as it is when written."""
    figs = []
    original = matplotlib.figure.Figure.savefig

    def record(fig, *args, **kwargs):
        figs.append(fig)
        return original(fig, *args, **kwargs)
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", record)
    return figs


def _outside(fig):
    """The titles of `fig` that reach past its left or right edge."""
    FigureCanvasAgg(fig)  # closed figures lose their canvas
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    titles = [fig._suptitle] + [ax.title for ax in fig.axes if ax.get_visible()]
    return [t.get_text() for t in titles if t is not None and t.get_text()
            and (t.get_window_extent(renderer).x0 < 0
                 or t.get_window_extent(renderer).x1 > fig.bbox.width)]


# --- operability ---------------------------------------------------------------------------

def test_one_period_heat_map_has_one_panel_per_sea_state(tmp_path, saved):
    """The made-up summary of test_operability has one wave period and two levels (4, 5):
    two panels, not one per cell (the pooled period's NaN keys were all different)."""
    path = _write(tmp_path / "known.h5", _known_cells())
    cells = operability.table(path)
    assert len(cells) == 5 and all(np.isnan(c.period) for c in cells)
    assert len(operability._panels(cells)) == 2
    operability.write(path, tmp_path / "out")
    heat = saved[0]
    assert len([ax for ax in heat.axes if ax.get_visible() and ax.get_title()]) == 2


def test_the_papers_conclusion_only_for_the_papers_sweeps(tmp_path):
    user = _write(tmp_path / "mine.h5", _known_cells())
    with h5py.File(user, "r+") as f:
        f.attrs[layout.SWEEP_NAMELIST] = "&sweep\n  base_deck = 'my_ship.nml'\n  levels = 4, 5\n/\n"
    _, found, text = operability.write(user, tmp_path / "out")
    assert not found and "paper's conclusion" not in text
    paper_deck = (ROOT / "input" / "sweep_operability.nml").read_text()
    ours = _write(tmp_path / "ours.h5", _known_cells())
    with h5py.File(ours, "r+") as f:   # its comments reworded: the same sweep
        f.attrs[layout.SWEEP_NAMELIST] = paper_deck.replace("! Operability", "!  Operability")
    _, found, text = operability.write(ours, tmp_path / "out")
    assert found and "## The paper's conclusion" in text


# --- Fig. 19 and titles ---------------------------------------------------------------------

# the III.B launch cut to 1 s, pushed towards the ship: its fenders hit the side at 0.3 s
PUSHED = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
    "t_end = 0.0 ", "t_end = 1.0 ").replace(
    "position = 0.0, 13.3, -15.0", "position = 0.0, 13.3, -15.0\n  velocity = 0.0, -0.6, 0.0")


def test_fig19_titles_fit_their_figures(davit, tmp_path, saved):
    """The paper's Fig. 19 (a colliding run named as its deck) and the sweep's Fig. 19 of
    a one-level sweep (one 6-inch panel under a long title)."""
    (tmp_path / "base.nml").write_text(PUSHED)
    sweep = tmp_path / "sweep.nml"
    sweep.write_text("&sweep base_deck = 'base.nml', levels = 4, clearances_b = 0.05 /\n")
    series = tmp_path / "series"
    result = davit("sweep", sweep, "-o", tmp_path / "s.h5", "--quiet", "--series", series)
    assert result.returncode == 0, result.stderr
    summary = layout.load_sweep(tmp_path / "s.h5")
    assert summary.collided[0] == 1
    sweep_figures.fig19(summary, tmp_path, "s")
    # the colliding launch's run file under a paper deck's name: the paper's Fig. 19
    runs = tmp_path / "runs"
    runs.mkdir()
    (runs / "iiib_level4_090.h5").write_bytes((series / "case_000001.h5").read_bytes())
    assert [p for p in paper.collisions(str(runs), str(tmp_path)) if p]
    assert len(saved) == 2
    for fig in saved:
        assert not _outside(fig)


# --- the sweep's base deck ------------------------------------------------------------------

def test_missing_base_deck_names_the_sweep_deck_line_and_folders(davit, tmp_path):
    sweep = tmp_path / "my_sweep.nml"
    sweep.write_text("! my sweep\n&sweep\n  levels = 4\n  base_deck = 'missing.nml'\n/\n")
    result = davit("sweep", sweep, "-o", tmp_path / "s.h5")
    assert result.returncode == 1
    message = result.stderr
    assert f"{sweep}:4:" in message and "'missing.nml'" in message
    assert str(tmp_path) in message and str(ROOT / "input") in message  # DAVIT_PATH


def test_base_deck_found_on_davit_path(davit, tmp_path):
    """A sweep deck copied anywhere finds a shipped base deck through DAVIT_PATH, as
    `davit run` finds its data files."""
    sweep = tmp_path / "sweep.nml"
    sweep.write_text("&sweep base_deck = 'iiib_level5_090.nml' /\n")
    result = davit("sweep", sweep, "--dry-run")
    assert result.returncode == 0, result.stderr


# --- davit bench outside the checkout -------------------------------------------------------

def test_bench_outside_the_checkout_finds_its_decks(davit_bin, tmp_path):
    """From a folder without input/, the decks come from DAVIT_PATH (conftest points it at
    the project's input/, as the installed davit points it at share/davit/input)."""
    import subprocess
    result = subprocess.run([davit_bin, "bench", "--quick", "-o", "b.h5"], cwd=tmp_path,
                            capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    with h5py.File(tmp_path / "b.h5", "r") as f:
        assert pathlib.Path(layout._text(f.attrs["decks"])) == ROOT / "input"


# --- stills and single-run titles -----------------------------------------------------------

@pytest.mark.parametrize("name, magic", [("still.jpg", b"\xff\xd8\xff"),
                                         ("still.png", b"\x89PNG")])
def test_still_writes_the_file_named(launch, tmp_path, name, magic):
    out = tmp_path / name
    assert cli.main(["animate", str(launch), "--frame", "1.0", "-o", str(out)]) == 0
    assert out.is_file() and out.read_bytes()[:len(magic)] == magic


def test_acceleration_title_keeps_the_digits(launch, tmp_path, saved):
    """A resolved CG peak of 1.44 m/s^2 shows as 1.44, not "1"."""
    run_file = tmp_path / "run.h5"
    run_file.write_bytes(launch.read_bytes())
    with h5py.File(run_file, "r+") as f:
        f[layout.PEAK_CG_ACCELERATION][...] = [1.44, 0.5]
    figures.acceleration(layout.load(run_file), tmp_path, "run")
    title = saved[0].axes[0].get_title()
    assert "resolved CG peak 1.44 m/s^2" in title.replace("\n", " ")


def _lowering(davit, folder, deck_name, source):
    text = (ROOT / "input" / source).read_text()
    text = re.sub(r"(?m)^(\s*t_end\s*=\s*)[0-9.]+", r"\g<1>0.2", text)
    deck = folder / deck_name
    deck.write_text(text)
    out = folder / (deck.stem + ".h5")
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return layout.load(out)


def test_fig13_title_only_for_the_papers_deck(davit, tmp_path, saved):
    figures.segment_tension(_lowering(davit, tmp_path, "my_lowering.nml", "lowering.nml"),
                            tmp_path, "mine")
    figures.segment_tension(_lowering(davit, tmp_path, "fig13_tension.nml",
                                      "fig13_tension.nml"), tmp_path, "paper")
    mine, ours = (fig.axes[0].get_title() for fig in saved)
    assert "Fig. 13" not in mine and mine.startswith("Cable segment tension")
    assert ours.startswith("Fig. 13: cable segment tension")


# --- the start-up transient -----------------------------------------------------------------

def _start(davit, tmp_path, name, calm=True, wind=None, ramp=None, winch=True):
    """The first 3 s of the III.B launch with the switches the README's explanation
    names: (sum of the sling tensions [N], vertical CG acceleration [m/s^2], time)."""
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text().replace(
        "t_end = 0.0 ", "t_end = 3.0 ")
    if calm:
        text = text.replace("wave_type = 'stokes2'", "wave_type = 'calm'")
    if not winch:
        text = text.replace("drum_speed = 0.7 ", "drum_speed = 0.0 ")
    if ramp is not None:
        text = text.replace("ramp_time = 1.0 ", f"ramp_time = {ramp} ")
    if wind is not None:
        text += f"&wind speed = {wind} /\n"
    deck = tmp_path / f"{name}.nml"
    deck.write_text(text)
    out = tmp_path / f"{name}.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    with h5py.File(out, "r") as f:
        return (f["slings/tension"][()].sum(axis=1), f["boat/acceleration"][()][:, 2],
                f["time"][()])


def test_startup_transient_comes_from_the_winch_ramp_and_the_wind(davit, tmp_path):
    weight = 8500.0 * GRAVITY   # the boat's mass (&boat mass default, paper III.B)
    # calm, no wind, winch stopped: the static start holds (slings carry W, no motion)
    tension, a_z, _ = _start(davit, tmp_path, "still", wind=0.0, winch=False)
    np.testing.assert_allclose(tension, weight, rtol=1e-3)
    assert np.max(np.abs(a_z)) < 1e-6
    # the winch's 1 s linear ramp: a step of 0.7/4/1 = 0.175 m/s^2 in the boat's
    # acceleration, which the lightly damped falls overshoot to about twice
    tension, a_z, t = _start(davit, tmp_path, "winch", wind=0.0)
    first = np.max(np.abs(a_z[t <= 1.0]))
    assert 1.6 * 0.175 < first < 2.1 * 0.175
    # a 5 s ramp makes the step five times smaller, and so the ringing
    _, a_slow, t = _start(davit, tmp_path, "slow", wind=0.0, ramp=5.0)
    assert np.max(np.abs(a_slow[t <= 1.0])) < 0.3 * first
    # the deck's 10 m/s wind acts in full from t = 0: the slings' load rings from W
    tension, a_z, t = _start(davit, tmp_path, "wind", winch=False)
    assert tension[0] == pytest.approx(weight, rel=1e-3)
    assert np.ptp(tension[t <= 1.0]) > 0.02 * weight and np.max(np.abs(a_z)) > 0.1
