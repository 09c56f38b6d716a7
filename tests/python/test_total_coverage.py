"""Calibration of the total error B_err = sqrt(B_se^2 + B_disc^2) against the continuous radiosity
(docs/accuracy.md, "How accurate is my answer?").

The continuous reference is the path tracer's patch averages (with their own B_se); the discrete solutions use the
recommended route (1000 Sobol rays per patch, emitter columns) with independent seeds. A (patch, channel) value is
covered when |B - B_pt| <= 1.96 sqrt(B_err^2 + B_se_pt^2).

Hypothesis test: the discretisation error of a patch is nearly the same in every seed and its three channels move
together, so neither the seeds nor the channels are independent trials; the patches are. Each reflecting patch's
coverage score is the fraction of its (seed, channel) values covered, and the mean score over the patches is tested
against 95 % with the standard error from the patches' spread (a two-sided z-test at level 1e-3, |z| <= 3.29;
neighbouring patches' errors are correlated, which makes the test somewhat stricter than its level). Sharpness: the
area-weighted RMS of B_err over the RMS of the actual error (the path tracer's noise taken out) lies in [0.5, 2].
Measured at 360 patches (100 mm, the floor cut along the blocks): 0.958 +- 0.006 of the patches, sharpness 1.35;
without B_disc (the statistical part alone) 0.915 +- 0.010 (z = -3.41) and sharpness 0.71, so the test fails."""
import os
import subprocess
import sys

import numpy as np
import pytest

import radwalk

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
Z_CRITICAL = 3.29  # two-sided, level 1e-3


def coverage_and_sharpness(scene, spp, seeds):
    """The patches' mean coverage score, its standard error and the sharpness (above)."""
    pt = radwalk.pathtrace(scene, spp=spp, seed=999).averages
    B_pt, se_pt = np.asarray(pt.B), np.asarray(pt.B_se)
    A = np.asarray(scene.areas)
    keep = (np.asarray(scene.E).max(axis=1) == 0) & (np.asarray(scene.rho).min(axis=1) > 0) & (B_pt.min(axis=1) > 0)
    covered = np.zeros((int(keep.sum()), 3))
    error2 = estimate2 = 0.0
    for seed in seeds:
        r = radwalk.solve(scene, rays=1000, seed=seed)
        d = (np.asarray(r.B) - B_pt)[keep]
        err = np.asarray(r.B_err)[keep]
        covered += np.abs(d) <= 1.96 * np.sqrt(err ** 2 + se_pt[keep] ** 2)
        w = A[keep][:, None]
        error2 += float((w * (d ** 2 - se_pt[keep] ** 2)).sum())
        estimate2 += float((w * err ** 2).sum())
    score = covered.mean(axis=1) / len(seeds)
    return score.mean(), score.std(ddof=1) / np.sqrt(len(score)), np.sqrt(estimate2 / error2)


def check(scene, spp, seeds):
    mean, standard_error, sharpness = coverage_and_sharpness(scene, spp, seeds)
    z = (mean - 0.95) / standard_error
    assert abs(z) <= Z_CRITICAL, (mean, standard_error, z)
    assert 0.5 <= sharpness <= 2.0, sharpness


# The default patching (the floor cut along the blocks' footprints) at 200 mm (125 patches: 0.923 +- 0.014, z = -1.93)
# and 100 mm (360 patches), and the plain split at 200 mm (109 patches: 0.935 +- 0.015). At 200 mm the former cut
# (137 patches: whole chords, pieces fanned from their first corner) left slivers and wedges on the floor whose
# error B_disc underrated (0.883 +- 0.018, z = -3.65; the floor's pieces 0.83): the first case fails on it.
@pytest.mark.parametrize("max_edge, contact_cut", [(200, True), (100, True), (200, False)])
def test_B_err_covers_the_path_tracer_on_the_cornell_box(max_edge, contact_cut):
    scene = radwalk.load(os.path.join(ROOT, "meshes", "cornell_box.obj"), max_edge=max_edge, contact_cut=contact_cut)
    check(scene, spp=4096, seeds=range(1, 6))


def test_B_err_covers_the_path_tracer_on_the_furniture_room(tmp_path):
    subprocess.run([sys.executable, os.path.join(ROOT, "tests", "realmesh", "make_furniture_room.py"), str(tmp_path)],
                   check=True, stdout=subprocess.DEVNULL)
    scene = radwalk.load(str(tmp_path / "furniture_room.obj"), max_edge=0.5)  # cut along the contacts
    check(scene, spp=8192, seeds=range(1, 4))
