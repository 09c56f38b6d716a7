#!/usr/bin/env bash
# The render scripts never leave an X server behind: test_with_xvfb.sh SOURCE_DIR [WRAPPER ARGS...]
#
# Runs scripts/paraview_render.py under WRAPPER (default: SOURCE_DIR/scripts/with_xvfb.sh) with a fake pvpython
# first on PATH that records its X server's pid ($RADWALK_XVFB_PID, which with_xvfb.sh sets; else the server's lock
# file /tmp/.X<N>-lock, which xvfb-run's server writes) and then crashes
# (SIGABRT) or hangs, and checks after each run that the server is gone (or a zombie: ended, not yet reaped):
#   1. pvpython aborts;  2. the wrapper gets SIGTERM;  3. timeout(1) ends the wrapper;  4. the wrapper gets SIGKILL.
# `test_with_xvfb.sh SRC xvfb-run -a` shows what xvfb-run does (it fails cases 2 to 4). Exit 0 when every case
# passed, 1 otherwise, 77 (skipped) without Xvfb or setpriv. Whatever it started is ended at its exit.
set -uo pipefail
src=$1
shift
wrapper=("$@")
[ ${#wrapper[@]} -gt 0 ] || wrapper=("$src/scripts/with_xvfb.sh")
for tool in Xvfb setpriv timeout; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool is missing" >&2; exit 77; }
done

work=$(mktemp -d "${TMPDIR:-/tmp}/radwalk_xvfb_test.XXXXXX")
cleanup() {  # anything a failing case left: the recorded servers and fake pvpythons
  # Only a pid that is still one of those: an ended one's number may by now belong to another process (pid_max is
  # often 32768, and a busy machine wraps it within seconds), e.g. the X server of a render test running beside this.
  for f in "$work"/record.*; do
    [ -f "$f" ] || continue
    while read -r pid; do
      cmd=$(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null) || continue
      case "$cmd" in
        Xvfb* | */Xvfb* | *"$work/bin/pvpython"* | "sleep 600"*) kill -KILL "$pid" 2>/dev/null ;;
      esac
    done <"$f"
  done
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/bin"
cat >"$work/bin/pvpython" <<'FAKE'
#!/bin/sh
# A pvpython that records its X server's pid and its own, then crashes or hangs ($FAKE_MODE).
if [ -n "${RADWALK_XVFB_PID:-}" ]; then
  echo "$RADWALK_XVFB_PID" >"$RECORD.tmp"
else
  tr -d ' \n' <"/tmp/.X${DISPLAY#:}-lock" >"$RECORD.tmp"
  echo >>"$RECORD.tmp"
fi
echo $$ >>"$RECORD.tmp"
mv "$RECORD.tmp" "$RECORD"
case "$FAKE_MODE" in
  abort) kill -ABRT $$ ;;
  hang) exec sleep 600 ;;
esac
FAKE
chmod +x "$work/bin/pvpython"

failures=0
gone() {  # pid ended (absent, or a zombie)
  [ -r "/proc/$1/stat" ] || return 0
  [ "$(awk '{print $3}' "/proc/$1/stat" 2>/dev/null)" = Z ]
}
expect_server_gone() {  # case record
  local server
  server=$(head -n 1 "$2" 2>/dev/null)
  if [ -z "$server" ]; then
    echo "FAIL $1: the fake pvpython never ran under an X server" >&2
    failures=$((failures + 1))
    return
  fi
  for _ in $(seq 50); do gone "$server" && break; sleep 0.1; done
  if gone "$server"; then
    echo "ok   $1: X server $server ended"
  else
    echo "FAIL $1: X server $server still running after the wrapper ended" >&2
    failures=$((failures + 1))
  fi
}
wait_for() {  # file: until it exists (20 s at most)
  for _ in $(seq 200); do [ -s "$1" ] && return 0; sleep 0.1; done
  return 1
}
# The render script under the wrapper, with the fake pvpython first on PATH; `env` execs the wrapper, so that $!
# of a background run is the wrapper's own pid.
render=(env "PATH=$work/bin:$PATH" "${wrapper[@]}" "$src/scripts/paraview_render.py" "$work/none.vtp" "$work/none.png")

echo "1. pvpython aborts"
RECORD="$work/record.abort" FAKE_MODE=abort "${render[@]}" >/dev/null 2>&1
status=$?
[ "$status" -ne 0 ] || { echo "FAIL 1: exit status 0 after a crash" >&2; failures=$((failures + 1)); }
expect_server_gone "1 (abort, exit $status)" "$work/record.abort"

echo "2. the wrapper gets SIGTERM"
RECORD="$work/record.term" FAKE_MODE=hang "${render[@]}" >/dev/null 2>&1 &
pid=$!
wait_for "$work/record.term"
kill -TERM "$pid"
wait "$pid"
expect_server_gone "2 (SIGTERM)" "$work/record.term"

echo "3. timeout(1) ends the wrapper"
RECORD="$work/record.timeout" FAKE_MODE=hang timeout 5 "${render[@]}" >/dev/null 2>&1
expect_server_gone "3 (timeout, exit $?)" "$work/record.timeout"

echo "4. the wrapper gets SIGKILL"
RECORD="$work/record.kill" FAKE_MODE=hang "${render[@]}" >/dev/null 2>&1 &
pid=$!
wait_for "$work/record.kill"
kill -KILL "$pid"
wait "$pid"
expect_server_gone "4 (SIGKILL)" "$work/record.kill"

echo "5. no temporary folder of the wrapper is left"
left=$(find "${TMPDIR:-/tmp}" -maxdepth 1 -name 'radwalk_xvfb.*' -newer "$work/bin/pvpython" 2>/dev/null)
if [ -n "$left" ]; then
  echo "FAIL 5: left behind: $left" >&2
  failures=$((failures + 1))
else
  echo "ok   5: none"
fi

[ "$failures" -eq 0 ] && echo "every case passed" || echo "$failures case(s) failed"
[ "$failures" -eq 0 ]
