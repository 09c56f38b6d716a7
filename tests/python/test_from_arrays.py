"""Scene.from_arrays: a mesh given as numpy arrays is validated and patched as the same mesh read from a file, and
solves to the closed form where there is one."""
import math
import re

import numpy as np
import pytest
import radwalk

# Two unit squares facing each other at distance 1 (z = 0 facing +z, z = 1 facing -z).
VERTICES = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                     [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=float)
FACES = np.array([[0, 1, 2, 3], [4, 7, 6, 5]])


def parallel_squares_F(X=1.0, Y=1.0):
    """The closed-form view factor between directly opposed X x Y rectangles at distance 1 (docs/reference-data.md)."""
    a = math.log(math.sqrt((1 + X * X) * (1 + Y * Y) / (1 + X * X + Y * Y)))
    b = X * math.sqrt(1 + Y * Y) * math.atan(X / math.sqrt(1 + Y * Y))
    c = Y * math.sqrt(1 + X * X) * math.atan(Y / math.sqrt(1 + X * X))
    return 2 / (math.pi * X * Y) * (a + b + c - X * math.atan(X) - Y * math.atan(Y))


def test_two_parallel_squares_from_arrays_solve_to_the_closed_form():
    rho, E = 0.5, 100.0
    scene = radwalk.Scene.from_arrays(VERTICES, FACES, rho=[rho, rho], emission=[E, 0.0])
    assert len(scene) == 2 and np.allclose(scene.areas, 1.0)
    assert np.allclose(scene.normals, [[0, 0, 1], [0, 0, -1]])
    rays = 100_000
    ff = radwalk.form_factors(scene, rays=rays, seed=7)
    B = radwalk.solve(scene, ff).B[:, 0]

    # Two bounces between the squares: B1 = E + rho F12 B2, B2 = rho F21 B1.
    def closed_form(F12, F21):
        B1 = E / (1 - rho * rho * F12 * F21)
        return np.array([B1, rho * F21 * B1])

    F = parallel_squares_F()
    assert F == pytest.approx(0.199824896, abs=1e-9)
    # Each row is R cosine-weighted rays, so each F_ij is a binomial proportion: se = sqrt(F (1 - F) / R), rows
    # independent. B's standard error by the delta method over the two rows; a two-sided z-test per patch at
    # alpha = 1e-3 (|z| < 3.29) with the fixed seed.
    se_F = math.sqrt(F * (1 - F) / rays)
    h = 1e-6
    dB_dF12 = (closed_form(F + h, F) - closed_form(F - h, F)) / (2 * h)
    dB_dF21 = (closed_form(F, F + h) - closed_form(F, F - h)) / (2 * h)
    se_B = np.sqrt((dB_dF12 * se_F) ** 2 + (dB_dF21 * se_F) ** 2)
    z = (B - closed_form(F, F)) / se_B
    assert np.all(np.abs(z) < 3.29), (B, closed_form(F, F), z)
    # And B is the exact solution of the traced F (the direct solve).
    F_hat = ff.F.toarray()
    assert B == pytest.approx(closed_form(F_hat[0, 1], F_hat[1, 0]), rel=1e-12)


def without_location(line):
    """A finding's text without where it is (FILE:LINE: or <arrays>:), which differs by design."""
    return re.sub(r"^(<arrays>|[^:]*\.obj)(:\d+)?: ", "", line)


def test_arrays_give_the_patches_and_findings_of_the_same_mesh_read_from_a_file(tmp_path):
    vertices = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0], [1, 3, 0],  # pentagon (a repair)
                         [3, 0, 0], [5, 0, 0], [5, 2, 0], [3, 2, 0],            # quad, split at max_edge
                         [0, 0, 2], [2, 0, 2], [0, 2, 2], [2, 2, 2]], float)    # a bow-tie (a crossing repair)
    faces = [[0, 1, 2, 4, 3], [5, 6, 7, 8], [9, 10, 11, 12]]
    rho = np.array([[0.5, 0.5, 0.5], [0.2, 0.4, 0.6], [0.5, 0.5, 0.5]])
    E = np.array([0.0, 3.0, 0.0])
    groups = ["roof", "", "roof"]
    with pytest.warns(UserWarning):
        from_arrays = radwalk.Scene.from_arrays(vertices, faces, rho, emission=E, groups=groups, max_edge=1.5)

    obj = tmp_path / "same.obj"
    lines = ["mtllib same.mtl"] + [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices]
    materials, names = [], []
    for f in range(len(faces)):
        key = (tuple(rho[f]), E[f])
        if key not in materials:
            materials.append(key)
        names.append(f"material_{materials.index(key)}")
    for f, corners in enumerate(faces):
        lines.append(f"g {groups[f]}" if groups[f] else "g")
        lines.append(f"usemtl {names[f]}")
        lines.append("f " + " ".join(str(v + 1) for v in corners))
    obj.write_text("\n".join(lines) + "\n")
    (tmp_path / "same.mtl").write_text("".join(
        f"newmtl material_{k}\nKd {r[0]!r} {r[1]!r} {r[2]!r}\nKe {e / math.pi!r} {e / math.pi!r} {e / math.pi!r}\n"
        for k, (r, e) in enumerate(materials)))
    with pytest.warns(UserWarning):
        from_file = radwalk.load(str(obj), max_edge=1.5)

    assert len(from_arrays) == len(from_file) > len(faces)
    for field in ("areas", "centroids", "normals", "face", "material", "rho", "E"):
        assert np.array_equal(getattr(from_arrays, field), getattr(from_file, field)), field
    assert [from_arrays.groups[g] for g in from_arrays.group] == [from_file.groups[g] for g in from_file.group]
    assert len(from_arrays.warnings) == len(from_file.warnings) >= 2
    assert [without_location(w) for w in from_arrays.warnings] == [without_location(w) for w in from_file.warnings]


def test_bad_arrays_are_refused_in_one_line_naming_the_face():
    with pytest.raises(radwalk.InputError, match=r"face 1.*bad vertex index"):
        radwalk.Scene.from_arrays(VERTICES, [[0, 1, 2, 3], [4, 7, 6, 99]], rho=0.5)
    with pytest.raises(radwalk.InputError, match="face 0.*at least 3"):
        radwalk.Scene.from_arrays(VERTICES, [[0, 1], [4, 7, 6, 5]], rho=0.5)
    with pytest.raises(radwalk.InputError, match="rho has shape"):
        radwalk.Scene.from_arrays(VERTICES, FACES, rho=[0.5, 0.5, 0.5])
    with pytest.raises(radwalk.InputError, match="vertices must be"):
        radwalk.Scene.from_arrays(VERTICES[:, :2], FACES, rho=0.5)
    with pytest.raises(radwalk.InputError, match="integers"):
        radwalk.Scene.from_arrays(VERTICES, FACES.astype(float), rho=0.5)
    with pytest.raises(radwalk.InputError, match=r"outside \[0, 1\)|reflectance"):
        radwalk.Scene.from_arrays(VERTICES, FACES, rho=1.5)
