"""Meshes that the own-ship tests write themselves, and their closed-form hydrostatics.

The Wigley hull (parabolic form): half-breadth y = B/2 (1 - xi^2)(1 - zeta^2) with
xi = 2x/L in [-1, 1] and zeta = z/T in [-1, 0]. Its integrals in closed form:
  V    = int int 2y dx dz           = 4/9 L B T            (C_b = 4/9)
  A_wp = int 2y(x, 0) dx            = 2/3 L B
  I_T  = int (2/3) y(x, 0)^3 dx     = 4/105 L B^3          -> BM_T = I_T / V = 3/35 B^2/T
  I_L  = int x^2 2y(x, 0) dx        = 1/30 L^3 B           -> BM_L = I_L / V = 3/40 L^2/T
  z_B  = int int z 2y dx dz / V     = -3/8 T               -> KB = 5/8 T
The box L x B x T: V = L B T, A_wp = L B, BM_T = B^2/(12 T), BM_L = L^2/(12 T), KB = T/2.
"""
import numpy as np


def wigley_closed_forms(length, beam, draught):
    volume = 4.0 / 9.0 * length * beam * draught
    return {"volume": volume, "waterplane_area": 2.0 / 3.0 * length * beam,
            "bm_t": 3.0 / 35.0 * beam**2 / draught, "bm_l": 3.0 / 40.0 * length**2 / draught,
            "kb": 5.0 / 8.0 * draught}


def box_closed_forms(length, beam, draught):
    return {"volume": length * beam * draught, "waterplane_area": length * beam,
            "bm_t": beam**2 / (12.0 * draught), "bm_l": length**2 / (12.0 * draught),
            "kb": 0.5 * draught}


def _oriented(vertices, faces, outward):
    """Faces ordered so that each normal (right-hand rule) agrees with outward(centroid)."""
    out = []
    for f in faces:
        p = vertices[f]
        n = np.cross(p[2] - p[0], p[3] - p[1])
        out.append(f if np.dot(n, outward(p.mean(axis=0))) > 0 else f[::-1])
    return out


def wigley_faces(length, beam, draught, nx, nz):
    """(vertices, quads) of the wetted Wigley hull, outward normals, open at z = 0; the
    stations cosine-spaced (finer at the ends), the waterlines finer at the keel."""
    xi = -np.cos(np.pi * np.arange(nx + 1) / nx)
    zeta = -np.sin(0.5 * np.pi * np.arange(nz + 1) / nz)      # 0 .. -1
    vertices, faces = [], []
    index = {}
    for side in (-1.0, 1.0):
        for i, a in enumerate(xi):
            for j, c in enumerate(zeta):
                y = side * 0.5 * beam * (1 - a**2) * (1 - c**2)
                key = (i, j) if abs(y) < 1e-14 else (i, j, side)
                if key not in index:
                    index[key] = len(vertices)
                    vertices.append([0.5 * length * a, y, draught * c])
        for i in range(nx):
            for j in range(nz):
                ids = []
                for ii, jj in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                    key = (ii, jj) if (ii, jj) in index else (ii, jj, side)
                    ids.append(index[key])
                faces.append(ids)
    vertices = np.array(vertices)
    # a panel whose four corners collapse to two (at a stem on the keel) carries nothing
    faces = [f for f in faces if len(set(f)) >= 3]

    def outward(c):
        return np.array([0.0, np.sign(c[1]) if abs(c[1]) > 1e-12 else 0.0, -1e-3])
    return vertices, _oriented(vertices, faces, outward)


def box_faces(length, beam, draught, nx, ny, nz):
    """(vertices, quads) of the wetted box, outward normals, open at z = 0."""
    x = np.linspace(-0.5 * length, 0.5 * length, nx + 1)
    y = np.linspace(-0.5 * beam, 0.5 * beam, ny + 1)
    z = np.linspace(-draught, 0.0, nz + 1)
    vertices, faces = [], []

    def patch(points):
        base = len(vertices)
        ni, nj = points.shape[:2]
        vertices.extend(points.reshape(-1, 3))
        for i in range(ni - 1):
            for j in range(nj - 1):
                faces.append([base + i * nj + j, base + (i + 1) * nj + j,
                              base + (i + 1) * nj + j + 1, base + i * nj + j + 1])
    patch(np.stack(np.meshgrid(x, y, [-draught], indexing="ij"), -1)[:, :, 0])
    for yy in (y[0], y[-1]):
        patch(np.stack(np.meshgrid(x, [yy], z, indexing="ij"), -1)[:, 0])
    for xx in (x[0], x[-1]):
        patch(np.stack(np.meshgrid([xx], y, z, indexing="ij"), -1)[0])
    vertices = np.array(vertices, float)

    def outward(c):
        return c / np.array([length, beam, 2.0 * draught]) + np.array([0.0, 0.0, 0.25])
    return vertices, _oriented(vertices, faces, outward)


def write_obj(path, vertices, faces, inward=False):
    """Wavefront OBJ (1-based indices); inward reverses every face."""
    with open(path, "w") as f:
        for v in vertices:
            f.write(f"v {v[0]:.12g} {v[1]:.12g} {v[2]:.12g}\n")
        for face in faces:
            face = face[::-1] if inward else face
            f.write("f " + " ".join(str(k + 1) for k in face) + "\n")


if __name__ == "__main__":
    # python test/python/wigley.py OUT.obj [L B T NX NZ]: the parabolic Wigley hull, NX
    # stations and NZ waterlines a side (default the own-ship how-to's 3 x 0.3 x 0.1875 m,
    # 24 x 6: 288 panels)
    import sys
    args = sys.argv[1:]
    if not args:
        sys.exit("usage: python test/python/wigley.py OUT.obj [L B T NX NZ]")
    dims = [float(a) for a in args[1:4]] or [3.0, 0.3, 0.1875]
    counts = [int(a) for a in args[4:6]] or [24, 6]
    write_obj(args[0], *wigley_faces(*dims, *counts))
