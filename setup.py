"""Builds the Python module `radwalk` with the project's CMake build, for the Python that runs this script.

Contract: `pip install .` (setuptools.build_meta, pyproject.toml) calls build_ext, which configures CMake in
build-pip/ beside this file with Python_EXECUTABLE = the running interpreter (so the module gets that Python's ABI
suffix), builds only the target radwalk_python (the C++ libraries and the bindings; no tests, no benchmarks) and
copies the module where setuptools packs it. The version is the one of `project(radwalk VERSION ...)` in
CMakeLists.txt. RADWALK_CMAKE_ARGS adds CMake arguments (e.g. "-DRADWALK_MPI=OFF"); ccache is used when installed,
with CCACHE_BASEDIR at the source root (whatever the environment says) so that a copy of the source shares the
cache of another checkout's build (scripts/build.sh does the same).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def project_version():
    match = re.search(r"project\(radwalk VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not match:
        raise RuntimeError("CMakeLists.txt: no 'project(radwalk VERSION x.y.z ...)' line to take the version from")
    return match.group(1)


class CMakeTarget(Extension):
    """An extension module that CMake builds (no sources for setuptools to compile)."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class BuildWithCMake(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("RADWALK_PIP_BUILD_DIR", ROOT / "build-pip"))
        configure = ["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", "-DRADWALK_PYTHON=ON",
                     "-DRADWALK_BUILD_TESTS=OFF", "-DRADWALK_BUILD_BENCH=OFF"]
        if shutil.which("ccache"):
            configure += ["-DCMAKE_C_COMPILER_LAUNCHER=ccache", "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
        configure += shlex.split(os.environ.get("RADWALK_CMAKE_ARGS", ""))
        env = dict(os.environ)
        env["CCACHE_BASEDIR"] = str(ROOT)  # this root, whatever the caller's: paths relative to it hash alike
        subprocess.run(configure, check=True, env=env)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", ext.target, "-j", str(os.cpu_count() or 1)],
                       check=True, env=env)
        built = build_dir / "python" / ("radwalk" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not built.exists():
            raise RuntimeError(f"CMake built no {built.name} in {built.parent} for {sys.executable}")
        destination = Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, destination)


setup(version=project_version(), ext_modules=[CMakeTarget("radwalk", "radwalk_python")],
      cmdclass={"build_ext": BuildWithCMake}, zip_safe=False)
