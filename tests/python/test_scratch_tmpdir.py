"""The pytest run leaves the temporary directory as it found it (conftest.py): tmp_path, tempfile and child
processes write into one scratch folder that a passing run removes and a failing run keeps and names. Checked by
running pytest on a two-test file beside a copy of the conftest, with TMPDIR pointed at a fresh empty folder."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

DEMO = '''
import os, subprocess, tempfile

def test_writes_temporaries(tmp_path):
    (tmp_path / "a.txt").write_text("x")
    with tempfile.NamedTemporaryFile(delete=False) as f:
        f.write(b"y")
    subprocess.run(["sh", "-c", 'echo z > "$TMPDIR/child.txt"'], check=True)
    assert os.environ.get("RADWALK_SCRATCH_DEMO_FAIL", "0") == "0"
'''


def run_demo(tmp_path, tmpdir, fail):
    project = tmp_path / ("fail" if fail else "pass")
    project.mkdir()
    shutil.copy(HERE / "conftest.py", project / "conftest.py")
    (project / "test_demo.py").write_text(DEMO)
    env = dict(os.environ, TMPDIR=str(tmpdir), RADWALK_SCRATCH_DEMO_FAIL="1" if fail else "0")
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(project)],
                          cwd=project, env=env, capture_output=True, text=True)


def test_a_passing_run_leaves_tmpdir_as_found_and_a_failing_run_keeps_one_named_folder(tmp_path):
    tmpdir = tmp_path / "tmpdir"
    tmpdir.mkdir()
    passed = run_demo(tmp_path, tmpdir, fail=False)
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert list(tmpdir.iterdir()) == []

    failed = run_demo(tmp_path, tmpdir, fail=True)
    assert failed.returncode != 0
    kept = list(tmpdir.iterdir())
    assert len(kept) == 1 and kept[0].name.startswith("radwalk-test-pytest-"), kept
    assert (kept[0] / "child.txt").exists()
    assert f"kept scratch folder {kept[0]}" in failed.stderr
