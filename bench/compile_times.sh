#!/usr/bin/env bash
# The most expensive translation units, in compile CPU-seconds (issue 33):
#   bench/compile_times.sh BUILD_DIR [N] [cmake args...]
# configures BUILD_DIR (Release unless the arguments say otherwise) with a launcher that times each
# compile, builds everything `make test` builds, and prints the N (default 10) costliest sources
# and the total. The compiler cache is off unless COMPILE_TIMES_CCACHE=1 (then only misses count).
# JOBS sets the build's parallelism (default: every core); JOBS=1 on a shared machine.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:?usage: bench/compile_times.sh BUILD_DIR [N] [cmake args...]}
top=${2:-10}
jobs=${JOBS:-$(nproc)}
shift $(($# >= 2 ? 2 : 1))
export COMPILE_TIMES_LOG="$(realpath -m "$build")/compile_times.log" COMPILE_TIMES_ROOT=$root
mkdir -p "$build"
rm -f "$COMPILE_TIMES_LOG"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER_LAUNCHER="$root/bench/compile_time_launcher.sh" "$@" >/dev/null
cmake --build "$build" -j "$jobs" >/dev/null
cmake --build "$build" -j "$jobs" --target benchmarks >/dev/null
sort -rn "$COMPILE_TIMES_LOG" | head -n "$top" | awk '{printf "%8.1f CPU-s  %s\n", $1, $2}'
awk '{s += $1; n++} END {printf "%8.1f CPU-s  in all, %d translation units\n", s, n}' "$COMPILE_TIMES_LOG"
