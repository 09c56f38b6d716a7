"""random_walk, compare, exact_variance and pathtrace through the module: names from the one method table,
results against the direct solve as hypothesis tests."""
import numpy as np
import pytest
from scipy.stats import norm

import radwalk
from conftest import mesh, run_cli, without_run_id

ALPHA = 1e-3  # family-wise significance level of each test below (Sidak over its checks)


def sidak_z(alpha, m):
    """Two-sided normal quantile for m checks at family-wise level alpha."""
    return norm.ppf(1 - (1 - (1 - alpha) ** (1 / m)) / 2)


def test_gathering_walks_agree_with_the_direct_solve():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    ff = radwalk.form_factors(scene, rays=400, seed=1)
    exact = radwalk.solve(scene, ff, solver="direct").B
    walk = radwalk.random_walk(scene, ff, method="gather-collision", walks_per_patch=2000, seed=11)
    z = (walk.B - exact) / walk.B_se
    assert np.abs(z).max() < sidak_z(ALPHA, z.size)


def test_exact_variance_is_the_variance_the_walks_report():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    ff = radwalk.form_factors(scene, rays=400, seed=1)
    for method in radwalk.walk_methods():
        exact = radwalk.exact_variance(scene, ff, method=method)
        count = {"walks_per_patch": 50} if method.startswith("gather") else {"particles": 5000}
        walk = radwalk.random_walk(scene, ff, method=method, theory=True, **count)
        assert np.array_equal(exact, walk.var_theory)


def test_compare_runs_every_method_of_the_table():
    scene = radwalk.load(mesh("cube.obj"))
    c = radwalk.compare(scene, walks_per_patch=200, runs=2, seed=4)
    assert list(c.estimators) == radwalk.walk_methods()
    assert len(c.rows["patch"]) == len(radwalk.walk_methods()) * len(scene) * 3
    z = np.concatenate([e.z.ravel() for e in c.estimators.values()])
    z = z[np.isfinite(z)]
    assert np.abs(z).max() < sidak_z(ALPHA, z.size)
    assert c.B_reference.shape == (len(scene), 3)


def test_pathtrace_renders_an_image_as_a_float_array():
    scene = radwalk.load(mesh("cube.obj"))
    r = radwalk.pathtrace(scene, spp=4, image=True, width=16, height=12, averages=False)
    assert r.image.shape == (12, 16, 3) and r.image_se.shape == (12, 16, 3)
    assert np.isfinite(r.image).all() and r.averages is None


def test_control_variate_equals_the_cli(tmp_path):
    """random_walk(control_variate=True) is the CLI's --control-variate: the same CSV byte for byte."""
    common = ["--max-edge", 0.5, "--rays", 300, "--seed", 4]
    run_cli("solve", mesh("cube.obj"), *common, "--solver", "random-walk", "--walk", "gather", "--estimator",
            "expected-value", "--walks-per-patch", 500, "--control-variate", "--csv", tmp_path / "cli.csv")
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    ff = radwalk.form_factors(scene, rays=300, seed=4)
    walk = radwalk.random_walk(scene, ff, method="gather-expected-value", walks_per_patch=500, seed=4,
                               control_variate=True)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **walk.fields})
    cli = without_run_id(open(tmp_path / "cli.csv", "rb").read())
    assert cli == without_run_id(open(tmp_path / "py.csv", "rb").read())
    plain = radwalk.random_walk(scene, ff, method="gather-expected-value", walks_per_patch=500, seed=4)
    assert not np.array_equal(plain.B, walk.B)  # the flag changes the walks
    with pytest.raises(radwalk.InputError, match="gathering"):
        radwalk.random_walk(scene, ff, method="shoot-collision", control_variate=True)


@pytest.mark.parametrize("kernel, flags, options", [
    ("matrix", ["--sampler", "sobol", "--replicates", 5, "--direct-light"],
     {"sampler": "sobol", "replicates": 5, "direct_light": True}),
    ("ray", ["--sampler", "jacobi", "--replicates", 3, "--direct-light", "--shadow-rays", 48],
     {"sampler": "jacobi", "replicates": 3, "direct_light": True, "shadow_rays": 48}),
])
def test_shooting_sampler_options_equal_the_cli(tmp_path, kernel, flags, options):
    """random_walk(sampler=, replicates=, direct_light=, shadow_rays=) are the CLI's --sampler, --replicates,
    --direct-light and --shadow-rays: the same CSV byte for byte, on either kernel."""
    rays = ["--rays", 300] if kernel == "matrix" else []  # the ray kernel stores no F: --rays does not apply
    run_cli("solve", mesh("cube.obj"), "--max-edge", 0.5, *rays, "--seed", 4, "--solver", "random-walk",
            "--walk", "shoot", "--estimator", "collision", "--kernel", kernel, "--particles", 6000, *flags,
            "--csv", tmp_path / "cli.csv")
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.5)
    fields = {}
    F = None
    if kernel == "matrix":
        F = radwalk.form_factors(scene, rays=300, seed=4)
        fields.update(F.diagnostics)
    walk = radwalk.random_walk(scene, F, method="shoot-collision", kernel=kernel, particles=6000, seed=4, **options)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**fields, **walk.fields})
    cli = without_run_id(open(tmp_path / "cli.csv", "rb").read())
    assert cli == without_run_id(open(tmp_path / "py.csv", "rb").read())
    plain = radwalk.random_walk(scene, F, method="shoot-collision", kernel=kernel, particles=6000, seed=4)
    assert not np.array_equal(plain.B, walk.B)  # the options change the particles


def test_shooting_sampler_options_are_checked_as_the_cli():
    scene = radwalk.load(mesh("cube.obj"))
    with pytest.raises(radwalk.InputError, match="did you mean"):
        radwalk.random_walk(scene, method="shoot-collision", sampler="sobl")
    with pytest.raises(radwalk.InputError, match="--sampler sobol or jacobi"):
        radwalk.random_walk(scene, method="shoot-collision", direct_light=True)
    with pytest.raises(radwalk.InputError, match="--replicates 1"):
        radwalk.random_walk(scene, method="shoot-collision", sampler="sobol", replicates=1)
