"""Scene.from_meshio and Result.to_meshio (Debian's python3-meshio): a meshio mesh solves as the same arrays do,
and a result goes out as cells with its fields as cell_data and comes back with the same patches."""
import math
import sys

import numpy as np
import pytest
import radwalk

import meshio  # noqa: E402  (Debian's python3-meshio: scripts/install-deps.sh installs it)

from test_from_arrays import parallel_squares_F  # noqa: E402  (the closed form of docs/reference-data.md)

# Two unit squares facing each other at distance 1 (z = 0 facing +z, z = 1 facing -z).
POINTS = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                   [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
QUADS = np.array([[0, 1, 2, 3], [4, 7, 6, 5]])


def squares(**cell_data):
    return meshio.Mesh(POINTS, [("quad", QUADS)], cell_data={k: [np.asarray(v)] for k, v in cell_data.items()})


def test_two_parallel_squares_from_meshio_give_the_closed_form_view_factor():
    scene = radwalk.Scene.from_meshio(squares(rho=[0.5, 0.5], E=[100.0, 0.0]), rho="rho", emission="E")
    assert len(scene) == 2 and np.allclose(scene.areas, 1.0)
    assert np.allclose(scene.E[:, 0], [100.0, 0.0]) and np.allclose(scene.rho, 0.5)
    rays = 100_000
    F_hat = radwalk.form_factors(scene, rays=rays, seed=11).F.toarray()
    F = parallel_squares_F()
    # Each row is `rays` independent cosine-weighted rays, so F_ij is a binomial proportion with standard error
    # sqrt(F (1 - F) / rays). Two z-tests (F_01, F_10), family-wise alpha = 1e-3 with Sidak's correction:
    # per test alpha = 1 - (1 - 1e-3)^(1/2), |z| <= 3.4808 (two-sided).
    se = math.sqrt(F * (1 - F) / rays)
    z_crit = 3.4808
    for i, j in ((0, 1), (1, 0)):
        z = (F_hat[i, j] - F) / se
        assert abs(z) <= z_crit, (i, j, F_hat[i, j], F, z)
    # The same test rejects a wrong answer: the view factor of squares at distance 1.1 (0.176) is far outside.
    assert abs((F_hat[0, 1] - parallel_squares_F(1 / 1.1, 1 / 1.1)) / se) > z_crit


def test_from_meshio_is_from_arrays_of_the_concatenated_blocks():
    # A triangle block then a quad block: the faces in the order of mesh.cells; rho as an array over all faces.
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], dtype=float)
    mesh = meshio.Mesh(points, [("triangle", [[0, 1, 2], [0, 2, 3]]), ("quad", [[1, 4, 5, 2]])],
                       cell_data={"gmsh:physical": [np.array([7, 7]), np.array([9])]})
    a = radwalk.Scene.from_meshio(mesh, rho=[0.1, 0.2, 0.3], groups="gmsh:physical")
    b = radwalk.Scene.from_arrays(points, [[0, 1, 2], [0, 2, 3], [1, 4, 5, 2]], rho=[0.1, 0.2, 0.3],
                                  groups=["7", "7", "9"])
    for name in ("areas", "centroids", "normals", "rho", "E", "face", "group"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert a.groups == b.groups == ["7", "9"]


def test_from_meshio_refuses_what_is_not_a_surface_and_names_missing_cell_data():
    mesh = meshio.Mesh(POINTS, [("quad", QUADS), ("line", [[0, 1]])])
    with pytest.raises(radwalk.InputError, match=r"mesh.cells\[1\]: cells of type 'line' are not surface polygons"):
        radwalk.Scene.from_meshio(mesh, rho=0.5)
    with pytest.raises(radwalk.InputError, match=r"rho='reflectance': the mesh has no cell_data 'reflectance' "
                                                 r"\(it has: rho\)"):
        radwalk.Scene.from_meshio(squares(rho=[0.5, 0.5]), rho="reflectance")
    # Validation is from_arrays' own: a reflectance of 1 is refused as there.
    with pytest.raises(radwalk.InputError, match=r"outside \[0, 1\)|reflectance") as refused:
        radwalk.Scene.from_meshio(squares(rho=[1.0, 0.5]), rho="rho")
    with pytest.raises(radwalk.InputError) as same:
        radwalk.Scene.from_arrays(POINTS, QUADS, rho=[1.0, 0.5])
    assert str(refused.value).replace("<meshio>", "<arrays>") == str(same.value)


def test_to_meshio_round_trip_keeps_the_patches_their_areas_and_B():
    scene = radwalk.Scene.from_meshio(squares(rho=[0.5, 0.5], E=[100.0, 0.0]), rho="rho", emission="E",
                                      max_edge=0.5)
    ff = radwalk.form_factors(scene, rays=2000, seed=3)
    result = radwalk.random_walk(scene, ff, method="gather-collision", walks_per_patch=200, seed=3)
    mesh = result.to_meshio(scene)
    assert [c.type for c in mesh.cells] == ["quad"]
    cell = {k: np.concatenate(v) for k, v in mesh.cell_data.items()}
    assert np.array_equal(cell["B_rgb"], result.B)
    assert np.array_equal(cell["B"], result.B.mean(axis=1))
    assert np.array_equal(cell["B_se"], result.B_se)
    assert np.array_equal(cell["area"], scene.areas)
    assert np.array_equal(cell["patch"], np.arange(len(scene)))
    # Back through from_meshio: the same patches (areas, corners, rho, E), so the same seed gives the same B.
    again = radwalk.Scene.from_meshio(mesh, rho="rho", emission="E")
    assert len(again) == len(scene)
    for name in ("areas", "centroids", "normals", "rho"):
        assert np.array_equal(getattr(again, name), getattr(scene, name)), name
    # The same corners (the points may be numbered in another order).
    assert np.array_equal(again.points[again.corners], scene.points[scene.corners])
    # E goes through Ke = E / pi and back (E = pi Ke): equal to rounding.
    assert np.allclose(again.E, scene.E, rtol=1e-15, atol=0)
    B_again = radwalk.random_walk(again, radwalk.form_factors(again, rays=2000, seed=3), method="gather-collision",
                                  walks_per_patch=200, seed=3).B
    assert np.allclose(B_again, result.B, rtol=1e-12, atol=0)
    # A result written for another scene is refused.
    with pytest.raises(radwalk.InputError, match="pass the scene the result was computed on"):
        result.to_meshio(radwalk.Scene.from_meshio(squares(rho=[0.5, 0.5]), rho="rho"))


def test_mixed_triangles_and_quads_keep_the_patch_order():
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], dtype=float)
    scene = radwalk.Scene.from_arrays(points, [[0, 1, 2], [1, 4, 5, 2], [0, 2, 3]], rho=0.5, emission=[1, 0, 0])
    mesh = radwalk.solve(scene, rays=100, seed=1).to_meshio(scene)
    assert [c.type for c in mesh.cells] == ["triangle", "quad", "triangle"]
    assert np.array_equal(np.concatenate(mesh.cell_data["patch"]), [0, 1, 2])


def test_without_meshio_the_error_names_the_debian_package(monkeypatch):
    monkeypatch.setitem(sys.modules, "meshio", None)  # `import meshio` now raises ImportError
    with pytest.raises(ImportError, match="apt install python3-meshio"):
        radwalk.Scene.from_meshio(object(), rho=0.5)
