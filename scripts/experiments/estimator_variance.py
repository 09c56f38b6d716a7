#!/usr/bin/python3
"""Estimator variance: empirical against theoretical per-walk variance, and efficiency ratios, per regime.

Runs radwalk.compare (the Python module: all six estimators, matrix kernel, the same traced F for the estimators
and the exact variance, as `radwalk compare`) on scenes chosen to show each regime:
  furnace          meshes/furnace.obj (closed, E and rho = 0.5 everywhere): gathering absorption has zero
                   variance; collision per-walk variance E^2 rho / (1 - rho)^2; expected value = rho^2 x collision
  black_emitter    scenes/cube_black_emitter.obj (emitter rho = 0): gathering absorption = collision, patch by patch
  parallel         meshes/parallel_squares.obj (open, emitter rho = 0): the same, in an open scene
  bright_emitters  scenes/cube_bright_emitters.obj (two adjacent emitters with rho = 0.9 see each other):
                   absorption pays for the emitters' reflection, collision wins
  cornell          meshes/cornell_box.obj --max-edge 200 (109 patches; small light)
Writes OUT/<scene>.csv (the long table of `radwalk compare --csv`), OUT/<scene>.vtp (ParaView: per-patch
var_<estimator> and var_theory_<estimator>, with underscores for hyphens), OUT/<scene>.json (counts, timings and
the per-method summary), OUT/ratios.csv, OUT/checks.csv and OUT/variance_scatter.png, OUT/efficiency_ratios.png."""

import json
import math
import os

import numpy as np

import rwexp
from rwexp import plt

radwalk = rwexp.import_radwalk()

METHODS = radwalk.walk_methods()  # the one method table (src/walk/walk_method.h)
CHANNELS = "rgb"
# (label, first, second): ratio = first / second
PAIRS = [("collision / absorption (gather)", "gather-collision", "gather-absorption"),
         ("expected value / collision (gather)", "gather-expected-value", "gather-collision"),
         ("shooting / gathering (collision)", "shoot-collision", "gather-collision"),
         ("shooting / gathering (absorption)", "shoot-absorption", "gather-absorption"),
         ("survival / collision (shoot)", "shoot-survival", "shoot-collision")]


def scenes(scale):
    m, s = rwexp.MESHES, rwexp.SCENES
    return [
        ("furnace", os.path.join(m, "furnace.obj"), 0.5, 20000),
        ("black_emitter", os.path.join(s, "cube_black_emitter.obj"), 0.5, 20000),
        ("parallel", os.path.join(m, "parallel_squares.obj"), 0.5, 20000),
        ("bright_emitters", os.path.join(s, "cube_bright_emitters.obj"), 0.5, 20000),
        ("cornell", os.path.join(m, "cornell_box.obj"), 200 if scale < 4 else 100, 8000),
    ]


def main():
    p = rwexp.parser("estimator_variance", __doc__)
    p.add_argument("--runs", type=int, default=5, help="independent runs per estimator")
    p.add_argument("--rays", type=int, default=10000, help="rays per patch of the traced F")
    p.add_argument("--scale", type=float, default=1, help="multiplies the walks (and refines the Cornell box at >= 4)")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    out = rwexp.Folder(a.out)
    data = {}
    for name, path, max_edge, walks in scenes(a.scale):
        walks = max(2, int(walks * a.scale))
        scene = radwalk.load(path, max_edge=max_edge)
        ff = radwalk.form_factors(scene, rays=a.rays, seed=a.seed, threads=a.threads)
        c = radwalk.compare(scene, ff, walks_per_patch=walks, runs=a.runs, seed=a.seed, kernel="matrix",
                            threads=a.threads)
        rows = [dict(zip(c.rows, values)) for values in zip(*c.rows.values())]
        for r in rows:
            r["channel"] = CHANNELS[r["channel"]]
        rwexp.write_csv(out.path(f"{name}.csv"), rows, list(c.rows), digits=12)
        fields = {"B_reference": c.B_reference}
        for m, e in c.estimators.items():
            k = m.replace("-", "_")
            fields.update({f"mean_{k}": e.mean, f"var_{k}": e.var, f"var_se_{k}": e.var_se, f"var_theory_{k}": e.var_theory,
                           f"z_{k}": e.z})
        radwalk.write_vtp(out.path(f"{name}.vtp"), scene, fields,
                          {"estimators": ",".join(c.estimators), "walks_per_patch": walks, "runs": a.runs,
                           "seed": a.seed, "kernel": "matrix"})
        js = {"scene": path, "max_edge": max_edge, "patches": len(scene), "rays_per_patch": a.rays, "seed": a.seed,
              "walks_per_patch": walks, "runs": a.runs, "timings_s": {**ff.timings, **c.timings},
              "estimators": {m: {"runs": e.runs, "walks_total": e.walks_total,
                                 "walks_per_estimate": e.walks_per_estimate, "steps": e.steps, "seconds": e.seconds,
                                 "mean_abs_z": e.mean_abs_z, "max_abs_z": e.max_abs_z,
                                 "var_over_theory": e.var_over_theory if math.isfinite(e.var_over_theory) else None,
                                 "spread_over_se": e.spread_over_se if math.isfinite(e.spread_over_se) else None,
                                 "mean_var_per_walk": e.mean_var_per_walk,
                                 "efficiency": e.efficiency} for m, e in c.estimators.items()}}
        with open(out.path(f"{name}.json"), "w") as f:
            json.dump(js, f, indent=1)
        data[name] = (rows, js, walks)
        print(f"{name}: {js['patches']} patches, {walks} walks/patch x {a.runs} runs, "
              f"{js['timings_s']['walks']:.2f} s of walks", flush=True)

    ratio_rows, check_rows = [], []
    for name, (rows, js, walks) in data.items():
        by = {m: [r for r in rows if r["estimator"] == m] for m in METHODS}
        for label, first, second in PAIRS:
            A, B = by[first], by[second]
            # Pooled-estimate variance var / walks, averaged over the (patch, channel) rows; efficiency ratio =
            # inverse variance ratio x inverse seconds ratio. Theory: the exact variances with the same seconds.
            def mean_pooled(rows, key):  # a variance below 1e-12 B^2 is rounding: 0
                return float(np.mean([0.0 if r[key] <= 1e-12 * r["mean"] ** 2 else r[key] / r["walks"]
                                      for r in rows]))

            def ratio(x, y):
                return x / y if y > 0 else (math.inf if x > 0 else math.nan)

            def relative_se(rows):  # of mean_pooled(rows, "var"), from the runs' spread of each row's variance
                m = mean_pooled(rows, "var")
                se = math.sqrt(sum((r["var_se"] / r["walks"]) ** 2 for r in rows if math.isfinite(r["var_se"])))
                return se / len(rows) / m if m > 0 else math.nan

            v_emp = ratio(mean_pooled(A, "var"), mean_pooled(B, "var"))
            v_th = ratio(mean_pooled(A, "var_theory"), mean_pooled(B, "var_theory"))
            cost = B[0]["seconds"] / A[0]["seconds"]
            e_emp = 1 / v_emp * cost if v_emp > 0 else math.inf
            e_th = 1 / v_th * cost if v_th > 0 else math.inf
            # The two methods ran independently: relative errors add in quadrature (seconds taken as exact).
            rel = math.hypot(relative_se(A), relative_se(B))
            ratio_rows.append(dict(scene=name, ratio=label, variance_ratio=v_emp, variance_ratio_theory=v_th,
                                   ratio_relative_se=rel,
                                   efficiency_ratio=e_emp, efficiency_ratio_theory=e_th,
                                   seconds_first=A[0]["seconds"], seconds_second=B[0]["seconds"],
                                   steps_first=A[0]["steps"], steps_second=B[0]["steps"]))
        checks(name, by, js, check_rows)

    fields = ["scene", "ratio", "variance_ratio", "variance_ratio_theory", "efficiency_ratio",
              "efficiency_ratio_theory", "ratio_relative_se", "seconds_first", "seconds_second", "steps_first", "steps_second"]
    rwexp.write_csv(out.path("ratios.csv"), ratio_rows, fields)
    print(rwexp.table(ratio_rows, fields[:6], "\nvariance_ratio: mean over (patch, channel) of the pooled-estimate "
                      "variance var/walks, first / second; efficiency_ratio: efficiency first / second;\n"
                      "*_theory: the same with the exact variances (and the measured seconds)"))
    cf = ["scene", "claim", "predicted", "measured", "note"]
    rwexp.write_csv(out.path("checks.csv"), check_rows, cf)
    print(rwexp.table(check_rows, cf[:4], "\nregime checks"))
    plot_scatter(data, out)
    plot_ratios(ratio_rows, out)


def checks(name, by, js, out):
    ga, gc, ge = by["gather-absorption"], by["gather-collision"], by["gather-expected-value"]
    if name == "furnace":
        E, rho = math.pi, 0.5
        out.append(dict(scene=name, claim="gather-absorption per-walk variance (max over patches)", predicted=0.0,
                        measured=max(r["var"] for r in ga), note="rows of a traced F sum to 1 in a closed scene"))
        out.append(dict(scene=name, claim="gather-collision per-walk variance E^2 rho/(1-rho)^2 (mean)",
                        predicted=E * E * rho / (1 - rho) ** 2, measured=float(np.mean([r["var"] for r in gc])),
                        note=f"spread over patches {np.std([r['var'] for r in gc]):.3g}"))
        out.append(dict(scene=name, claim="expected value / collision per-walk variance = rho^2",
                        predicted=rho ** 2, measured=float(np.mean([e["var"] for e in ge]) /
                                                           np.mean([c["var"] for c in gc])), note=""))
    if name in ("black_emitter", "parallel"):
        rel = [abs(x["var"] - y["var"]) / y["var"] for x, y in zip(ga, gc) if y["var"] > 0]
        same = all(x["var"] == y["var"] for x, y in zip(ga, gc))
        out.append(dict(scene=name, claim="gather-absorption var = gather-collision var (max relative difference)",
                        predicted=0.0, measured=max(rel),
                        note="bit-identical per patch" if same else "same streams, different scores"))
        rel_t = [abs(x["var_theory"] - y["var_theory"]) / y["var_theory"] for x, y in zip(ga, gc)
                 if y["var_theory"] > 0]
        out.append(dict(scene=name, claim="theory: absorption var = collision var (max relative difference)",
                        predicted=0.0, measured=max(rel_t), note=""))
    if name == "bright_emitters":
        ra = float(np.mean([x["var"] for x in ga]) / np.mean([y["var"] for y in gc]))
        rt = float(np.mean([x["var_theory"] for x in ga]) / np.mean([y["var_theory"] for y in gc]))
        out.append(dict(scene=name, claim="absorption / collision mean per-walk variance", predicted=rt,
                        measured=ra, note="predicted = ratio of the exact variances"))
    # Every scene: the measured per-walk variance against the exact one, and the z statistics.
    for m in METHODS:
        rows = [r for r in by[m] if r["var_theory"] > 1e-12 * max(r["mean"] ** 2, 1e-300)]
        if rows:
            out.append(dict(scene=name, claim=f"{m}: mean var / var_theory", predicted=1.0,
                            measured=float(np.mean([r["var"] / r["var_theory"] for r in rows])),
                            note=f"mean |z| {np.mean([abs(r['z']) for r in by[m]]):.2f} (unbiased: 0.80)"))


def plot_scatter(data, rw):
    names = list(data)
    fig, axes = plt.subplots(2, 3, figsize=(15, 9.5))
    colors = dict(zip(METHODS, ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:pink"]))
    markers = dict(zip(METHODS, ["o", "s", "D", "^", "v", "P"]))
    notes = []
    for ax, name in zip(axes.flat, names):
        rows, js, walks = data[name]
        lo, hi = math.inf, 0
        zero = []
        for m in METHODS:
            pts = [(r["var_theory"], r["var"]) for r in rows if r["estimator"] == m]
            pos_se = [r["var_se"] for r in rows if r["estimator"] == m and r["var_theory"] > 0 and r["var"] > 0]
            pos = [(t, e) for t, e in pts if t > 0 and e > 0]
            if len(pos) < len(pts):
                zt = [(t, e) for t, e in pts if not (t > 0 and e > 0)]
                both = sum(1 for t, e in zt if t <= 0 and e <= 0)
                note = f"{m}: {len(zt)}/{len(pts)}"
                note += " exactly 0 in both" if both == len(zt) else (
                    f" (theory <= {max(t for t, e in zt):.2g}, measured <= {max(e for t, e in zt):.2g})")
                zero.append(note)
            if not pos:
                continue
            t, e = zip(*pos)
            lo, hi = min(lo, *t, *e), max(hi, *t, *e)
            ax.scatter(t, e, s=14, color=colors[m], marker=markers[m], alpha=0.6, label=m)
            # 2 standard errors of each empirical variance (the spread of the runs' variances), clipped at the
            # axis' floor where the bar would reach 0 on a log axis.
            err = [2 * se if math.isfinite(se) else 0.0 for se in pos_se]
            ax.errorbar(t, e, yerr=[[min(d, v * 0.95) for d, v in zip(err, e)], err], fmt="none",
                        ecolor=colors[m], elinewidth=0.6, alpha=0.5)
        ax.plot([lo / 2, hi * 2], [lo / 2, hi * 2], "k-", lw=0.8, label="identity")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("exact per-walk variance (units of B$^2$)")
        ax.set_ylabel("empirical per-walk variance (units of B$^2$)")
        ax.set_title(f"{name}: {js['patches']} patches, {walks} walks/patch x runs", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        rwexp.log_ticks(ax)
        if zero:
            notes.append(f"{name}:\n  " + "\n  ".join(zero))
    axes.flat[0].legend(fontsize=8, loc="lower right")
    for ax in list(axes.flat)[len(names):]:
        ax.axis("off")
    axes.flat[-1].text(0.0, 1.0, "Rows (patch, channel) not drawn on log axes\n(a zero variance):\n\n" +
                       "\n".join(notes), transform=axes.flat[-1].transAxes, fontsize=8, va="top", family="monospace")
    fig.suptitle("Empirical against exact per-walk (per-particle) variance, every patch and channel, matrix kernel\n"
                 "(B in W per squared length unit of the scene: mm for the Cornell box); bars: 2 standard errors "
                 "from the runs' spread")
    rwexp.save(fig, rw.path("variance_scatter.png"))


def plot_ratios(ratio_rows, rw):
    """One panel per pair of methods: the efficiency ratio per scene as a dot (measured: filled; with the exact
    variances: open) on a log axis; an infinite ratio (the second method has zero variance) is a right-pointing triangle at the panel's right edge, a zero ratio a left-pointing one at its
    left edge, an undefined one (both zero) the word n/a."""
    scenes_ = list(dict.fromkeys(r["scene"] for r in ratio_rows))
    cmap = plt.get_cmap("tab10")
    finite = [v for r in ratio_rows for v in (r["efficiency_ratio"], r["efficiency_ratio_theory"])
              if math.isfinite(v) and v > 0]
    lo, hi = min(finite) / 10, max(finite) * 10
    fig, axes = plt.subplots(len(PAIRS), 1, figsize=(8.5, 1.25 + 1.35 * len(PAIRS)), sharex=True)
    for ax, (label, first, second) in zip(axes, PAIRS):
        rows = {r["scene"]: r for r in ratio_rows if r["ratio"] == label}
        for k, name in enumerate(scenes_):
            r = rows.get(name)
            if r is None:
                continue
            y = len(scenes_) - 1 - k
            for key, filled, dy in (("efficiency_ratio", True, 0.12), ("efficiency_ratio_theory", False, -0.12)):
                v = r[key]
                style = dict(color=cmap(k), mfc=cmap(k) if filled else "white", ms=7, linestyle="none")
                if math.isnan(v):
                    ax.text(lo * 1.3, y + dy, "n/a", fontsize=7, va="center", color=cmap(k))
                elif v == math.inf:
                    ax.plot([hi / 1.3], [y + dy], ">", **style)
                    if filled:
                        ax.text(hi / 1.8, y, "infinite", fontsize=7, va="center", ha="right", color=cmap(k))
                elif v <= 0:
                    ax.plot([lo * 1.3], [y + dy], "<", **style)
                    if filled:
                        ax.text(lo * 1.8, y, "0", fontsize=7, va="center", ha="left", color=cmap(k))
                else:
                    ax.plot([v], [y + dy], "o", **style)
                    r2 = 2 * r["ratio_relative_se"]
                    if filled and math.isfinite(r2) and r2 > 0:  # 2 standard errors of the measured ratio
                        ax.errorbar([v], [y + dy], xerr=[[v - v / (1 + r2)], [v * r2]], fmt="none",
                                    ecolor=cmap(k), elinewidth=1)
        ax.axvline(1, color="k", lw=0.8)
        ax.set_yticks(range(len(scenes_)))
        ax.set_yticklabels(list(reversed(scenes_)), fontsize=8)
        ax.set_ylim(-0.6, len(scenes_) - 0.4)
        ax.set_title(f"{label}: efficiency of {first} / {second}", fontsize=9, loc="left")
        ax.grid(True, axis="x", which="major", alpha=0.3)
        ax.set_xscale("log")
    axes[-1].set_xlim(lo, hi)
    rwexp.log_ticks(axes[-1], y=False)
    axes[-1].set_xlabel("efficiency ratio (> 1: the first method wins); efficiency = 1 / (pooled variance x seconds)")
    from matplotlib.lines import Line2D
    fig.legend([Line2D([], [], marker="o", color="0.3", linestyle="none"),
                Line2D([], [], marker="o", color="0.3", mfc="white", linestyle="none"),
                Line2D([], [], marker=">", color="0.3", linestyle="none"),
                Line2D([], [], marker="<", color="0.3", linestyle="none")],
               ["measured (bar: 2 standard errors)", "exact variances, measured seconds", "infinite (second: zero variance)",
                "0 (first: zero variance)"], loc="upper center", ncol=2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 0.92))
    fig.savefig(rw.path("efficiency_ratios.png"), dpi=110)
    plt.close(fig)
    print(f"wrote {rw.path('efficiency_ratios.png')}")


if __name__ == "__main__":
    main()
