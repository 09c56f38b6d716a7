"""Calibration of B_se on the Cornell box (docs/accuracy.md, "How accurate is my answer?").

Hypothesis test: at 328 patches (--max-edge 100) and the recommended route (1000 Sobol rays per patch, emitter
columns), over 20 seeds, the fraction of the reflecting (patch, channel) values within 1.96 sqrt(B_se^2 +
B_se_ref^2) of a reference solved with 30 times the rays. The seeds' fractions are independent, so their mean is
tested against 95 % with the standard error from their spread (a two-sided z-test at level 1e-3, |z| <= 3.29); the
values within one seed are correlated, which the spread of the seeds' fractions takes into account. Sharpness:
the RMS of B_se over the RMS of the actual error lies in [0.5, 2] (the issue's band; its own noise over 20 seeds
is a few per cent)."""
import os

import numpy as np

import radwalk

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SEEDS = 20
Z_CRITICAL = 3.29  # two-sided, level 1e-3


def test_B_se_covers_the_discrete_solution_95_percent_of_the_time():
    scene = radwalk.load(os.path.join(ROOT, "meshes", "cornell_box.obj"), max_edge=100)
    ref = radwalk.solve(scene, radwalk.form_factors(scene, rays=30000, seed=999), discretisation_directions=0)
    B_ref, se_ref = np.asarray(ref.B), np.asarray(ref.B_se)
    keep = (np.asarray(scene.E).max(axis=1) == 0) & (np.asarray(scene.rho).max(axis=1) > 0)
    fractions, error2, se2 = [], 0.0, 0.0
    for seed in range(1, SEEDS + 1):
        r = radwalk.solve(scene, rays=1000, seed=seed, discretisation_directions=0)
        d = (np.asarray(r.B) - B_ref)[keep]
        se = np.asarray(r.B_se)[keep]
        fractions.append(float((np.abs(d) <= 1.96 * np.sqrt(se ** 2 + se_ref[keep] ** 2)).mean()))
        error2 += float((d ** 2).sum() - (se_ref[keep] ** 2).sum())
        se2 += float((se ** 2).sum())
    fractions = np.array(fractions)
    mean, standard_error = fractions.mean(), fractions.std(ddof=1) / np.sqrt(SEEDS)
    z = (mean - 0.95) / standard_error
    assert abs(z) <= Z_CRITICAL, (mean, standard_error, z)
    sharpness = np.sqrt(se2 / error2)
    assert 0.5 <= sharpness <= 2.0, sharpness
