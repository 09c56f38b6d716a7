"""The Scene's numpy views, in-place edits of rho and E against edited MTL files, and F's zero-copy layout."""
import numpy as np
import pytest

import radwalk
from conftest import mesh, run_cli, without_run_id


def edit_mtl(path, material, key, values):
    """Rewrites `key` of `material` in the MTL beside path (as a user would in a text editor)."""
    mtl = path.with_suffix(".mtl")
    lines, current = [], None
    for line in mtl.read_text().splitlines():
        words = line.split()
        if words[:1] == ["newmtl"]:
            current = words[1]
        if current == material and words[:1] == [key]:
            line = key + " " + " ".join(repr(v) for v in values)
        lines.append(line)
    mtl.write_text("\n".join(lines) + "\n")


def test_views_describe_the_patches():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    n = len(scene)
    assert scene.areas.shape == (n,) and scene.centroids.shape == (n, 3) and scene.normals.shape == (n, 3)
    assert scene.face.shape == scene.material.shape == scene.group.shape == (n,)
    assert scene.areas.sum() == pytest.approx(scene.total_area, rel=1e-12)
    assert np.allclose(np.linalg.norm(scene.normals, axis=1), 1)
    assert scene.material.max() < len(scene.materials)
    with pytest.raises(ValueError):
        scene.areas[0] = 1  # geometry is read-only
    assert scene.rho.flags.writeable and scene.E.flags.writeable


def test_rho_set_per_material_solves_as_an_edited_MTL(cube, tmp_path):
    scene = radwalk.load(cube)  # before the edit
    edit_mtl(cube, "white", "Kd", (0.7, 0.6, 0.25))
    run_cli("solve", cube, "--seed", 5, "--csv", tmp_path / "cli.csv")
    ff = radwalk.form_factors(scene, seed=5)
    before = radwalk.solve(scene, ff).B.copy()
    scene.set_material("white", rho=(0.7, 0.6, 0.25))
    after = radwalk.solve(scene, ff)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **after.fields})
    assert without_run_id((tmp_path / "cli.csv").read_bytes()) == without_run_id((tmp_path / "py.csv").read_bytes())
    assert not np.array_equal(before, after.B)


def test_rho_and_E_edited_per_patch_in_place_solve_as_an_edited_MTL(cube, tmp_path):
    scene = radwalk.load(cube)
    edit_mtl(cube, "white", "Kd", (0.3, 0.4, 0.5))
    edit_mtl(cube, "light", "Ke", (2.0, 1.0, 0.5))
    run_cli("solve", cube, "--seed", 5, "--csv", tmp_path / "cli.csv")
    white = [m.name for m in scene.materials].index("white")
    light = [m.name for m in scene.materials].index("light")
    scene.rho[scene.material == white] = (0.3, 0.4, 0.5)
    scene.E[scene.material == light] = np.pi * np.array([2.0, 1.0, 0.5])
    ff = radwalk.form_factors(scene, seed=5)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **radwalk.solve(scene, ff).fields})
    assert without_run_id((tmp_path / "cli.csv").read_bytes()) == without_run_id((tmp_path / "py.csv").read_bytes())


def test_F_is_a_float32_csr_view_without_a_copy():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    ff = radwalk.form_factors(scene, rays=200)
    a, b = ff.F, ff.F
    assert a.dtype == np.float32 and a.indices.dtype == np.int32 and a.indptr.dtype == np.int32
    assert np.shares_memory(a.data, b.data) and np.shares_memory(a.indices, b.indices)
    assert a.shape == (len(scene), len(scene)) and a.nnz == ff.nnz
    assert not a.data.flags.writeable
    # Closed cube: every ray lands on a front face, so every row sums to 1 (up to float32 rounding).
    assert np.allclose(np.asarray(a.sum(axis=1)).ravel(), 1, atol=1e-5)
    del ff  # the views keep the C++ matrix alive
    assert np.isfinite(a.data).all()


def test_groups_follow_the_input_face_through_repairs(tmp_path):
    # A pentagon (triangulated into three faces by the reader: a repair) between two quads: the patches of the
    # third input face must get its own group, not that of the reader's third (repaired) face.
    obj = tmp_path / "groups.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\n"
                   "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                   "g first\nf 1 2 3 4\ng pentagon\nf 1 2 3 5 4\ng last\nf 6 7 8 9\n")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scene = radwalk.load(str(obj))
    names = [scene.groups[g] for g in scene.group]
    by_face = {int(f): {n for n, ff in zip(names, scene.face) if ff == f} for f in set(scene.face)}
    assert {f: len(v) for f, v in by_face.items()} == {0: 1, 1: 1, 2: 1}
    assert "first" in by_face[0].pop() and "pentagon" in by_face[1].pop() and "last" in by_face[2].pop()


def test_group_names_are_the_files_names_without_empty_duplicates(tmp_path):
    # `o desk` then `g top` declares the object alone too (no face is in it): only groups holding patches are
    # listed, named as the file names them.
    obj = tmp_path / "named.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                   "v 0 0 2\nv 1 0 2\nv 1 1 2\n"
                   "o desk\ng top\nf 1 2 3 4\no lamp\nf 5 6 7 8\ng shade\nf 9 10 11\n")
    scene = radwalk.load(str(obj))
    assert scene.groups == ["desk/top", "lamp", "lamp/shade"]
    assert [scene.groups[g] for g in scene.group] == ["desk/top", "lamp", "lamp/shade"]
    # --response group:NAME still finds them by the names the file gives.
    lit = radwalk.load(str(obj))
    lit.E[:] = 1.0
    m = radwalk.measure(lit, "group:lamp", F=radwalk.form_factors(lit, rays=100, seed=1), method="direct")
    assert m.response.startswith("group") and all(v > 0 for v in m.M)
