#!/usr/bin/env bash
# Runs each libFuzzer target on its corpus for a while: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]
# Inputs that crash, hang (> 10 s) or use more than 2 GB are written to BUILD_DIR/fuzz/artifacts/;
# the script fails if any target found one. New corpus entries stay in BUILD_DIR/fuzz/corpus/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(model expression)
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build/fuzz/artifacts"
status=0
for t in "${targets[@]}"; do
  echo "fuzz: fuzz_$t for ${seconds} s on $build/fuzz/corpus/$t"
  if ! "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -dict="fuzz/$t.dict" -print_final_stats=1 -artifact_prefix="$build/fuzz/artifacts/$t-" \
      "$build/fuzz/corpus/$t" 2>"$build/fuzz/fuzz_$t.log"; then
    echo "fuzz: fuzz_$t found a failing input (see $build/fuzz/artifacts/ and $build/fuzz/fuzz_$t.log):"
    tail -n 40 "$build/fuzz/fuzz_$t.log"
    status=1
  else
    grep -E '^stat::(number_of_executed_units|peak_rss_mb)' "$build/fuzz/fuzz_$t.log" || true
  fi
done
exit $status
