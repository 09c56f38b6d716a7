#!/usr/bin/env bash
# Installs the Debian 12 packages radwalk needs, skipping apt entirely when all are present.
set -euo pipefail
packages=(
  build-essential cmake pkg-config ccache
  libeigen3-dev libembree-dev libopenmesh-dev libvtk9-dev catch2 libtbb-dev libcli11-dev
  nlohmann-json3-dev libtinyobjloader-dev libpng-dev libjpeg-dev zlib1g-dev libexpat1-dev libboost-dev libopenexr-dev python3-matplotlib python3-scipy
  pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest  # the Python module (python/)
  python3-meshio  # Scene.from_meshio, Result.to_meshio (optional for the module, needed by its tests)
  python3-venv python3-pip python3-setuptools  # pip install . (pyproject.toml, setup.py)
  openmpi-bin libopenmpi-dev  # MPI runs (src/core/distributed.h) and the mpi test label (tests/mpi)
  clang libclang-rt-14-dev llvm-14  # the fuzz harnesses (tests/fuzz): libFuzzer, sanitizer runtimes, symbolizer
  mkdocs  # the manual as a site (scripts/build-docs.sh, mkdocs.yml) and the docs test label (tests/docs)
)
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
