#!/usr/bin/env bash
# pvpython through scripts/pvpython.sh leaves no Open MPI session folder: test_no_mpi_session.sh SOURCE_DIR
#
# Debian's pvpython initialises MPI as a singleton unless told --no-mpi, and a script that ends through sys.exit
# (every script with an exit status: tests/paraview/check_outputs.py, scripts/paraview_render.py) leaves the
# singleton's empty job-family folder ompi.HOST.UID/jf.N in the temporary directory, one more at every run. This runs
# such a script (ParaView's simple module imported, then sys.exit(0)) with a temporary directory of its own, and
# checks that it holds nothing afterwards. It fails without the --no-mpi that scripts/pvpython.sh passes. No X
# needed (nothing is rendered). Exit 0 passed, 1 failed, 77 (skipped) where ParaView cannot be fetched.
set -uo pipefail
src=$1
skip=77
status=0
"$src/scripts/pvpython.sh" --fetch || status=$?
if [ "$status" -ne 0 ]; then
  [ "$status" -eq "$skip" ] && echo "SKIP: ParaView packages cannot be fetched here (see above)" >&2
  exit "$status"
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/radwalk_no_mpi_session.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/tmp"
cat >"$work/exits.py" <<'PY'
import sys
from paraview.simple import *  # noqa: F401,F403  (the process module, which initialises MPI unless --no-mpi)
print("pvpython ran", flush=True)
sys.exit(0)
PY
TMPDIR=$work/tmp "$src/scripts/pvpython.sh" "$work/exits.py" || { echo "FAIL: pvpython exited with $?" >&2; exit 1; }
left=$(cd "$work/tmp" && find . -mindepth 1 | sort)
if [ -n "$left" ]; then
  echo "FAIL: pvpython left in its temporary directory:" >&2
  echo "$left" >&2
  exit 1
fi
echo "pvpython left nothing in its temporary directory"
