"""Paper figures, `all` and `regress` on short runs of the paper decks written by the Fortran
code: every figure writes a PNG, the multi-run figures find their runs by name, a fender
contact set up by hand is found where kinematics puts it, a file with a missing dataset is
refused with its name, and `all` dispatches each file by its kind."""
import pathlib
import shutil
import struct
import sys
import types

import h5py
import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import dispatch, layout, paper, regress

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHORT = {"t_end = 0.0 ": "t_end = 0.4 ", "output_interval = 0.02": "output_interval = 0.01"}
# Colliding set-up: the ship's side moved out to 5 cm from the fenders (fender y = 13.3 -
# 1.4 = 11.9 m), the boat moving towards it at 0.5 m/s: contact after about 0.1 s.
GAP, SPEED = 0.05, 0.5
COLLIDE = {"position = 0.0, 13.3, -15.0": f"position = 0.0, 13.3, -15.0\n  velocity = 0.0, "
                                          f"{-SPEED}, 0.0"}
COLLIDE_TAIL = f"&contact\n  side_y = {11.9 - GAP}\n/\n"
CASES = {  # output name: (deck, replacements, extra text)
    "iiib_level5_090.h5": ("iiib_level5_090.nml", {**SHORT, **COLLIDE}, COLLIDE_TAIL),
    "iiib_level5_090_nowind.h5": ("iiib_level5_090_nowind.nml", SHORT, ""),
    "fig13_tension.h5": ("fig13_tension.nml", {}, ""),          # the whole 10 s deck
}


def png_size(path):
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    return struct.unpack(">II", data[16:24])


@pytest.fixture(scope="module")
def paper_folder(davit, tmp_path_factory):
    """A folder of short paper-deck runs named as `bash make.sh paper` names them."""
    folder = tmp_path_factory.mktemp("paper")
    for name, (deck, replace, extra) in CASES.items():
        text = (ROOT / "input" / deck).read_text()
        for old, new in replace.items():
            assert old in text, (deck, old)
            text = text.replace(old, new)
        path = folder / deck
        path.write_text(text + extra)
        result = davit("run", path, "-o", folder / name)
        assert result.returncode == 0, result.stderr
        path.unlink()
    return folder


@pytest.fixture(scope="module")
def all_output(paper_folder, tmp_path_factory):
    """`python -m postproc all` over the folder: (exit status, output folder)."""
    out = tmp_path_factory.mktemp("all_png")
    return cli.main(["all", str(paper_folder), "-o", str(out)]), out


def test_all_draws_every_figure(all_output):
    status, out = all_output
    assert status == 0
    names = {p.name for p in out.glob("*.png")}
    per_run = {f"{stem}_{fig}.png" for stem in ("iiib_level5_090", "iiib_level5_090_nowind",
                                                 "fig13_tension")
               for fig in ("trajectory", "acceleration", "sling_tension", "segment_tension",
                           "contact")}
    multi = {"fig18_level5_wind_trajectories.png", "fig17_level5_nowind_trajectories.png",
             "fig19_collisions_regular_wind.png"}
    assert names == per_run | multi
    for name in names:
        width, height = png_size(out / name)
        assert width > 400 and height > 300 and (out / name).stat().st_size > 10000


def test_folder_figures_by_name(paper_folder, tmp_path):
    """Runs found by name (fig13_tension.h5 is not one); Fig. 19 only where a run collided:
    the no-wind group has none, so no figure."""
    runs = paper.collect_runs(str(paper_folder))
    assert [(r.level, r.angle, r.irregular, r.wind) for r in runs] == [(5, 90, False, False),
                                                                       (5, 90, False, True)]
    assert cli.main(["collisions", str(paper_folder), "-o", str(tmp_path)]) == 0
    assert [p.name for p in tmp_path.glob("*.png")] == ["fig19_collisions_regular_wind.png"]


def test_run_cases_find_the_contact_set_up_by_hand(paper_folder):
    """First contact at gap/speed (the slings barely slow the boat in 0.1 s); the other runs
    keep their initial 1.4 m clearance (13.3 - 1.4 m fenders to the side at the paper's
    y1 = 10.5 m, F12)."""
    cases = {item.path.split("/")[-1]: regress.run_case(item)
             for item in paper.collect_runs(str(paper_folder))}
    hit = cases["iiib_level5_090.h5"]
    assert hit.collided.tolist() == [1] and hit.min_clearance[0] <= 0.0
    first = layout.load(str(paper_folder / "iiib_level5_090.h5")).event(layout.FIRST_CONTACT_TIME)
    assert first == pytest.approx(GAP / SPEED, abs=0.005)
    calm = cases["iiib_level5_090_nowind.h5"]
    assert calm.collided.tolist() == [0]
    assert calm.clearance_b[0] == pytest.approx(1.4 / 2.8, abs=1e-3)
    assert calm.min_clearance[0] == pytest.approx(1.4, abs=0.01)


def test_regress_on_runs(paper_folder, capsys):
    """F2 on the Fig. 13 deck (physics: the falls carry W/4 plus the rigging's share and
    settle in 2.5 +- 1.5 s); the other facts' runs are too short or absent: no input."""
    assert cli.main(["regress", str(paper_folder)]) == 0
    out = capsys.readouterr().out
    rows = {v.fact: v for v in regress.report(str(paper_folder))}
    for fact in ("F2 tension ~ W/4", "F2 with rigging", "F2 settling", "F2 sections"):
        assert rows[fact].result == regress.PASS, rows[fact]
    assert rows["F9 wind"].result == regress.NO_INPUT
    assert rows["F7 collisions (sweeps)"].result == regress.NO_INPUT
    assert "| F2 settling |" in out


def test_missing_dataset_is_refused_with_its_name(paper_folder, tmp_path, capsys):
    broken = tmp_path / "iiib_level5_090_nowind.h5"
    shutil.copy(paper_folder / "iiib_level5_090_nowind.h5", broken)
    with h5py.File(broken, "a") as f:
        del f[layout.BOAT_ACCELERATION]
    assert cli.main(["acceleration", str(broken), "-o", str(tmp_path)]) == 1
    err = capsys.readouterr().err
    assert str(broken) in err and layout.BOAT_ACCELERATION in err
    bogus = tmp_path / "bogus.h5"
    bogus.write_bytes(b"not hdf5")
    assert cli.main(["all", str(tmp_path), "-o", str(tmp_path / "png")]) == 1
    err = capsys.readouterr().err
    assert str(broken) in err and layout.BOAT_ACCELERATION in err
    assert f"{bogus}: cannot read as HDF5" in err
    assert list((tmp_path / "png").glob("*_sling_tension.png"))  # the rest is still drawn


def _h5(path, groups):
    with h5py.File(path, "w") as f:
        for name in groups:
            f.create_group(name)
        f.attrs["davit_version"] = "test"
    return str(path)


def test_file_kinds(paper_folder, sea_run, tmp_path):
    assert layout.file_kind(paper_folder / "iiib_level5_090_nowind.h5") == "run"
    assert layout.file_kind(sea_run[1]) == "sea"
    assert layout.file_kind(_h5(tmp_path / "r.h5", [layout.RAO_GROUP])) == "rao"
    assert layout.file_kind(_h5(tmp_path / "s.h5", [layout.SWEEP_GROUP])) == "sweep"
    assert layout.file_kind(_h5(tmp_path / "w.h5", [layout.STUDY_GROUP])) == "study"
    assert layout.file_kind(_h5(tmp_path / "x.h5", ["other"])) is None


def test_all_dispatches_sweep_and_study_files_to_their_modules(tmp_path, monkeypatch):
    calls = []
    study = types.ModuleType("postproc.study_figures")
    study.STUDY_FIGURES = {"chart": lambda path, outdir: calls.append(("study", path)) or None}
    sweep = types.ModuleType("postproc.sweep_figures")
    sweep.SWEEP_FIGURES = {"fig20": lambda summary, outdir, stem:
                           calls.append(("sweep", summary, stem)) or None}
    monkeypatch.setitem(sys.modules, "postproc.study_figures", study)
    monkeypatch.setitem(sys.modules, "postproc.sweep_figures", sweep)
    monkeypatch.setattr(layout, "load_sweep", lambda path: ("summary", path), raising=False)
    study_path = _h5(tmp_path / "wp.h5", [layout.STUDY_GROUP])
    sweep_path = _h5(tmp_path / "sw.h5", [layout.SWEEP_GROUP])
    written, errors = dispatch.make_all(str(tmp_path), str(tmp_path / "png"), log=lambda m: None)
    assert errors == [] and written == []
    assert calls == [("sweep", ("summary", sweep_path), "sw"), ("study", study_path)]


def test_all_skips_kinds_without_their_module(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "postproc.study_figures", None)   # as if absent
    _h5(tmp_path / "wp.h5", [layout.STUDY_GROUP])
    lines = []
    written, errors = dispatch.make_all(str(tmp_path), str(tmp_path), log=lines.append)
    assert errors == [] and written == []
    assert any("skipped" in line and "wp.h5" in line for line in lines)


def test_deck_values_from_the_recorded_deck(paper_folder):
    run = layout.load(str(paper_folder / "iiib_level5_090.h5"))
    assert run.deck("sea", "level") == 5.0
    assert run.deck("sea", "wave_type") == "stokes2"
    assert run.deck("boat", "velocity") == (0.0, -SPEED, 0.0)
    assert run.deck("contact", "side_y") == pytest.approx(11.9 - GAP)
    assert run.deck("ship", "frozen", "absent") == "absent"
    assert np.isclose(run.deck("simulation", "t_end"), 0.4)
