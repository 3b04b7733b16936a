#!/usr/bin/env bash
# Runs each libFuzzer target on its corpus for a while: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]
# Inputs that crash, hang (> 10 s) or use more than 2 GB are written to BUILD_DIR/fuzz/artifacts/;
# the script fails if any target found one. New corpus entries stay in BUILD_DIR/fuzz/corpus/
# (in BUILD_DIR/fuzz/found/ for a fixed-seed run, below).
# With FUZZ_RUNS=N each target instead executes exactly N inputs from seed 1 (FUZZ_RUNS_MODEL,
# FUZZ_RUNS_EXPRESSION, FUZZ_RUNS_URDF, FUZZ_RUNS_SWEEP_SPEC and FUZZ_RUNS_METRIC set N per target: a model input costs ten times an
# expression, a URDF input, written to a file and read back, more still) with address
# randomisation off (GiNaC's term order, hence coverage, depends on load addresses) and
# everything the process sees the same from any clone: it runs in BUILD_DIR/fuzz with relative
# paths and a fixed environment (libFuzzer's comparison tracing feeds stack and heap addresses
# back into its mutations, and those move with the length of the environment and argv), reads
# its seeds as a sorted list (-seed_inputs; a corpus directory lists equal-sized inputs in the
# filesystem's order) and writes new inputs to a fresh BUILD_DIR/fuzz/found/TARGET, and does not
# reload them on a timer (-reload=0) nor purge the allocator on one (-purge_allocator_interval=-1:
# libFuzzer purges every second once the RSS passes half its limit, which moves later blocks and
# with them the addresses the target compares; fuzz_model passed 1 GB at input 90 000), and
# keeps the process to one thread that touches the heap (the memory limit, below). Stop 45: CI's
# clone found sqrt(-1) with fuzz_metric where ours did not. The same build and corpus now explore
# the same inputs, at the same heap addresses, in any folder and under any load.
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
# One target: its set-up, its run and its report on stdout; fails when the target found something.
run_target() {
  local t=$1 runner=() per_target runs work aslr work_dir log run
  per_target="FUZZ_RUNS_${t^^}"
  runs=${!per_target:-${FUZZ_RUNS:-}}
  if [ -n "$runs" ]; then
    work="$build/fuzz"
    cp "fuzz/$t.dict" "$work/$t.dict"
    cp .ci/lsan.supp "$work/lsan.supp"
    (cd "$work" && find "corpus/$t" -type f | LC_ALL=C sort | paste -sd, - >"seeds-$t.txt")
    rm -rf "$work/found/$t" && mkdir -p "$work/found/$t"
    [ "$t" != urdf ] || rm -rf "$work/urdf-input"
    aslr="address randomisation on: setarch -R is refused here, so runs may differ"
    if setarch "$(uname -m)" -R true 2>/dev/null; then
      runner=(setarch "$(uname -m)" -R)
      aslr="address randomisation off"
    fi
    echo "fuzz: fuzz_$t for $runs inputs (seed 1, $aslr) from the" \
      "$(tr , '\n' <"$work/seeds-$t.txt" | wc -l) seeds of $work/corpus/$t in name order"
    # malloc_context_size=0: no allocation or free stack kept per block, a third of fuzz_model's
    # CPU time (ASan's stack depot), the same inputs explored and the same checks made; a
    # finding's report then lacks those stacks, which a rerun of its artifact prints (below).
    # -detect_leaks=0: no leak check after each input, whose extra run of an input made the
    # exploration depend on the machine's load (docs/errors.md, "CI"); LeakSanitizer still checks
    # at the run's end, and `make fuzz` (timed runs) keeps the per-input check.
    # The 2 GB memory limit is ASan's (hard_rss_limit_mb: a thread of ASan's own reads the RSS
    # every 100 ms and allocates nothing on the heap) plus libFuzzer's per-allocation limit, not
    # libFuzzer's RSS thread (-rss_limit_mb=0): that thread's start-up reallocates and frees heap
    # blocks (ASan's thread set-up calls pthread_getattr_np) while the first inputs run, so which
    # blocks the target's allocations got depended on timing, and with them the addresses its
    # comparisons fed back to libFuzzer: fuzz_model's exploration parted after ~75 000-88 000
    # inputs (docs/errors.md, "CI"). With this, two runs side by side agree input for input.
    run=(env -i PATH=/usr/bin:/bin LSAN_OPTIONS="suppressions=lsan.supp:print_suppressions=0"
      UBSAN_OPTIONS="$UBSAN_OPTIONS" ASAN_OPTIONS=malloc_context_size=0:hard_rss_limit_mb=2048
      FUZZ_URDF_DIR=urdf-input "${runner[@]}" "./fuzz_$t"
      -runs="$runs" -seed=1 -reload=0 -purge_allocator_interval=-1 -detect_leaks=0
      -rss_limit_mb=0 -malloc_limit_mb=2048
      -seed_inputs="@seeds-$t.txt" -dict="$t.dict"
      -artifact_prefix="artifacts/$t-" "found/$t")
    work_dir="$work"
  else
    echo "fuzz: fuzz_$t for ${seconds} s on $build/fuzz/corpus/$t"
    run=("$build/fuzz/fuzz_$t" -max_total_time="$seconds" -rss_limit_mb=2048 -dict="fuzz/$t.dict"
      -artifact_prefix="$build/fuzz/artifacts/$t-" "$build/fuzz/corpus/$t")
    work_dir=.
  fi
  log="$PWD/$build/fuzz/fuzz_$t.log"
  [[ "$build" = /* ]] && log="$build/fuzz/fuzz_$t.log"
  if ! (cd "$work_dir" && "${run[@]}" -timeout=10 -print_final_stats=1 \
      2>"$log"); then
    echo "fuzz: fuzz_$t found a failing input (see $build/fuzz/artifacts/ and $build/fuzz/fuzz_$t.log):"
    tail -n 40 "$build/fuzz/fuzz_$t.log"
    echo "fuzz: for the allocation stacks: $build/fuzz/fuzz_$t $build/fuzz/artifacts/$t-*"
    echo "fuzz: a leak reported at the run's end names no input: \`make fuzz\` checks after each"
    return 1
  fi
  grep -E '^#[0-9]+[[:space:]]+DONE|^stat::(number_of_executed_units|peak_rss_mb)' \
    "$build/fuzz/fuzz_$t.log" || true
}

# FUZZ_JOBS targets at a time (each is one process on one core; `make fuzz` passes the number of
# cores): the fixed-seed runs explore alike whatever runs beside them (above). Each target's
# report is printed when all have ended, in the targets' order.
jobs=${FUZZ_JOBS:-1}
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  (if run_target "$t" >"$build/fuzz/fuzz_$t.out" 2>&1; then echo 0; else echo 1; fi) \
    >"$build/fuzz/fuzz_$t.status" &
done
wait
status=0
for t in "${targets[@]}"; do
  cat "$build/fuzz/fuzz_$t.out"
  [ "$(cat "$build/fuzz/fuzz_$t.status" 2>/dev/null)" = 0 ] || status=1
done
exit $status
