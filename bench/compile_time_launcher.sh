#!/usr/bin/env bash
# Compiler launcher for bench/compile_times.sh: runs the compile (through ccache when
# COMPILE_TIMES_CCACHE=1) and appends "<CPU seconds> <source>" to $COMPILE_TIMES_LOG.
set -uo pipefail
src=unknown
for a in "$@"; do case "$a" in *.cpp | *.cc | *.c) src=$a ;; esac; done
wrap=()
[ "${COMPILE_TIMES_CCACHE:-0}" = 1 ] && wrap=(ccache)
/usr/bin/time -f "%U %S" -o "$COMPILE_TIMES_LOG.$$" "${wrap[@]}" "$@"
rc=$?
read -r user sys <"$COMPILE_TIMES_LOG.$$" 2>/dev/null || { user=0; sys=0; }
rm -f "$COMPILE_TIMES_LOG.$$"
awk -v u="$user" -v s="$sys" -v f="${src#"$COMPILE_TIMES_ROOT"/}" 'BEGIN { print u + s, f }' >>"$COMPILE_TIMES_LOG"
exit $rc
