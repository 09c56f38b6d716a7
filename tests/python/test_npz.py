"""Binary form factors (.npz): scipy reads radwalk's file as the same matrix as its Matrix Market text, and radwalk
reads scipy's uncompressed save_npz back (the same solve as from .mtx); a compressed one is refused in one line."""
import numpy as np
import scipy.io
import scipy.sparse

from conftest import mesh, run_cli, without_run_id

SCENE = mesh("cube.obj")
COMMON = ["--max-edge", 0.5, "--rays", 300, "--seed", 3]


def test_scipy_reads_the_npz_as_the_mtx(tmp_path):
    run_cli("formfactors", SCENE, *COMMON, "-o", tmp_path / "F.npz")
    run_cli("formfactors", SCENE, *COMMON, "-o", tmp_path / "F.mtx")
    F = scipy.sparse.load_npz(tmp_path / "F.npz")
    G = scipy.io.mmread(tmp_path / "F.mtx").tocsr().astype(np.float32)
    assert F.format == "csr" and F.dtype == np.float32 and F.shape == G.shape
    assert F.has_sorted_indices and F.nnz == G.nnz > 0
    assert (F != G).nnz == 0  # every value bit for bit (the .mtx holds the shortest decimal of each float)


def test_radwalk_reads_scipys_npz_and_refuses_a_compressed_one(tmp_path):
    run_cli("formfactors", SCENE, *COMMON, "-o", tmp_path / "F.mtx")
    G = scipy.io.mmread(tmp_path / "F.mtx").tocsr().astype(np.float32)
    scipy.sparse.save_npz(tmp_path / "scipy.npz", G, compressed=False)
    run_cli("solve", SCENE, "--max-edge", 0.5, "--form-factors", tmp_path / "F.mtx", "--csv", tmp_path / "a.csv")
    run_cli("solve", SCENE, "--max-edge", 0.5, "--form-factors", tmp_path / "scipy.npz", "--csv", tmp_path / "b.csv")
    a = without_run_id(open(tmp_path / "a.csv", "rb").read())
    b = without_run_id(open(tmp_path / "b.csv", "rb").read())
    assert a == b
    scipy.sparse.save_npz(tmp_path / "zipped.npz", G, compressed=True)
    r = run_cli("solve", SCENE, "--max-edge", 0.5, "--form-factors", tmp_path / "zipped.npz", check=False)
    assert r.returncode == 2
    message = r.stderr.strip()
    assert "\n" not in message and "zipped.npz" in message and "compressed=False" in message
