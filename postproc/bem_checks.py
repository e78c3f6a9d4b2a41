"""Checks of a user's hull mesh and of its hydrostatics before a BEM solve
(`python -m postproc.bem build --mesh FILE`).

A wetted hull open at the waterline z = 0 and closed below it encloses, with its waterplane,
the displaced volume V. The divergence theorem gives V three ways over the wetted surface
alone, V = int x n_x dS = int y n_y dS = int z n_z dS (the waterplane adds nothing to any
of them: n_x = n_y = 0 and z = 0 there), with n the outward normal. So
- all three negative and equal: the normals point inwards (flipped, with a message);
- the three disagree: the mesh has a hole below the waterline or normals of mixed
  orientation (refused);
- no waterplane (its area ~ 0): the mesh is closed over the top, e.g. a deck at z = 0, or
  lies wholly below the water (refused).
The hull must float stably: GM_T and GM_L > 0 (KB + BM - KG), else refused with the
numbers, since the linear restoring of every later step (RAOs, time domain) would be
negative.
"""
import numpy as np

# relative disagreement of the three divergence-theorem volumes that counts as open
VOLUME_TOLERANCE = 0.02
# waterplane area below this fraction of V^(2/3): no waterplane
WATERPLANE_FLOOR = 1e-3


class MeshError(ValueError):
    """A hull mesh that cannot give a meaningful BEM database."""


def flipped(mesh):
    """The same mesh with every panel's vertex order (its normal) reversed."""
    import capytaine as cpt
    return cpt.Mesh(mesh.vertices, np.asarray(mesh.faces)[:, ::-1], name=mesh.name)


def check_wetted_mesh(mesh, tol=VOLUME_TOLERANCE):
    """(mesh with outward normals, list of messages); raises MeshError for a mesh that is
    not closed below the waterline, has no waterplane, or encloses no volume."""
    messages = []
    vx, vy, vz = (float(v) for v in mesh.volumes)
    volumes = np.array([vx, vy, vz])
    scale = np.max(np.abs(volumes))
    if scale <= 0.0 or not np.all(np.isfinite(volumes)):
        raise MeshError("the wetted mesh encloses no volume (is any of it below z = 0?)")
    if np.all(volumes < 0.0):
        mesh = flipped(mesh)
        volumes = -volumes
        messages.append(f"normals pointed into the hull (divergence-theorem volume "
                        f"{-vz:.6g} m^3): every panel flipped to point outwards")
    spread = (volumes.max() - volumes.min()) / volumes.max()
    if np.any(volumes <= 0.0) or spread > tol:
        raise MeshError(f"the wetted mesh is not closed below the waterline or its normals "
                        f"are of mixed orientation: its divergence-theorem volumes "
                        f"int x n_x, int y n_y, int z n_z are {volumes[0]:.6g}, "
                        f"{volumes[1]:.6g}, {volumes[2]:.6g} m^3 (they agree within "
                        f"{tol:.0%} for a closed hull)")
    area = float(mesh.waterplane_area)
    if not area > WATERPLANE_FLOOR * volumes[2]**(2.0 / 3.0):
        raise MeshError(f"the wetted mesh has no waterplane (area {area:.3g} m^2): it must "
                        f"be open at the waterline z = 0 (no deck panels there) and cross it")
    messages.append(f"mesh closed below the waterline: volumes {volumes[0]:.6g}, "
                    f"{volumes[1]:.6g}, {volumes[2]:.6g} m^3 (spread {spread:.2%})")
    return mesh, messages


def hydrostatics(mesh, cg):
    """Hydrostatics of the wetted mesh (open at z = 0, outward normals) about a CG in the
    mesh frame (z up): V, A_wp, centre of buoyancy, BM_T, BM_L, KB and GM_T, GM_L, with KB
    and KG measured from the keel (the mesh's lowest point)."""
    import capytaine as cpt
    body = cpt.FloatingBody(mesh=mesh, center_of_mass=np.asarray(cg, float))
    volume = float(body.disp_volume)
    cob = np.asarray(body.center_of_buoyancy, float)
    bm_t = float(body.transversal_metacentric_radius)
    bm_l = float(body.longitudinal_metacentric_radius)
    keel = float(np.min(mesh.vertices[:, 2]))
    zg = float(cg[2])
    return {"volume": volume, "waterplane_area": float(body.waterplane_area),
            "centre_of_buoyancy": cob, "bm_t": bm_t, "bm_l": bm_l,
            "kb": cob[2] - keel, "kg": zg - keel,
            "gm_t": cob[2] + bm_t - zg, "gm_l": cob[2] + bm_l - zg}


def check_stability(h):
    """Raise MeshError unless GM_T > 0 and GM_L > 0 (h: hydrostatics())."""
    for name, gm, bm in (("transverse", h["gm_t"], h["bm_t"]),
                         ("longitudinal", h["gm_l"], h["bm_l"])):
        if not gm > 0.0:
            raise MeshError(f"the hull is unstable: {name} GM = KB + BM - KG = "
                            f"{h['kb']:.4g} + {bm:.4g} - {h['kg']:.4g} = {gm:.4g} m <= 0 "
                            f"(lower the CG with --cg, or check the mesh's draught)")


def report(h):
    """One line per hydrostatic quantity, for the build's log."""
    return [f"displaced volume {h['volume']:.6g} m^3, waterplane area "
            f"{h['waterplane_area']:.6g} m^2",
            f"KB {h['kb']:.4g} m, BM_T {h['bm_t']:.4g} m, BM_L {h['bm_l']:.4g} m, "
            f"KG {h['kg']:.4g} m: GM_T {h['gm_t']:.4g} m, GM_L {h['gm_l']:.4g} m"]
