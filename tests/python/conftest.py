"""Shared fixtures of the Python module's tests: the CLI of the same build, the source tree, small scenes."""
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

SOURCE = Path(os.environ.get("RADWALK_SOURCE", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("RADWALK_CLI", str(SOURCE / "build" / "apps" / "radwalk"))


def pytest_configure(config):
    """Gives the run a scratch folder of its own in the temporary directory it was given: tmp_path's folders
    (pytest's --basetemp), tempfile's and those of every child process (TMPDIR) go there. It is removed when the
    run passes and kept, and named, when a test failed (as the C++ tests' scratch folders)."""
    scratch = tempfile.mkdtemp(prefix="radwalk-test-pytest-")
    config._radwalk_scratch = scratch
    config.option.basetemp = os.path.join(scratch, "basetemp")
    os.environ["TMPDIR"] = scratch
    tempfile.tempdir = scratch


def pytest_unconfigure(config):
    scratch = getattr(config, "_radwalk_scratch", None)
    if scratch is None:
        return
    failed = getattr(config, "_radwalk_failed", True)
    if failed:
        print(f"radwalk test: kept scratch folder {scratch}", file=sys.stderr)
    else:
        shutil.rmtree(scratch, ignore_errors=True)


def pytest_sessionfinish(session, exitstatus):
    session.config._radwalk_failed = exitstatus != 0


def run_cli(*args, check=True):
    """Runs the radwalk program of the same build; returns the CompletedProcess (text)."""
    result = subprocess.run([CLI, *map(str, args), "-q"], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"radwalk {' '.join(map(str, args))} failed: {result.stderr}")
    return result


@pytest.fixture
def cube(tmp_path):
    """A private copy of the bundled cube (OBJ + MTL), so that tests may edit its MTL."""
    for name in ("cube.obj", "cube.mtl"):
        shutil.copy(SOURCE / "meshes" / name, tmp_path / name)
    return tmp_path / "cube.obj"


def mesh(name):
    return str(SOURCE / "meshes" / name)


def data(name):
    return str(SOURCE / "tests" / "data" / name)


def without_run_id(data):
    """A file's bytes without the run id the CLI writes into it (docs/reliability.md, "Run id"): the CSV's last
    column `run_id`, the `% run_id` / `# run_id` comment lines. The module writes none (it is not a CLI run)."""
    lines = data.split(b"\n")
    if lines and lines[0].endswith(b",run_id"):
        lines = [l.rsplit(b",", 1)[0] if l else l for l in lines]
    return b"\n".join(l for l in lines if not l.startswith((b"% run_id", b"# run_id")))
