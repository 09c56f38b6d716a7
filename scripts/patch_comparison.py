"""Two radwalk patch tables compared patch by patch: a run's and the path tracer's on the run's own patches.

The tables are the CSV files `radwalk solve --csv` and `radwalk pathtrace --csv` write (docs/units-and-formats.md:
one row per patch, columns area, cx cy cz, nx ny nz, rho_*, E_*, material, B_*, B_se_*). The usual pair: a run
writes its patches (-o run.vtp) and B (--csv run.csv); `radwalk pathtrace run.vtp --csv pt.csv --open-shells
one-sided` averages the continuous radiosity over the same patches read back. Used by bench/target_error.py,
bench/per_material.py and the realmesh test tests/realmesh/run_furniture_target.py; needs numpy.

  read_table(path)        -> a table: dict of numpy arrays, one row per patch: B, B_se, E, rho (n x 3), area (n),
                             key (n x 6: centroid, normal), material (n names), row (n: the CSV row, from 0).
  matched(run, reference) -> (run rows, reference rows, unmatched): the reference's rows matched to the run's by
                             centroid and normal (below), both as tables in the same order.
  measured_error(run, reference) -> (e, e_sd, noise, unmatched): the relative error with the reference's noise
                             taken out (below).
  measured_discretisation_error(run, reference) -> (e_disc, e_disc_sd, e_stat): e with the run's own stated
                             statistical error taken out as well (below).
  material_means(run, reference) -> {material: MaterialMean}, per material in order of first appearance (below).
  coverage(run, reference) -> (coverage, values, sharpness): how well the run's stated total error B_err covers its
                             difference from the reference (below).

Matching: the reference read back may list the patches in another order (back patches, repaired faces) and drop a
few (faces the reader repairs away, slivers), so rows are matched by their centroid (divided by the largest
|coordinate| of the run's centroids) and normal, both rounded to 1e-6; a reference row matched twice is an error
(ValueError). The run's rows that match nothing are left out and counted.

Measured error, over the (patch, channel) values of the reflecting, non-emitting patches the reference sees
(E = 0, rho > 0, B_ref > 0), A the patch area, se the reference's standard error:
  e     = sqrt(max(sum A (B - B_ref)^2 - sum A se^2, 0) / sum A B_ref^2)   (the reference's own noise taken out),
  e_sd  = the standard deviation of e from the reference's noise: the subtracted sum is an estimate,
          Var(sum A (d + n)^2 - sum A se^2) ~ sum A^2 (2 se^4 + 4 d^2 se^2) (n ~ N(0, se^2) per value, d^2 taken as
          max((B - B_ref)^2 - se^2, 0)), carried to e by de = d(e^2) / (2 e),
  noise = sqrt(sum A se^2 / sum A B_ref^2), the reference's relative noise.
Its discretisation part, over the same values, s the run's own B_se:
  e_stat = sqrt(sum A s^2 / sum A B_ref^2), the run's stated statistical error,
  e_disc = sqrt(max(e^2 - e_stat^2, 0)): B - B_ref = (discretisation bias) + (run's noise) + (reference's noise),
           the two noises independent, zero-mean and independent of the bias, so E[sum A (B - B_ref)^2] = sum A
           bias^2 + sum A s_true^2 + sum A se_true^2; both stated variances are unbiased estimates of the true ones
           (their coverage: docs/accuracy.md), so e_disc estimates the relative L2 norm of the bias alone. This is
           what "at equal discretisation error" compares: a run with fewer rays a patch is not charged for its noise.
  e_disc_sd = e e_sd / e_disc (sqrt(2 e e_sd) at e_disc = 0): the standard deviation of e_disc from the reference's
           noise, carried from e^2's as e_sd is (d(e_disc^2) = d(e^2)); the run's stated B_se is taken as exact.

Coverage, over the same matched values, B_err the run's stated total error (its B_err columns; B_se where it has
none), se the reference's standard error:
  coverage  = the fraction with |B - B_ref| <= 1.96 sqrt(B_err^2 + se^2)   (0.95 where both errors are right and
              the differences normal),
  sharpness = sqrt(sum A B_err^2 / max(sum A (B - B_ref)^2 - sum A se^2, 0))   (1 where B_err has the size of the
              actual error; above 1 it over-states, below under-states).

Per material m, over each table's own reflecting non-emitting patches of m (E = 0 and rho > 0 in some channel; no
matching: a material's mean is the area average over its surfaces whatever their tiling, and the path tracer, reading
the run's .vtp back, may split its faces otherwise: on the furniture room 21 of a run's 1,995 leaves had no match,
which left a third of the shelf's area out of the comparison while the run's error bar is for the whole), all
channels together:
  mean      = sum_i A_i sum_c B_ic / (3 sum_i A_i)      (the run's; mean_ref likewise),
  d         = mean / mean_ref - 1,
  sigma     = sqrt(s_run^2 + s_ref^2) / mean_ref, s_run = sum_i A_i sum_c B_se_ic / (3 sum A) (the run's statistical
              errors added as if fully correlated: a bound whatever their correlation), s_ref = sqrt(sum_i A_i^2
              sum_c se_ic^2) / (3 sum A) (the reference's patches are independent),
  sigma_ind = the same with the run's patches taken as independent (sqrt(sum A^2 B_se^2) / (3 sum A)),
  s_ref_rel = s_ref / mean_ref.
"""
import collections
import csv

import numpy as np

MaterialMean = collections.namedtuple("MaterialMean",
                                      "elements mean mean_ref d sigma sigma_ind s_ref_rel")


def read_table(path):
    """The patch table of a radwalk CSV file (see the module's docstring)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    get = lambda k: np.array([[float(r[k + "_" + c]) for c in "rgb"] for r in rows]).reshape(len(rows), 3)
    table = {k: get(k) for k in ("B", "B_se", "E", "rho")}
    table["B_err"] = get("B_err") if rows and "B_err_r" in rows[0] else table["B_se"]
    table["area"] = np.array([float(r["area"]) for r in rows])
    table["key"] = np.array([[float(r[k]) for k in ("cx", "cy", "cz", "nx", "ny", "nz")] for r in rows]).reshape(-1, 6)
    table["material"] = np.array([r.get("material", "") for r in rows], dtype=object)
    table["row"] = np.arange(len(rows))
    return table


def matched(run, reference):
    """(run's matched rows, reference's rows in the same order, count of the run's rows without a match)."""
    scale = np.abs(run["key"][:, :3]).max() if len(run["key"]) else 1.0
    round_key = lambda k: [tuple(x) for x in np.round(np.hstack([k[:, :3] / scale, k[:, 3:]]) * 1e6).astype(np.int64)]
    where = {k: i for i, k in enumerate(round_key(reference["key"]))}
    order = np.array([where.get(k, -1) for k in round_key(run["key"])], dtype=np.int64)
    found = order >= 0
    if len(set(order[found].tolist())) != int(found.sum()):
        raise ValueError("two of the run's patches match one of the reference's")
    return ({k: v[found] for k, v in run.items()}, {k: v[order[found]] for k, v in reference.items()},
            int((~found).sum()))


def _counted_values(run, reference, column="B_se"):
    """(W, B, B_ref, s, se, unmatched) over the matched (patch, channel) values the errors count (reflecting,
    non-emitting, B_ref > 0): W the patch area, s the run's `column` (B_se or B_err), se the reference's B_se."""
    r, ref, unmatched = matched(run, reference)
    keep = (ref["E"].max(1) == 0)[:, None] & (ref["rho"] > 0) & (ref["B"] > 0)
    W = np.repeat(ref["area"][:, None], 3, 1)[keep]
    return W, r["B"][keep], ref["B"][keep], r[column][keep], ref["B_se"][keep], unmatched


def _reference_noise_out(W, B, B_ref, se):
    """(e, e_sd, noise) over counted values (see the module's docstring)."""
    diff = B - B_ref
    se2 = se ** 2
    err2 = float((W * diff ** 2).sum())
    noise2 = float((W * se2).sum())
    size2 = float((W * B_ref ** 2).sum())
    d2 = np.maximum(diff ** 2 - se2, 0.0)
    var_e2 = float((W ** 2 * (2 * se2 ** 2 + 4 * d2 * se2)).sum()) / size2 ** 2
    e = np.sqrt(max(err2 - noise2, 0.0) / size2)
    e_sd = np.sqrt(var_e2) / (2 * e) if e > 0 else np.sqrt(np.sqrt(var_e2))
    return e, e_sd, np.sqrt(noise2 / size2)


def measured_error(run, reference):
    """(e, e_sd, noise, unmatched) of the run against the reference (see the module's docstring)."""
    W, B, B_ref, _, se, unmatched = _counted_values(run, reference)
    return _reference_noise_out(W, B, B_ref, se) + (unmatched,)


def measured_discretisation_error(run, reference):
    """(e_disc, e_disc_sd, e_stat) of the run against the reference (see the module's docstring)."""
    W, B, B_ref, s, se, _ = _counted_values(run, reference)
    e, e_sd, _ = _reference_noise_out(W, B, B_ref, se)
    e_stat2 = float((W * s ** 2).sum()) / float((W * B_ref ** 2).sum())
    e_disc = np.sqrt(max(e * e - e_stat2, 0.0))
    e_disc_sd = e * e_sd / e_disc if e_disc > 0 else np.sqrt(2 * e * e_sd)
    return e_disc, e_disc_sd, np.sqrt(e_stat2)


def coverage(run, reference):
    """(coverage, values, sharpness) of the run's B_err against the reference (see the module's docstring)."""
    W, B, B_ref, err, se, _ = _counted_values(run, reference, "B_err")
    diff = B - B_ref
    inside = int((np.abs(diff) <= 1.96 * np.sqrt(err ** 2 + se ** 2)).sum())
    measured2 = float((W * diff ** 2).sum()) - float((W * se ** 2).sum())
    sharpness = np.sqrt(float((W * err ** 2).sum()) / measured2) if measured2 > 0 else float("inf")
    return inside / max(diff.size, 1), int(diff.size), sharpness


def material_means(run, reference):
    """{material: MaterialMean} over each table's own reflecting non-emitting patches (see the module's docstring)."""
    def counted(t, m):
        return np.where((t["E"].max(1) == 0) & (t["rho"].max(1) > 0) & (t["material"] == m))[0]

    def mean_of(t, idx):
        A = t["area"][idx][:, None]
        S = 3 * float(A.sum())
        return (float((A * t["B"][idx]).sum()) / S, float((A * t["B_se"][idx]).sum()) / S,
                float(np.sqrt((A ** 2 * t["B_se"][idx] ** 2).sum())) / S)

    out = collections.OrderedDict()
    for m in dict.fromkeys(run["material"][(run["E"].max(1) == 0) & (run["rho"].max(1) > 0)]):
        idx, ref_idx = counted(run, m), counted(reference, m)
        if len(ref_idx) == 0:
            continue
        mean, s_run, s_ind = mean_of(run, idx)
        mean_ref, _, s_ref = mean_of(reference, ref_idx)
        out[m] = MaterialMean(len(idx), mean, mean_ref, mean / mean_ref - 1, np.hypot(s_run, s_ref) / mean_ref,
                              np.hypot(s_ind, s_ref) / mean_ref, s_ref / mean_ref)
    return out
