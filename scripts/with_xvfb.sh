#!/usr/bin/env bash
# scripts/with_xvfb.sh COMMAND [ARGS...]: runs COMMAND with DISPLAY on an X server (Xvfb) of its own, and ends that
# server whatever happens to COMMAND or to this script: COMMAND's exit or crash, SIGINT, SIGTERM, SIGHUP (e.g.
# from timeout(1) or CTest), and even SIGKILL of this script (the server is started with the parent-death signal,
# setpriv --pdeathsig, so the kernel ends it when this script's process goes). COMMAND gets the same parent-death
# signal, so it never outlives the server either. Exit status: COMMAND's (128 + N when it died of signal N); 129,
# 130 or 143 when this script got SIGHUP, SIGINT or SIGTERM; 77 when Xvfb or setpriv is missing; 70 when the
# server did not start within 30 s.
#
# Unlike xvfb-run, which leaves its Xvfb running when it is itself terminated (its clean-up is an EXIT trap that a
# signal skips). The server chooses a free display itself (-displayfd) and listens on no TCP port.
#   scripts/with_xvfb.sh scripts/pvpython.sh scripts/paraview_render.py results/cb.vtp cb.png
#   scripts/with_xvfb.sh /usr/bin/python3 scripts/render_vtp.py results/cb.vtp cb.png
# Screen: $RADWALK_XVFB_SCREEN, default 1024x768x24. COMMAND sees the server's pid as $RADWALK_XVFB_PID.
set -uo pipefail
[ $# -ge 1 ] || { echo "usage: with_xvfb.sh COMMAND [ARGS...]" >&2; exit 2; }
for tool in Xvfb setpriv; do
  command -v "$tool" >/dev/null || { echo "with_xvfb.sh: $tool is missing (apt-get install xvfb util-linux)" >&2; exit 77; }
done

work=$(mktemp -d "${TMPDIR:-/tmp}/radwalk_xvfb.XXXXXX")
server='' child=''
end_all() {
  trap - EXIT HUP INT TERM
  if [ -n "$child" ] && kill -0 "$child" 2>/dev/null; then
    kill -TERM "$child" 2>/dev/null
    for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$child" 2>/dev/null || break; sleep 0.2; done
    kill -KILL "$child" 2>/dev/null
    wait "$child" 2>/dev/null
  fi
  if [ -n "$server" ]; then
    kill -TERM "$server" 2>/dev/null
    for _ in 1 2 3 4 5 6 7 8 9 10; do kill -0 "$server" 2>/dev/null || break; sleep 0.2; done
    kill -KILL "$server" 2>/dev/null
    wait "$server" 2>/dev/null
  fi
  rm -rf "$work"
}
trap end_all EXIT
trap 'exit 129' HUP
trap 'exit 130' INT
trap 'exit 143' TERM

# The server writes its display number to fd 3 once it accepts connections.
setpriv --pdeathsig KILL -- Xvfb -displayfd 3 -screen 0 "${RADWALK_XVFB_SCREEN:-1024x768x24}" -nolisten tcp \
  3>"$work/display" >"$work/xvfb.log" 2>&1 &
server=$!
display=''
for _ in $(seq 300); do
  display=$(head -n 1 "$work/display" 2>/dev/null)
  [ -n "$display" ] && break
  kill -0 "$server" 2>/dev/null || break
  sleep 0.1
done
if [ -z "$display" ]; then
  echo "with_xvfb.sh: Xvfb did not start:" >&2
  cat "$work/xvfb.log" >&2
  exit 70
fi
rm -rf "$work"  # no longer needed (the server keeps its open log), so that even SIGKILL leaves no folder

# COMMAND runs in the background so that the traps above run as soon as a signal arrives.
DISPLAY=":$display" RADWALK_XVFB_PID=$server setpriv --pdeathsig KILL -- "$@" &
child=$!
wait "$child"
status=$?
child=''
exit "$status"
