"""`pip install .` from a clean copy of the source, offline, into a virtual environment that sees Debian's numpy
and scipy, exactly as the README says; then `import radwalk` from another directory (no PYTHONPATH) gives the same
numbers as the module of this build. Label python; it compiles the library once more (through ccache when
scripts/build.sh used it, which makes it a minute or two)."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import radwalk
from conftest import SOURCE, mesh

SOLVE = """
import json, sys, radwalk
scene = radwalk.load(sys.argv[1])
ff = radwalk.form_factors(scene, rays=500, seed=3)
result = radwalk.solve(scene, ff)
print(json.dumps({"file": radwalk.__file__, "version": radwalk.__version__, "B": result.B.tolist()}))
"""


def clean_copy(destination):
    """The source as a clean clone has it: the files git tracks (or, outside a git checkout, everything but the
    build folders)."""
    listed = subprocess.run(["git", "-C", str(SOURCE), "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            capture_output=True)
    if listed.returncode == 0 and listed.stdout:
        for name in listed.stdout.decode().split("\0"):
            if name and (SOURCE / name).is_file():
                (destination / name).parent.mkdir(parents=True, exist_ok=True)
                shutil.copy2(SOURCE / name, destination / name)
    else:
        shutil.copytree(SOURCE, destination, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("build", "build-*", ".git", "*.egg-info"))


def test_pip_install_into_a_venv_then_import_from_elsewhere(tmp_path):
    source = tmp_path / "radwalk-src"
    source.mkdir()
    clean_copy(source)
    assert (source / "pyproject.toml").exists() and not (source / "build").exists()

    venv = tmp_path / "env"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    pip = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index", str(source)],
                         capture_output=True, text=True, env=env)
    assert pip.returncode == 0, pip.stdout[-4000:] + pip.stderr[-4000:]

    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    run = subprocess.run([str(python), "-c", SOLVE, mesh("cube.obj")], capture_output=True, text=True,
                         cwd=elsewhere, env=env)
    assert run.returncode == 0, run.stderr
    installed = json.loads(run.stdout)
    assert Path(installed["file"]).is_relative_to(venv), installed["file"]
    assert installed["version"] == radwalk.__version__

    scene = radwalk.load(mesh("cube.obj"))
    here = radwalk.solve(scene, radwalk.form_factors(scene, rays=500, seed=3))
    assert installed["B"] == here.B.tolist()  # the same code and seed: the same numbers, bit for bit
