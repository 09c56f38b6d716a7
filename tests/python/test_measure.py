"""radwalk.measure against `radwalk measure --json`: the same M, standard error and variances on the same seed."""
import json

import numpy as np
import pytest

import radwalk
from conftest import mesh, run_cli

SCENE = mesh("cornell_box.obj")
RAYS, SEED = 300, 5


@pytest.fixture(scope="module")
def scene():
    return radwalk.load(SCENE)


@pytest.fixture(scope="module")
def ff(scene):
    return radwalk.form_factors(scene, rays=RAYS, seed=SEED)


def cli_measurement(tmp_path, *args):
    out = tmp_path / "m.json"
    # The ray kernel stores no form factors: --rays does not apply there (the CLI refuses it).
    rays = [] if "ray" in args else ["--rays", RAYS]
    run_cli("measure", SCENE, *rays, "--seed", SEED, *args, "--json", out)
    return json.load(open(out))


def without_seconds(d):
    """The times differ from run to run."""
    return {k: v for k, v in d.items() if k != "seconds"}


def same(a, b):
    """Equal arrays, null (JSON) and NaN alike: the CLI's JSON prints every double exactly (17 digits)."""
    return np.array_equal(np.array([np.nan if v is None else v for v in a], dtype=float), np.asarray(b, dtype=float),
                          equal_nan=True)


@pytest.mark.parametrize("method, response, extra", [
    ("direct", "material:white", {}),
    ("adjoint-direct", "patches:0,3,7", {}),
    ("gather-collision", "material:white", {"walks": 3000, "theory": True}),
    ("shoot-survival", "material:red", {"walks": 3000, "theory": True}),
    ("gather-expected-value", "material:white", {"walks": 500, "kernel": "ray"}),
    ("importance-gather", "material:green", {"walks": 500, "importance_sweeps": 2, "theory": True}),
    ("importance-shoot", "camera", {"walks": 500, "width": 32, "height": 24}),
])
def test_measure_equals_the_cli(scene, ff, tmp_path, method, response, extra):
    flags = {"walks": "--walks", "kernel": "--kernel", "importance_sweeps": "--importance-sweeps",
             "width": "--width", "height": "--height"}
    args = ["--method", method, "--response", response]
    for k, v in extra.items():
        args += ["--theory"] if k == "theory" else [flags[k], v]
    cli = cli_measurement(tmp_path, *args)
    m = radwalk.measure(scene, response, ff, method=method, seed=SEED, **extra)
    j = cli["measurement"]
    assert same(j["M"], m.M)
    assert without_seconds(m.metadata["measurement"]) == without_seconds(j)  # every key and value
    assert m.response == j["response"]
    # M_se covers the form factors' noise (traced here) and the walks'; the parts are in error_estimate.
    assert m.metadata.get("error_estimate") == cli.get("error_estimate")
    parts = cli.get("error_estimate", {}).get("statistical", {})
    if m.deterministic:
        assert same(j["M_se"], m.M_se) and same(parts["form_factors_M_se"], m.M_se) and np.all(m.M_se > 0)
    else:
        assert same(j["M_se"], m.M_se) and same(j["var_per_walk"], m.var_per_walk)
        assert j["walks_total"] == m.walks_total and j["steps"] == m.steps
        if "var_per_walk_theory" in j:
            assert same(j["var_per_walk_theory"], m.var_per_walk_theory)
    for key in ("importance", "camera"):
        assert m.metadata.get(key) == cli.get(key)


def test_weights_as_an_array_measure_what_the_spec_does(scene, ff):
    spec = radwalk.measure(scene, "material:white", ff, method="direct")
    weights = radwalk.measure(scene, spec.R, ff, method="direct")
    assert np.array_equal(spec.M, weights.M)
    assert weights.response == "weights given in Python"


def test_the_exact_importance_has_zero_variance(scene, ff):
    direct = radwalk.measure(scene, "material:white", ff, method="direct")
    exact = radwalk.measure(scene, "material:white", ff, method="importance-shoot", walks=200)
    assert np.allclose(exact.M, direct.M, rtol=1e-12)
    walks_se = np.array(exact.metadata["error_estimate"]["statistical"]["walks_M_se"])
    assert np.all(walks_se < 1e-10 * direct.M)  # the walks' own part; M_se adds the form factors' noise
    assert np.allclose(exact.M_se, direct.M_se, rtol=1e-6)


def test_bad_responses_and_methods_raise_the_cli_message(scene, ff):
    with pytest.raises(ValueError, match="did you mean 'white'"):
        radwalk.measure(scene, "material:whte", ff)
    with pytest.raises(ValueError, match="did you mean 'adjoint-direct'"):
        radwalk.measure(scene, "patches:0", ff, method="adjoint-drect")
    with pytest.raises(ValueError, match="every weight is 0|all zero|0"):
        radwalk.measure(scene, np.zeros(len(scene)), ff)
    assert "adjoint-direct" in radwalk.measure_methods() and "shoot-survival" in radwalk.measure_methods()
