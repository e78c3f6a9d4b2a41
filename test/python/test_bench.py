"""`davit bench --quick`: exits 0, prints its tables and writes /bench, whose numbers agree
with each other (rates = counts / wall time, real-time factor = simulated / wall time,
speed-up = wall time on 1 thread / on 2 threads, the paper-literal step from the RK4
limit). No timing thresholds: the speed goals live in the README."""
import math
import pathlib
import re

import h5py
import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUN_FIELDS = ("name", "deck", "cases", "threads", "dt", "simulated_time", "wall_time",
              "steps", "rhs_evaluations", "rhs_per_second", "steps_per_second",
              "real_time_factor", "setup_time", "worst_step_wall_time",
              "worst_interval_wall_time", "accuracy_known", "cg_error_before_contact",
              "cg_error_after_contact", "peak_sling_tension_error",
              "peak_segment_tension_error")
DATASETS = ({f"bench/runs/{field}" for field in RUN_FIELDS}
            | {"bench/sweep/speed_up", "bench/paper_literal/rate_max",
               "bench/paper_literal/rk4_limit", "bench/paper_literal/safety_factor",
               "bench/sea/name", "bench/sea/value", "bench/sea/unit",
               "bench/study/cells", "bench/study/decided"})
ROWS = [("regular", "iiib_level5_090.nml", 1), ("regular_rosw", "iiib_level5_090.nml", 1),
        ("regular_fast", "iiib_level5_090_fast.nml", 1),
        ("irregular", "iiib_level5_090_irregular.nml", 1),
        ("irregular_rosw", "iiib_level5_090_irregular.nml", 1),
        ("irregular_fast", "iiib_level5_090_irregular_fast.nml", 1),
        ("irregular_single", "iiib_level5_090_irregular_single.nml", 1),
        ("irregular_single_rosw", "iiib_level5_090_irregular_single.nml", 1),
        ("irregular_single_fast", "iiib_level5_090_irregular_single_fast.nml", 1),
        ("regular_multirate", "iiib_level5_090.nml", 1),
        ("irregular_single_multirate", "iiib_level5_090_irregular_single.nml", 1),
        ("regular_mri2", "iiib_level5_090.nml", 1),
        ("irregular_mri2", "iiib_level5_090_irregular.nml", 1),
        ("irregular_single_mri2", "iiib_level5_090_irregular_single.nml", 1),
        ("regular_mri2b", "iiib_level5_090.nml", 1),
        ("irregular_mri2b", "iiib_level5_090_irregular.nml", 1),
        ("irregular_single_mri2b", "iiib_level5_090_irregular_single.nml", 1),
        ("paper_literal", "iiib_level5_090_literal.nml", 1),
        ("paper_literal_rosw", "iiib_level5_090_literal.nml", 1),
        ("paper_literal_rosw_loose", "iiib_level5_090_literal.nml", 1),
        ("sweep", "bench_sweep.nml", 1), ("sweep", "bench_sweep.nml", 2),
        ("operability", "bench_operability.nml", 2)]
SCENES = [name for name, _, _ in ROWS if name not in ("sweep", "operability")]
RK4 = [SCENES.index(n) for n in ("regular", "regular_fast", "irregular", "irregular_fast",
                                 "irregular_single", "paper_literal")]
S1, S2 = len(SCENES), len(SCENES) + 1
EXACT = dict(rtol=1e-12, atol=0)


def _text(values):
    return [v.decode().strip() if isinstance(v, bytes) else str(v).strip() for v in values]


@pytest.fixture(scope="module")
def bench(davit, tmp_path_factory):
    """(stdout, {dataset: value}, root attributes) of one quick bench."""
    out = tmp_path_factory.mktemp("bench") / "bench.h5"
    result = davit("bench", "--quick", "-o", out, "--decks", ROOT / "input")
    assert result.returncode == 0, result.stderr
    data, meta = {}, {}
    with h5py.File(out, "r") as f:
        f.visititems(lambda name, obj: data.__setitem__(name, obj[()])
                     if isinstance(obj, h5py.Dataset) else None)
        f.visititems(lambda name, obj: meta.__setitem__(name, dict(obj.attrs))
                     if isinstance(obj, h5py.Dataset) else None)
        attrs = dict(f.attrs)
    return result.stdout, data, meta, attrs


def test_bench_writes_every_dataset_with_units(bench):
    _, data, meta, attrs = bench
    assert DATASETS <= set(data)
    for name in DATASETS:
        assert {"units", "description"} <= set(meta[name]), name
    assert int(attrs["quick"]) == 1
    for key in ("davit_version", "cpu", "compiler", "compiler_options"):
        assert attrs[key], key
    assert "-fopenmp" in attrs["compiler_options"].decode()


def test_bench_rows_are_the_fixed_scenes_and_the_sweep(bench):
    _, data, _, _ = bench
    rows = list(zip(_text(data["bench/runs/name"]), _text(data["bench/runs/deck"]),
                    data["bench/runs/threads"].tolist()))
    assert [(name, pathlib.Path(deck).name, threads) for name, deck, threads in rows] == ROWS
    cases = data["bench/runs/cases"]
    assert cases[:S1].tolist() == [1] * S1 and cases[S1] == cases[S2] == 8


def test_rates_are_counts_over_wall_time(bench):
    _, data, _, _ = bench
    runs = {field: data[f"bench/runs/{field}"] for field in RUN_FIELDS}
    wall = runs["wall_time"]
    assert np.all(wall > 0) and np.all(runs["simulated_time"] > 0)
    np.testing.assert_allclose(runs["rhs_per_second"], runs["rhs_evaluations"] / wall, **EXACT)
    np.testing.assert_allclose(runs["steps_per_second"], runs["steps"] / wall, **EXACT)
    np.testing.assert_allclose(runs["real_time_factor"], runs["simulated_time"] / wall,
                               **EXACT)
    # RK4 scenes: four evaluations per step, counted by the run driver (a located event
    # adds two or three for its interpolant and counts its redone step as a step)
    rk4_rhs, rk4_steps = runs["rhs_evaluations"][RK4], runs["steps"][RK4]
    assert np.all(rk4_rhs >= 4 * rk4_steps) and np.all(rk4_rhs <= 4.1 * rk4_steps)
    # quick: the first 20 s of the launch scenes, 2 s of the paper-literal ones
    np.testing.assert_allclose(runs["simulated_time"][:S1], [20.0] * 17 + [2.0] * 3, **EXACT)
    assert runs["steps"][0] >= 20000 and runs["steps"][3] >= 20000
    # quick scenes are not compared with the references (the full ones are)
    np.testing.assert_array_equal(runs["accuracy_known"], 0)


def test_worst_step_and_frame_bound_the_totals(bench):
    """A step's wall time is within the scene's; an output interval's is the sum of its
    steps' (one clock), so the worst interval is at least the worst step (every step of a
    quick scene ends inside a whole interval); the sweep rows carry none."""
    _, data, _, _ = bench
    step = data["bench/runs/worst_step_wall_time"]
    frame = data["bench/runs/worst_interval_wall_time"]
    setup = data["bench/runs/setup_time"]
    wall = data["bench/runs/wall_time"]
    assert np.all(step[:S1] > 0) and np.all(step[:S1] <= wall[:S1])
    assert np.all(frame[:S1] >= step[:S1]) and np.all(frame[:S1] <= wall[:S1])
    # the set-up (deck, BEM databases, sea) is timed apart from the time loop
    assert np.all(setup[:S1] > 0) and np.all(setup[:S1] < 5.0)
    np.testing.assert_array_equal(step[S1:], 0)


def test_operability_study_row(bench):
    """The study row: two cells, rounds of 8 launches up to 32 each (cases = launches run),
    every launch 5 s long in the quick bench; the decided count is printed as stored."""
    stdout, data, _, _ = bench
    row = len(ROWS) - 1
    assert data["bench/study/cells"][0] == 2
    assert 0 <= data["bench/study/decided"][0] <= 2
    launches = data["bench/runs/cases"][row]
    assert launches % 8 == 0 and 16 <= launches <= 64
    np.testing.assert_allclose(data["bench/runs/simulated_time"][row], 5.0 * launches,
                               rtol=1e-9)
    assert (f"operability study: {data['bench/study/decided'][0]} of 2 cells decided"
            in stdout)


def test_sweep_speed_up_is_the_wall_time_ratio(bench):
    _, data, _, _ = bench
    wall = data["bench/runs/wall_time"]
    np.testing.assert_allclose(data["bench/sweep/speed_up"], [wall[S1] / wall[S2]], **EXACT)
    # a case does not depend on the thread that runs it: the same work on 1 and 2 threads
    for field in ("steps", "rhs_evaluations", "simulated_time"):
        assert data[f"bench/runs/{field}"][S1] == data[f"bench/runs/{field}"][S2], field


def test_paper_literal_step_is_the_rk4_limit_with_margin(bench):
    _, data, _, _ = bench
    rate = data["bench/paper_literal/rate_max"][0]
    limit = data["bench/paper_literal/rk4_limit"][0]
    safety = data["bench/paper_literal/safety_factor"][0]
    dt = data["bench/runs/dt"][SCENES.index("paper_literal")]
    np.testing.assert_allclose(limit, 2.83 / rate, **EXACT)
    assert 0 < safety < 1
    # the largest whole fraction of the deck's 0.02 s output interval below safety x limit
    n = round(0.02 / dt)
    assert math.isclose(n * dt, 0.02, rel_tol=1e-12)
    assert dt <= safety * limit < 0.02 / (n - 1)
    np.testing.assert_array_equal(data["bench/runs/dt"][[0, 3, S1, S2]], 1e-3)


def test_printed_table_is_the_file(bench):
    stdout, data, _, _ = bench
    lines = [line for line in stdout.splitlines() if line.startswith("| ")]
    rows = [line for line in lines
            if line.split("|")[1].strip() in SCENES + ["sweep", "operability"]]
    assert len(rows) == len(ROWS)
    for i, row in enumerate(rows):
        cells = [c.strip() for c in row.strip("|").split("|")]
        assert int(cells[6]) == data["bench/runs/steps"][i]
        assert int(cells[7]) == data["bench/runs/rhs_evaluations"][i]
        assert math.isclose(float(cells[10]), data["bench/runs/real_time_factor"][i],
                            rel_tol=5e-3)
    speed_up = re.search(r"sweep speed-up, 1 -> 2 threads: ([0-9.]+) \(8 cases\)", stdout)
    assert speed_up and math.isclose(float(speed_up.group(1)), data["bench/sweep/speed_up"][0],
                                     rel_tol=5e-3)
    sea = [line for line in lines if line.startswith("| sea: ")]
    grid = [line for line in lines if line.startswith("| sea grid: ")]
    assert len(sea) == 3 and len(grid) == 5 and len(data["bench/sea/value"]) == 9


def test_bench_usage_and_missing_decks(davit, tmp_path):
    assert davit("bench", "--bogus").returncode == 2
    assert davit("bench", "-o").returncode == 2
    out = tmp_path / "bench.h5"
    result = davit("bench", "--quick", "-o", out, "--decks", tmp_path)
    assert result.returncode == 1
    assert "iiib_level5_090.nml" in result.stderr
    assert not out.exists() and not pathlib.Path(str(out) + ".tmp").exists()
