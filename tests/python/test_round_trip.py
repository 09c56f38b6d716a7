"""Round trips: the module's load, form factors and solvers give the CLI's outputs byte for byte on the same seed."""
import numpy as np
import pytest

import radwalk
from conftest import mesh, run_cli, without_run_id

SCENE = mesh("cube.obj")
MAX_EDGE, RAYS, SEED = 0.5, 400, 7
COMMON = ["--max-edge", MAX_EDGE, "--rays", RAYS, "--seed", SEED]


@pytest.fixture(scope="module")
def scene():
    return radwalk.load(SCENE, max_edge=MAX_EDGE)


@pytest.fixture(scope="module")
def ff(scene):
    return radwalk.form_factors(scene, rays=RAYS, seed=SEED)


def same_bytes(a, b):
    """Equal bytes, up to the CLI's run id (its only documented difference from the module's files)."""
    return without_run_id(open(a, "rb").read()) == without_run_id(open(b, "rb").read())


def test_form_factors_and_their_diagnostics_equal_the_cli(scene, ff, tmp_path):
    run_cli("formfactors", SCENE, *COMMON, "-o", tmp_path / "cli.mtx", "--csv", tmp_path / "cli.csv")
    radwalk.write_matrix_market(tmp_path / "py.mtx", ff, scene)
    radwalk.write_csv(tmp_path / "py.csv", scene, ff.diagnostics)
    assert same_bytes(tmp_path / "cli.mtx", tmp_path / "py.mtx")
    assert same_bytes(tmp_path / "cli.csv", tmp_path / "py.csv")


@pytest.mark.parametrize("solver", ["auto", "direct", "gauss-seidel", "jacobi"])
def test_solve_equals_the_cli(scene, ff, tmp_path, solver):
    run_cli("solve", SCENE, *COMMON, "--solver", solver, "--csv", tmp_path / "cli.csv")
    result = radwalk.solve(scene, ff, solver=solver)
    assert result.status == "converged"
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **result.fields})
    assert same_bytes(tmp_path / "cli.csv", tmp_path / "py.csv")


def test_solve_without_F_estimates_it_as_the_cli(scene, ff):
    assert np.array_equal(radwalk.solve(scene, rays=RAYS, seed=SEED).B, radwalk.solve(scene, ff).B)


@pytest.mark.parametrize("walk, estimator, count", [("gather", "collision", ["--walks-per-patch", 300]),
                                                    ("gather", "absorption", ["--walks-per-patch", 300]),
                                                    ("shoot", "survival", ["--particles", 20000])])
def test_random_walks_equal_the_cli(scene, ff, tmp_path, walk, estimator, count):
    run_cli("solve", SCENE, *COMMON, "--solver", "random-walk", "--walk", walk, "--estimator", estimator, *count,
            "--csv", tmp_path / "cli.csv")
    n = {"--walks-per-patch": "walks_per_patch", "--particles": "particles"}[count[0]]
    result = radwalk.random_walk(scene, ff, method=f"{walk}-{estimator}", seed=SEED, **{n: count[1]})
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **result.fields})
    assert same_bytes(tmp_path / "cli.csv", tmp_path / "py.csv")
    assert result.metadata["solution"]["walks_total"] == result.walks_total


def test_pathtrace_averages_equal_the_cli(scene, tmp_path):
    run_cli("pathtrace", SCENE, "--max-edge", MAX_EDGE, "--spp", 16, "--seed", SEED, "--csv", tmp_path / "cli.csv")
    result = radwalk.pathtrace(scene, spp=16, seed=SEED)
    radwalk.write_csv(tmp_path / "py.csv", scene, result.averages.fields)
    assert same_bytes(tmp_path / "cli.csv", tmp_path / "py.csv")  # vov_* columns included
    vov = result.averages.vov
    assert vov.shape == result.averages.B.shape and (vov >= 0).all() and (vov > 0).any()


def test_F_read_back_from_matrix_market_solves_the_same(scene, ff, tmp_path):
    radwalk.write_matrix_market(tmp_path / "F.mtx", ff, scene)
    again = radwalk.read_form_factors(tmp_path / "F.mtx", scene)
    assert np.array_equal(radwalk.solve(scene, again).B, radwalk.solve(scene, ff).B)


def test_a_scipy_matrix_solves_as_the_FormFactors_it_came_from(scene, ff):
    # F as scipy gives it (float32 CSR): converted back without a change.
    assert np.array_equal(radwalk.solve(scene, ff.F.copy()).B, radwalk.solve(scene, ff).B)


def test_the_thread_count_does_not_change_the_result(scene, ff):
    one = radwalk.random_walk(scene, ff, walks_per_patch=400, seed=3, threads=1)
    two = radwalk.random_walk(scene, ff, walks_per_patch=400, seed=3, threads=2)
    assert np.array_equal(one.B, two.B) and np.array_equal(one.var, two.var)


def test_metadata_uses_the_json_schema_of_the_cli(scene, ff, tmp_path):
    """Result.metadata carries the CLI's "solution" object under the same keys (docs/json-schema.md, version 2)."""
    import json
    run_cli("solve", SCENE, *COMMON, "--solver", "gauss-seidel", "--json", tmp_path / "cli.json")
    cli = json.load(open(tmp_path / "cli.json"))
    result = radwalk.solve(scene, ff, solver="gauss-seidel")
    assert result.metadata["schema_version"] == cli["schema_version"] == 2
    py, js = result.metadata["solution"], cli["solution"]
    assert set(py) == set(js) - {"mean_B"}  # mean_B: the CLI's summary line only
    timed = {"seconds", "factor_seconds"}
    assert {k: v for k, v in py.items() if k not in timed | {"info"}} == \
           {k: v for k, v in js.items() if k not in timed | {"info", "mean_B"}}
    assert "walks_total" in py and "walks" not in py
