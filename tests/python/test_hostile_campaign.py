"""A campaign of hostile arguments against every public entry point of the module, from a fixed seed.

Each call must either succeed with finite outputs or raise one of the module's documented exceptions:
radwalk.InputError (a ValueError: bad input, the CLI's one-line message), radwalk.NumericalError (a system with no
finite solution) or TypeError (an argument of the wrong Python type, refused by pybind11's conversion). Anything
else (another exception, a non-finite output, a call running longer than CALL_LIMIT_S) is a finding. The campaign
runs in a child process, so a crash fails this test with the call that crashed (the child prints each call before
making it) instead of killing the test runner. About 600 calls on a 6-patch scene, a few seconds."""
import os
import subprocess
import sys
import textwrap

from conftest import mesh

SEED = 20261204
CALLS = 600
CALL_LIMIT_S = 10

CHILD = textwrap.dedent(r"""
    import math, os, random, signal, sys, tempfile, traceback, warnings
    import numpy as np, scipy.sparse as sp, radwalk

    warnings.simplefilter("ignore")
    radwalk.set_progress(False)
    rng = random.Random(SEED)
    nrng = np.random.default_rng(SEED)
    scene0 = radwalk.load(SCENE)
    n = len(scene0)
    ff0 = radwalk.form_factors(scene0, rays=64, seed=1, threads=1)
    tmp = tempfile.mkdtemp(prefix="radwalk-campaign-")

    class Slow(Exception):
        pass

    def alarm(*_):
        raise Slow()
    signal.signal(signal.SIGALRM, alarm)

    # --- hostile values ------------------------------------------------------------------------------------
    INTS = [-1, 0, 1, 2, 3, -2**63, 2**63 - 1, 2**63, 2**64, 2**31, -2**31 - 1, 2**40, True, 1.5, None, "3",
            np.int64(-1), np.uint64(2**64 - 1), float("nan")]
    SMALL_INTS = [1, 2, 3, 4, 16]
    FLOATS = [float("nan"), float("inf"), -float("inf"), -1.0, 0.0, 1e-308, 5e-324, 1e308, 0.5, 2**63, -0.0,
              None, "0.5", 1j]
    STRINGS = ["", "nope", "\n", "gather-collision", "shoot-collision", "direct", "jacobi", "matrix", "ray",
               "analog", "mis", "light", "patches:0", "camera", "material:white", "group:x", "csv:/nonexistent:a",
               "patches:99", "patches:-1", "\x00", "é\xff", "a" * 5000, 3, None]

    def hostile_array(shape_hint=None):
        kind = rng.choice(["float64", "float32", "int64", "uint8", "bool", "complex128", "object", "str"])
        shape = shape_hint if shape_hint is not None and rng.random() < 0.5 else rng.choice(
            [(0,), (n,), (n, 3), (n + 1,), (n + 1, 3), (3, n), (n, n), (n, 4), (), (1,), (n, 3, 1)])
        if kind == "object":
            a = np.empty(shape, dtype=object)
            a[...] = rng.choice([None, "x", 1.0])
            return a
        if kind == "str":
            return np.full(shape, "x")
        a = nrng.standard_normal(shape) * rng.choice([1, 1e-300, 1e300, 0.1])
        special = rng.choice([None, np.nan, np.inf, -np.inf, -1.0, 2.0, 1e308])
        if special is not None and a.size:
            a.flat[rng.randrange(a.size)] = special
        a = a.astype(kind) if kind not in ("float64",) else a
        if rng.random() < 0.3 and a.ndim >= 1 and a.shape[0] > 1:
            a = np.repeat(a, 2, axis=0)[::2]   # non-contiguous view
        if rng.random() < 0.2 and a.ndim == 2:
            a = np.asfortranarray(a)
        return a

    def hostile_sparse():
        G = ff0.F.copy()
        choice = rng.randrange(12)
        if choice == 0:
            return None
        if choice == 1:
            return ff0
        if choice == 2:
            return G
        F = sp.csr_matrix((n, n), dtype=np.float32)
        idx, ptr, data = G.indices.copy(), G.indptr.copy(), G.data.copy()
        if choice == 3:
            idx = idx.astype(rng.choice([np.int64, np.uint64, np.int16, np.float64]))
            if idx.size:
                idx[rng.randrange(idx.size)] = rng.choice([n, -1, 2**32, 2**33 + 1, 10**9])
        elif choice == 4:
            ptr = ptr[::-1].copy() if rng.random() < 0.5 else ptr[:-1]
        elif choice == 5:
            data = data * rng.choice([-1, np.nan, np.inf, 1e38, 1e-45])
        elif choice == 6:
            return hostile_array((n, n))
        elif choice == 7:
            return rng.choice([G.tocoo(), G.tocsc(), G.tolil(), G.todok(), G.tobsr(blocksize=(3, 3)), G.todia()])
        elif choice == 8:
            C = G.tocoo()
            C.col = C.col.copy()
            if C.col.size:
                C.col[0] = rng.choice([n, -1, 2**31 - 1])
            return C
        elif choice == 9:
            return sp.random(n + rng.choice([-1, 1]), n, density=0.5, format="csr", random_state=1)
        elif choice == 10:
            return rng.choice(["F.mtx", 3, [[0.1] * n] * n, [[1, 2], [3]], object()])
        elif choice == 11:
            ptr = ptr.astype(np.int64)
            ptr[-1] = 2**40
        F.data, F.indices, F.indptr = data, idx, ptr
        return F

    def scene():
        s = radwalk.load(SCENE)
        if rng.random() < 0.25:
            target = rng.choice(["rho", "E"])
            try:
                getattr(s, target)[rng.randrange(n), rng.randrange(3)] = rng.choice(
                    [np.nan, np.inf, -1.0, 1.0, 1e301, 0.99, 0.0])
            except (ValueError, TypeError):
                pass
        return s

    def pick(values):
        return rng.choice(values)

    # --- the entry points: name -> () -> (callable, kwargs) -----------------------------------------------
    def path():
        return rng.choice([os.path.join(tmp, "out.csv"), os.path.join(tmp, "out.vtp"), os.path.join(tmp, "F.mtx"),
                           os.path.join(tmp, "F.npz"), tmp, "/nonexistent/x.csv", "", SCENE, SCENE[:-3] + "mtl",
                           os.path.join(tmp, "a\nb.csv")])

    def fields():
        d = {}
        for _ in range(rng.randrange(3)):
            name = rng.choice(["B", "x", "B\n", "var", "", "9a", "ok_name", "a,b"])
            value = hostile_array((n, 3))
            d[name] = (value, rng.choice(["csvname", "\n", 3])) if rng.random() < 0.2 else value
        return d

    ENTRIES = {
        "load": lambda: (radwalk.load, dict(path=rng.choice([SCENE, "/nonexistent.obj", tmp, "", "x\x00y", 3]),
                                            max_edge=pick(FLOATS + [0.3]), max_area=pick(FLOATS + [0.0]),
                                            strict=pick([True, False, None]))),
        "form_factors": lambda: (radwalk.form_factors, dict(scene=scene(), rays=pick(INTS + SMALL_INTS),
                                                            rays_per_area=pick(FLOATS), min_rays=pick(INTS),
                                                            seed=pick(INTS), threads=pick(INTS))),
        "solve": lambda: (radwalk.solve, dict(scene=scene(), F=hostile_sparse(), solver=pick(STRINGS),
                                              tol=pick(FLOATS), max_iterations=pick(INTS + SMALL_INTS),
                                              rays=pick(SMALL_INTS), threads=pick(INTS))),
        "random_walk": lambda: (radwalk.random_walk, dict(
            scene=scene(), F=hostile_sparse(), method=pick(STRINGS + radwalk.walk_methods()), kernel=pick(STRINGS),
            walks_per_patch=pick(INTS + SMALL_INTS), seed=pick(INTS), survival=pick(STRINGS),
            survival_constant=pick(FLOATS), patches=pick([[], [0], [n], [-1], [0, 0], None, "0"]),
            rays=pick(SMALL_INTS), threads=pick(INTS), sampler=pick(["random", "sobol", "jacobi", "x"]),
            replicates=pick(INTS + SMALL_INTS), shadow_rays=pick(INTS))),
        "random_walk (shooting)": lambda: (radwalk.random_walk, dict(
            scene=scene(), F=hostile_sparse(), method=pick(["shoot-collision", "shoot-absorption", "shoot-survival"]),
            particles=pick(INTS + [64, 200]), direct_light=pick([True, False]),
            sampler=pick(["random", "sobol", "jacobi"]), replicates=pick(SMALL_INTS + INTS), rays=pick(SMALL_INTS))),
        "compare": lambda: (radwalk.compare, dict(scene=scene(), F=hostile_sparse(),
                                                  methods=pick([None, [], ["x"], ["gather-collision"], "gather"]),
                                                  runs=pick(INTS + SMALL_INTS), walks_per_patch=pick(INTS + [16]),
                                                  rays=pick(SMALL_INTS), threads=pick(INTS))),
        "exact_variance": lambda: (radwalk.exact_variance, dict(scene=scene(), F=hostile_sparse(),
                                                                method=pick(STRINGS + radwalk.walk_methods()),
                                                                survival=pick(STRINGS), survival_constant=pick(FLOATS),
                                                                rays=pick(SMALL_INTS), threads=pick(INTS))),
        "solve_adaptive": lambda: (radwalk.solve_adaptive, dict(scene=scene(), refine_tol=pick(FLOATS),
                                                                steps=pick(INTS + [1]), max_patches=pick(INTS + [50]),
                                                                floor_fraction=pick(FLOATS), noise_z=pick(FLOATS),
                                                                rays=pick(SMALL_INTS), rays_per_area=pick(FLOATS),
                                                                min_rays=pick(INTS), threads=pick(INTS))),
        "measure": lambda: (radwalk.measure, dict(scene=scene(),
                                                  response=rng.choice([hostile_array((n,)), pick(STRINGS)]),
                                                  F=hostile_sparse(), method=pick(STRINGS + radwalk.measure_methods()),
                                                  walks=pick(INTS + [64]), importance_sweeps=pick(INTS + [2]),
                                                  defensive=pick(FLOATS), camera=pick([[], [0] * 10, [np.nan] * 10,
                                                                                      [1] * 3]),
                                                  width=pick(INTS + [8]), height=pick(INTS + [8]),
                                                  rays=pick(SMALL_INTS), threads=pick(INTS))),
        "pathtrace": lambda: (radwalk.pathtrace, dict(scene=scene(), spp=pick(INTS + [2, 4]),
                                                      integrator=pick(STRINGS), image=pick([True, False]),
                                                      averages=pick([True, False]), width=pick(INTS + [8]),
                                                      height=pick(INTS + [8]),
                                                      camera=pick([[], [0.5, 0.5, 3, 0.5, 0.5, 0, 0, 1, 0, 40],
                                                                   [np.nan] * 10, [0] * 10, [1e308] * 10, [1]]),
                                                      threads=pick(INTS))),
        "write_csv": lambda: (radwalk.write_csv, dict(path=path(), scene=scene(), fields=fields())),
        "write_vtp": lambda: (radwalk.write_vtp, dict(path=path(), scene=scene(), fields=fields(),
                                                      metadata=pick([{}, {"a": 1}, {"\n": 1}, {"a": 2**70},
                                                                     {"a": np.nan}, {"a": "x\ny"}, {3: 1}]))),
        "write_matrix_market": lambda: (radwalk.write_matrix_market, dict(path=path(), F=hostile_sparse(),
                                                                          scene=scene())),
        "read_form_factors": lambda: (radwalk.read_form_factors, dict(path=path(), scene=scene())),
        "set_material": lambda: (scene().set_material, dict(material=pick(["white", "light", "x", 0, 1, 2, -1,
                                                                           2**70, None, 1.5]),
                                                             rho=pick(FLOATS + [(0.1, 0.2, 0.3), (0.1,), "r"]),
                                                             Ke=pick(FLOATS + [(1, 2, 3), []]))),
    }

    def finite(x):
        # Whether every number reachable from a result is finite (NaN allowed only where documented:
        # the patches a walk did not estimate, and compare's per-patch arrays; not checked there).
        if x is None:
            return True
        if isinstance(x, np.ndarray):
            return x.dtype.kind not in "fc" or bool(np.isfinite(x).all())
        if isinstance(x, float):
            return math.isfinite(x)
        if isinstance(x, radwalk.Result):
            return finite(x.B) and finite(x.B_se)
        if isinstance(x, radwalk.FormFactors):
            return finite(x.F.data)
        if isinstance(x, radwalk.Measurement):
            return finite(x.M) and finite(x.M_se)
        if isinstance(x, radwalk.PathtraceResult):
            return finite(x.image) and (x.averages is None or finite(x.averages))
        if isinstance(x, radwalk.AdaptiveResult):
            return finite(x.result)
        return True

    ALLOWED = (radwalk.InputError, radwalk.NumericalError, TypeError)
    findings, outcomes = [], {}
    names = sorted(ENTRIES)
    for k in range(CALLS):
        name = names[k % len(names)]
        fn, kwargs = ENTRIES[name]()
        # Drop some arguments at random, so defaults are exercised too.
        kwargs = {a: v for a, v in kwargs.items() if a in ("scene", "path", "F", "response") or rng.random() < 0.7}
        if name in ("random_walk", "compare", "solve_adaptive", "exact_variance") and "F" in kwargs and \
                kwargs["F"] is None:
            kwargs["rays"] = 16
        text = f"{k} {name}: " + ", ".join(f"{a}={repr(v)[:80]}" for a, v in kwargs.items() if a != "scene").replace("\n", " ")
        print(text, flush=True)
        signal.setitimer(signal.ITIMER_REAL, CALL_LIMIT_S)
        try:
            out = fn(**kwargs)
            outcome = "ok" if finite(out) else "NON-FINITE OUTPUT"
        except ALLOWED as e:
            outcome = type(e).__name__
            if isinstance(e, radwalk.InputError) and "\n" in str(e):
                outcome = "MULTI-LINE MESSAGE " + repr(str(e))
        except Slow:
            outcome = f"SLOWER THAN {CALL_LIMIT_S} s"
        except BaseException as e:
            outcome = "UNEXPECTED " + type(e).__name__ + ": " + repr(str(e))[:300]
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
        outcomes[outcome.split(" ")[0]] = outcomes.get(outcome.split(" ")[0], 0) + 1
        if outcome not in ("ok", "InputError", "NumericalError", "TypeError"):
            findings.append(text + " -> " + outcome)
    for f in os.listdir(tmp):
        os.remove(os.path.join(tmp, f))
    os.rmdir(tmp)
    print("OUTCOMES", outcomes, flush=True)
    print("FINDINGS", len(findings), flush=True)
    for f in findings:
        print("FINDING", f, flush=True)
""")


def test_hostile_arguments_never_crash_hang_or_give_non_finite_results():
    code = f"SEED = {SEED}\nCALLS = {CALLS}\nCALL_LIMIT_S = {CALL_LIMIT_S}\nSCENE = {mesh('cube.obj')!r}\n" + CHILD
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600,
                            env={**os.environ, "OMP_NUM_THREADS": "1"})
    lines = result.stdout.strip().splitlines()
    assert result.returncode == 0, (f"the campaign's child died ({result.returncode}) during: "
                                    f"{lines[-1] if lines else '(nothing)'}\n{result.stderr[-3000:]}")
    findings = [l for l in lines if l.startswith("FINDING ")]
    assert lines[-len(findings) - 1] == f"FINDINGS {len(findings)}"
    assert not findings, "\n".join(findings[:30])
    outcomes = eval(lines[-len(findings) - 2][len("OUTCOMES "):])
    # The campaign must exercise both sides: accepted calls and refusals.
    assert outcomes.get("ok", 0) >= 30 and outcomes.get("InputError", 0) >= 100, outcomes
