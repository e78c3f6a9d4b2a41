"""Your own ship from a mesh file (postproc.bem build --mesh): the mesh checks, the
hydrostatics against closed forms (a Wigley hull and a box the test writes), clear errors
for an unstable hull, defaults taken from the hull, and `bem rao`'s refusals."""
import copy
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

from postproc import bem_checks, bem_db, bem_mesh, bem_rao

import wigley

pytest.importorskip("capytaine")

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATABASE = ROOT / "input" / "ship_bem.nc"
# the Wigley III model's main dimensions (L/B = 10, L/T = 16)
L, B, T = 3.0, 0.3, 0.1875
CG_Z = -0.06            # KG = 0.1275 m: GM_T = KB + BM_T - KG = 0.1172 + 0.0411 - 0.1275 > 0


def _wigley(tmp_path, nx, nz, inward=False, name="wigley.obj"):
    path = tmp_path / name
    wigley.write_obj(path, *wigley.wigley_faces(L, B, T, nx, nz), inward=inward)
    return path


def _errors(hull, closed, cg=(0.0, 0.0, CG_Z)):
    h = bem_checks.hydrostatics(hull.mesh, cg)
    return {k: h[k] / closed[k] - 1.0 for k in closed}


def test_wigley_hydrostatics_converge_to_the_closed_forms(tmp_path):
    """V, A_wp, BM_T, BM_L and KB of the meshed Wigley hull against 4/9 LBT, 2/3 LB,
    3/35 B^2/T, 3/40 L^2/T, 5/8 T: within 0.2 % on 80 x 16 panels a side, and the error
    falls 4x when the panels halve (second order: flat panels on a curved hull)."""
    closed = wigley.wigley_closed_forms(L, B, T)
    coarse = _errors(bem_mesh.file_hull(_wigley(tmp_path, 40, 8), omega_max=10.0), closed)
    fine = _errors(bem_mesh.file_hull(_wigley(tmp_path, 80, 16, name="fine.obj"),
                                      omega_max=10.0), closed)
    for key in closed:
        assert abs(fine[key]) < 0.002, (key, fine[key])
        assert 3.5 < coarse[key] / fine[key] < 4.5, (key, coarse[key], fine[key])


def test_box_hydrostatics_match_the_closed_forms(tmp_path):
    """The box: V, A_wp and KB exact; BM_T and BM_L are the panel-centroid (midpoint rule)
    second moments, B^2/(12 T) (1 - 1/n_y^2) with n_y panels across (and n_x along)."""
    nx, ny, nz = 10, 6, 4
    path = tmp_path / "box.obj"
    wigley.write_obj(path, *wigley.box_faces(2.0, 1.0, 0.5, nx, ny, nz))
    closed = wigley.box_closed_forms(2.0, 1.0, 0.5)
    err = _errors(bem_mesh.file_hull(path, omega_max=10.0), closed, cg=(0.0, 0.0, 0.0))
    for key in ("volume", "waterplane_area", "kb"):
        assert abs(err[key]) < 1e-9, (key, err[key])
    assert err["bm_t"] == pytest.approx(-1.0 / ny**2, abs=1e-9)
    assert err["bm_l"] == pytest.approx(-1.0 / nx**2, abs=1e-9)


def test_inward_normals_are_flipped_with_a_message(tmp_path):
    out = bem_mesh.file_hull(_wigley(tmp_path, 20, 5, inward=True), omega_max=10.0)
    assert "normals pointed into the hull" in out.extra["mesh_checks"]
    reference = bem_mesh.file_hull(_wigley(tmp_path, 20, 5, name="out.obj"), omega_max=10.0)
    assert "normals pointed" not in reference.extra["mesh_checks"]
    np.testing.assert_allclose(out.mesh.faces_normals, reference.mesh.faces_normals,
                               atol=1e-12)
    assert bem_checks.hydrostatics(out.mesh, (0, 0, CG_Z))["volume"] > 0


def test_a_hole_below_the_waterline_is_refused(tmp_path):
    vertices, faces = wigley.wigley_faces(L, B, T, 20, 5)
    # drop the starboard panels of the middle stations: a hole in the side
    keep = [f for f in faces if not (abs(vertices[f][:, 0].mean()) < 0.3
                                     and vertices[f][:, 1].mean() < 0)]
    path = tmp_path / "holed.obj"
    wigley.write_obj(path, vertices, keep)
    with pytest.raises(bem_checks.MeshError, match="not closed below the waterline"):
        bem_mesh.file_hull(path, omega_max=10.0)


def test_a_hull_without_waterplane_is_refused(tmp_path):
    """A closed box wholly below the water (top at z = -0.2 m): no waterplane, so no
    heave, roll or pitch restoring."""
    vertices, faces = wigley.box_faces(2.0, 1.0, 0.5, 4, 2, 2)
    vertices = vertices - [0.0, 0.0, 0.2]
    x, y = np.linspace(-1.0, 1.0, 5), np.linspace(-0.5, 0.5, 3)
    base = len(vertices)
    lid = np.array([[a, b, -0.2] for a in x for b in y])
    top = [[base + i * 3 + j, base + (i + 1) * 3 + j, base + (i + 1) * 3 + j + 1,
            base + i * 3 + j + 1] for i in range(4) for j in range(2)]
    path = tmp_path / "submerged.obj"
    wigley.write_obj(path, np.vstack([vertices, lid]), faces + top)
    with pytest.raises(bem_checks.MeshError, match="no waterplane"):
        bem_mesh.file_hull(path, omega_max=10.0)


def test_unstable_hull_is_refused_by_build_with_its_numbers(tmp_path):
    """CG on the waterline: KG = T = 0.1875 m > KM = 5/8 T + 3/35 B^2/T = 0.1583 m."""
    mesh = _wigley(tmp_path, 20, 5)
    out = tmp_path / "never.nc"
    result = subprocess.run([sys.executable, "-m", "postproc.bem", "build", "--mesh",
                             str(mesh), "--cg", "0", "0", "0", "--omegas", "5", "-q", "-o",
                             str(out)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 1
    assert "unstable: transverse GM = KB + BM - KG" in result.stderr
    reported = float(re.search(r"= (-?[0-9.]+) m <= 0", result.stderr).group(1))
    # 20 x 5 panels a side: the closed form within 1 %
    assert reported == pytest.approx(5.0 / 8.0 * T + 3.0 / 35.0 * B**2 / T - T, rel=0.01)
    assert not out.exists()


def test_mesh_defaults_come_from_the_hull():
    """Gyradii of a --mesh hull: 0.38 B (roll) and 0.25 L (pitch, yaw) of that hull; the
    paper's 32.6375 m only for the paper's default box."""
    from postproc import bem_build
    hull = bem_mesh.Hull("file", None, None, L, B, T, float("nan"))
    radii, sources = bem_build.default_gyradii(hull)
    assert radii == pytest.approx((0.38 * B, 0.25 * L, 0.25 * L))
    assert sources[1] == "0.25 L of the hull"
    radii, _ = bem_build.default_gyradii(hull, (0.1, None, 0.9))
    assert radii == pytest.approx((0.1, 0.25 * L, 0.9))
    box = bem_mesh.Hull("box", None, None, bem_mesh.BOX_LENGTH, 20.8, 4.4, float("nan"))
    assert bem_build.default_gyradii(box, paper_box=True)[0][1] == pytest.approx(32.6375)


def test_bem_rao_refuses_negative_gm_instead_of_nan():
    result = subprocess.run([sys.executable, "-m", "postproc.bem", "rao", str(DATABASE),
                             "--gm", "-0.5", "--omegas", "0.5", "--headings-deg", "90"],
                            cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert result.returncode == 1
    assert "no roll restoring" in result.stderr and "GM -0.5 m <= 0" in result.stderr
    assert "nan" not in result.stdout.lower()


def test_one_heading_database_answers_only_its_heading():
    base = bem_db.Database(DATABASE)
    one = copy.copy(base)
    one.values = dict(base.values)
    k = int(np.argmin(np.abs(base.heading - np.pi)))
    one.values[bem_db.HEADING] = base.heading[k:k + 1]
    for name in (bem_db.EXCITATION_RE, bem_db.EXCITATION_IM):
        one.values[name] = np.asarray(base[name])[:, k:k + 1]
    xi, _ = bem_rao.raos(one, [0.6], [np.pi])
    ref, _ = bem_rao.raos(base, [0.6], [np.pi])
    np.testing.assert_allclose(xi, ref, rtol=1e-12)
    with pytest.raises(ValueError, match="covers the one heading 180 deg only"):
        bem_rao.raos(one, [0.6], [np.pi, 0.5 * np.pi])
