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
Error = RMS over (patch, channel) of (B - B_ref) / B_ref. Writes OUT/speed_accuracy.csv, OUT/*.png, the
reference's .vtp and .csv (as `radwalk solve`'s) and F_ref.mtx."""

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
    p.add_argument("--scale", type=int, default=1,
                   help="multiplies walk and ray budgets (adds one budget step per factor 4) and adds "
                        "--max-edge 25 when >= 4")
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
    extra = int(round(math.log(a.scale, 4))) if a.scale > 1 else 0
    walk_budgets = [16 * 4 ** k for k in range(5 + extra)]       # walks per patch (gather), x N particles (shoot)
    ray_budgets = [64 * 4 ** k for k in range(4 + extra)]        # rays per patch of the working F
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
                         budget=a.ref_rays, budget_unit="rays/patch", ff_seconds=ref_ff_s, solve_seconds=math.nan,
                         total_seconds=ref_ff_s, error=ref_noise, status="converged", iterations=0, steps=0,
                         note="error = RMS difference of two reference seeds / sqrt 2"))

        def record(panel, method, kernel, budget, unit, result, ff_s, note="", steps=None):
            solve_s = result.timings.get("solve", result.timings.get("patch_averages"))
            rows.append(dict(max_edge=me, patches=N, panel=panel, method=method, kernel=kernel, budget=budget,
                             budget_unit=unit, ff_seconds=ff_s, solve_seconds=solve_s, total_seconds=ff_s + solve_s,
                             error=rwexp.rms_relative_error(result.B, B_ref), status=result.status,
                             iterations=result.iterations, steps=result.steps if steps is None else steps,
                             note=note))

        def walks(panel, F, ff_s, kernel):
            for walk, ests in (("gather", GATHER), ("shoot", SHOOT)):
                for est in ests:
                    for w in walk_budgets:
                        r = radwalk.random_walk(scene, F, method=f"{walk}-{est}", kernel=kernel, seed=a.seed,
                                                threads=T, **walk_budget(walk, w, N))
                        record(panel, f"{walk}-{est}", kernel, w, "walks/patch", r, ff_s)

        # Panel A: shared F_ref.
        record("A", "direct", "matrix", 0, "-", radwalk.solve(scene, F_ref, solver="direct", threads=T), 0.0)
        for s in DETERMINISTIC[1:]:
            for tol in tols:
                record("A", s, "matrix", tol, "tol",
                       radwalk.solve(scene, F_ref, solver=s, tol=tol, max_iterations=100000000, threads=T), 0.0)
        walks("A", F_ref, 0.0, "matrix")
        print(f"  panel A done", flush=True)

        # Panel B: from scratch.
        for rays in ray_budgets:
            ff = radwalk.form_factors(scene, rays=rays, seed=a.seed, threads=T)
            ff_s = ff.timings["form_factors"]
            for s in DETERMINISTIC:
                record("B", s, "matrix", rays, "rays/patch",
                       radwalk.solve(scene, ff, solver=s, tol=1e-6, max_iterations=100000000, threads=T), ff_s)
            if rays == 1024:
                walks("B", ff, ff_s, "matrix")
        walks("B", None, 0.0, "ray")
        # The continuous path tracer's patch averages (MIS, no F): its error against the discrete reference also
        # holds the discretisation error (about 1e-3 at these patch sizes, see discretisation_error.py).
        for w in walk_budgets:
            pt = radwalk.pathtrace(scene, spp=w, seed=a.seed, threads=T).averages
            record("B", "pathtrace-mis", "continuous", w, "samples/patch", pt, 0.0,
                   note="continuous solution: error includes the discretisation error", steps=0)
        print(f"  panel B done", flush=True)

    fields = ["max_edge", "patches", "panel", "method", "kernel", "budget", "budget_unit", "ff_seconds",
              "solve_seconds", "total_seconds", "error", "status", "iterations", "steps", "note"]
    rwexp.write_csv(rw.path("speed_accuracy.csv"), rows, fields)
    print(f"wrote {rw.path('speed_accuracy.csv')}")
    plot(rows, levels, rw)
    summary(rows, levels)


STYLE = {
    "direct": ("k", "*"), "jacobi": ("tab:gray", "s"), "gauss-seidel": ("tab:brown", "D"),
    "southwell": ("tab:olive", "P"),
    "gather-absorption": ("tab:blue", "o"), "gather-collision": ("tab:orange", "o"),
    "gather-expected-value": ("tab:green", "o"),
    "shoot-collision": ("tab:red", "^"), "shoot-absorption": ("tab:purple", "^"), "shoot-survival": ("tab:pink", "^"),
    "pathtrace-mis": ("tab:cyan", "X"),
}


FLOOR = 1e-9  # errors below this (the direct solve against itself in panel A: rounding only) are drawn here


def plot(rows, levels, rw):
    for me in levels:
        fig, axes = plt.subplots(1, 2, figsize=(14, 7.8), sharey=True)
        ref = [r for r in rows if r["max_edge"] == me and r["panel"] == "reference"][0]
        handles = {}
        for ax, panel in zip(axes, "AB"):
            sel = [r for r in rows if r["max_edge"] == me and r["panel"] == panel]
            keys = []
            for r in sel:
                k = (r["method"], r["kernel"])
                if k not in keys:
                    keys.append(k)
            for method, kernel in keys:
                pts = sorted([r for r in sel if r["method"] == method and r["kernel"] == kernel],
                             key=lambda r: r["total_seconds"])
                t = [max(r["total_seconds"], 1e-5) for r in pts]
                e = [max(r["error"], FLOOR) for r in pts]
                color, marker = STYLE[method]
                ray = kernel == "ray"
                label = method + (" (ray kernel, no F)" if ray else " (continuous, no F)" if kernel == "continuous" else "")
                if method == "direct" and panel == "A":
                    label = "direct (= reference: error < 1e-9, drawn at 1e-9)"
                (h,) = ax.plot(t, e, "--" if ray else "-", color=color, marker=marker, label=label, ms=6,
                               mfc="none" if ray else color)
                handles.setdefault(label, h)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(FLOOR / 2, None)
            ax.grid(True, which="both", alpha=0.3)
            ax.set_xlabel("wall time (s): " + ("solve stage only (F_ref given)" if panel == "A" else
                                                "form factors + solve"))
            if panel == "B":
                h = ax.axhline(ref["error"], color="k", lw=1, ls=":")
                handles["noise of the reference itself (two seeds)"] = h
        axes[0].set_ylabel("RMS relative per-patch error of B (1)")
        axes[0].set_title(f"A: solver error only, every method reads the same F_ref")
        bmax = max(r["budget"] for r in rows if r["panel"] == "B" and r["budget_unit"] == "rays/patch")
        axes[1].set_title(f"B: from scratch (deterministic: own F, 64..{int(bmax)} rays/patch;\n"
                          "matrix walks: F of 1024 rays/patch; ray-kernel walks: no F)", fontsize=10)
        fig.suptitle(f"Cornell box, max edge {me:g} mm ({int(ref['patches'])} patches): error against wall time; "
                     f"reference = direct solve with F from {int(ref['budget'])} rays/patch")
        fig.legend(list(handles.values()), list(handles.keys()), loc="lower center", ncol=4, fontsize=8.5)
        fig.tight_layout(rect=(0, 0.15, 1, 1))
        fig.savefig(rw.path(f"speed_accuracy_e{int(me)}.png"), dpi=110)
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
