"""radwalk.solve_to_target_error against `radwalk solve --target-error`: the hierarchical route by default on both,
the uniform one with hierarchical=False and --target-route uniform (the same start: about 500 patches for a scene
loaded without max_edge or max_area); the same steps, patches and B on the same seed."""
import json

import numpy as np
import pytest

import radwalk
from conftest import mesh, run_cli

SCENE = mesh("cornell_box.obj")


def test_solve_to_target_error_equals_the_cli(tmp_path):
    run_cli("solve", SCENE, "--target-error", 0.03, "--target-route", "uniform", "--seed", 2, "--csv",
            tmp_path / "cli.csv", "--json", tmp_path / "cli.json")
    scene = radwalk.load(SCENE)
    r = radwalk.solve_to_target_error(scene, 0.03, seed=2, hierarchical=False)
    assert len(scene) == 37  # the scene passed in is not changed
    cli = json.load(open(tmp_path / "cli.json"))
    assert r.reached and cli["target_error"]["reached"] and cli["target_error"]["route"] == "uniform"
    assert cli["patches"] == len(r.scene) > 37  # started from about 500 patches, not the input faces
    assert [s["patches"] for s in cli["target_error"]["steps"]] == [s["patches"] for s in r.steps]
    rows = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True)
    B = np.asarray(r.result.B)
    # the CSV keeps 12 significant digits
    np.testing.assert_allclose(np.column_stack([rows["B_r"], rows["B_g"], rows["B_b"]]), B, rtol=1e-11, atol=0)
    # each material's mean (the default, as the CLI's --target-each material): the same groups and figures
    assert cli["target_error"]["each"] == "material"
    assert [g["name"] for g in r.groups] == [g["name"] for g in cli["target_error"]["groups"]] != []
    for a, b in zip(r.groups, cli["target_error"]["groups"]):
        assert a["total"] == pytest.approx(b["total"], rel=1e-9) and a["total"] <= 0.03


def test_each_material_or_none():
    scene = radwalk.load(SCENE)
    none = radwalk.solve_to_target_error(scene, 0.2, seed=1, each="none")
    assert none.groups == [] and none.result.metadata["target_error"]["each"] == "none"
    objects = radwalk.solve_to_target_error(scene, 0.2, seed=1, each="object")
    assert len(objects.groups) > 0 and all(g["total"] <= 0.2 for g in objects.groups)
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.2, each="colour")
    with pytest.raises(radwalk.InputError):  # the rays transport stores no F for a group's adjoint
        radwalk.solve_to_target_error(scene, 0.2, hierarchical=True, hierarchical_transport="rays", each="material")


@pytest.mark.parametrize("hierarchical", [True, False])
def test_a_scene_with_its_own_patching_starts_there(hierarchical):
    scene = radwalk.load(SCENE, max_edge=200)
    r = radwalk.solve_to_target_error(scene, 0.2, seed=1, hierarchical=hierarchical)
    assert r.steps[0]["patches"] == len(scene)


def test_options_out_of_range_raise():
    scene = radwalk.load(SCENE)
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 1.5)
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.03, discretisation_directions=0)


def test_the_contact_cut_comes_before_its_own_split(tmp_path):
    # load keeps the input faces as patches when it splits nothing, so nothing is cut; the target error splits them
    # itself and, as the CLI's --target-error, cuts along the contacts first (the default), or not with
    # contact_cut=False (--no-contact-cut): the same steps and patches as the CLI either way.
    for flags, kwargs in (([], {}), (["--no-contact-cut"], {"contact_cut": False})):
        run_cli("solve", SCENE, "--target-error", 0.2, "--seed", 1, *flags, "--json", tmp_path / "c.json")
        cli = json.load(open(tmp_path / "c.json"))
        scene = radwalk.load(SCENE, **kwargs)
        assert not scene.cut and len(scene) == 37
        r = radwalk.solve_to_target_error(scene, 0.2, seed=1)
        assert [s["patches"] for s in cli["target_error"]["steps"]] == [s["patches"] for s in r.steps]
        assert r.scene.cut == cli["contact_cut"] == (not kwargs)
    # rho edited on the Scene in place carries over to the pieces of the cut (none of the file's materials has 0.3).
    scene = radwalk.load(SCENE)
    scene.rho[:] = 0.3
    r = radwalk.solve_to_target_error(scene, 0.2, seed=1)
    assert r.scene.cut and np.all(np.asarray(r.scene.rho) == 0.3)


@pytest.mark.parametrize("transport", ["form-factors", "rays"])
def test_hierarchical_equals_the_cli(tmp_path, transport):
    """hierarchical=True (the default) is `radwalk solve --target-error` (its default route): the same steps, leaves
    and B on a seed, with either transport."""
    run_cli("solve", SCENE, "--target-error", 0.06, "--rays", 200, "--seed", 3,
            "--hierarchical-transport", transport, "--csv", tmp_path / "cli.csv", "--json", tmp_path / "cli.json")
    scene = radwalk.load(SCENE)
    r = radwalk.solve_to_target_error(scene, 0.06, rays=200, seed=3, hierarchical_transport=transport)
    cli = json.load(open(tmp_path / "cli.json"))
    assert r.reached and cli["target_error"]["reached"]
    assert [s["patches"] for s in cli["target_error"]["steps"]] == [s["patches"] for s in r.steps]
    assert cli["patches"] == len(r.scene)
    rows = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True)
    np.testing.assert_allclose(np.column_stack([rows["B_r"], rows["B_g"], rows["B_b"]]), np.asarray(r.result.B),
                               rtol=1e-11, atol=0)
    assert cli["target_error"]["transport"] == transport
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.06, tol=1e-6, hierarchical=True, hierarchical_transport="rays")
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.06, hierarchical=False, hierarchical_transport="rays")
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.06, hierarchical=True, hierarchical_transport="walks")


def test_hierarchical_split_equals_the_cli(tmp_path):
    """hierarchical_split="adaptive" is `--hierarchical-split adaptive`: the same steps, leaves and B on a seed;
    unknown names and the option with hierarchical=False are refused."""
    run_cli("solve", SCENE, "--hierarchical", "--target-error", 0.06, "--rays", 200, "--seed", 3,
            "--hierarchical-split", "adaptive", "--csv", tmp_path / "cli.csv", "--json", tmp_path / "cli.json")
    scene = radwalk.load(SCENE)
    r = radwalk.solve_to_target_error(scene, 0.06, rays=200, seed=3, hierarchical=True, hierarchical_split="adaptive")
    cli = json.load(open(tmp_path / "cli.json"))
    assert cli["hierarchy"]["split"] == "adaptive"
    assert [s["patches"] for s in cli["target_error"]["steps"]] == [s["patches"] for s in r.steps]
    assert cli["patches"] == len(r.scene)
    rows = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True)
    np.testing.assert_allclose(np.column_stack([rows["B_r"], rows["B_g"], rows["B_b"]]), np.asarray(r.result.B),
                               rtol=1e-11, atol=0)
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.06, hierarchical=True, hierarchical_split="bands")
    with pytest.raises(radwalk.InputError):
        radwalk.solve_to_target_error(scene, 0.06, hierarchical=False, hierarchical_split="adaptive")
