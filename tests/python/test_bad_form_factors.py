"""A caller's F (scipy.sparse or a dense array) is checked before anything reads it: scipy checks neither the
range of indices nor the order of indptr, so an unchecked F read one past the end, crashed, corrupted the heap, or
(int64 indices above 2^32) wrapped silently into valid columns. Every bad F raises radwalk.InputError naming what
is wrong. Each case runs in a child process, so a crash fails the case instead of killing the test run."""
import subprocess
import sys
import textwrap

import pytest

from conftest import mesh

PRELUDE = textwrap.dedent(f"""
    import numpy as np, scipy.sparse as sp, radwalk
    scene = radwalk.load({mesh("cube.obj")!r})
    n = len(scene)
    G = radwalk.form_factors(scene, rays=200, seed=1).F.copy()   # a sound F (float32 CSR, sorted)

    def csr(data, indices, indptr, shape=None):
        # Built without scipy's checks, as a caller's arrays may arrive.
        F = sp.csr_matrix((n, n), dtype=np.float32)
        F.data, F.indices, F.indptr = np.asarray(data), np.asarray(indices), np.asarray(indptr)
        if shape is not None:
            F._shape = shape
        return F
""")

# (what, expression building F, text the message must contain)
CASES = [
    ("column one past the end", "csr(G.data, np.where(np.arange(G.nnz) == 0, n, G.indices).astype(np.int32), G.indptr)",
     "outside [0, 6)"),
    ("column far out", "csr(G.data, np.where(np.arange(G.nnz) == 3, 10**9, G.indices).astype(np.int32), G.indptr)",
     "outside [0, 6)"),
    ("negative column", "csr(G.data, np.where(np.arange(G.nnz) == 2, -5, G.indices).astype(np.int32), G.indptr)",
     "outside [0, 6)"),
    ("int64 column above 2^32 (wraps to a valid one)",
     "csr(G.data, np.where(np.arange(G.nnz) == 1, 2**32 + 1, G.indices).astype(np.int64), G.indptr.astype(np.int64))",
     "outside [0, 6)"),
    ("uint64 column above 2^63", "(lambda i: (i.__setitem__(1, np.uint64(2**64 - 1)), csr(G.data, i, G.indptr))[1])(G.indices.astype(np.uint64))",
     "2^63"),
    ("indptr decreasing", "csr(G.data, G.indices, np.array([0, 5, 3, 10, 15, 20, G.nnz], np.int32))", "decreases"),
    ("indptr too short", "csr(G.data, G.indices, G.indptr[:-1])", "offsets"),
    ("indptr not from 0", "csr(G.data, G.indices, G.indptr + 1)", "starts at"),
    ("indptr beyond the indices", "csr(G.data, G.indices, np.append(G.indptr[:-1], G.nnz + 100).astype(np.int32))",
     "ends at"),
    ("float indices", "csr(G.data, G.indices.astype(np.float64), G.indptr)", "integers"),
    ("NaN value", "csr(np.where(np.arange(G.nnz) == 0, np.nan, G.data).astype(np.float32), G.indices, G.indptr)",
     "finite"),
    ("infinite value", "sp.csr_matrix(np.full((n, n), np.inf))", "finite"),
    ("negative value", "csr(-G.data, G.indices, G.indptr)", ">= 0"),
    ("float64 beyond float32", "sp.csr_matrix(np.full((n, n), 1e300))", "float32"),
    ("complex values", "sp.csr_matrix(np.ones((n, n), np.complex128) / n)", "real"),
    ("wrong shape", "sp.csr_matrix((n, n + 1), dtype=np.float32)", "patches"),
    ("wrong shape, dense", "np.zeros((n + 1, n))", "patches"),
    ("1-D array", "np.zeros(n * n)", "patches"),
    ("coo with a row out of range", "sp.coo_matrix((np.array([0.5]), (np.array([n]), np.array([0]))), shape=(n + 1, n))",
     "patches"),
    ("coo with a column out of range (set after construction)",
     "(lambda F: (setattr(F, 'col', np.array([n + 3], np.int32)), F)[1])(sp.coo_matrix((np.array([0.5]), (np.array([0]), np.array([0]))), shape=(n, n)))",
     "outside [0, 6)^2"),
    ("csc with a row out of range",
     "(lambda F: (setattr(F, 'indices', np.where(np.arange(F.nnz) == 0, -1, F.indices).astype(np.int32)), F)[1])(G.tocsc())",
     "outside [0, 6)"),
    ("a string", "'F.mtx'", "FormFactors"),
]


def run(expression):
    code = PRELUDE + textwrap.dedent(f"""
        F = {expression}
        try:
            r = radwalk.solve(scene, F)
        except radwalk.InputError as e:
            print("InputError:", e)
        else:
            print("accepted:", np.isfinite(r.B).all())
    """)
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("what, expression, expected", CASES, ids=[c[0] for c in CASES])
def test_a_bad_F_is_refused_with_InputError(what, expression, expected):
    result = run(expression)
    assert result.returncode == 0, f"{what}: the child died ({result.returncode}): {result.stderr[-2000:]}"
    out = result.stdout.strip()
    assert out.startswith("InputError:"), f"{what}: not refused: {out} {result.stderr[-2000:]}"
    assert expected in out and "\n" not in out


def test_a_sound_F_in_any_format_gives_the_same_B():
    code = PRELUDE + textwrap.dedent("""
        ref = radwalk.solve(scene, G).B
        unsorted = G.copy()
        for i in range(n):   # reverse each row's entries and claim the indices are sorted
            a, b = unsorted.indptr[i], unsorted.indptr[i + 1]
            unsorted.indices[a:b] = unsorted.indices[a:b][::-1].copy()
            unsorted.data[a:b] = unsorted.data[a:b][::-1].copy()
        unsorted.has_sorted_indices = True
        for F in (G.tocsc(), G.tocoo(), G.tolil(), G.todok(), G.tobsr(blocksize=(2, 2)), G.toarray(),
                  G.astype(np.float64), sp.csr_array(G), unsorted,
                  sp.csr_matrix((G.data, G.indices.astype(np.int64), G.indptr.astype(np.int64)), shape=G.shape)):
            assert np.array_equal(radwalk.solve(scene, F).B, ref), type(F)
        print("ok")
    """)
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0 and result.stdout.strip() == "ok", result.stderr[-3000:]
