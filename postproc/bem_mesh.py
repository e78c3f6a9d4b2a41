"""Hull meshes for the BEM database (`python -m postproc.bem build`).

All meshes are in Capytaine's frame: x forward, y to PORT, z UP, the calm waterline at
z = 0, the hull below it. The two built-in hulls are symmetric about the centreline and
about midship, so they are built as one quarter (x <= 0, y <= 0) mirrored twice
(Capytaine's ReflectionSymmetricMesh): the influence matrices then come in 4 blocks of a
quarter of the size, ~8x less work to build and ~16x less to factorise.

Each builder returns a `Hull`: the wetted mesh, the lid on the inner free surface
(removes the irregular frequencies; no DOF on it) and the hull's main dimensions.
"""
from dataclasses import dataclass, field

import numpy as np

# Table 1 of the paper: L_wl, L_pp, B, T, C_b
L_WL = 130.55
L_PP = 126.0
BEAM = 20.8
DRAUGHT = 4.4
BLOCK_COEFFICIENT = 0.68
# The paper's equivalent box (the Froude-Krylov box of eq. 42): l = sqrt(C_b) L_wl
BOX_LENGTH = float(np.sqrt(BLOCK_COEFFICIENT) * L_WL)
# Exponent m of the ship hull's section shape 1 - (depth/T)^m (see ship_hull)
SHIP_SECTION_EXPONENT = 6


@dataclass
class Hull:
    kind: str               # 'box', 'ship' or 'file'
    mesh: object            # capytaine mesh of the wetted hull (z <= 0)
    lid: object             # capytaine mesh of the lid, or None
    length: float           # waterline length [m]
    beam: float             # waterline beam [m]
    draught: float          # [m]
    lid_z: float            # lid position [m] (nan without a lid)
    extra: dict = field(default_factory=dict)   # hull-specific attributes

    @property
    def panels(self):
        return int(self.mesh.nb_faces)

    @property
    def lid_panels(self):
        return 0 if self.lid is None else int(self.lid.nb_faces)


def _even(n):
    return max(2, 2 * int(round(n / 2)))


def box_resolution(length, beam, draught, panels):
    """(nx, ny, nz) of a box mesh with about `panels` panels on the wetted hull: square-ish
    panels of side h on the bottom and sides, at least 4 panels over the draught (slightly
    finer vertically, where the pressure decays); nx and ny even for the symmetries."""
    best = None
    for h in np.geomspace(0.2, 20.0, 400)[::-1]:
        nx, ny = _even(length / h), _even(beam / h)
        nz = max(4, int(round(draught / (0.8 * h))))
        count = nx * ny + 2 * nz * (nx + ny)
        if best is None or abs(count - panels) < abs(best[3] - panels):
            best = (nx, ny, nz, count)
    return best[:3]


def _both_symmetries(quarter, name):
    from capytaine.meshes.symmetric_meshes import ReflectionSymmetricMesh
    half = ReflectionSymmetricMesh(quarter, plane="yOz", name=f"half_of_{name}")
    return ReflectionSymmetricMesh(half, plane="xOz", name=name)


def lid_position(length, beam, omega_max, g=9.81):
    """Lowest lid depth z < 0 (Capytaine's rule for a rectangular waterplane, with its 10 %
    margin) that keeps the lid's own irregular frequencies above omega_max."""
    p = np.hypot(1.0 / length, 1.0 / beam)
    arg = np.pi * g * p / omega_max**2
    if arg >= 1.0:
        return -np.inf  # any depth keeps them above omega_max
    return float(-0.9 * np.arctanh(arg) / (np.pi * p))


def _grid(n, cluster):
    """n + 1 points in [0, 1]: uniform (cluster 0), or blended with a spacing that refines
    towards 1 (cluster 1: towards the end; 2: towards both ends)."""
    s = np.linspace(0.0, 1.0, n + 1)
    if cluster == 1:
        t = np.sin(0.5 * np.pi * s)
    elif cluster == 2:
        t = 0.5 * (1.0 - np.cos(np.pi * s))
    else:
        return s
    return 0.5 * (s + t)


def _quads(p, q, r):
    """Quads of a structured patch whose vertices are p(i, j), q(i, j), r(i, j) (x, y, z)."""
    ni, nj = p.shape
    vertices = np.stack([p.ravel(), q.ravel(), r.ravel()], axis=1)
    idx = np.arange(ni * nj).reshape(ni, nj)
    faces = [[idx[i, j], idx[i + 1, j], idx[i + 1, j + 1], idx[i, j + 1]]
             for i in range(ni - 1) for j in range(nj - 1)]
    return vertices, faces


def _box_quarter(cpt, length, beam, draught, nx, ny, nz, cluster):
    """Quarter x <= 0, y <= 0 of the open box, panels refined towards the bilge and end
    edges and the waterline (the flow is singular at the sharp edges)."""
    cx = 1 if cluster else 0
    x = -0.5 * length * _grid(nx // 2, cx)
    y = -0.5 * beam * _grid(ny // 2, cx)
    z = -draught * (_grid(nz, 2 if cluster else 0))
    patches = []
    X, Y = np.meshgrid(x, y, indexing="ij")
    patches.append((_quads(X, Y, np.full_like(X, -draught)), (0.0, 0.0, -1.0)))   # bottom
    X, Z = np.meshgrid(x, z, indexing="ij")
    patches.append((_quads(X, np.full_like(X, y[-1]), Z), (0.0, -1.0, 0.0)))        # side
    Y, Z = np.meshgrid(y, z, indexing="ij")
    patches.append((_quads(np.full_like(Y, x[-1]), Y, Z), (-1.0, 0.0, 0.0)))        # end
    return _join_patches(cpt, patches, "quarter_of_box")


def _box_lid_quarter(cpt, length, beam, z, nx, ny, cluster):
    """Quarter of the lid at depth z on the bottom's grid (conforming with the hull)."""
    cx = 1 if cluster else 0
    X, Y = np.meshgrid(-0.5 * length * _grid(nx // 2, cx), -0.5 * beam * _grid(ny // 2, cx),
                       indexing="ij")
    return _join_patches(cpt, [(_quads(X, Y, np.full_like(X, z)), (0.0, 0.0, -1.0))],
                         "quarter_of_lid")


def _join_patches(cpt, patches, name):
    meshes = []
    for (vertices, faces), normal in patches:
        m = cpt.Mesh(vertices, faces)
        if np.dot(m.faces_normals[0], normal) < 0:
            m = cpt.Mesh(vertices, [f[::-1] for f in faces])
        meshes.append(m)
    if len(meshes) == 1:
        return meshes[0]
    return meshes[0].join_meshes(*meshes[1:], name=name)


def box_hull(length=BOX_LENGTH, beam=BEAM, draught=DRAUGHT, panels=2000, omega_max=2.0,
             lid=True, cluster=True):
    """Rectangular barge l x B x d, open at the waterline, panels refined towards its edges
    and the waterline. The lid lies on the bottom's grid at a z-level of the side panels
    (conforming with the hull), at mid-draught or, if that is deeper than lid_position
    allows for omega_max, the deepest level that it allows. (A lid at -0.1 d, or one with
    its own coarser grid, changed the sway and heave damping at 0.6-1 rad/s by 5-20 %
    against the no-lid solution; this one by <= 6 % at 4,000 panels and converges.)"""
    import capytaine as cpt
    nx, ny, nz = box_resolution(length, beam, draught, panels)
    mesh = _both_symmetries(_box_quarter(cpt, length, beam, draught, nx, ny, nz, cluster),
                            "box")
    lid_mesh, zl = None, float("nan")
    if lid:
        levels = -draught * _grid(nz, 2 if cluster else 0)
        allowed = levels[(levels >= lid_position(length, beam, omega_max))
                         & (levels >= -0.5 * draught - 1e-9) & (levels < 0.0)]
        zl = float(allowed.min()) if allowed.size else float(levels[1])
        lid_mesh = _both_symmetries(_box_lid_quarter(cpt, length, beam, zl, nx, ny, cluster),
                                    "lid")
    return Hull("box", mesh, lid_mesh, length, beam, draught, zl,
                extra={"resolution_x_y_z": np.array([nx, ny, nz], dtype=np.int32),
                       "panels_refined_to_edges": np.int32(cluster)})


def ship_form(block_coefficient, exponent=SHIP_SECTION_EXPONENT):
    """Parallel-midbody fraction xi_p of the ship hull: half-breadth
    y = B/2 X(xi) Z(zeta), xi = 2x/L, zeta = -z/T, X = 1 for |xi| <= xi_p and
    1 - ((|xi| - xi_p)/(1 - xi_p))^2 beyond, Z = 1 - zeta^m, so C_b = mean(X) mean(Z)
    = (xi_p + 2 (1 - xi_p)/3) m/(m + 1)."""
    xi_p = 3.0 * block_coefficient * (exponent + 1) / exponent - 2.0
    if not 0.0 <= xi_p < 1.0:
        raise ValueError(f"block coefficient {block_coefficient} out of reach of the ship form "
                         f"with section exponent {exponent}")
    return xi_p


def _ship_halfbreadth(x, z, length, beam, draught, xi_p, exponent):
    xi = np.abs(2.0 * x / length)
    fx = np.where(xi <= xi_p, 1.0, 1.0 - ((xi - xi_p) / (1.0 - xi_p))**2)
    fz = 1.0 - np.clip(-z / draught, 0.0, 1.0)**exponent
    return 0.5 * beam * np.clip(fx, 0.0, 1.0) * fz


def ship_halfbreadth(x, z, length=L_PP, beam=BEAM, draught=DRAUGHT,
                     block_coefficient=BLOCK_COEFFICIENT, exponent=SHIP_SECTION_EXPONENT):
    """Half-breadth of the ship hull (ship_hull's lines) at x from midship and z up from
    the waterline (z <= 0 below it; above it, the waterline's)."""
    return _ship_halfbreadth(np.asarray(x, float), np.minimum(np.asarray(z, float), 0.0),
                             length, beam, draught, ship_form(block_coefficient, exponent),
                             exponent)


def ship_resolution(length, beam, draught, panels):
    """(nx, nz) per side of the ship mesh: panels = 2 nx nz, aspect ~ length / girth."""
    girth = draught + beam / 2
    nz = max(4, int(round(np.sqrt(panels / 2 * girth / length))))
    nx = _even(panels / (2 * nz))
    return nx, nz


def ship_hull(length=L_PP, beam=BEAM, draught=DRAUGHT, block_coefficient=BLOCK_COEFFICIENT,
              panels=2000, omega_max=2.0, lid=True, exponent=SHIP_SECTION_EXPONENT):
    """Ship-shaped hull, fore-aft and port-starboard symmetric (see ship_form), meshed with
    panels clustered towards the bilge and the ends."""
    import capytaine as cpt
    xi_p = ship_form(block_coefficient, exponent)
    nx, nz = ship_resolution(length, beam, draught, panels)
    nxq = nx // 2
    # x from the stern (-L/2) to midship, finer at the end; zeta clustered at the keel
    x = -0.5 * length * np.cos(0.5 * np.pi * np.linspace(0.0, 1.0, nxq + 1))
    zeta = np.sin(0.5 * np.pi * np.linspace(0.0, 1.0, nz + 1))
    z = -draught * zeta
    X, Z = np.meshgrid(x, z, indexing="ij")
    Y = -_ship_halfbreadth(X, Z, length, beam, draught, xi_p, exponent)  # starboard = y < 0
    vertices = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    idx = np.arange((nxq + 1) * (nz + 1)).reshape(nxq + 1, nz + 1)
    faces = []
    for i in range(nxq):
        for j in range(nz):
            faces.append([idx[i, j], idx[i, j + 1], idx[i + 1, j + 1], idx[i + 1, j]])
    quarter = cpt.Mesh(vertices, faces, name="quarter_of_ship")
    # outward normals point to starboard (-y) on this quarter
    if np.mean(quarter.faces_normals[:, 1]) > 0:
        quarter = cpt.Mesh(vertices, [f[::-1] for f in faces], name="quarter_of_ship")
    mesh = _both_symmetries(quarter, "ship")
    lid_mesh, zl = None, float("nan")
    if lid:
        zl = max(lid_position(length * (xi_p + 2 * (1 - xi_p) / 3), beam, omega_max),
                 -0.5 * draught)
        lid_mesh = _both_symmetries(_ship_lid_quarter(cpt, length, beam, draught, xi_p,
                                                      exponent, zl, max(2, nxq // 3),
                                                      max(2, nz // 2)), "lid")
    cwp = xi_p + 2.0 * (1.0 - xi_p) / 3.0
    return Hull("ship", mesh, lid_mesh, length, beam, draught, zl,
                extra={"block_coefficient": block_coefficient, "parallel_midbody": xi_p,
                       "section_exponent": exponent, "waterplane_coefficient": cwp,
                       "resolution_x_z": np.array([nx, nz], dtype=np.int32)})


def _ship_lid_quarter(cpt, length, beam, draught, xi_p, exponent, z, nx, ny):
    """Quarter of the lid: the hull's section at depth z, from the centreline to the side,
    stopping one lid panel short of the stem (where the breadth goes to zero)."""
    # stop half a panel short of the stem, to keep a finite breadth at the end of the lid
    xs = -0.5 * length * (1.0 - 0.5 / nx) * np.cos(0.5 * np.pi * np.linspace(0.0, 1.0, nx + 1))
    vertices, faces = [], []
    for i, xv in enumerate(xs):
        yw = _ship_halfbreadth(np.array([xv]), np.array([z]), length, beam, draught, xi_p,
                               exponent)[0] * 0.98
        for j in range(ny + 1):
            vertices.append([xv, -yw * j / ny, z])
    vertices = np.array(vertices)
    for i in range(nx):
        for j in range(ny):
            a = i * (ny + 1) + j
            faces.append([a, a + 1, a + ny + 2, a + ny + 1])
    lid = cpt.Mesh(vertices, faces, name="quarter_of_lid")
    if np.mean(lid.faces_normals[:, 2]) > 0:
        lid = cpt.Mesh(vertices, [f[::-1] for f in faces], name="quarter_of_lid")
    return lid


def file_hull(path, omega_max=2.0, lid=True, file_format=None):
    """A mesh file Capytaine (or meshio) reads, in Capytaine's frame (z up, waterline z = 0);
    clipped to its immersed part, checked (postproc.bem_checks: closed below the waterline,
    normals outwards or flipped, a waterplane; MeshError otherwise); lid generated by
    Capytaine. The check's messages are in extra["mesh_checks"]."""
    import capytaine as cpt
    from .bem_checks import check_wetted_mesh
    mesh = cpt.load_mesh(path, file_format=file_format)
    mesh, messages = check_wetted_mesh(mesh.immersed_part())
    v = mesh.vertices
    length = float(v[:, 0].max() - v[:, 0].min())
    beam = float(v[:, 1].max() - v[:, 1].min())
    draught = float(-v[:, 2].min())
    lid_mesh, zl = None, float("nan")
    if lid:
        zl = max(lid_position(length, beam, omega_max), -0.5 * draught)
        # Capytaine's default lid panel is the hull's mean panel size, which left a slender
        # hull's waterplane (a Wigley model, B = 0.3 m) without a lid: panels of B/6 or finer
        for radius in (beam / 6.0, beam / 10.0, beam / 16.0):
            lid_mesh = mesh.generate_lid(z=zl, faces_max_radius=radius)
            if lid_mesh.nb_faces > 0:
                break
        if lid_mesh.nb_faces == 0:
            lid_mesh, zl = None, float("nan")
    return Hull("file", mesh, lid_mesh, length, beam, draught, zl,
                extra={"mesh_file": str(path), "mesh_checks": "; ".join(messages)})


# The lifeboat of the paper's section III.B with the plan shape of review G25: the &boat
# keys length, beam, breadth_exponent (src/boat/hull.f90); floating draught and CG height
# above the keel (&boat keel = 1.1: the keel 1.1 m below the CG) as issue 18 states them.
BOAT_LENGTH = 11.5               # [m] paper III.B
BOAT_BEAM = 2.8                  # [m] paper III.B
BOAT_BREADTH_EXPONENT = 4.3      # review G25: b(x) = B (1 - |2x/L|^4.3)
BOAT_DRAUGHT = 0.3175            # [m] rho V = 8,500 kg at rho = 1025 (lifeboat_draught)
BOAT_KEEL_TO_CG = 1.1            # [m] KG, review G25 (&boat keel)
BOAT_MASS = 8500.0               # [kg] paper III.B
BOAT_INERTIA = (25020.0, 51745.0, 51745.0)   # [kg m^2] paper III.B


def lifeboat_plan_coefficient(exponent=BOAT_BREADTH_EXPONENT):
    """Waterplane (= plan-area) coefficient of b(x) = B (1 - |2x/L|^p): int_0^1 (1 - s^p) ds
    = p/(p + 1) (0.811 for p = 4.3; review G25's A3 = 26.2 m^2)."""
    return exponent / (exponent + 1.0)


def lifeboat_draught(mass=BOAT_MASS, length=BOAT_LENGTH, beam=BOAT_BEAM,
                     exponent=BOAT_BREADTH_EXPONENT, rho=1025.0):
    """Floating draught of the wall-sided, flat-bottomed boat: m / (rho A_wp)."""
    return mass / (rho * length * beam * lifeboat_plan_coefficient(exponent))


def lifeboat_transverse_inertia(length=BOAT_LENGTH, beam=BOAT_BEAM,
                                exponent=BOAT_BREADTH_EXPONENT):
    """I_T = int b^3/12 dx = L B^3/12 int_0^1 (1 - s^p)^3 ds, the binomial sum
    1 - 3/(p+1) + 3/(2p+1) - 1/(3p+1) (the waterplane's second moment about the centreline)."""
    p = exponent
    shape = 1.0 - 3.0 / (p + 1) + 3.0 / (2 * p + 1) - 1.0 / (3 * p + 1)
    return length * beam**3 / 12.0 * shape


def lifeboat_longitudinal_inertia(length=BOAT_LENGTH, beam=BOAT_BEAM,
                                  exponent=BOAT_BREADTH_EXPONENT):
    """I_L = int x^2 b dx = L^3 B/4 int_0^1 s^2 (1 - s^p) ds = L^3 B/4 (1/3 - 1/(p + 3))."""
    return length**3 * beam / 4.0 * (1.0 / 3.0 - 1.0 / (exponent + 3.0))


def lifeboat_halfbreadth(x, length=BOAT_LENGTH, beam=BOAT_BEAM, exponent=BOAT_BREADTH_EXPONENT):
    return 0.5 * beam * np.clip(1.0 - np.abs(2.0 * np.asarray(x) / length)**exponent, 0.0, 1.0)


def lifeboat_resolution(length, beam, draught, panels):
    """(nx, ny, nz) of the lifeboat mesh (whole hull: nx along, ny across the bottom, nz
    over the draught; ~ nx (ny + 2 nz) panels), square-ish panels of side h on the bottom
    (ny across the midship beam), at least 4 over the draught, nx and ny even."""
    best = None
    for h in np.geomspace(0.02, 2.0, 400)[::-1]:
        nx, ny = _even(length / h), _even(beam / h)
        nz = max(4, int(round(draught / (0.8 * h))))
        count = nx * ny + 2 * nz * nx
        if best is None or abs(count - panels) < abs(best[3] - panels):
            best = (nx, ny, nz, count)
    return best[:3]


def _lifeboat_levels(draught, nz, z_split):
    """nz + 1 side levels from 0 down to -draught with z_split one of them (the lid's
    level), each of the two intervals clustered towards its ends (waterline, lid, bilge)."""
    if not -draught < z_split < 0.0:
        return -draught * _grid(nz, 2)
    n_up = int(np.clip(round(nz * -z_split / draught), 1, nz - 1))
    upper = z_split * _grid(n_up, 2)
    lower = z_split + (-draught - z_split) * _grid(nz - n_up, 2)
    return np.concatenate([upper, lower[1:]])


def _lifeboat_quarter(cpt, length, beam, exponent, x, y_frac, z, z_bottom, sides=True):
    """Quarter x <= 0, y <= 0 of the plan b(x) at depth z_bottom (bottom or lid) and, with
    sides, the vertical side at the levels z. x runs from midship (x[0] = 0) to the stem
    (x[-1] = -L/2, zero breadth): the last column of the plan is triangles meeting there."""
    yb = -lifeboat_halfbreadth(x, length, beam, exponent)
    nxq, nyq = len(x) - 1, len(y_frac) - 1
    vertices, faces = [], []
    index = {}

    def vid(key, point):
        if key not in index:
            index[key] = len(vertices)
            vertices.append(point)
        return index[key]

    def plan(i, j):
        if i == nxq:                                 # the stem: one vertex
            return vid(("p", i, 0), (x[i], 0.0, z_bottom))
        return vid(("p", i, j), (x[i], yb[i] * y_frac[j], z_bottom))

    for i in range(nxq):
        for j in range(nyq):
            if i + 1 == nxq:
                faces.append([plan(i, j), plan(i + 1, j), plan(i, j + 1)])
            else:
                faces.append([plan(i, j), plan(i + 1, j), plan(i + 1, j + 1), plan(i, j + 1)])
    patches = [((np.array(vertices), faces), (0.0, 0.0, -1.0))]
    if sides:
        vertices, faces, index = [], [], {}

        def side(i, k):
            yy = 0.0 if i == nxq else yb[i]
            return vid(("s", i, k), (x[i], yy, z[k]))

        for i in range(nxq):
            for k in range(len(z) - 1):
                faces.append([side(i, k), side(i, k + 1), side(i + 1, k + 1), side(i + 1, k)])
        patches.append(((np.array(vertices), faces), (0.0, -1.0, 0.0)))
    return _join_patches(cpt, patches, "quarter_of_lifeboat")


def lifeboat_hull(length=BOAT_LENGTH, beam=BOAT_BEAM, draught=BOAT_DRAUGHT,
                  exponent=BOAT_BREADTH_EXPONENT, panels=2000, omega_max=8.0, lid=True):
    """The G25 lifeboat: plan b(x) = B (1 - |2x/L|^p), vertical sides, flat bottom, open at
    the waterline, sharp stems at x = +-L/2 (wedges of half-angle atan(p B/L) = 46 deg).
    Panels refined towards the stems (cosine spacing along x), the bilge (across the
    bottom) and the waterline, bilge and lid (over the draught). The lid is the bottom's
    plan grid at the deepest level lid_position allows for omega_max (for 8 rad/s on this
    waterplane, -0.139 m; the boat's first irregular frequency without it is ~5.7 rad/s),
    or mid-draught if that is shallower, and the side grid has a node level there, so lid
    and hull conform as for the box."""
    import capytaine as cpt
    nx, ny, nz = lifeboat_resolution(length, beam, draught, panels)
    nxq, nyq = nx // 2, ny // 2
    x = -0.5 * length * _grid(nxq, 1)
    y_frac = _grid(nyq, 1)
    zl = float("nan")
    if lid:
        zl = max(lid_position(length * lifeboat_plan_coefficient(exponent), beam, omega_max),
                 -0.5 * draught)
    z = _lifeboat_levels(draught, nz, zl if lid else 0.0)
    mesh = _both_symmetries(_lifeboat_quarter(cpt, length, beam, exponent, x, y_frac, z,
                                              -draught), "lifeboat")
    lid_mesh = None
    if lid:
        lid_mesh = _both_symmetries(_lifeboat_quarter(cpt, length, beam, exponent, x, y_frac,
                                                      z, zl, sides=False), "lid")
    return Hull("lifeboat", mesh, lid_mesh, length, beam, draught, zl,
                extra={"breadth_exponent": exponent,
                       "plan_coefficient": lifeboat_plan_coefficient(exponent),
                       "resolution_x_y_z": np.array([nx, ny, nz], dtype=np.int32)})
