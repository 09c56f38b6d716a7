#!/usr/bin/env bash
# scripts/pvpython.sh [PVPYTHON ARGS...]: ParaView's pvpython without installing ParaView.
#
# Debian 12's `apt-get install paraview` would remove libvtk9-dev and python3-vtk9, which radwalk builds with, so
# this script never installs it: it downloads (apt-get download) the packages that
#   apt-get install -s --no-install-recommends paraview python3-paraview libqt5svg5
# would add (39 on a machine with radwalk's dependencies, about 76 MB of .debs), unpacks them with dpkg -x into a
# cache folder (about 570 MB, kept between runs), and runs the unpacked pvpython with
#   PYTHONPATH=<tree>/usr/lib/python3/dist-packages  (ParaView's own paraview and vtkmodules come first)
#   LD_LIBRARY_PATH=<tree>/usr/lib/<multiarch>       (its -pv5.11 VTK libraries and the Qt libraries it adds)
# The rest (Python 3.11, Qt5 core, MPI, ...) comes from the system, where radwalk's dependencies put it.
# Debian's ParaView renders through X: run it under scripts/with_xvfb.sh (an X server of its own, always ended) where
# there is no display, e.g.
#   scripts/with_xvfb.sh scripts/pvpython.sh scripts/paraview_render.py cb.vtp cb.png
#
# MPI: Debian's pvpython is built with MPI and initialises it by default as a singleton, whose Open MPI session
# folder (/tmp/ompi.HOST.UID/jf.N, or under $TMPDIR) is left behind whenever the script ends through sys.exit (as
# every script with an exit status does) instead of returning. radwalk's scripts never use ParaView's MPI, so
# pvpython is started with --no-mpi (a single process leaves nothing in /tmp), unless the arguments say --mpi.
#
# Cache: $RADWALK_PARAVIEW_CACHE, default ${XDG_CACHE_HOME:-$HOME/.cache}/radwalk/paraview (outside any build).
# `scripts/pvpython.sh --fetch` only fetches and unpacks; `--print-env` prints the environment as shell exports.
# Exit 77 (the test suite's "skipped") when the packages cannot be fetched (no apt, no network, unknown package).
set -euo pipefail

home=${HOME:-$(getent passwd "$(id -u)" 2>/dev/null | cut -d: -f6)}
cache=${RADWALK_PARAVIEW_CACHE:-${XDG_CACHE_HOME:-${home:-/tmp}/.cache}/radwalk/paraview}
root=$cache/root
packages=(paraview python3-paraview libqt5svg5)

skip() {
  echo "pvpython.sh: cannot fetch ParaView: $*" >&2
  exit 77
}

plan() {  # the packages an install would add, one per line
  apt-get install -s --no-install-recommends "${packages[@]}" 2>/dev/null | awk '/^Inst /{print $2}'
}

fetch() {
  command -v apt-get >/dev/null && command -v dpkg >/dev/null || skip "no apt-get or dpkg (Debian 12 needed)"
  mkdir -p "$cache"
  local list
  list=$(plan || true)
  if ! grep -qx paraview <<<"$list"; then
    if [ "$(id -u)" -eq 0 ]; then
      echo "pvpython.sh: apt-get update (package lists do not offer paraview yet)" >&2
      apt-get update -qq >/dev/null 2>&1 || skip "apt-get update failed"
      list=$(plan || true)
    fi
    grep -qx paraview <<<"$list" || skip "apt offers no installable paraview package here (is this Debian 12?)"
  fi
  local work
  work=$(mktemp -d "$cache/fetch.XXXXXX")
  trap 'rm -rf "$work"' RETURN
  mkdir -p "$work/debs" "$work/root"
  echo "pvpython.sh: downloading $(wc -l <<<"$list") packages into $cache" >&2
  (cd "$work/debs" && apt-get download $list >/dev/null 2>&1) || skip "apt-get download failed"
  for deb in "$work"/debs/*.deb; do dpkg -x "$deb" "$work/root"; done
  [ -x "$work/root/usr/bin/pvpython" ] || { echo "pvpython.sh: the unpacked tree has no usr/bin/pvpython" >&2; exit 1; }
  echo "$list" >"$work/root/.radwalk-packages"
  rm -rf "$root"
  mv "$work/root" "$root"
}

# One fetch at a time (a second caller waits, then finds the tree).
mkdir -p "$cache"
exec 9>"$cache/.lock"
command -v flock >/dev/null && flock 9
[ -f "$root/.radwalk-packages" ] && [ -x "$root/usr/bin/pvpython" ] || fetch
flock -u 9 2>/dev/null || true

libdir=$(ls -d "$root"/usr/lib/*-linux-gnu* 2>/dev/null | head -n 1)
export PYTHONPATH=$root/usr/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}
export LD_LIBRARY_PATH=$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
case "${1:-}" in
  --fetch) exit 0 ;;
  --print-env)
    printf 'export PYTHONPATH=%q\nexport LD_LIBRARY_PATH=%q\nPVPYTHON=%q\n' "$PYTHONPATH" "$LD_LIBRARY_PATH" \
      "$root/usr/bin/pvpython"
    exit 0 ;;
esac
mpi=(--no-mpi)
for arg in "$@"; do
  case "$arg" in --mpi | --no-mpi) mpi=() ;; esac
done
exec "$root/usr/bin/pvpython" "${mpi[@]}" "$@"
