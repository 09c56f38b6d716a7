"""The path tracer's area-weighted sums carry the error of their patches' B_se (docs/accuracy.md).

Each sample of each patch draws from its own stream (pathtrace/patch_average.h), so the patch averages' errors are
independent and the standard error of a sum S_m = sum_{i in m} A_i B_i over the patches of material m is
sqrt(sum_i A_i^2 B_se_i^2). Hypothesis test: on the Cornell box at 328 patches, 40 seeds of 64 samples per patch;
for each material and channel the variance of S_m over the seeds against the mean claimed variance. Their ratio,
pooled over the 4 materials and 3 channels, is a chi-square over its degrees of freedom; counting the three
channels of a material as one (they share the paths: a conservative 4 x 39 = 156 degrees of freedom), it lies in
[0.66, 1.42] with probability 0.999 (chi2(156) quantiles 0.0005 and 0.9995 over 156). Correlated patches (1.5
times the claimed standard deviation, a variance ratio of 2.25) or a B_se off by the square root of the samples
would fall far outside."""
import os

import numpy as np

import radwalk

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SEEDS = 40
LOW, HIGH = 0.66, 1.42


def test_per_material_sums_scatter_as_their_patches_B_se_say():
    scene = radwalk.load(os.path.join(ROOT, "meshes", "cornell_box.obj"), max_edge=100)
    A = np.asarray(scene.areas)
    material = np.asarray(scene.material)
    groups = [material == m for m in np.unique(material)]
    sums, claimed = [], []
    for seed in range(1, SEEDS + 1):
        r = radwalk.pathtrace(scene, spp=64, seed=seed).averages
        B, se = np.asarray(r.B), np.asarray(r.B_se)
        sums.append([(A[g, None] * B[g]).sum(axis=0) for g in groups])
        claimed.append([((A[g, None] * se[g]) ** 2).sum(axis=0) for g in groups])
    sums, claimed = np.array(sums), np.array(claimed)
    ratio = (sums.var(axis=0, ddof=1) / claimed.mean(axis=0)).mean()
    assert LOW <= ratio <= HIGH, ratio
