"""The ParaView scene and the launch animation (postproc.scene, postproc.animate), read back
with meshio and imageio from a 2 s launch of the default deck, and the scene rendered by
ParaView itself (pvpython on the state file, under xvfb)."""
import math
import os
import pathlib
import shutil
import subprocess
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

from postproc import __main__ as cli
from postproc import launch_geometry as geo
from postproc import layout, scene

meshio = pytest.importorskip("meshio")
EVERY = 3
# points per frame of each part: the BEM ship's hull lines (stations of closed sections:
# both sides from the keel through the waterline to the deck); 8 corners of each of the
# davit's 10 members (per davit a post, an arm and a brace, the beam between the posts'
# tops, a tie from each top to it, the winch's pedestal); the boat's sections; reeving A's
# 8 cable nodes + block and hook of each sling; the same as vertices; 2 fenders x 2 ends;
# the recorded sea's patch (a launch in waves writes its components)
POINTS = {"ship": geo.SHIP_STATIONS * 2 * (sum(geo.SHIP_LEVELS) + 1), "davit": 8 * 10,
          "boat": geo.BOAT_RING * geo.BOAT_SHAPE_STATIONS, "falls": 12, "nodes": 12,
          "fenders": 4, "sea": scene.SEA_POINTS ** 2}
# Table 1's ship (the &ship defaults the deck keeps) and the default deck's davit heads
SHIP_BEAM, SHIP_DRAUGHT, SHIP_DEPTH, SHIP_LWL = 20.8, 4.4, 11.4, 130.55
HEADS_Z = 20.55        # m above the still water (&rigging head_fore/head_aft z = -20.55)
PNG_SIZE = (800, 450)


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
    assert "paraview.simple" in text and '"tension_kN"' in text
    assert "ColorBy(shown, None)" not in text   # ParaView 5.11: invalid association 'NONE'
    for name in scene.PARTS:
        assert (pvd.parent / f"{pvd.stem}_scene" / f"{name}.pvd").exists()
        assert f'"{name}"' in text
    for unit in ("[kN]", "[m]"):
        assert unit in text


def _first(pvd, part):
    return meshio.read(next(f for _, n, f in _pvd(pvd) if n == part))


def test_bem_ship_is_drawn_from_its_lines(written):
    """The BEM ship of the default deck: Table 1's waterline length and beam, keel at the
    draught below the still water, deck at the moulded depth above the keel, a ship's
    fine ends (narrower than the beam at the stem and stern) and the parallel midbody
    under the davits."""
    _, pvd, _, _ = written
    ship = _first(pvd, "ship")
    x, y, z = ship.points.T
    assert math.isclose(np.ptp(x), SHIP_LWL, rel_tol=1e-3)
    assert math.isclose(np.ptp(y), SHIP_BEAM, rel_tol=2e-3)
    assert math.isclose(z.min(), -SHIP_DRAUGHT, abs_tol=0.05)
    assert math.isclose(z.max(), SHIP_DEPTH - SHIP_DRAUGHT, abs_tol=0.05)
    waterline = np.abs(z) < 0.05
    ends = waterline & (np.abs(x) > 0.45 * SHIP_LWL)
    middle = waterline & (np.abs(x) < 10.0)
    assert ends.any() and np.abs(y[ends]).max() < 0.3 * SHIP_BEAM
    assert np.allclose(np.abs(y[middle]), 0.5 * SHIP_BEAM, atol=0.05)
    zone = ship.cell_data["zone"]
    assert set(np.concatenate(zone).tolist()) == {geo.BOTTOM, geo.TOPSIDES, geo.DECK}


def test_davit_stands_on_the_deck_under_its_heads(written):
    """Posts from the deck up past the heads, arms out to them."""
    run, pvd, _, _ = written
    davit = _first(pvd, "davit").points
    assert math.isclose(davit[:, 2].min(), SHIP_DEPTH - SHIP_DRAUGHT, abs_tol=0.01)
    assert HEADS_Z < davit[:, 2].max() < HEADS_Z + 2.0
    heads = layout.to_plot_frame(np.array([geo.deck(run, "rigging", "head_fore"),
                                           geo.deck(run, "rigging", "head_aft")]))
    for head in heads:
        assert np.min(np.linalg.norm(davit - head, axis=1)) < geo.DAVIT_WIDTH
    # inboard of the ship's side, which is at B/2
    assert np.all(np.abs(davit[:, 1][davit[:, 2] < 8.0]) < 0.5 * SHIP_BEAM)


def test_boat_shape_is_the_model_hull_with_a_canopy(written):
    """The boat at rest: its bottom `keel` (1.1 m) below the CG, its roof `height` (3.1 m)
    above the keel, no wider than its beam (2.8 m), 11.5 m long."""
    run, pvd, _, _ = written
    boat = _first(pvd, "boat").points
    cg = layout.to_plot_frame(run.get(layout.BOAT_POSITION)[0])
    euler = run.get(layout.BOAT_EULER)[0]
    assert np.max(np.abs(euler)) < 0.01
    assert math.isclose(boat[:, 2].min(), cg[2] - 1.1, abs_tol=0.05)
    assert math.isclose(boat[:, 2].max(), cg[2] - 1.1 + 3.1, abs_tol=0.05)
    assert math.isclose(np.ptp(boat[:, 0]), 11.5, abs_tol=0.1)
    assert np.ptp(boat[:, 1]) < 2.8 + 0.05


def test_box_ship_is_a_box(short_run, tmp_path):
    """&ship model = 'fk_box' (the default): the paper's box and the side plane."""
    _, h5 = short_run
    scene.write(str(h5), str(tmp_path), 500)
    ship = meshio.read(next((tmp_path / "short_scene").glob("ship_*.vtu")))
    assert len(ship.points) == 12
    assert math.isclose(np.ptp(ship.points[:, 0]), SHIP_LWL, abs_tol=1e-4)   # Float32


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


def _install_paraview():
    """None when pvpython and xvfb-run are there, after installing Debian's paraview and
    xvfb with apt-get where missing (as root, or through sudo without a password, as
    make.sh's setup_paraview does); else why they cannot be had."""
    if shutil.which("pvpython") and shutil.which("xvfb-run"):
        return None
    if not shutil.which("apt-get"):
        return "no apt-get on this machine (install ParaView 5.11+ and xvfb yourself)"
    prefix = []
    if os.geteuid() != 0:
        if not shutil.which("sudo") or subprocess.run(["sudo", "-n", "true"],
                                                      capture_output=True).returncode:
            return "not root and no password-less sudo to run apt-get install paraview xvfb"
        prefix = ["sudo", "-n"]
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    for command in (["apt-get", "update", "-qq"],
                    ["apt-get", "install", "-y", "-qq", "paraview", "xvfb"]):
        result = subprocess.run(prefix + command, capture_output=True, text=True, env=env,
                                timeout=1800)
        if result.returncode:
            return f"{' '.join(command)} failed: {result.stderr.strip()[-300:]}"
    if shutil.which("pvpython") and shutil.which("xvfb-run"):
        return None
    return "apt-get installed paraview and xvfb but pvpython or xvfb-run is not on PATH"


@pytest.fixture(scope="module")
def pvpython():
    reason = _install_paraview()
    if reason is not None:
        pytest.skip(f"ParaView cannot be installed: {reason}")
    return ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "pvpython"]


def _viridis(values, low, high):
    """8-bit RGB of matplotlib's viridis at values over [low, high]."""
    from matplotlib import colormaps
    rgba = colormaps["viridis"](np.clip((np.asarray(values) - low) / (high - low), 0, 1))
    return np.round(255 * np.asarray(rgba)[..., :3]).astype(int)


def test_pvpython_renders_the_state(written, pvpython, tmp_path):
    """pvpython loads the state file and renders the last frame to a PNG: not blank, the
    orange boat in it, and the falls in the viridis colours of their recorded tensions over
    the run's range (read here from the run file), away from the scalar bar."""
    from PIL import Image
    run, _, state, _ = written
    png = tmp_path / "frame.png"
    t = float(run.time[::EVERY][-1])
    command = pvpython + [str(state), "--screenshot", str(png), "--time", str(t),
                          "--size", *map(str, PNG_SIZE)]
    for _ in range(3):
        result = subprocess.run(command, capture_output=True, text=True, timeout=300,
                                cwd=tmp_path)
        # xvfb-run -a's X server not ready for the window: "bad X server connection"
        # (about one run in ten here); pvpython never got to the state file, so run again
        if result.returncode == 0 or "bad X server connection" not in result.stderr:
            break
    assert result.returncode == 0 and png.exists(), (result.stdout + result.stderr)[-3000:]
    with Image.open(png) as image:
        rgb = np.asarray(image.convert("RGB")).astype(int)
    assert rgb.shape == (PNG_SIZE[1], PNG_SIZE[0], 3)
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 1000
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    assert np.count_nonzero((r > 150) & (g > 40) & (g < 140) & (b < 60)) > 500   # the boat
    # the cable's tension at this frame, coloured over the sampled frames' range
    segment = run.get(layout.RIGGING_SEGMENT_TENSION)[::EVERY]
    sling = run.get(layout.SLING_TENSION)[::EVERY]
    low, high = 1e-3 * min(segment.min(), sling.min()), 1e-3 * max(segment.max(), sling.max())
    cable = _viridis(1e-3 * np.median(segment[-1]), low, high)
    middle = rgb[:, :int(0.75 * PNG_SIZE[0])]      # the tension bar is in the upper right
    near = np.linalg.norm(middle - cable, axis=-1) < 40
    assert np.count_nonzero(near) > 100, f"no falls in {cable} in {png}"


def _bem_run(tmp_path, **attrs):
    """A run (no data) whose deck names a BEM database with these root attributes."""
    import h5py
    database = tmp_path / "hull.nc"
    with h5py.File(database, "w") as f:
        for key, value in attrs.items():
            f.attrs[key] = value
    deck = f"&ship model = 'bem', database = '{database}' /\n"
    return layout.Run(str(tmp_path / "run.h5"), {"input_namelist": deck}, {}, {})


def test_hull_lines_follow_a_ship_form_database(tmp_path):
    """A database solved on the ship form gives its own dimensions; the equivalent box
    (input/ship_bem.nc's kind) gives Table 1's ship (the deck's &ship keys)."""
    run = _bem_run(tmp_path, hull_kind="ship", length=100.0, beam=16.0, draught=5.0,
                   block_coefficient=0.7, section_exponent=4)
    lines = geo.hull_lines(run)
    assert (lines.length, lines.beam, lines.draught) == (100.0, 16.0, 5.0)
    assert (lines.block_coefficient, lines.exponent) == (0.7, 4.0)
    rings, _ = geo.ship_hull_lines(run, lines)
    assert math.isclose(np.ptp(rings[..., 1]), 16.0, rel_tol=2e-3)
    box = geo.hull_lines(_bem_run(tmp_path, hull_kind="box", length=107.65, beam=20.8,
                                  draught=4.4))
    assert (box.length, box.beam, box.draught) == (SHIP_LWL, SHIP_BEAM, SHIP_DRAUGHT)
