#!/usr/bin/python3
"""Speed against accuracy on the Cornell box: every discrete method's error against wall time (log-log).

Runs on the Python module radwalk (the library code of the radwalk program; the times are the library's stage
timings, as in the program's JSON summaries). For each patch level (--max-edge values), the scene loaded once:
  reference  F with --ref-rays rays per patch (seed S) -> F_ref.mtx, then the direct solve. A second reference
             with seed S + 1 measures the reference's own noise (RMS difference / sqrt 2), the floor under every
             error in panel B.
  panel A    solver error only: every method uses the same F_ref; error against the reference; time = the
             solve stage. Deterministic solvers at tol 1e-2 .. 1e-8, matrix-kernel random walks (6 estimators)
             at several walk budgets.
  panel B    everything from scratch: deterministic solvers with their own F at several ray budgets (total
             time = form-factor stage + solve stage; the form-factor time is also a column of its own),
             matrix-kernel walks on a 1024-ray F (time = its form-factor stage + walks), ray-kernel walks
             (no F at all; time = walks, tracing included), and the path tracer's patch averages.
Error = RMS over (patch, channel) of (B - B_ref) / B_ref (one seed; the results do not depend on the load). Times
are the median of --repeats runs (default 3; each stage timed, the chart's horizontal bars span the fastest to the
slowest run): the same computation repeated, since wall time on a shared machine zigzags.
Charts, one per patch level (OUT/speed_accuracy_e<L>.png): one row per setting (A: F given, B: from scratch), one
panel per family of methods (deterministic solvers, gathering walks, shooting walks, the path tracer), each with
its own legend, on common axes; panel B's grey band is the reference's own noise (errors inside it are not
resolved). Writes OUT/speed_accuracy.csv (raw data: every run's median, min and max times), the reference's .vtp
and .csv (as `radwalk solve`'s) and F_ref.mtx. Progress: one line per method and budget."""

import math
import os

import numpy as np

import rwexp
from rwexp import plt

radwalk = rwexp.import_radwalk()

GATHER = ["absorption", "collision", "expected-value"]
SHOOT = ["collision", "absorption", "survival"]
DETERMINISTIC = ["direct", "jacobi", "gauss-seidel", "southwell"]



def walk_budget(walk, w, N):
    """The count argument of a walk budget w: walks from each patch (gather), or w x N particles in total (shoot)."""
    return {"walks_per_patch": w} if walk == "gather" else {"particles": w * N}


def main():
    p = rwexp.parser("speed_accuracy", __doc__)
    p.add_argument("--max-edge", type=float, nargs="+", default=[100, 50], help="patch levels (mm)")
    p.add_argument("--ref-rays", type=int, default=100000, help="rays per patch of the reference F")
    p.add_argument("--scale", type=float, default=1,
                   help="walk and ray budgets: one budget step more per factor 4 (fewer below 1, at least 2 steps); "
                        "adds --max-edge 25 when >= 4 (default 1)")
    p.add_argument("--repeats", type=int, default=3, help="timed runs of every point, median drawn (default 3)")
    p.add_argument("--replot", action="store_true", help="only redraw the charts from OUT/speed_accuracy.csv")
    a = p.parse_args()
    if a.replot:
        rows = rwexp.read_table(os.path.join(a.out, "speed_accuracy.csv"))
        levels = sorted({r["max_edge"] for r in rows}, reverse=True)
        plot(rows, levels, rwexp.Folder(a.out))
        summary(rows, levels)
        return
    os.makedirs(a.out, exist_ok=True)
    rw = rwexp.Folder(a.out)
    T = a.threads
    scene_file = os.path.join(rwexp.MESHES, "cornell_box.obj")
    levels = list(a.max_edge) + ([25.0] if a.scale >= 4 and 25.0 not in a.max_edge else [])
    extra = int(round(math.log(a.scale, 4)))
    walk_budgets = [16 * 4 ** k for k in range(max(2, 5 + extra))]  # walks per patch (gather), x N particles (shoot)
    ray_budgets = [64 * 4 ** k for k in range(max(2, 4 + extra))]   # rays per patch of the working F
    R = max(1, a.repeats)

    def repeated(run, stage):
        """Runs run() R times: the last result and the seconds of its stage (timings key) in every run."""
        seconds = []
        for _ in range(R):
            result = run()
            seconds.append(result.timings[stage])
        return result, seconds
    tols = [1e-2, 1e-4, 1e-6, 1e-8]
    rows = []
    for me in levels:
        tag = f"e{int(me)}"
        scene = radwalk.load(scene_file, max_edge=me)

        # Reference (and its noise from a second seed).
        refs = []
        for s in (a.seed, a.seed + 1):
            ff = radwalk.form_factors(scene, rays=a.ref_rays, seed=s, threads=T)
            ref = radwalk.solve(scene, ff, solver="direct", threads=T)
            if s == a.seed:
                radwalk.write_matrix_market(rw.path(f"{tag}_Fref_s{s}.mtx"), ff, scene)
                radwalk.write_csv(rw.path(f"{tag}_reference_s{s}.csv"), scene, {**ff.diagnostics, **ref.fields})
                radwalk.write_vtp(rw.path(f"{tag}_reference.vtp"), scene, {**ff.diagnostics, **ref.fields},
                                  {"method": ref.method, "scene": scene_file, "seed": s, "max_edge": me})
            refs.append((np.array(ref.B), ff.timings["form_factors"], ff))
        B_ref, ref_ff_s, F_ref = refs[0]
        N = B_ref.shape[0]
        ref_noise = rwexp.rms_relative_error(refs[1][0], B_ref) / math.sqrt(2)
        del refs[1]
        print(f"max-edge {me}: {N} patches, reference F {a.ref_rays} rays/patch in {ref_ff_s:.1f} s, "
              f"reference noise (RMS relative) {ref_noise:.2e}", flush=True)
        rows.append(dict(max_edge=me, patches=N, panel="reference", method="direct (reference)", kernel="matrix",
                         budget=a.ref_rays, budget_unit="rays/patch", repeats=1, ff_seconds=ref_ff_s,
                         solve_seconds=math.nan, total_seconds=ref_ff_s, total_min=ref_ff_s, total_max=ref_ff_s,
                         error=ref_noise, status="converged", iterations=0, steps=0,
                         note="error = RMS difference of two reference seeds / sqrt 2"))

        def record(panel, method, kernel, budget, unit, run, ff_seconds=(0.0,), note="", steps=None,
                   stage="solve"):
            """Times run() (R repeats) and records its error; ff_seconds: the F's stage times (its own repeats)."""
            result, solve_seconds = repeated(run, stage)
            ff_med, ff_lo, ff_hi = rwexp.median_spread(ff_seconds)
            s_med, s_lo, s_hi = rwexp.median_spread(solve_seconds)
            rows.append(dict(max_edge=me, patches=N, panel=panel, method=method, kernel=kernel, budget=budget,
                             budget_unit=unit, repeats=R, ff_seconds=ff_med, solve_seconds=s_med,
                             total_seconds=ff_med + s_med, total_min=ff_lo + s_lo, total_max=ff_hi + s_hi,
                             error=rwexp.rms_relative_error(result.B, B_ref), status=result.status,
                             iterations=result.iterations, steps=result.steps if steps is None else steps,
                             note=note))
            r = rows[-1]
            print(f"  {panel} {method:22s} {kernel:10s} {budget:>8g} {unit:13s} {r['total_seconds']:9.4f} s "
                  f"[{r['total_min']:.4f}, {r['total_max']:.4f}]  error {r['error']:.3g}", flush=True)

        def walks(panel, F, ff_s, kernel):
            for walk, ests in (("gather", GATHER), ("shoot", SHOOT)):
                for est in ests:
                    for w in walk_budgets:
                        record(panel, f"{walk}-{est}", kernel, w, "walks/patch",
                               lambda: radwalk.random_walk(scene, F, method=f"{walk}-{est}", kernel=kernel,
                                                           seed=a.seed, threads=T, **walk_budget(walk, w, N)), ff_s)

        # Panel A: shared F_ref.
        record("A", "direct", "matrix", 0, "-", lambda: radwalk.solve(scene, F_ref, solver="direct", threads=T))
        for s in DETERMINISTIC[1:]:
            for tol in tols:
                record("A", s, "matrix", tol, "tol",
                       lambda: radwalk.solve(scene, F_ref, solver=s, tol=tol, max_iterations=100000000, threads=T))
        walks("A", F_ref, (0.0,), "matrix")
        print("  panel A done", flush=True)

        # Panel B: from scratch.
        for rays in ray_budgets:
            ff, ff_s = repeated(lambda: radwalk.form_factors(scene, rays=rays, seed=a.seed, threads=T),
                                "form_factors")
            for s in DETERMINISTIC:
                record("B", s, "matrix", rays, "rays/patch",
                       lambda: radwalk.solve(scene, ff, solver=s, tol=1e-6, max_iterations=100000000, threads=T),
                       ff_s)
            if rays == 1024:
                walks("B", ff, ff_s, "matrix")
        walks("B", None, (0.0,), "ray")
        # The continuous path tracer's patch averages (MIS, no F): its error against the discrete reference also
        # holds the discretisation error (about 1e-3 at these patch sizes, see discretisation_error.py).
        for w in walk_budgets:
            record("B", "pathtrace-mis", "continuous", w, "samples/patch",
                   lambda: radwalk.pathtrace(scene, spp=w, seed=a.seed, threads=T).averages,
                   note="continuous solution: error includes the discretisation error", steps=0,
                   stage="patch_averages")
        print("  panel B done", flush=True)

    fields = ["max_edge", "patches", "panel", "method", "kernel", "budget", "budget_unit", "repeats", "ff_seconds",
              "solve_seconds", "total_seconds", "total_min", "total_max", "error", "status", "iterations", "steps",
              "note"]
    rwexp.write_csv(rw.path("speed_accuracy.csv"), rows, fields)
    print(f"wrote {rw.path('speed_accuracy.csv')}")
    plot(rows, levels, rw)
    summary(rows, levels)


FAMILIES = [  # (title, methods): one panel each
    ("deterministic solvers", ["direct", "jacobi", "gauss-seidel", "southwell"]),
    ("gathering walks (from each patch)", [f"gather-{e}" for e in GATHER]),
    ("shooting walks (from the light)", [f"shoot-{e}" for e in SHOOT]),
    ("path tracer (continuous, no F)", ["pathtrace-mis"]),
]
STYLE = {
    "direct": ("k", "*"), "jacobi": ("tab:gray", "s"), "gauss-seidel": ("tab:brown", "D"),
    "southwell": ("tab:olive", "P"),
    "gather-absorption": ("tab:blue", "o"), "gather-collision": ("tab:orange", "v"),
    "gather-expected-value": ("tab:green", "s"),
    "shoot-collision": ("tab:red", "^"), "shoot-absorption": ("tab:purple", "D"), "shoot-survival": ("tab:pink", "o"),
    "pathtrace-mis": ("tab:cyan", "X"),
}
FLOOR = 1e-9  # errors below this (the direct solve against itself in panel A: rounding only) are drawn here


def plot(rows, levels, rw):
    for me in levels:
        sel_all = [r for r in rows if r["max_edge"] == me and r["panel"] in ("A", "B")]
        ref = [r for r in rows if r["max_edge"] == me and r["panel"] == "reference"][0]
        t_all = [max(r["total_min"], 1e-5) for r in sel_all] + [r["total_max"] for r in sel_all]
        e_all = [max(r["error"], FLOOR) for r in sel_all]
        fig, axes = plt.subplots(2, 4, figsize=(17, 8.6), sharex=True, sharey="row")
        for row_k, panel in enumerate("AB"):
            for col, (title, methods) in enumerate(FAMILIES):
                ax = axes[row_k, col]
                sel = [r for r in sel_all if r["panel"] == panel and r["method"] in methods]
                if not sel:
                    ax.text(0.5, 0.5, "needs no F: see row B" if panel == "A" else "", ha="center", va="center",
                            transform=ax.transAxes, color="0.4")
                for method in methods:
                    for kernel in ("matrix", "ray", "continuous"):
                        # In budget order (more rays, walks, a smaller tol: more work), not by time, whose
                        # noise would make the line zigzag.
                        pts = sorted((r for r in sel if r["method"] == method and r["kernel"] == kernel),
                                     key=lambda r: -r["budget"] if r["budget_unit"] == "tol" else r["budget"])
                        if not pts:
                            continue
                        t = np.array([max(r["total_seconds"], 1e-5) for r in pts])
                        lo = np.array([max(r["total_min"], 1e-5) for r in pts])
                        hi = np.array([r["total_max"] for r in pts])
                        e = [max(r["error"], FLOOR) for r in pts]
                        color, marker = STYLE[method]
                        ray = kernel == "ray"
                        label = method.replace("gather-", "").replace("shoot-", "")
                        label += " (ray kernel, no F)" if ray else " (F of 1024 rays)" if (
                            panel == "B" and method[:5] in ("gathe", "shoot")) else ""
                        if method == "direct" and panel == "A":
                            label = "direct (the reference itself: drawn at 1e-9)"
                        ax.errorbar(t, e, xerr=[t - lo, hi - t], fmt="--" if ray else "-", color=color,
                                    marker=marker, ms=5, mfc="white" if ray else color, capsize=2, elinewidth=0.8,
                                    label=label)
                if panel == "B":
                    ax.axhspan(FLOOR / 10, ref["error"], color="0.88", zorder=0,
                               label=f"reference's own noise ({ref['error']:.3f})")
                ax.set_xscale("log")
                ax.set_yscale("log")
                ax.grid(True, which="both", alpha=0.3)
                if sel or panel == "B":
                    ax.legend(fontsize=7.5, loc="lower left")
                if row_k == 0:
                    ax.set_title(title, fontsize=10)
                if col == 0:
                    ax.set_ylabel(("A: F given (F_ref)" if panel == "A" else "B: from scratch") +
                                  "\nRMS relative error of B per patch")
                if row_k == 1:
                    ax.set_xlabel("wall time (s), median of repeats; bars: fastest to slowest" if col == 0 else
                                  "wall time (s)")
        axes[0, 0].set_xlim(min(t_all) / 1.5, max(t_all) * 1.5)
        axes[0, 0].set_ylim(FLOOR / 2, max(e_all) * 2)
        e_B = [r["error"] for r in sel_all if r["panel"] == "B"] + [ref["error"]]
        axes[1, 0].set_ylim(min(e_B) / 2, max(e_B) * 2)
        for ax in axes.flat:
            rwexp.log_ticks(ax)
        bmax = max(r["budget"] for r in rows if r["panel"] == "B" and r["budget_unit"] == "rays/patch")
        fig.suptitle(f"Cornell box, max edge {me:g} mm ({int(ref['patches'])} patches): error against wall time. "
                     f"Reference: direct solve, F of {int(ref['budget'])} rays/patch. A: time of the solve alone. "
                     f"B: form factors (deterministic: own F of 64..{int(bmax)} rays/patch, tol 1e-6) + solve",
                     fontsize=10.5)
        fig.tight_layout(rect=(0, 0, 1, 0.97))
        fig.savefig(rw.path(f"speed_accuracy_e{int(me)}.png"), dpi=100)
        plt.close(fig)
        print(f"wrote {rw.path(f'speed_accuracy_e{int(me)}.png')}")


def summary(rows, levels):
    for me in levels:
        sel = [r for r in rows if r["max_edge"] == me and r["panel"] in "AB"]
        print(rwexp.table(sorted(sel, key=lambda r: (r["panel"], r["method"], r["kernel"], r["budget"])),
                          ["panel", "method", "kernel", "budget", "ff_seconds", "solve_seconds", "total_seconds",
                           "error", "status"], f"\nmax-edge {me:g}"))


if __name__ == "__main__":
    main()
