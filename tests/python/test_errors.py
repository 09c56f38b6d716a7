"""Errors map to exceptions carrying the CLI's one-line text (the CLI prints 'radwalk: error: TEXT', exit 2)."""
import pytest

import radwalk
from conftest import data, mesh, run_cli


def cli_error(*args):
    result = run_cli(*args, check=False)
    assert result.returncode == 2
    prefix = "radwalk: error: "
    line = result.stderr.strip().splitlines()[-1]
    assert line.startswith(prefix)
    return line[len(prefix):]


@pytest.mark.parametrize("scene, strict", [("no_such_scene.obj", False), (data("bad_index.obj"), False),
                                           (data("nan_coordinate.obj"), False), (data("missing_mtl.obj"), False),
                                           (data("pentagon.obj"), True)])
def test_load_raises_the_cli_message(scene, strict):
    with pytest.raises(ValueError) as error:
        radwalk.load(scene, strict=strict)
    assert isinstance(error.value, radwalk.InputError)
    assert str(error.value) == cli_error("check", scene, *(["--strict"] if strict else []))


def test_repairs_are_warnings():
    with pytest.warns(UserWarning):
        scene = radwalk.load(data("pentagon.obj"))
    assert scene.warnings


def test_bad_options_raise_value_errors_naming_the_choices():
    scene = radwalk.load(mesh("cube.obj"))
    with pytest.raises(ValueError, match="gather-collision"):
        radwalk.random_walk(scene, method="gather-colision")
    with pytest.raises(ValueError, match="walks"):
        radwalk.random_walk(scene, walks_per_patch=1)
    with pytest.raises(ValueError, match="solver"):
        radwalk.solve(scene, solver="gauss-seidl")
    with pytest.raises(ValueError):
        radwalk.form_factors(scene, rays=0)


def test_negative_rho_is_refused_by_the_solver():
    scene = radwalk.load(mesh("cube.obj"))
    scene.rho[0] = -0.5
    with pytest.raises(ValueError, match="rho"):
        radwalk.solve(scene)


def test_writers_refuse_to_overwrite_the_scene(cube):
    scene = radwalk.load(cube)
    with pytest.raises(ValueError):
        radwalk.write_csv(cube.with_suffix(".mtl"), scene)

