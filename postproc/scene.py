"""`python -m postproc scene RUN.h5 [-o OUTDIR] [--every N]`: the launch as a ParaView
time series.

Writes, for every N-th sample, one VTK XML unstructured grid (.vtu) per part into
OUTDIR/<stem>_scene/, an index OUTDIR/<stem>.pvd (all parts, timestep = simulated time
[s]; ParaView opens it as a multiblock), one <part>.pvd per part beside the frames, and a
ParaView state OUTDIR/<stem>_state.py (File > Load State, or pvpython) that opens the parts,
colours the falls by tension and the fenders by contact force.

Frame: metres, z up: davit's inertial N (x, y, z down) turned 180 deg about x, the paper's
oxy1z1 (x, y1 = -y, z1 = -z; layout.to_plot_frame), so the still water is z = 0 and the
boat on the starboard side is at negative y.
"""
import os

import numpy as np

from . import launch_geometry as geo
from . import layout, vtk_xml

PARTS = ("ship", "boat", "falls", "nodes", "fenders", "sea")
SEA_POINTS = 31          # the sea patch's points per side (2 for the still water)
SEA_MARGIN = 2.0         # its half-size in boat lengths (at least SEA_MIN_HALF)
SEA_MIN_HALF = 20.0      # m
NODE_RADIUS = 0.1        # glyph radius of drums, hooks, dead ends and lumps [m]


def _quads_between(first, second):
    """Quads joining two rings of 4 point indices (a section to the next one)."""
    return [[first[i], first[(i + 1) % 4], second[(i + 1) % 4], second[i]] for i in range(4)]


def ship_cells():
    """The box's 6 faces and the side plane (points 8-11): quads."""
    bottom, top = [0, 1, 2, 3], [4, 5, 6, 7]
    return np.array([bottom[::-1], top] + _quads_between(bottom, top) + [[8, 9, 10, 11]])


def boat_cells():
    """Quads of the hull surface between consecutive sections, and the two end sections."""
    rings = [list(range(4 * i, 4 * i + 4)) for i in range(geo.BOAT_STATIONS)]
    quads = [q for a, b in zip(rings, rings[1:]) for q in _quads_between(a, b)]
    return np.array(quads + [rings[0][::-1], rings[-1]])


class Scene:
    """Everything drawn, over the chosen frames, in the inertial frame N."""

    def __init__(self, run, every):
        self.run = run
        self.frames = geo.frame_indices(run, every)
        self.ship_local = np.vstack([geo.ship_box(run), geo.side_plane(run)])
        self.ship = geo.ship_pose(run, self.frames).apply(self.ship_local)
        self.boat = geo.boat_pose(run, self.frames).apply(geo.boat_hull(run))
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
        half = max(SEA_MARGIN * float(geo.deck(self.run, "boat", "length")), SEA_MIN_HALF)
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
        kind = np.r_[np.zeros(6, np.int32), 1]
        return self.ship[i], [(vtk_xml.QUAD, ship_cells())], {}, {"surface": kind}

    def _boat(self, i):
        return self.boat[i], [(vtk_xml.QUAD, boat_cells())], {}, {}

    def _falls(self, i):
        f = self.falls
        tension = f.tension[i]
        at_point = np.zeros(len(f.kind))
        np.maximum.at(at_point, f.segments[:, 0], tension)
        np.maximum.at(at_point, f.segments[:, 1], tension)
        return (f.points[i], [(vtk_xml.LINE, f.segments)],
                {"tension": at_point, "kind": f.kind.astype(np.int32)},
                {"tension": tension, "sling": f.sling.astype(np.int32)})

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
        return (self.fenders[i].reshape(-1, 3), [(vtk_xml.LINE, segments)],
                {"contact_force": np.repeat(force, 2)}, {"contact_force": force})

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
pvpython {name}. Metres, z up (davit's N turned 180 deg about x: y1 = -y, z1 = -z)."""
import os

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene,
                             GetColorTransferFunction, PVDReader, Render, Show)

FOLDER = {folder!r}
if not os.path.isdir(FOLDER):  # moved with its frames: look beside this file
    FOLDER = os.path.join(os.path.dirname(os.path.abspath(globals().get("__file__", "."))),
                          {relative!r})
view = GetActiveViewOrCreate("RenderView")


def part(name, opacity=1.0, colour=None, array=None, width=None, points=None):
    reader = PVDReader(registrationName=name, FileName=os.path.join(FOLDER, name + ".pvd"))
    shown = Show(reader, view)
    shown.Opacity = opacity
    if colour is not None:
        ColorBy(shown, None)
        shown.AmbientColor = shown.DiffuseColor = colour
    if array is not None:
        ColorBy(shown, array)
        shown.SetScalarBarVisibility(view, True)
    if width is not None:
        shown.LineWidth = width
        shown.RenderLinesAsTubes = 1
    if points is not None:
        shown.SetRepresentationType("Points")
        shown.PointSize = points
        shown.RenderPointsAsSpheres = 1
    return reader, shown


part("ship", opacity=0.35, colour=[0.55, 0.55, 0.6])
part("boat", colour=[1.0, 0.45, 0.0])
part("sea", opacity=0.5, colour=[0.2, 0.45, 0.8])
part("falls", array=("CELLS", "tension"), width=4)
GetColorTransferFunction("tension").RescaleTransferFunction(0.0, {tension_max!r})
part("nodes", colour=[0.1, 0.1, 0.1], points=10)
part("fenders", array=("CELLS", "contact_force"), width=8)
GetColorTransferFunction("contact_force").RescaleTransferFunction(0.0, {force_max!r})
GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
view.CameraFocalPoint = {focus!r}
view.CameraPosition = {camera!r}
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraViewAngle = 30.0
Render(view)
'''


def write_state(path, folder, scene):
    """The ParaView state script: the parts' readers and colours, the tension and force
    colour ranges of the whole run, and a camera astern and outboard of the boat looking
    at the middle of its way down (z up frame)."""
    boat = layout.to_plot_frame(scene.run.get(layout.BOAT_POSITION))
    focus = 0.5 * (boat.min(axis=0) + boat.max(axis=0))
    camera = focus + np.array([-30.0, -45.0, 12.0])
    text = STATE.format(stem=os.path.basename(path)[:-len("_state.py")],
                        name=os.path.basename(path), folder=os.path.abspath(folder),
                        relative=os.path.basename(folder),
                        tension_max=float(max(np.max(scene.falls.tension), 1.0)),
                        force_max=float(max(np.max(scene.fender_force), 1.0)),
                        focus=[round(float(v), 3) for v in focus],
                        camera=[round(float(v), 3) for v in camera])
    with open(path, "w") as f:
        f.write(text)
    return path
