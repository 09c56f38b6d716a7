"""radwalk.solve_adaptive against `radwalk solve --refine`: the same refined patches and B on the same seed."""
import json

import numpy as np

import radwalk
from conftest import mesh, run_cli, without_run_id

SCENE = mesh("cornell_box.obj")
ARGS = dict(refine_tol=0.3, steps=2, rays=400, seed=3)


def test_solve_adaptive_equals_the_cli(tmp_path):
    run_cli("solve", SCENE, "--refine", 0.3, "--refine-steps", 2, "--rays", 400, "--seed", 3,
            "--csv", tmp_path / "cli.csv", "--json", tmp_path / "cli.json")
    scene = radwalk.load(SCENE)
    a = radwalk.solve_adaptive(scene, **ARGS)
    assert len(scene) == 37  # the scene passed in is not changed
    radwalk.write_csv(tmp_path / "py.csv", a.scene, {**a.form_factors.diagnostics, "jump": a.jump, **a.result.fields})
    assert without_run_id(open(tmp_path / "cli.csv", "rb").read()) == open(tmp_path / "py.csv", "rb").read()
    cli = json.load(open(tmp_path / "cli.json"))
    assert cli["patches"] == len(a.scene)
    refine = a.result.metadata["refine"]
    assert refine["stop_reason"] == cli["refine"]["stop_reason"] == a.stop_reason
    strip = ("form_factor_seconds", "solve_seconds", "refine_seconds", "seconds")
    steps = [{k: v for k, v in s.items() if k not in strip} for s in cli["refine"]["steps"]]
    assert [{k: v for k, v in s.items() if k not in strip} for s in a.steps] == steps
    assert a.jump.shape == (len(a.scene),)
    assert a.result.metadata["patches"] == len(a.scene)


def test_the_refined_scene_keeps_materials_and_groups_and_can_be_re_solved():
    scene = radwalk.load(SCENE)
    a = radwalk.solve_adaptive(scene, **ARGS)
    assert len(a.scene) > len(scene)
    assert set(a.scene.face) == set(scene.face)
    for f in set(scene.face):  # every piece of an input face has that face's material and group
        assert set(a.scene.material[a.scene.face == f]) == set(scene.material[scene.face == f])
        assert set(a.scene.group[a.scene.face == f]) == set(scene.group[scene.face == f])
    # The refined mesh with its own F solves to the refinement's B.
    assert np.array_equal(radwalk.solve(a.scene, a.form_factors).B, a.result.B)


def test_options_out_of_range_raise():
    import pytest
    scene = radwalk.load(SCENE)
    with pytest.raises(ValueError):
        radwalk.solve_adaptive(scene, refine_tol=-1)
