#!/usr/bin/env bash
# Runs each libFuzzer target on its corpus for a while: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]
# Inputs that crash, hang (> 10 s) or use more than 2 GB are written to BUILD_DIR/fuzz/artifacts/;
# the script fails if any target found one. New corpus entries stay in BUILD_DIR/fuzz/corpus/.
# With FUZZ_RUNS=N each target instead executes exactly N inputs from seed 1 (FUZZ_RUNS_MODEL,
# FUZZ_RUNS_EXPRESSION, FUZZ_RUNS_URDF, FUZZ_RUNS_SWEEP_SPEC and FUZZ_RUNS_METRIC set N per target: a model input costs ten times an
# expression, a URDF input, written to a file and read back, more still) with address
# randomisation off (GiNaC's term order, hence coverage, depends on load addresses): the same
# build and corpus then explore the same inputs, so CI's short run is reproducible.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
seconds=${2:?usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(model expression urdf sweep_spec metric)
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
mkdir -p "$build/fuzz/artifacts"
status=0
for t in "${targets[@]}"; do
  budget=(-max_total_time="$seconds")
  runner=()
  per_target="FUZZ_RUNS_${t^^}"
  runs=${!per_target:-${FUZZ_RUNS:-}}
  if [ -n "$runs" ]; then
    budget=(-runs="$runs" -seed=1)
    if setarch "$(uname -m)" -R true 2>/dev/null; then runner=(setarch "$(uname -m)" -R); fi
    echo "fuzz: fuzz_$t for $runs inputs (seed 1) on $build/fuzz/corpus/$t"
  else
    echo "fuzz: fuzz_$t for ${seconds} s on $build/fuzz/corpus/$t"
  fi
  if ! "${runner[@]}" "$build/fuzz/fuzz_$t" "${budget[@]}" -timeout=10 -rss_limit_mb=2048 \
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
