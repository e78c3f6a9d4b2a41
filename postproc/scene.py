"""`python -m postproc scene RUN.h5 [-o OUTDIR] [--every N]`: the launch as a ParaView
time series.

Writes, for every N-th sample, one VTK XML unstructured grid (.vtu) per part into
OUTDIR/<stem>_scene/, an index OUTDIR/<stem>.pvd (all parts, timestep = simulated time
[s]; ParaView opens it as a multiblock), one <part>.pvd per part beside the frames, and a
ParaView state OUTDIR/<stem>_state.py (File > Load State in ParaView 5.11+, or
`pvpython <stem>_state.py --screenshot frame.png [--time T]`) that opens the parts, colours
the falls by tension and the fenders by contact force [kN] (viridis, inferno: over the
run's range) and the sea by its elevation [m], and puts the camera outboard of the boat.

Parts: the ship (the BEM ship's hull from its lines, geo.ship_hull_lines; the paper's box
and the contact's side plane for &ship model = 'fk_box'), the davits (geo.davit_members:
posts from the deck up to the heads of &rigging), the boat (geo.boat_shape), the falls and
slings with their tensions, their nodes, the fenders, and the sea rebuilt from
/sea/components. The ship and davits move with the recorded ship, the boat with its own.

Frame: metres, z up: davit's inertial N (x, y, z down) turned 180 deg about x, the paper's
oxy1z1 (x, y1 = -y, z1 = -z; layout.to_plot_frame), so the still water is z = 0 and the
boat on the starboard side is at negative y.
"""
import os

import numpy as np

from . import launch_geometry as geo
from . import layout, vtk_xml

PARTS = ("ship", "davit", "boat", "falls", "nodes", "fenders", "sea")
SEA_POINTS = 41          # the sea patch's points per side (2 for the still water)
SEA_MARGIN = 2.0         # its half-size in boat lengths (at least SEA_MIN_HALF) ...
SEA_SHIP_MARGIN = 0.6    # ... and in ship lengths, so that it reaches past the ship's ends
SEA_MIN_HALF = 20.0      # m
NODE_RADIUS = 0.1        # glyph radius of drums, hooks, dead ends and lumps [m]
CAMERA_DISTANCE = 1.0    # the camera's distance in that which just fits the launch's box
KILO = 1.0e-3            # N -> kN of the "_kN" arrays that the state file colours by


def _quads_between(first, second):
    """Quads joining two rings of 4 point indices (a section to the next one)."""
    return [[first[i], first[(i + 1) % 4], second[(i + 1) % 4], second[i]] for i in range(4)]


def ship_cells():
    """The box's 6 faces and the side plane (points 8-11): quads."""
    bottom, top = [0, 1, 2, 3], [4, 5, 6, 7]
    return np.array([bottom[::-1], top] + _quads_between(bottom, top) + [[8, 9, 10, 11]])


def ship_box_zones():
    """Zones of ship_cells' quads: bottom, deck, the four sides, the contact plane."""
    return np.r_[geo.BOTTOM, geo.DECK, np.full(4, geo.TOPSIDES), geo.SIDE_PLANE]


def ring_quads(stations, ring, closed):
    """Quads between consecutive rings of `ring` points (station-major numbering); each
    ring's edges in order, with the last point back to the first where `closed`."""
    edges = ring if closed else ring - 1
    return np.array([[s * ring + j, s * ring + (j + 1) % ring, (s + 1) * ring + (j + 1) % ring,
                      (s + 1) * ring + j] for s in range(stations - 1) for j in range(edges)])


def ship_lines_cells(zone):
    """Cells of geo.ship_hull_lines: the quads between its rings (zone of each, the ring
    edge's) and the transom (the stern ring above the waterline) as one polygon."""
    ring, (nb, na) = len(zone) + 1, geo.SHIP_LEVELS
    quads = ring_quads(geo.SHIP_STATIONS, ring, closed=False)
    transom = np.r_[np.arange(nb, nb + na + 1), ring - 1 - np.arange(nb + na, nb - 1, -1)]
    zones = np.r_[np.tile(zone, geo.SHIP_STATIONS - 1), geo.TOPSIDES]
    return [(vtk_xml.QUAD, quads), (vtk_xml.POLYGON, transom[None, :])], zones


def boat_shape_cells():
    """Quads of geo.boat_shape: round each section, from one to the next."""
    return ring_quads(geo.BOAT_SHAPE_STATIONS, geo.BOAT_RING, closed=True)


class Scene:
    """Everything drawn, over the chosen frames, in the inertial frame N."""

    def __init__(self, run, every):
        self.run = run
        self.frames = geo.frame_indices(run, every)
        self.model = geo.ship_model(run)
        self.lines = geo.hull_lines(run) if self.model == "bem" else None
        if self.lines is None:      # the paper's box, and the contact's side plane
            self.ship_local = np.vstack([geo.ship_box(run), geo.side_plane(run)])
            self.ship_cells = [(vtk_xml.QUAD, ship_cells())]
            self.ship_zones = ship_box_zones()
        else:                       # the BEM ship: its hull lines
            rings, zone = geo.ship_hull_lines(run, self.lines)
            self.ship_local = rings.reshape(-1, 3)
            self.ship_cells, self.ship_zones = ship_lines_cells(zone)
        ship_pose = geo.ship_pose(run, self.frames)
        self.ship = ship_pose.apply(self.ship_local)
        davit_points, self.davit_quads = geo.prisms(geo.davit_members(run, self.lines),
                                                    geo.DAVIT_WIDTH)
        self.davit = ship_pose.apply(davit_points)
        self.heads = ship_pose.apply([geo.deck(run, "rigging", "head_fore"),
                                      geo.deck(run, "rigging", "head_aft")])
        self.boat = geo.boat_pose(run, self.frames).apply(geo.boat_shape(run))
        self.falls = geo.falls(run, self.frames)
        self.fenders = geo.fenders(run, self.frames)
        force = run.get(layout.CONTACT_FORCE)
        self.fender_force = force[self.frames] if force is not None else \
            np.zeros(self.fenders.shape[:2])
        self.sea_x, self.sea_y = self._sea_grid()
        self.sheave_radius = float(geo.deck(run, "rigging", "sheave_radius"))

    def _sea_grid(self):
        """A square patch around the boat's mean horizontal position."""
        centre = np.mean(self.run.get(layout.BOAT_POSITION)[:, :2], axis=0)
        ship_length = np.ptp(self.ship_local[:, 0])
        half = max(SEA_MARGIN * float(geo.deck(self.run, "boat", "length")),
                   SEA_SHIP_MARGIN * ship_length, SEA_MIN_HALF)
        waves = geo.has_sea(self.run)
        axis = np.linspace(-half, half, SEA_POINTS if waves else 2)
        return np.meshgrid(centre[0] + axis, centre[1] + axis, indexing="ij")

    def times(self):
        return self.run.time[self.frames]

    def part(self, name, i):
        """(points, cells, point_data, cell_data) of part `name` at frame i, z up."""
        points, cells, pdata, cdata = getattr(self, "_" + name)(i)
        return layout.to_plot_frame(points), cells, pdata, cdata

    def _ship(self, i):
        return self.ship[i], self.ship_cells, {}, {"zone": self.ship_zones.astype(np.int32)}

    def _davit(self, i):
        return self.davit[i], [(vtk_xml.QUAD, self.davit_quads)], {}, {}

    def _boat(self, i):
        return self.boat[i], [(vtk_xml.QUAD, boat_shape_cells())], {}, {}

    def _falls(self, i):
        f = self.falls
        tension = f.tension[i]
        at_point = np.zeros(len(f.kind))
        np.maximum.at(at_point, f.segments[:, 0], tension)
        np.maximum.at(at_point, f.segments[:, 1], tension)
        return (f.points[i], [(vtk_xml.LINE, f.segments)],
                {"tension": at_point, "tension_kN": KILO * at_point,
                 "kind": f.kind.astype(np.int32)},
                {"tension": tension, "tension_kN": KILO * tension,
                 "sling": f.sling.astype(np.int32)})

    def _nodes(self, i):
        f = self.falls
        wheel = np.isin(f.kind, (geo.SHEAVE, geo.BLOCK))
        radius = np.where(wheel, self.sheave_radius, NODE_RADIUS)
        cells = np.arange(len(f.kind))[:, None]
        return (f.points[i], [(vtk_xml.VERTEX, cells)],
                {"kind": f.kind.astype(np.int32), "radius": radius}, {})

    def _fenders(self, i):
        nf = self.fenders.shape[1]
        force = self.fender_force[i]
        segments = np.arange(2 * nf).reshape(nf, 2)
        ends = np.repeat(force, 2)
        return (self.fenders[i].reshape(-1, 3), [(vtk_xml.LINE, segments)],
                {"contact_force": ends, "contact_force_kN": KILO * ends},
                {"contact_force": force, "contact_force_kN": KILO * force})

    def _sea(self, i):
        n = self.sea_x.shape[0]
        eta = geo.sea_elevation(self.run, self.times()[i], self.sea_x, self.sea_y)
        points = np.stack([self.sea_x, self.sea_y, -eta], axis=-1).reshape(-1, 3)
        index = np.arange(n * n).reshape(n, n)
        quads = np.stack([index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]],
                         axis=-1).reshape(-1, 4)
        return points, [(vtk_xml.QUAD, quads)], {"elevation": eta.ravel()}, {}


def write(path, outdir, every=1):
    """Write the scene of run file `path` into `outdir`; returns (pvd, state file, frame
    count)."""
    run = layout.load(path)
    run.require([layout.BOAT_POSITION, layout.BOAT_EULER, layout.SLING_TENSION],
                "boat on its falls (a 'launch' or boat run)")
    stem = os.path.splitext(os.path.basename(path))[0]
    scene = Scene(run, every)
    folder = os.path.join(outdir, f"{stem}_scene")
    os.makedirs(folder, exist_ok=True)
    entries = []
    for i, t in enumerate(scene.times()):
        for p, name in enumerate(PARTS):
            file = os.path.join(folder, f"{name}_{i:05d}.vtu")
            vtk_xml.write_vtu(file, *scene.part(name, i))
            entries.append((t, p, name, file))
    for p, name in enumerate(PARTS):
        vtk_xml.write_pvd(os.path.join(folder, f"{name}.pvd"),
                          [(t, 0, n, f) for t, q, n, f in entries if q == p])
    pvd = vtk_xml.write_pvd(os.path.join(outdir, f"{stem}.pvd"), entries)
    state = write_state(os.path.join(outdir, f"{stem}_state.py"), folder, scene)
    return pvd, state, len(scene.frames)


STATE = '''"""ParaView state of the davit launch {stem} (postproc.scene): File > Load State, or

    pvpython {name} [--screenshot PNG] [--time T] [--size W H]

which renders one frame (by default at the peak fall tension, t = {peak_time} s) to PNG.
Metres, z up (davit's N turned 180 deg about x: y1 = -y, z1 = -z). Ship: {ship}."""
import os
import sys

from paraview import simple
from paraview.simple import (AnnotateTime, ColorBy, ExtractSurface, GenerateSurfaceNormals,
                             GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,
                             GetOpacityTransferFunction, GetScalarBar, PVDReader, Render,
                             SaveScreenshot, Show)

FOLDER = {folder!r}
if not os.path.isdir(FOLDER):  # moved with its frames: look beside this file
    FOLDER = os.path.join(os.path.dirname(os.path.abspath(globals().get("__file__", "."))),
                          {relative!r})
TEXT = [0.1, 0.1, 0.15]
view = GetActiveViewOrCreate("RenderView")
simple._DisableFirstRenderCameraReset()    # keep the camera set below
view.OrientationAxesVisibility = 0
for key, value in (("UseColorPaletteForBackground", 0), ("BackgroundColorMode", "Gradient"),
                   ("UseGradientBackground", 1), ("Background", [0.97, 0.98, 1.0]),
                   ("Background2", [0.62, 0.75, 0.88])):
    if view.GetProperty(key) is not None:
        setattr(view, key, value)


def part(name, colour=None, opacity=1.0, smooth=False):
    """A part's time series, shown in one colour (colour) or left for colour_map; a
    smooth part's surface is shaded with normals that keep edges sharper than 40 deg."""
    reader = PVDReader(registrationName=name, FileName=os.path.join(FOLDER, name + ".pvd"))
    if smooth:
        surface = ExtractSurface(registrationName=name + "_surface", Input=reader)
        reader = GenerateSurfaceNormals(registrationName=name + "_shaded", Input=surface,
                                        FeatureAngle=40.0, Splitting=1)
    shown = Show(reader, view)
    shown.Opacity = opacity
    if colour is not None:
        shown.ColorArrayName = ["POINTS", ""]
        shown.AmbientColor = shown.DiffuseColor = colour
    return reader, shown


def colour_map(shown, association, array, title, low, high, preset=None, points=None,
               location="Upper Right Corner", labels="%-#.1f"):
    """Colour by an array over [low, high] (fixed: the whole run's range), with a scalar
    bar titled with its units."""
    ColorBy(shown, (association, array))
    lut = GetColorTransferFunction(array)
    if preset is not None:
        lut.ApplyPreset(preset, True)
    if points is not None:
        lut.RGBPoints = points
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(low, high)
    GetOpacityTransferFunction(array).RescaleTransferFunction(low, high)
    bar = GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle, bar.HorizontalTitle = title, "", 1
    bar.WindowLocation = location
    bar.TitleColor = bar.LabelColor = TEXT
    bar.TitleFontSize, bar.LabelFontSize = 16, 14
    bar.ScalarBarLength = 0.3
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = bar.RangeLabelFormat = labels
    if bar.GetProperty("DrawBackground") is not None:   # legible over the hull
        bar.DrawBackground, bar.BackgroundColor = 1, [1.0, 1.0, 1.0, 0.6]
    shown.SetScalarBarVisibility(view, True)
    return lut


_, ship = part("ship", smooth=True)
ColorBy(ship, ("CELLS", "zone"))
zones = GetColorTransferFunction("zone")
zones.InterpretValuesAsCategories = 1
zones.Annotations = ["0", "bottom", "1", "topsides", "2", "deck", "3", "contact plane"]
zones.IndexedColors = [0.55, 0.14, 0.1, 0.36, 0.4, 0.47, 0.66, 0.68, 0.64, 0.8, 0.8, 0.85]
ship.SetScalarBarVisibility(view, False)
part("davit", colour=[0.93, 0.93, 0.9])
part("boat", colour=[1.0, 0.42, 0.0], smooth=True)
_, falls = part("falls")
falls.LineWidth = 5
falls.RenderLinesAsTubes = 1
colour_map(falls, "CELLS", "tension_kN", "Fall and sling tension [kN]", {tension_low!r},
           {tension_high!r}, preset="Viridis (matplotlib)")
_, nodes = part("nodes", colour=[0.1, 0.1, 0.1])
nodes.SetRepresentationType("Points")
nodes.PointSize = 8
nodes.RenderPointsAsSpheres = 1
_, fenders = part("fenders")
fenders.LineWidth = 10
fenders.RenderLinesAsTubes = 1
FORCE = {force_high!r}     # the largest fender contact force [kN] (0: no contact)
if FORCE > 0.0:
    colour_map(fenders, "CELLS", "contact_force_kN", "Fender contact force [kN]", 0.0, FORCE,
               preset="Inferno (matplotlib)", location="Upper Left Corner")
else:
    fenders.ColorArrayName = ["POINTS", ""]
    fenders.AmbientColor = fenders.DiffuseColor = [0.1, 0.1, 0.1]
_, sea = part("sea", opacity=0.9)
SEA = {sea_high!r}       # the largest |elevation| drawn [m]
if SEA > 0.0:            # the waves: elevation in blues, crests light
    colour_map(sea, "POINTS", "elevation", "Sea surface elevation [m]", -SEA, SEA,
               points=[-SEA, 0.03, 0.17, 0.38, 0.0, 0.12, 0.38, 0.66, SEA, 0.62, 0.82, 0.95],
               location="Lower Right Corner", labels="%-#.2f")
else:                    # still water
    sea.ColorArrayName = ["POINTS", ""]
    sea.AmbientColor = sea.DiffuseColor = [0.12, 0.38, 0.66]
clock = Show(AnnotateTime(registrationName="time", Format="{stem}: t = {{time:.2f}} s"), view)
clock.WindowLocation = "Upper Center"
clock.FontSize, clock.Color = 18, TEXT

scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
view.CameraFocalPoint = {focus!r}
view.CameraPosition = {camera!r}
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0


def _option(name, count=1):
    """The `count` values after `name` on pvpython's command line, or None."""
    argv = list(getattr(sys, "argv", []))
    if name not in argv[:len(argv) - count]:
        return None
    at = argv.index(name)
    return argv[at + 1:at + 1 + count]


if _option("--screenshot"):
    time = _option("--time")
    wanted = float(time[0]) if time else {peak_time!r}
    steps = list(scene.TimeKeeper.TimestepValues)
    scene.AnimationTime = min(steps, key=lambda step: abs(step - wanted))  # nearest frame
    size = [int(v) for v in (_option("--size", 2) or (1600, 900))]
    view.ViewSize = size
    Render(view)
    SaveScreenshot(_option("--screenshot")[0], view, ImageResolution=size)
else:
    Render(view)
'''


def camera(scene):
    """(focal point, camera position) in the plot frame: the focus on the middle of the
    box holding the boat's way down (its recorded positions and the boat afloat under
    them), the davit heads and the ship's side beside them; the camera outboard of the
    boat, abaft and above it, at the distance that fits that box in a 30 deg view."""
    boat = layout.to_plot_frame(scene.run.get(layout.BOAT_POSITION)[scene.frames])
    heads = layout.to_plot_frame(scene.heads[0])
    afloat = np.c_[boat[:, :2], np.full(len(boat), -0.5)]
    points = np.vstack([boat, heads, afloat])
    low, high = points.min(axis=0), points.max(axis=0)
    focus = 0.5 * (low + high)
    radius = 0.5 * (np.linalg.norm(high - low) + float(geo.deck(scene.run, "boat", "length")))
    ship_y = float(np.mean(layout.to_plot_frame(scene.ship[0])[:, 1]))
    outboard = 1.0 if np.mean(boat[:, 1]) >= ship_y else -1.0
    direction = np.array([-0.55, outboard, 0.08])
    direction /= np.linalg.norm(direction)
    return focus, focus + CAMERA_DISTANCE * direction * radius / np.tan(np.radians(15.0))


def write_state(path, folder, scene):
    """The ParaView state script: the parts' readers and colours, the tension, force and
    elevation colour ranges of the whole run in kN and m, and the camera (camera())."""
    focus, position = camera(scene)
    tension = KILO * scene.falls.tension
    peak = int(np.argmax(tension.max(axis=1)))
    sea = 0.0
    if geo.has_sea(scene.run):
        sea = max(float(np.max(np.abs(geo.sea_elevation(scene.run, t, scene.sea_x,
                                                          scene.sea_y))))
                  for t in scene.times())
    text = STATE.format(stem=os.path.basename(path)[:-len("_state.py")],
                        name=os.path.basename(path), folder=os.path.abspath(folder),
                        relative=os.path.basename(folder),
                        ship=(scene.lines.source if scene.lines is not None
                              else "the paper's box (&ship model = 'fk_box')"),
                        tension_low=round(float(tension.min()), 3),
                        tension_high=round(float(max(tension.max(), tension.min() + 1e-3)), 3),
                        force_high=round(float(KILO * np.max(scene.fender_force)), 3),
                        sea_high=round(sea, 3), peak_time=float(scene.times()[peak]),
                        focus=[round(float(v), 3) for v in focus],
                        camera=[round(float(v), 3) for v in position])
    with open(path, "w") as f:
        f.write(text)
    return path
