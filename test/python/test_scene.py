"""The ParaView scene and the launch animation (postproc.scene, postproc.animate), read back
with meshio and imageio from a 2 s launch of the default deck."""
import math
import pathlib
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import launch_geometry as geo
from postproc import layout, scene

meshio = pytest.importorskip("meshio")
ROOT = pathlib.Path(__file__).resolve().parents[2]
EVERY = 3
# points per frame of each part: box + side plane; 15 sections of 4; reeving A's 8 cable
# nodes + block and hook of each sling; the same as vertices; 2 fenders x 2 ends; the
# recorded sea's patch (a launch in waves writes its components)
POINTS = {"ship": 12, "boat": 4 * geo.BOAT_STATIONS, "falls": 12, "nodes": 12,
          "fenders": 4, "sea": scene.SEA_POINTS ** 2}


@pytest.fixture(scope="module")
def launch(davit, tmp_path_factory):
    """A 2 s launch of input/iiib_level5_090.nml (the deck's text with t_end = 2)."""
    folder = tmp_path_factory.mktemp("launch")
    text = (ROOT / "input" / "iiib_level5_090.nml").read_text()
    deck = folder / "launch.nml"
    deck.write_text(text.replace("t_end = 0.0", "t_end = 2.0", 1))
    out = folder / "launch.h5"
    result = davit("run", deck, "-o", out)
    assert result.returncode == 0, result.stderr
    return out


@pytest.fixture(scope="module")
def written(launch, tmp_path_factory):
    folder = tmp_path_factory.mktemp("scene")
    pvd, state, frames = scene.write(str(launch), str(folder), EVERY)
    return layout.load(str(launch)), pathlib.Path(pvd), pathlib.Path(state), frames


def _pvd(path):
    """[(timestep, part name, file path)] of a .pvd."""
    root = ElementTree.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("name"), path.parent / d.get("file"))
            for d in root.iter("DataSet")]


def test_blocks_are_recorded_above_their_hooks(written):
    run = written[0]
    blocks = run.get(layout.RIGGING_BLOCKS)
    assert blocks.shape == (len(run.time), 2, 3)
    hooks = geo.hooks(run, np.array([0]))[0]
    # at rest on its 1 m sling, just stretched: straight above the hook (z down)
    assert np.allclose(blocks[0, :, :2], hooks[:, :2], atol=1e-6)
    assert np.all((hooks[:, 2] - blocks[0, :, 2] > 1.0) & (hooks[:, 2] - blocks[0, :, 2] < 1.01))


def test_deck_defaults_match_the_run(written):
    """The Fortran defaults repeated in launch_geometry: the fenders' clearance to the side
    plane is the recorded one."""
    run = written[0]
    fender_y = geo.fenders(run, np.array([0]))[0, :, :, 1]
    side_y = geo.side_plane(run)[0, 1]
    assert math.isclose(float(fender_y.min() - side_y),
                        float(run.get(layout.CONTACT_CLEARANCE)[0]), abs_tol=1e-9)


def test_pvd_steps_are_the_sampled_times(written):
    run, pvd, _, frames = written
    assert frames == math.ceil(len(run.time) / EVERY)
    entries = _pvd(pvd)
    assert len(entries) == frames * len(scene.PARTS)
    for name in scene.PARTS:
        times = [t for t, part, _ in entries if part == name]
        assert np.array_equal(times, run.time[::EVERY])
        assert [t for t, _, _ in _pvd(pvd.parent / f"{pvd.stem}_scene" / f"{name}.pvd")] == times


def test_frames_read_back_with_their_points(written):
    _, pvd, _, _ = written
    for _, name, file in _pvd(pvd)[::7]:
        assert len(meshio.read(file).points) == POINTS[name], name


def test_tensions_are_the_recorded_ones(written):
    run, pvd, _, _ = written
    files = [file for _, name, file in _pvd(pvd) if name == "falls"]
    cells = np.array([meshio.read(f).cell_data["tension"][0] for f in files])
    seg = run.get(layout.RIGGING_SEGMENT_TENSION)[::EVERY]
    sling = run.get(layout.SLING_TENSION)[::EVERY]
    assert np.array_equal(cells[:, :seg.shape[1]], seg)
    assert np.array_equal(cells[:, seg.shape[1]:], sling)
    assert cells.min() == min(seg.min(), sling.min())
    assert cells.max() == max(seg.max(), sling.max())


def test_z_is_up_and_the_blocks_are_the_recorded_ones(written):
    run, pvd, _, _ = written
    falls = meshio.read([f for _, n, f in _pvd(pvd) if n == "falls"][-1])
    sea = meshio.read([f for _, n, f in _pvd(pvd) if n == "sea"][-1])
    kind = falls.point_data["kind"]
    blocks = layout.to_plot_frame(run.get(layout.RIGGING_BLOCKS)[::EVERY][-1])
    assert np.allclose(falls.points[kind == geo.BLOCK][:2], blocks, atol=1e-5)
    assert np.all(falls.points[:, 2] > 10.0)
    # the sea patch is the recorded sea, rebuilt at the frame's time (z up = eta)
    t = run.time[::EVERY][-1]
    eta = layout.sea_elevation(run, t, sea.points[:, 0], -sea.points[:, 1])
    assert np.allclose(sea.points[:, 2], eta, atol=1e-5) and np.ptp(eta) > 1e-3


def test_state_file_opens_the_parts(written):
    _, pvd, state, _ = written
    text = state.read_text()
    compile(text, str(state), "exec")
    assert "paraview.simple" in text and '"tension"' in text
    for name in scene.PARTS:
        assert (pvd.parent / f"{pvd.stem}_scene" / f"{name}.pvd").exists()


def test_scene_of_a_run_without_the_davit(short_run, tmp_path):
    """The slings hang from fixed anchors: two lines with the sling tensions."""
    _, h5 = short_run
    assert cli.main(["scene", str(h5), "-o", str(tmp_path), "--every", "500"]) == 0
    run = layout.load(str(h5))
    files = sorted((tmp_path / "short_scene").glob("falls_*.vtu"))
    assert len(files) == math.ceil(len(run.time) / 500)
    last = meshio.read(files[-1])
    assert len(last.points) == 4
    assert np.array_equal(last.cell_data["tension"][0],
                          run.get(layout.SLING_TENSION)[::500][-1])


def test_animation_gif_and_mp4(launch, tmp_path):
    imageio = pytest.importorskip("imageio.v3")
    run = layout.load(str(launch))
    every = math.ceil(len(run.time) / 4)
    frames = math.ceil(len(run.time) / every)
    gif = tmp_path / "launch.gif"
    assert cli.main(["animate", str(launch), "-o", str(gif), "--every", str(every),
                     "--fps", "10"]) == 0
    assert imageio.imread(gif, index=None).shape[0] == frames
    pytest.importorskip("imageio_ffmpeg")
    mp4 = tmp_path / "launch.mp4"
    assert cli.main(["animate", str(launch), "-o", str(mp4), "--every", str(every)]) == 0
    import imageio.v2
    with imageio.v2.get_reader(mp4) as reader:
        assert reader.count_frames() == frames


def test_still_frame(launch, tmp_path):
    png = tmp_path / "still.png"
    assert cli.main(["animate", str(launch), "--frame", "1.0", "-o", str(png)]) == 0
    from PIL import Image
    with Image.open(png) as image:
        assert image.size == (1024, 720)
