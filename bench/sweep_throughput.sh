#!/bin/bash
# Study throughput (issue 24, docs/sweeps.md "Speed"): 1000 cases of the double pendulum and 100
# of the figure-eight kite, 10 s each, as a user runs them: `lagrange sweep` with 1 and 2
# workers, under `mpirun -n 2`, and through Dask with two local worker processes. Every figure
# is the median of RUNS whole-process runs under /usr/bin/time (start-up, derivation and reading
# included, after one warm-up run),
# the machine load (uptime) printed beside it, and the parallel efficiency of 2 workers (wall
# and cpu of -j 1 against -j 2); Dask's sweep call is also timed alone.
#
#   bench/sweep_throughput.sh [BUILD_DIR=build] [RUNS=3]
#
# Needs the `lagrange` and `_lagrange` targets built, GNU time, and for the last two rows
# mpirun (openmpi-bin) and python3-distributed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
runs=${2:-3}
lagrange=$build/lagrange
work=$(mktemp -d /tmp/sweep-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT

# The median wall and cpu (user + system) seconds of RUNS runs of COMMAND… under /usr/bin/time,
# after one warm-up run; each run is stopped after 900 s.
medians() {
  timeout 900 "$@" > /dev/null 2>&1 || true
  for _ in $(seq "$runs"); do
    timeout 900 /usr/bin/time -f '%e %U %S' -o "$work/time" "$@" > /dev/null 2>&1
    cat "$work/time"
  done | awk '
    function median(a, n,   i, j, t) {
      for (i = 2; i <= n; i++) for (j = i; j > 1 && a[j - 1] > a[j]; j--) {
        t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
      return a[int((n + 1) / 2)]
    }
    {n++; w[n] = $1; c[n] = $2 + $3}
    END {print median(w, n), median(c, n)}'
}

# bench LABEL CASES COMMAND…: one row, the study directory removed before each run. On a
# shared machine the wall time measures the share of the cores the study got as much as the
# study; the cpu seconds (every process of the study) show the work itself.
bench() {
  local label=$1 cases=$2
  shift 2
  local load wall cpu
  load=$(uptime | sed 's/.*load average: //')
  read -r wall cpu < <(medians sh -c "rm -rf '$work/study' && exec \"\$@\"" sh "$@")
  last_wall=$wall last_cpu=$cpu
  awk -v l="$label" -v w="$wall" -v c="$cpu" -v n="$cases" -v load="$load" \
    'BEGIN {printf "  %-28s wall %7.3f s %7.1f cases/s  cpu %7.3f s %6.2f ms/case  (load %s)\n",
            l, w, n / w, c, 1e3 * c / n, load}'
}

# The pool's own time, the "run X s" of the study's summary line (the cases alone: without
# start-up, derivation and the reading of the model), of one run of COMMAND…
run_seconds() {
  rm -rf "$work/study"
  "$@" | sed -n 's/.* run \([0-9.]*\) s .*/\1/p'
}

# …and of 2 × RUNS runs with -j 1 and -j 2 in turn, so that a drift of the machine's speed
# meets both alike: the median of each, and the median of the pairs' efficiencies
# (-j 1 run / (2 × -j 2 run)).
cases_alone() {
  for _ in $(seq "$((2 * runs))"); do
    echo "$(run_seconds "$@" -j 1) $(run_seconds "$@" -j 2)"
  done | awk -v load="$(uptime | sed 's/.*load average: //')" '
    function median(a, n,   i, j, t) {
      for (i = 2; i <= n; i++) for (j = i; j > 1 && a[j - 1] > a[j]; j--) {
        t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
      return a[int((n + 1) / 2)]
    }
    {n++; one[n] = $1; two[n] = $2; eff[n] = $1 / (2 * $2)}
    END {printf "  the cases alone (the summary line'"'"'s run time), %d pairs in turn: -j 1 %.3f s, -j 2 %.3f s, efficiency %.0f %% (median of the pairs; load %s)\n",
         n, median(one, n), median(two, n), 100 * median(eff, n), load}'
}

study() {
  local model=$1 name=$2 low=$3 high=$4 cases=$5 metric=$6
  local base=("$root/examples/$model" --vary "$name=$low:$high:$cases" --t-end 10
              --metric "$metric")
  local args=("${base[@]}" -o "$work/study")
  echo "$model: $cases cases of 10 s, $name from $low to $high, metric $metric"
  rm -rf "$work/study"
  "$lagrange" sweep "${args[@]}" -j 1 | sed -n 's/^  \(derive\|tapes\)/  once: \1/p'
  bench "lagrange sweep -j 1" "$cases" "$lagrange" sweep "${args[@]}" -q -j 1
  local wall1=$last_wall cpu1=$last_cpu
  bench "lagrange sweep -j 2" "$cases" "$lagrange" sweep "${args[@]}" -q -j 2
  awk -v w1="$wall1" -v c1="$cpu1" -v w2="$last_wall" -v c2="$last_cpu" \
    'BEGIN {printf "  efficiency at 2 workers: wall %.0f %% (-j 1 wall / (2 x -j 2 wall)), cpu %.0f %%\n",
            100 * w1 / (2 * w2), 100 * c1 / c2}'
  # The hardware's ceiling: two independent -j 1 studies at once, each on a core, slow each other
  # (shared caches, memory bandwidth); their wall time over one study's alone is the most two
  # workers of one study can reach.
  bench "two -j 1 studies at once" "$((2 * cases))" env W="$work" sh -c \
    'rm -rf "$W/a" "$W/b"; "$0" sweep "$@" -o "$W/a" -q -j 1 & "$0" sweep "$@" -o "$W/b" -q -j 1; wait' \
    "$lagrange" "${base[@]}"
  awk -v w1="$wall1" -v w2="$last_wall" \
    'BEGIN {printf "  the ceiling: each of two -j 1 studies at once runs at %.0f %% of one alone\n",
            100 * w1 / w2}'
  cases_alone "$lagrange" sweep "${args[@]}"

  if command -v mpirun > /dev/null; then
    bench "mpirun -n 2 lagrange sweep" "$cases" mpirun -n 2 --oversubscribe --allow-run-as-root \
      "$lagrange" sweep "${args[@]}" -q
  fi
  if /usr/bin/python3 -c "import distributed" 2> /dev/null &&
    compgen -G "$build/python/lagrange/_lagrange*.so" > /dev/null; then
    bench "dask, 2 worker processes" "$cases" env PYTHONPATH="$build/python" /usr/bin/python3 \
      "$root/bench/sweep_dask.py" "$root/examples/$model" "$name" "$low" "$high" "$cases" 10 \
      "$metric"
    echo "  dask, the sweep call alone: $(PYTHONPATH="$build/python" /usr/bin/python3 \
      "$root/bench/sweep_dask.py" "$root/examples/$model" "$name" "$low" "$high" "$cases" 10 \
      "$metric" 2> /dev/null | tail -1)   (load $(uptime | sed 's/.*load average: //'))"
  fi
}

echo "sweep throughput, $(date -u +%F), $(nproc) cores"
study double_pendulum.yaml l2 0.5 1.5 1000 "max(abs(theta1))"
study figure_eight.yaml W 6 10 100 "mean(drum.power, t > 5)"
