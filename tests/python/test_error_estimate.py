"""radwalk.solve reports B_se from the traced form factors' noise (docs/accuracy.md), as the CLI does.

Hypothesis test: on the bundled cube at 0.5 patches per edge, over 40 seeds of 300 rays per patch, the spread of B
across seeds (the actual statistical error) against the mean reported B_se: the ratio of the pooled variances is
an F-like statistic; with 39 degrees of freedom per patch pooled over the patches its log lies within 0.35 of 0
unless B_se is off by more than about 20 % (a wide, stated acceptance band [0.7, 1.4] for the variance ratio, far
outside the pooled estimate's own noise of a few per cent)."""
import os

import numpy as np
import pytest

import radwalk

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def test_solve_B_se_matches_the_spread_over_seeds():
    scene = radwalk.load(os.path.join(ROOT, "meshes", "cube.obj"), max_edge=0.5)
    Bs, ses = [], []
    for seed in range(1, 41):
        r = radwalk.solve(scene, rays=300, seed=seed, threads=1)
        assert r.B_se is not None and r.B_se.shape == r.B.shape
        Bs.append(np.array(r.B))
        ses.append(np.array(r.B_se))
    Bs, ses = np.array(Bs), np.array(ses)
    reflecting = (np.asarray(scene.E).max(axis=1) == 0) & (np.asarray(scene.rho).max(axis=1) > 0)
    spread = Bs.var(axis=0, ddof=1)[reflecting].sum()
    reported = (ses ** 2).mean(axis=0)[reflecting].sum()
    assert 0.7 <= spread / reported <= 1.4, (spread, reported)


def test_solve_with_a_callers_matrix_has_no_B_se():
    scene = radwalk.load(os.path.join(ROOT, "meshes", "cube.obj"))
    F = radwalk.form_factors(scene, rays=200).F.copy()
    assert radwalk.solve(scene, F).B_se is None
    assert radwalk.solve(scene, radwalk.form_factors(scene, rays=200)).B_se is not None
