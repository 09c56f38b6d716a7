"""scripts/patch_comparison.py's measured discretisation error: a run = truth + bias + its own noise, the reference =
truth + its noise, both noises stated (B_se) and Gaussian, so e_disc^2 must estimate the bias's relative squared
norm. A hypothesis test: fixed seed, two-sided significance 0.001 (z = 3.29), the tolerance from the variance of
the estimate, sum over values of (4 b^2 sigma^2 + 2 sigma^4) / size^2 with sigma^2 = s^2 + se^2. It fails if the
run's noise were not taken out: that adds s^2 = 2.25e-4 to e^2, 30 standard deviations."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.environ.get("RADWALK_SOURCE", os.path.join(os.path.dirname(__file__), "..", "..")),
                                "scripts"))
import patch_comparison as pc  # noqa: E402


def table(B, B_se, n):
    """A patch table as read_table returns it: unit areas, distinct centroids, one material."""
    key = np.zeros((n, 6))
    key[:, 0] = np.arange(n) + 1.0
    key[:, 5] = 1.0
    return {"B": B, "B_se": B_se, "B_err": B_se, "E": np.zeros((n, 3)), "rho": np.full((n, 3), 0.5), "area": np.ones(n),
            "key": key, "material": np.array(["m"] * n, dtype=object), "row": np.arange(n)}


def test_the_discretisation_error_estimates_the_bias_alone():
    n, s, se = 4000, 0.015, 0.005
    rng = np.random.default_rng(1)
    truth = np.ones((n, 3))
    bias = 0.02 * np.sqrt(2) * np.cos(np.arange(3 * n).reshape(n, 3))  # relative rms 0.02
    run = table(truth + bias + rng.normal(0, s, (n, 3)), np.full((n, 3), s), n)
    reference = table(truth + rng.normal(0, se, (n, 3)), np.full((n, 3), se), n)

    e_disc, _, e_stat = pc.measured_discretisation_error(run, reference)
    size2 = float((reference["B"] ** 2).sum())
    expected = float((bias ** 2).sum()) / size2
    sigma2 = s * s + se * se
    sd = np.sqrt(float((4 * bias ** 2 * sigma2 + 2 * sigma2 ** 2).sum())) / size2
    assert abs(e_stat - s * np.sqrt(3 * n / size2)) < 1e-12
    assert abs(e_disc ** 2 - expected) <= 3.29 * sd, (e_disc ** 2, expected, sd)
    e = pc.measured_error(run, reference)[0]
    assert e ** 2 - expected > 3.29 * sd  # the run's noise is in e: the test above can tell the two apart


def test_a_materials_mean_needs_no_matching_patches():
    """The same surface tiled otherwise by the reference (two unit patches against four of area 0.5, no centroid in
    common): the means are the area averages of each table's own patches, exactly; an emitter and a black patch are
    left out of both, and the reference's noise enters s_ref = sqrt(sum A^2 se^2) / (3 sum A)."""
    run = table(np.array([[1.0] * 3, [3.0] * 3]), np.full((2, 3), 0.1), 2)
    reference = table(np.array([[1.0] * 3, [1.0] * 3, [3.0] * 3, [3.3] * 3]), np.full((4, 3), 0.2), 4)
    reference["area"] = np.full(4, 0.5)
    reference["key"][:, 0] += 0.25  # no reference centroid equals a run's
    for t in (run, reference):  # an emitter and a black patch of the same material: counted in neither
        t["B"] = np.vstack([t["B"], [[9.0] * 3, [5.0] * 3]])
        t["B_se"] = t["B_err"] = np.vstack([t["B_se"], np.zeros((2, 3))])
        t["E"] = np.vstack([t["E"], [[1.0] * 3, [0.0] * 3]])
        t["rho"] = np.vstack([t["rho"], [[0.5] * 3, [0.0] * 3]])
        t["area"] = np.append(t["area"], [1.0, 1.0])
        t["material"] = np.append(t["material"], ["m", "m"]).astype(object)
        t["key"] = np.vstack([t["key"], [[100.0, 0, 0, 0, 0, 1], [101.0, 0, 0, 0, 0, 1]]])
        t["row"] = np.arange(len(t["B"]))
    assert pc.matched(run, reference)[2] == 2  # the two unit patches; the emitter and the black one match
    g = pc.material_means(run, reference)["m"]
    assert g.elements == 2
    assert abs(g.mean - 2.0) < 1e-12 and abs(g.mean_ref - 2.075) < 1e-12
    assert abs(g.d - (2.0 / 2.075 - 1)) < 1e-12
    s_ref = np.sqrt(4 * 3 * (0.5 * 0.2) ** 2) / (3 * 2.0)
    assert abs(g.s_ref_rel - s_ref / 2.075) < 1e-12
    assert abs(g.sigma - np.hypot(0.1, s_ref) / 2.075) < 1e-12


def test_coverage_and_sharpness_of_a_right_error_bar():
    """Run = truth + noise s, reference = truth + noise se, the run's B_err = s: 95 % of the differences lie within
    1.96 sqrt(B_err^2 + se^2) and the sharpness is 1, each within 3.29 standard deviations (two-sided 0.001): the
    coverage's binomial sqrt(0.95 0.05 / values), the sharpness's from sum d^2's variance 2 N sigma^4 (sigma^2 =
    s^2 + se^2), halved for the square root. A bar half as wide covers about 68 % (fails the first check) and has
    sharpness 0.5."""
    n, s, se = 4000, 0.015, 0.005
    rng = np.random.default_rng(2)
    truth = np.full((n, 3), 2.0)
    run = table(truth + rng.normal(0, s, (n, 3)), np.full((n, 3), s), n)
    reference = table(truth + rng.normal(0, se, (n, 3)), np.full((n, 3), se), n)
    cover, values, sharp = pc.coverage(run, reference)
    assert values == 3 * n
    assert abs(cover - 0.95) <= 3.29 * np.sqrt(0.95 * 0.05 / values), cover
    sigma2 = s * s + se * se
    assert abs(sharp - 1) <= 3.29 * 0.5 * np.sqrt(2 * values) * sigma2 / (values * s * s), sharp
    run["B_err"] = run["B_err"] / 2
    cover_half, _, sharp_half = pc.coverage(run, reference)
    assert abs(cover_half - 0.95) > 3.29 * np.sqrt(0.95 * 0.05 / values) and abs(sharp_half - sharp / 2) < 1e-12
