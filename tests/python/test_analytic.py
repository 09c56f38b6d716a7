"""radwalk.form_factors(..., analytic=True): the CLI's --analytic from Python (docs/form-factors.md, "The analytic
route"): rows of the closed cube sum to 1, F is reciprocal, the per-row standard errors are 0 where every pair was
proven clear, the CLI's F is the same, and the ray options are refused."""
import numpy as np
import pytest

import radwalk
from conftest import mesh, run_cli


def test_analytic_cube_rows_sum_to_one_and_are_reciprocal():
    scene = radwalk.load(mesh("cube.obj"), max_edge=0.25)
    ff = radwalk.form_factors(scene, analytic=True)
    F = ff.F.toarray().astype(np.float64)
    assert np.allclose(F.sum(axis=1), 1, atol=1e-6)
    A = scene.areas
    G = A[:, None] * F
    assert np.allclose(G, G.T, rtol=2**-22, atol=0)
    assert np.all(ff.diagnostics["row_std_error"] == 0)
    assert ff.info["analytic_sampled_pairs"] == 0 and ff.info["analytic_clear_pairs"] > 0


def test_analytic_matches_the_cli(tmp_path):
    scene = radwalk.load(mesh("cornell_box.obj"), max_edge=200)
    ff = radwalk.form_factors(scene, analytic=True, seed=3)
    out = tmp_path / "F.mtx"
    run_cli("formfactors", mesh("cornell_box.obj"), "--max-edge", 200, "--analytic", "--seed", 3, "-o", out)
    import scipy.io
    G = scipy.io.mmread(str(out)).tocsr().astype(np.float32)
    assert np.array_equal(ff.F.toarray(), G.toarray())
    assert np.all(ff.diagnostics["row_std_error"] >= 0)


def test_analytic_refuses_ray_options():
    scene = radwalk.load(mesh("cube.obj"))
    for kwargs in ({"rays": 10}, {"rays_per_area": 5.0}, {"stratified": False}):
        with pytest.raises(ValueError, match="analytic"):
            radwalk.form_factors(scene, analytic=True, **kwargs)
    with pytest.raises(ValueError, match="power of 2"):
        radwalk.form_factors(scene, analytic=True, visibility_samples=100)
