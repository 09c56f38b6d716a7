#!/usr/bin/env bash
# Builds the manual (docs/, nav in mkdocs.yml) into a browsable site with Debian's mkdocs (package mkdocs,
# installed by scripts/install-deps.sh), then checks every relative link and #anchor of README.md and docs/
# (scripts/check_docs_links.py). Fails on any mkdocs warning (--strict: a link to a missing page) and on any
# broken link or anchor. Usage: scripts/build-docs.sh [SITE_DIR]   (default build/docs-site)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
site="${1:-$root/build/docs-site}"
case "$site" in /*) ;; *) site="$PWD/$site" ;; esac
cd "$root"
if ! command -v mkdocs >/dev/null; then
  echo "build-docs: mkdocs is missing: apt-get install mkdocs (or ./scripts/install-deps.sh)" >&2
  exit 2
fi
/usr/bin/python3 scripts/check_docs_links.py "$root"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
# The hook is loaded from scripts/: no __pycache__ left in the source tree.
status=0
PYTHONDONTWRITEBYTECODE=1 mkdocs build --strict --clean --config-file mkdocs.yml --site-dir "$site" >"$log" 2>&1 || status=$?
cat "$log"
if [ "$status" -ne 0 ] || grep -q 'WARNING' "$log"; then
  echo "build-docs: mkdocs reported warnings or failed (exit $status)" >&2
  exit 1
fi
echo "build-docs: site in $site (open $site/index.html)"
