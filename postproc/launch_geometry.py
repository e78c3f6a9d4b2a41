"""The launch's hardware as points in the inertial frame N (z down), one frame per sample.

Shared by the ParaView scene (postproc.scene) and the animation (postproc.animate), so that
both draw the same ship, boat, falls and fenders. The run file holds the motion (boat and
ship poses, block positions, tensions); the fixed geometry comes from the deck the run was
made from (root attribute input_namelist). That text only holds the keys the deck states,
so the Fortran defaults of the keys drawn here are repeated in DEFAULTS (their sources:
src/io/ship_keys.f90, src/io/rigging_keys.f90, src/io/config.f90); a changed default there
must be changed here too (test_scene checks a few against a run).
"""
import os
from dataclasses import dataclass

import h5py
import numpy as np

from . import bem_mesh, layout

# (group, key) -> the Fortran default
DEFAULTS = {
    ("ship", "length_waterline"): 130.55, ("ship", "beam"): 20.8,
    ("ship", "draught"): 4.4, ("ship", "depth"): 11.4,
    ("ship", "cg_x"): 0.0, ("ship", "cg_z"): 0.0, ("ship", "block_coefficient"): 0.68,
    ("ship", "model"): "fk_box", ("ship", "database"): "ship_bem.nc",
    ("boat", "length"): 11.5, ("boat", "beam"): 2.8, ("boat", "height"): 3.1,
    ("boat", "keel"): 1.1, ("boat", "breadth_exponent"): 4.3,
    ("slings", "hook_fore"): (4.6, 0.0, -1.55), ("slings", "hook_aft"): (-4.6, 0.0, -1.55),
    ("slings", "anchor_fore"): (4.6, 13.3, -19.55),
    ("slings", "anchor_aft"): (-4.6, 13.3, -19.55),
    ("rigging", "reeving"): "a",
    ("rigging", "head_fore"): (4.6, 13.3, -20.55), ("rigging", "head_aft"): (-4.6, 13.3, -20.55),
    ("rigging", "head_spacing"): 0.32, ("rigging", "lead_sheave"): (0.0, 11.5, -21.0),
    ("rigging", "drum_position"): (0.0, 8.0, -16.5), ("rigging", "sheave_radius"): 0.16,
    ("contact", "fender_x"): (3.0, -3.0), ("contact", "fender_y"): -1.4,
    ("contact", "fender_z"): (-0.8, 0.2),
}
BOAT_STATIONS = 15       # sections along the boat's hull shape b(x) = B (1 - |2x/L|^p)
BOAT_SHAPE_STATIONS = 25  # the same for the scene's boat (boat_shape), sine-spaced
BOAT_RING = 8            # points per section of boat_shape
SHIP_STATIONS = 41       # sections of the ship's hull lines, stern to stem (cosine-spaced)
SHIP_LEVELS = (8, 5)     # levels per side below the waterline (keel to it) and above it
SHIP_TRANSOM = 0.6       # half-breadth of the transom at the deck, in B/2
SHIP_DECK_FULLNESS = 0.4  # the deck line's parallel part: xi_p + this x (1 - xi_p)
# ship-part zones (cell data "zone"): below the waterline, topsides, deck, contact plane
BOTTOM, TOPSIDES, DECK, SIDE_PLANE = range(4)
DAVIT_WIDTH = 0.35       # side of the davit members' square section [m]
DAVIT_INBOARD = 1.0      # the posts' feet inboard of the deck edge [m]
DAVIT_HEADROOM = 0.4     # the posts' tops above the higher of the heads and lead sheave [m]
# node kinds of the rigging (the scene's point data "kind")
DRUM, SHEAVE, BLOCK, HOOK, DEAD_END, LUMP, ANCHOR = range(7)
KIND_NAMES = ("drum", "sheave", "block", "hook", "dead_end", "lump", "anchor")


def deck(run, group, key):
    """A deck key of the run as stated, else davit's default (DEFAULTS)."""
    value = run.deck(group, key, DEFAULTS[(group, key)])
    if isinstance(DEFAULTS[(group, key)], tuple) and not isinstance(value, tuple):
        value = (value,)
    return np.asarray(value, dtype=float) if not isinstance(value, str) else value.lower()


def rotations(euler):
    """C = Rz Ry Rx (src/core/rotation.f90) of each row of (roll, pitch, yaw): (n, 3, 3),
    body components to inertial ones."""
    s1, s2, s3 = (np.sin(euler[:, i]) for i in range(3))
    c1, c2, c3 = (np.cos(euler[:, i]) for i in range(3))
    c = np.empty((len(euler), 3, 3))
    c[:, 0] = np.stack([c2 * c3, s1 * s2 * c3 - s3 * c1, c1 * s2 * c3 + s3 * s1], axis=1)
    c[:, 1] = np.stack([c2 * s3, s1 * s2 * s3 + c1 * c3, c1 * s2 * s3 - c3 * s1], axis=1)
    c[:, 2] = np.stack([-s2, s1 * c2, c1 * c2], axis=1)
    return c


@dataclass
class Pose:
    """Origin r (n, 3) and rotation c (n, 3, 3) of a body over the frames."""
    r: np.ndarray
    c: np.ndarray

    def apply(self, local):
        """Inertial positions (n, m, 3) of body-frame points local (m, 3)."""
        return self.r[:, None, :] + np.einsum("nij,mj->nmi", self.c, np.asarray(local, float))


def ship_pose(run, frames):
    """The ship's pose: its recorded CG and attitude, or at rest at the origin (scenes
    without a ship body, where the ship frame is the inertial one)."""
    if run.has(*layout.SHIP):
        return Pose(run.get(layout.SHIP_POSITION)[frames],
                    rotations(run.get(layout.SHIP_EULER)[frames]))
    n = len(frames)
    return Pose(np.zeros((n, 3)), np.broadcast_to(np.eye(3), (n, 3, 3)).copy())


def boat_pose(run, frames):
    """The boat's recorded CG and attitude."""
    return Pose(run.get(layout.BOAT_POSITION)[frames],
                rotations(run.get(layout.BOAT_EULER)[frames]))


def ship_box(run):
    """The ship's hull as a box (8 corners, ship frame): waterline length x beam, keel at
    the draught below the still waterline, deck at the moulded depth above the keel; the
    CG (the frame's origin) cg_x forward of midship and cg_z below the waterline."""
    half_l = 0.5 * deck(run, "ship", "length_waterline")
    half_b = 0.5 * deck(run, "ship", "beam")
    x0, waterline = -deck(run, "ship", "cg_x"), -deck(run, "ship", "cg_z")
    keel = waterline + deck(run, "ship", "draught")
    top = keel - deck(run, "ship", "depth")
    return np.array([[x0 + sx * half_l, sy * half_b, z] for z in (keel, top)
                     for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))])


def ship_model(run):
    """&ship model: 'fk_box' (the paper's box) or 'bem' (Cummins' ship from a database)."""
    return deck(run, "ship", "model")


def bem_database(run):
    """The BEM database a 'bem' run read (&ship database, relative to the deck's folder,
    then the run file's, then DAVIT_PATH's, then the project's input/), or None."""
    name = str(run.deck("ship", "database", DEFAULTS[("ship", "database")]))
    if os.path.isabs(name):
        return name if os.path.isfile(name) else None
    deck_file = str(run.attrs.get("input_file", ""))
    folders = [os.path.dirname(deck_file) if os.path.isabs(deck_file) else None,
               os.path.dirname(os.path.abspath(run.path))]
    folders += os.environ.get("DAVIT_PATH", "").split(os.pathsep)
    folders.append(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "input"))
    for folder in folders:
        if folder and os.path.isfile(os.path.join(folder, name)):
            return os.path.join(folder, name)
    return None


@dataclass
class Lines:
    """The ship hull's lines (bem_mesh.ship_hull's form): waterline length, beam, draught,
    block coefficient, section exponent, and where they came from."""
    length: float
    beam: float
    draught: float
    block_coefficient: float
    exponent: float
    source: str


def hull_lines(run):
    """The BEM ship's lines: the database's own where its mesh was the ship form
    (hull_kind 'ship'); else (the paper's equivalent box, or a mesh file: hydrodynamic
    stand-ins, not the ship) the ship of Table 1 as the deck states it."""
    path = bem_database(run)
    if path is not None:
        with h5py.File(path, "r") as f:
            attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
        if attrs.get("hull_kind") == "ship":
            value = lambda k, d: float(np.ravel(attrs.get(k, d))[0])  # noqa: E731
            return Lines(value("length", bem_mesh.L_PP), value("beam", bem_mesh.BEAM),
                         value("draught", bem_mesh.DRAUGHT),
                         value("block_coefficient", bem_mesh.BLOCK_COEFFICIENT),
                         value("section_exponent", bem_mesh.SHIP_SECTION_EXPONENT),
                         f"the BEM mesh's lines ({os.path.basename(path)})")
    return Lines(float(deck(run, "ship", "length_waterline")), float(deck(run, "ship", "beam")),
                 float(deck(run, "ship", "draught")),
                 float(deck(run, "ship", "block_coefficient")),
                 float(bem_mesh.SHIP_SECTION_EXPONENT), "Table 1's lines (&ship)")


def _deck_plan(xi, xi_p):
    """Half-breadth of the deck line in B/2 at xi = 2x/L: the waterline's parabolic ends
    from a longer parallel part (flare), and no less than the transom aft."""
    xi_d = xi_p + SHIP_DECK_FULLNESS * (1.0 - xi_p)
    u = np.abs(xi)
    plan = np.where(u <= xi_d, 1.0, 1.0 - ((u - xi_d) / (1.0 - xi_d)) ** 2)
    return np.where(xi < 0, np.maximum(plan, SHIP_TRANSOM), np.clip(plan, 0.0, 1.0))


def ship_hull_lines(run, lines=None):
    """The ship's hull from its lines (ship frame, z down): SHIP_STATIONS closed sections
    (rings), each from the keel up the starboard side to the deck edge and back down the
    port side; below the waterline the BEM ship form (bem_mesh.ship_halfbreadth), above it
    the waterline's breadth flaring out to the deck line (_deck_plan) at the moulded depth.
    Returns (points (stations, ring, 3), zone of each ring edge (ring - 1,))."""
    lines = lines or hull_lines(run)
    nb, na = SHIP_LEVELS
    x0, waterline = -deck(run, "ship", "cg_x"), -deck(run, "ship", "cg_z")
    freeboard = float(deck(run, "ship", "depth")) - lines.draught
    xi_p = bem_mesh.ship_form(lines.block_coefficient, lines.exponent)
    zeta = np.sin(0.5 * np.pi * np.linspace(1.0, 0.0, nb + 1))      # keel (1) to waterline
    rise = np.linspace(0.0, 1.0, na + 1)[1:]                         # waterline to deck
    rings = []
    for xi in -np.cos(np.pi * np.linspace(0.0, 1.0, SHIP_STATIONS)):
        x = 0.5 * lines.length * xi
        below = bem_mesh.ship_halfbreadth(x, -zeta * lines.draught, lines.length, lines.beam,
                                          lines.draught, lines.block_coefficient, lines.exponent)
        top = 0.5 * lines.beam * _deck_plan(xi, xi_p)
        above = below[-1] + (top - below[-1]) * rise ** 1.5
        half = np.r_[below, above]
        z = np.r_[waterline + zeta * lines.draught, waterline - rise * freeboard]
        side = np.stack([np.full_like(z, x0 + x), half, z], axis=1)
        port = side[::-1] * [1.0, -1.0, 1.0]
        rings.append(np.vstack([side, port]))
    zone = np.r_[np.full(nb, BOTTOM), np.full(na, TOPSIDES), DECK, np.full(na, TOPSIDES),
                 np.full(nb, BOTTOM)]
    return np.array(rings), zone


def ship_deck_halfbreadth(run, x, lines=None):
    """Half-breadth of the deck at x (ship frame): the box's B/2, or the deck line."""
    if ship_model(run) != "bem":
        return 0.5 * float(deck(run, "ship", "beam"))
    lines = lines or hull_lines(run)
    xi_p = bem_mesh.ship_form(lines.block_coefficient, lines.exponent)
    xi = np.clip(2.0 * (x + deck(run, "ship", "cg_x")) / lines.length, -1.0, 1.0)
    return 0.5 * lines.beam * float(_deck_plan(xi, xi_p))


def ship_deck_z(run):
    """The deck at the moulded depth above the keel (ship frame, z down)."""
    return float(-deck(run, "ship", "cg_z") + deck(run, "ship", "draught")
                 - deck(run, "ship", "depth"))


def davit_members(run, lines=None):
    """The davits as straight members [(start, end)] in the ship frame (z down): per head,
    a post from the deck (DAVIT_INBOARD inside its edge) up past the heads, an arm out to
    the head and a brace; a beam between the posts' tops that carries the lead sheave(s);
    a pedestal from the deck up to each winch drum."""
    heads = [deck(run, "rigging", "head_fore"), deck(run, "rigging", "head_aft")]
    lead, drum = deck(run, "rigging", "lead_sheave"), deck(run, "rigging", "drum_position")
    deck_z = ship_deck_z(run)
    top_z = min(min(h[2] for h in heads), lead[2]) - DAVIT_HEADROOM
    members, tops = [], []
    for head in heads:
        side = np.sign(head[1]) or 1.0
        y = side * (ship_deck_halfbreadth(run, head[0], lines) - DAVIT_INBOARD)
        foot, top = np.array([head[0], y, deck_z]), np.array([head[0], y, top_z])
        members += [(foot, top), (top, head), (foot + 0.55 * (top - foot), 0.5 * (top + head))]
        tops.append(top)
    members.append((np.r_[heads[0][0], lead[1], top_z], np.r_[heads[1][0], lead[1], top_z]))
    members += [(t, np.r_[t[0], lead[1], top_z]) for t in tops]
    if deck(run, "rigging", "reeving") == "a":
        drums = [drum]
    else:
        drums = [np.r_[h[0], drum[1:]] for h in heads]
    members += [(np.r_[d[:2], deck_z], d) for d in drums if d[2] < deck_z]
    return members


def prisms(members, width):
    """Square prisms of side `width` along members [(start, end)]: points (8 m, 3) and
    quads (6 m, 4) (4 sides and 2 ends each)."""
    points, quads = [], []
    for start, end in members:
        start, end = np.asarray(start, float), np.asarray(end, float)
        axis = (end - start) / max(np.linalg.norm(end - start), 1e-12)
        helper = np.array([0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
        u = np.cross(axis, helper)
        u *= 0.5 * width / np.linalg.norm(u)
        v = np.cross(axis, u)
        corners = [u + v, -u + v, -u - v, u - v]
        base = len(points)
        points += [start + c for c in corners] + [end + c for c in corners]
        a, b = list(range(base, base + 4)), list(range(base + 4, base + 8))
        quads += [[a[i], a[(i + 1) % 4], b[(i + 1) % 4], b[i]] for i in range(4)]
        quads += [a[::-1], b]
    return np.array(points), np.array(quads)


def boat_shape(run):
    """The lifeboat drawn (boat frame, z down): BOAT_SHAPE_STATIONS sections of BOAT_RING
    points, the model's hull (plan b(x) = B (1 - |2x/L|^p), flat bottom `keel` below the
    CG, vertical sides; src/boat/hull.f90) up to a gunwale at 45 % of `height`, and above
    it a canopy narrowing to a roof at `height` above the keel (a totally enclosed boat)."""
    length, beam = deck(run, "boat", "length"), deck(run, "boat", "beam")
    keel, height = deck(run, "boat", "keel"), deck(run, "boat", "height")
    p = deck(run, "boat", "breadth_exponent")
    x = 0.5 * length * np.sin(0.5 * np.pi * np.linspace(-1.0, 1.0, BOAT_SHAPE_STATIONS))
    half = 0.5 * beam * (1 - np.abs(2 * x / length) ** p)
    # (breadth fraction, height fraction) from the starboard keel round to the port keel
    ring = [(1.0, 0.0), (1.0, 0.45), (0.85, 0.75), (0.45, 1.0)]
    ring = ring + [(-f, h) for f, h in ring[::-1]]
    return np.array([[xi, f * hi, keel - h * height] for xi, hi in zip(x, half)
                     for f, h in ring])


def side_plane(run):
    """The contact side plane (4 corners, ship frame): y = &contact side_y over the
    waterline length, from the still waterline up to the deck (its freeboard)."""
    box = ship_box(run)
    side_y = run.deck("contact", "side_y", 0.5 * deck(run, "ship", "beam") + 0.1)
    x_lo, x_hi = box[:, 0].min(), box[:, 0].max()
    waterline, top = -deck(run, "ship", "cg_z"), box[:, 2].min()
    return np.array([[x_lo, side_y, waterline], [x_hi, side_y, waterline],
                     [x_hi, side_y, top], [x_lo, side_y, top]])


def boat_hull(run):
    """The boat's hull (BOAT_STATIONS sections of 4 corners, boat frame): the strip
    model's plan shape b(x) = B (1 - |2x/L|^p), keel `keel` below the CG, `height` deep."""
    length, beam = deck(run, "boat", "length"), deck(run, "boat", "beam")
    keel, height = deck(run, "boat", "keel"), deck(run, "boat", "height")
    p = deck(run, "boat", "breadth_exponent")
    x = np.linspace(-0.5 * length, 0.5 * length, BOAT_STATIONS)
    half = 0.5 * beam * (1 - np.abs(2 * x / length) ** p)
    return np.array([[xi, sy * hi, z] for xi, hi in zip(x, half)
                     for sy, z in ((-1, keel), (1, keel), (1, keel - height),
                                   (-1, keel - height))])


def hooks(run, frames):
    """Inertial hook positions (n, 2, 3), fore then aft."""
    local = [deck(run, "slings", "hook_fore"), deck(run, "slings", "hook_aft")]
    return boat_pose(run, frames).apply(local)


def fenders(run, frames):
    """Inertial end points (n, nf, 2, 3) of each fender's vertical span, boat frame
    (fender_x, fender_y, fender_z)."""
    xs = np.atleast_1d(deck(run, "contact", "fender_x"))
    y, (z0, z1) = float(deck(run, "contact", "fender_y")), deck(run, "contact", "fender_z")
    local = [[x, y, z] for x in xs for z in (z0, z1)]
    return boat_pose(run, frames).apply(local).reshape(len(frames), len(xs), 2, 3)


@dataclass
class Falls:
    """The falls and slings over the frames as polylines: points (n, m, 3), each point's
    kind (m), the segments as point index pairs (s, 2), each segment's tension (n, s) and
    whether it is a sling (s)."""
    points: np.ndarray
    kind: np.ndarray
    segments: np.ndarray
    tension: np.ndarray
    sling: np.ndarray


def _cable_nodes(run):
    """Reeving A or B as in src/rigging/falls.f90 build_reeving: per cable, the ship-frame
    nodes (drum, lead sheave, head sheave(s)) with None at each block (its index)."""
    h = np.array([0.5 * float(deck(run, "rigging", "head_spacing")), 0.0, 0.0])
    heads = [deck(run, "rigging", "head_fore"), deck(run, "rigging", "head_aft")]
    drum, lead = deck(run, "rigging", "drum_position"), deck(run, "rigging", "lead_sheave")
    if deck(run, "rigging", "reeving") == "a":
        return [[(DRUM, drum), (SHEAVE, lead), (SHEAVE, heads[0] - h), (BLOCK, 0),
                 (SHEAVE, heads[0] + h), (SHEAVE, heads[1] + h), (BLOCK, 1),
                 (DEAD_END, heads[1] - h)]]
    cables = []
    for a, head in enumerate(heads):
        side = np.sign(head[0]) * h
        cables.append([(DRUM, np.r_[head[0], drum[1:]]), (SHEAVE, np.r_[head[0], lead[1:]]),
                       (SHEAVE, head - side), (BLOCK, a), (DEAD_END, head + side)])
    return cables


def _polyline(columns, kinds, segments, tensions, slings, nodes, tension, sling):
    """Append a polyline of node columns (n, 3) to the Falls accumulators."""
    start = len(columns)
    for kind, column in nodes:
        columns.append(column)
        kinds.append(kind)
    for i in range(len(nodes) - 1):
        segments.append((start + i, start + i + 1))
        tensions.append(tension[:, i] if np.ndim(tension) == 2 else tension)
        slings.append(sling)


def falls(run, frames):
    """The cables (davit rigging: /rigging/segment_tension, cable 1 then 2) and the slings
    from each block down its lumps to its hook (tension: the hook segment's, the only one
    recorded); without the davit rigging, the two slings from their fixed anchors."""
    n = len(frames)
    hook = _sling_ends(run, frames)
    sling_tension = run.get(layout.SLING_TENSION)[frames]
    columns, kinds, segments, tensions, slings = [], [], [], [], []
    seg = run.get(layout.RIGGING_SEGMENT_TENSION)
    if seg is None:
        anchors = [deck(run, "slings", "anchor_fore"), deck(run, "slings", "anchor_aft")]
        for s in range(2):
            _polyline(columns, kinds, segments, tensions, slings,
                      [(ANCHOR, np.broadcast_to(anchors[s], (n, 3))), (HOOK, hook[:, s])],
                      sling_tension[:, s], True)
        return _assemble(columns, kinds, segments, tensions, slings)
    ship = ship_pose(run, frames)
    blocks = _block_positions(run, frames, hook)
    first = 0
    for cable in _cable_nodes(run):
        nodes = [(kind, blocks[:, where] if kind == BLOCK else ship.apply([where])[:, 0])
                 for kind, where in cable]
        _polyline(columns, kinds, segments, tensions, slings, nodes,
                  seg[frames][:, first:first + len(nodes) - 1], False)
        first += len(nodes) - 1
    lumps = run.get(layout.SLING_LUMPS)
    per_sling = 0 if lumps is None else lumps.shape[1] // 2
    for s in range(2):
        chain = [(BLOCK, blocks[:, s])]
        chain += [(LUMP, lumps[frames][:, s * per_sling + j]) for j in reversed(range(per_sling))]
        chain += [(HOOK, hook[:, s])]
        _polyline(columns, kinds, segments, tensions, slings, chain, sling_tension[:, s], True)
    return _assemble(columns, kinds, segments, tensions, slings)


def _sling_ends(run, frames):
    """The slings' lower ends: the hooks, and once released (/events/release_time) where
    the hooks let go, as the Fortran freezes the falls there (src/system/observables.f90)."""
    ends = hooks(run, frames)
    release = run.event(layout.RELEASE_TIME)
    if release is None or release > run.time[-1]:
        return ends
    at = int(np.searchsorted(run.time, release))
    after = run.time[frames] >= release
    ends[after] = hooks(run, np.array([min(at, len(run.time) - 1)]))[0]
    return ends


def _block_positions(run, frames, hook):
    """Recorded block positions, or (files from before /rigging/block_position) each block
    drawn on its hook, so the falls still end at the boat."""
    blocks = run.get(layout.RIGGING_BLOCKS)
    return hook if blocks is None else blocks[frames]


def _assemble(columns, kinds, segments, tensions, slings):
    return Falls(points=np.stack(columns, axis=1), kind=np.array(kinds),
                 segments=np.array(segments), tension=np.stack(tensions, axis=1),
                 sling=np.array(slings))


def has_sea(run):
    """Whether the file records its waves (/sea/components: sea runs, and launches in waves)."""
    return run.has(layout.SEA_OMEGA, layout.SEA_K, layout.SEA_DIRECTION, layout.SEA_AMPLITUDE,
                   layout.SEA_PHASE)


def sea_elevation(run, t, x, y):
    """Surface elevation eta (up) at (x, y) and time t: the recorded wave components where
    the file has them, else the still water (0)."""
    if not has_sea(run):
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)
    return layout.sea_elevation(run, t, x, y)


def frame_indices(run, every):
    """The sample indices drawn: every `every`-th, from the first."""
    if every < 1:
        raise ValueError(f"--every must be >= 1 (got {every})")
    return np.arange(0, len(run.time), every)
