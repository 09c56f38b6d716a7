#!/usr/bin/python3
"""Speed against accuracy on the Cornell box: every discrete method's error against wall time (log-log).

For each patch level (--max-edge values):
  reference  `radwalk formfactors --rays REF` (seed 1) -> F_ref.mtx, then `radwalk solve --solver direct
             --form-factors F_ref.mtx`. A second reference with seed 2 measures the reference's own noise
             (RMS difference / sqrt 2), the floor under every error in panel B.
  panel A    solver error only: every method reads the same F_ref.mtx; error against the reference; time = the
             solve stage of the JSON summary (timings_s.solve). Deterministic solvers at tol 1e-2 .. 1e-8,
             matrix-kernel random walks (6 estimators) at several walk budgets.
  panel B    everything from scratch: deterministic solvers with their own F at several ray budgets (total
             time = form-factor stage + solve stage; the form-factor time is also a column of its own),
             matrix-kernel walks on a 1024-ray F (time = its form-factor stage + walks), ray-kernel walks
             (no F at all; time = walks, tracing included).
Error = RMS over (patch, channel) of (B - B_ref) / B_ref. Writes OUT/speed_accuracy.csv, OUT/*.png, the
reference's .vtp and the matrices."""

import math
import os

import numpy as np

import rwexp
from rwexp import plt

GATHER = ["absorption", "collision", "expected-value"]
SHOOT = ["collision", "absorption", "survival"]
DETERMINISTIC = ["direct", "jacobi", "gauss-seidel", "southwell"]



def walk_count_option(walk):
    """radwalk's count option for a walk direction: walks from each patch, or particles in total."""
    return "--walks-per-patch" if walk == "gather" else "--particles"

def main():
    p = rwexp.parser("speed_accuracy", __doc__.splitlines()[0])
    p.add_argument("--max-edge", type=float, nargs="+", default=[100, 50], help="patch levels (mm)")
    p.add_argument("--ref-rays", type=int, default=100000, help="rays per patch of the reference F")
    p.add_argument("--scale", type=int, default=1,
                   help="multiplies walk and ray budgets (adds one budget step per factor 4) and adds "
                        "--max-edge 25 when >= 4")
    p.add_argument("--replot", action="store_true", help="only redraw the charts from OUT/speed_accuracy.csv")
    a = p.parse_args()
    if a.replot:
        rows = rwexp.read_csv(os.path.join(a.out, "speed_accuracy.csv"))
        levels = sorted({r["max_edge"] for r in rows}, reverse=True)
        plot(rows, levels, rwexp.Folder(a.out))
        summary(rows, levels)
        return
    rw = rwexp.Radwalk(a.radwalk, a.out, a.threads)
    scene = os.path.join(rwexp.MESHES, "cornell_box.obj")
    levels = list(a.max_edge) + ([25.0] if a.scale >= 4 and 25.0 not in a.max_edge else [])
    extra = int(round(math.log(a.scale, 4))) if a.scale > 1 else 0
    walk_budgets = [16 * 4 ** k for k in range(5 + extra)]       # walks per patch (gather), x N particles (shoot)
    ray_budgets = [64 * 4 ** k for k in range(4 + extra)]        # rays per patch of the working F
    tols = [1e-2, 1e-4, 1e-6, 1e-8]
    rows = []
    for me in levels:
        tag = f"e{int(me)}"
        common = [scene, "--max-edge", me, "--seed", a.seed]

        # Reference (and its noise from a second seed).
        refs = []
        for s in (a.seed, a.seed + 1):
            F = rw.path(f"{tag}_Fref_s{s}.mtx")
            ff = rw.run(["formfactors", scene, "--max-edge", me, "--seed", s, "--rays", a.ref_rays, "-o", F],
                        rw.path(f"{tag}_Fref_s{s}.json"))["json"]
            csvp = rw.path(f"{tag}_reference_s{s}.csv")
            extra_out = ["-o", rw.path(f"{tag}_reference.vtp")] if s == a.seed else []
            rw.run(["solve", scene, "--max-edge", me, "--solver", "direct", "--form-factors", F, "--csv", csvp]
                   + extra_out, rw.path(f"{tag}_reference_s{s}.json"))
            refs.append((rwexp.read_B(csvp), ff["timings_s"]["form_factors"], F))
        B_ref, ref_ff_s, F_ref = refs[0]
        N = B_ref.shape[0]
        ref_noise = rwexp.rms_relative_error(refs[1][0], B_ref) / math.sqrt(2)
        print(f"max-edge {me}: {N} patches, reference F {a.ref_rays} rays/patch in {ref_ff_s:.1f} s, "
              f"reference noise (RMS relative) {ref_noise:.2e}")
        rows.append(dict(max_edge=me, patches=N, panel="reference", method="direct (reference)", kernel="matrix",
                         budget=a.ref_rays, budget_unit="rays/patch", ff_seconds=ref_ff_s, solve_seconds=math.nan,
                         total_seconds=ref_ff_s, error=ref_noise, status="converged", iterations=0, steps=0,
                         note="error = RMS difference of two reference seeds / sqrt 2"))

        def solve(panel, method, kernel, budget, unit, args, ff_s, name):
            csvp = rw.path(f"{tag}_{name}.csv")
            js = rw.run(["solve"] + common + args + ["--csv", csvp], rw.path(f"{tag}_{name}.json"),
                        ok_codes=(0, 1))["json"]
            sol = js["solution"]
            solve_s = js["timings_s"]["solve"]
            B = rwexp.read_B(csvp)
            os.remove(csvp)
            os.remove(rw.path(f"{tag}_{name}.json"))
            rows.append(dict(max_edge=me, patches=N, panel=panel, method=method, kernel=kernel, budget=budget,
                             budget_unit=unit, ff_seconds=ff_s, solve_seconds=solve_s, total_seconds=ff_s + solve_s,
                             error=rwexp.rms_relative_error(B, B_ref), status=sol["status"],
                             iterations=sol["iterations"], steps=sol["steps"], note=""))

        # Panel A: shared F_ref.
        shared = ["--form-factors", F_ref]
        solve("A", "direct", "matrix", 0, "-", shared + ["--solver", "direct"], 0.0, "A_direct")
        for s in DETERMINISTIC[1:]:
            for tol in tols:
                solve("A", s, "matrix", tol, "tol", shared + ["--solver", s, "--tol", tol, "--max-iterations",
                                                              100000000], 0.0, f"A_{s}_{tol:g}")
        for walk, ests in (("gather", GATHER), ("shoot", SHOOT)):
            for est in ests:
                for w in walk_budgets:
                    n = w if walk == "gather" else w * N
                    solve("A", f"{walk}-{est}", "matrix", w, "walks/patch", shared + [
                        "--solver", "random-walk", "--walk", walk, "--estimator", est, "--kernel", "matrix",
                        walk_count_option(walk), n], 0.0, f"A_{walk}_{est}_{w}")

        # Panel B: from scratch.
        for rays in ray_budgets:
            F = rw.path(f"{tag}_F_{rays}.mtx")
            ff = rw.run(["formfactors"] + common + ["--rays", rays, "-o", F], rw.path(f"{tag}_F_{rays}.json"))
            ff_s = ff["json"]["timings_s"]["form_factors"]
            for s in DETERMINISTIC:
                solve("B", s, "matrix", rays, "rays/patch", ["--form-factors", F, "--solver", s, "--tol", 1e-6,
                                                             "--max-iterations", 100000000], ff_s, f"B_{s}_{rays}")
            if rays == 1024:
                for walk, ests in (("gather", GATHER), ("shoot", SHOOT)):
                    for est in ests:
                        for w in walk_budgets:
                            n = w if walk == "gather" else w * N
                            solve("B", f"{walk}-{est}", "matrix", w, "walks/patch", [
                                "--form-factors", F, "--solver", "random-walk", "--walk", walk, "--estimator", est,
                                "--kernel", "matrix", walk_count_option(walk), n], ff_s, f"B_{walk}_{est}_m{w}")
            if rays != ray_budgets[-1]:
                os.remove(F)
        for walk, ests in (("gather", GATHER), ("shoot", SHOOT)):
            for est in ests:
                for w in walk_budgets:
                    n = w if walk == "gather" else w * N
                    solve("B", f"{walk}-{est}", "ray", w, "walks/patch", [
                        "--solver", "random-walk", "--walk", walk, "--estimator", est, "--kernel", "ray",
                        walk_count_option(walk), n], 0.0, f"B_{walk}_{est}_r{w}")
        # The continuous path tracer's patch averages (MIS, no F): its error against the discrete reference also
        # holds the discretisation error (about 1e-3 at these patch sizes, see discretisation_error.py).
        for w in walk_budgets:
            csvp, jsp = rw.path(f"{tag}_B_pt_{w}.csv"), rw.path(f"{tag}_B_pt_{w}.json")
            js = rw.run(["pathtrace"] + common + ["--spp", w, "--csv", csvp], jsp)["json"]
            t = js["timings_s"]["patch_averages"]
            B = rwexp.read_B(csvp)
            os.remove(csvp)
            os.remove(jsp)
            rows.append(dict(max_edge=me, patches=N, panel="B", method="pathtrace-mis", kernel="continuous",
                             budget=w, budget_unit="samples/patch", ff_seconds=0.0, solve_seconds=t,
                             total_seconds=t, error=rwexp.rms_relative_error(B, B_ref),
                             status=js["solution"]["status"], iterations=0, steps=0,
                             note="continuous solution: error includes the discretisation error"))
        os.remove(rw.path(f"{tag}_reference_s{a.seed + 1}.csv"))  # keep one reference (csv, vtp, F_ref)
        os.remove(rw.path(f"{tag}_Fref_s{a.seed + 1}.mtx"))

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
