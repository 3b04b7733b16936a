#!/usr/bin/env bash
# Optimal control against CasADi in the same run (issue 34, docs/benchmarks.md "Optimal control
# against CasADi"): `lagrange optimize` and CasADi's C++ API (bench/optimal_control_casadi.cpp,
# built by bench/casadi.sh) on the same transcription of the cart-pole swing-up, run in turn
# A B A B …, RUNS times each. Each run prints its own split; the table gives per figure the median
# over the runs and the median of the pairwise ratios lagrange / CasADi.
#   bench/optimal_control.sh BUILD_DIR [RUNS=7 [N=100]]
# CASE=panda: the Panda's point-to-point motion instead (N default 50), CasADi reading the arm's
# equations as `lagrange derive --format json` prints them (bench/optimal_control_casadi_panda.cpp);
# CASE=kite: the point-mass kite's power cycle (examples/optimal/power_cycle_pointmass.yaml, N
# default 40, DEGREE default 3), CasADi reading the kite's equations from `lagrange derive --format
# json` and lagrange's starting point from `lagrange optimize --ipopt max_iter=0 -o`
# (bench/optimal_control_casadi_kite.cpp).
# HESSIAN=exact|limited-memory (default exact) for both, GRAPH=mx|sx (default mx for the Panda,
# sx for the kite) for CasADi.
# COMPILE=off|auto (default auto): lagrange's tapes on the interpreter, or on machine code from
# the cache (one `--compile on` run before the timed ones fills it; the summary's `hessian` and
# `residual` lines say which ran).
# BUILD_DIR is lagrange's CMake build (target `lagrange` built); CasADi is built under
# CASADI_DIR (default BUILD_DIR/casadi; see bench/casadi.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: $0 BUILD_DIR [RUNS [N]]}" && pwd)
runs=${2:-7}
case=${CASE:-cartpole}
casadi=${CASADI_DIR:-$build/casadi}
"$root/bench/casadi.sh" "$casadi" 10 >/dev/null  # builds the peers (and CasADi) if needed
work=$(mktemp -d /tmp/optimal-control-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
if [ "$case" = panda ]; then
  N=${3:-50}
  hessian=${HESSIAN:-exact}
  model=$root/examples/optimal/panda_point_to_point.yaml
  title="Panda point-to-point, N = $N, d = 3, $hessian Hessian (CasADi: ${GRAPH:-mx} graph), tol 1e-8"
  "$build/lagrange" derive "$model" --format json >"$work/panda.json"
  lagrange_args=(--hessian "$hessian")
  peer_args=("$work/panda.json" "$N" 3 "$hessian" "${GRAPH:-mx}")
  peer=$casadi/bench/optimal_control_casadi_panda
elif [ "$case" = kite ]; then
  N=${3:-40}
  degree=${DEGREE:-3}
  hessian=${HESSIAN:-exact}
  model=$root/examples/optimal/power_cycle_pointmass.yaml
  title="point-mass kite power cycle, N = $N, d = $degree, $hessian Hessian (CasADi: ${GRAPH:-sx} graph), tol 1e-8"
  # GiNaC orders terms by hashes seeded from load addresses (docs/errors.md, "Determinism"), so
  # the printed equations' term order, and with it CasADi's round-off, changes from run to run
  # unless address randomisation is off; lagrange's own tapes use a canonical order.
  norandom=()
  setarch "$(uname -m)" -R true 2>/dev/null && norandom=(setarch "$(uname -m)" -R)
  "${norandom[@]}" "$build/lagrange" derive "$model" --format json >"$work/kite.json"
  # lagrange's starting point, as Ipopt receives it (stopped before its first iteration).
  "$build/lagrange" optimize "$model" --intervals "$N" --degree "$degree" --ipopt max_iter=0 \
    -o "$work/start.csv" >/dev/null 2>&1 || [ -s "$work/start.csv" ]
  lagrange_args=(--hessian "$hessian" --degree "$degree")
  # Baumgarte rate 0: the model's own (it sets none, and dop853 projects instead).
  peer_args=("$work/kite.json" "$work/start.csv" "$N" "$degree" "$hessian" "${GRAPH:-sx}" 0)
  peer=$casadi/bench/optimal_control_casadi_kite
else
  N=${3:-100}
  model=$root/examples/optimal/cart_pole_swing_up.yaml
  title="cart-pole swing-up, N = $N, d = 3, exact Hessian, tol 1e-8"
  lagrange_args=()
  peer_args=("$N")
  peer=$casadi/bench/optimal_control_casadi
fi

now() { date +%s.%N; }

# One run of each, whole-process wall time appended to the program's own output.
run_lagrange() {
  local t0 out
  t0=$(now)
  out=$("$build/lagrange" optimize "$model" --intervals "$N" --compile "$compile" "${lagrange_args[@]}")
  # "… (13 iterations)", "objective  58.88…", "time  0.033 s set-up (…), 0.282 s solve (0.022 s
  # in our functions)"
  awk -v wall="$(echo "$(now) - $t0" | bc -l)" '
    /iterations\)/ {gsub(/[()]/, ""); for (i = 1; i <= NF; ++i) if ($i == "iterations") it = $(i - 1)}
    $1 == "objective" {J = $2}
    $1 == "time" {setup = $2; for (i = 1; i <= NF; ++i) {if ($i == "solve") solve = $(i - 2);
                                                          if ($i == "in" && $(i + 1) == "our") fn = substr($(i - 2), 2)}}
    END {print J, it, setup, solve, fn, wall}' <<<"$out"
}
run_casadi() {
  local t0 out
  t0=$(now)
  out=$(CASADIPATH=$casadi/build/lib "$peer" "${peer_args[@]}")
  # "casadi: J = …, status …, 13 iterations, set-up … s, solve … s, functions … s, …"
  awk -v wall="$(echo "$(now) - $t0" | bc -l)" '
    $1 == "casadi:" {for (i = 1; i <= NF; ++i) {
       if ($i == "J") J = $(i + 2); if ($i == "iterations,") it = $(i - 1);
       if ($i == "set-up") setup = $(i + 1); if ($i == "solve") solve = $(i + 1);
       if ($i == "functions") fn = $(i + 1)}}
    END {sub(/,$/, "", J); print J, it, setup, solve, fn, wall}' <<<"$out"
}

compile=${COMPILE:-auto}
[ "$compile" = off ] ||
  "$build/lagrange" optimize "$model" --intervals "$N" --compile on "${lagrange_args[@]}" >/dev/null
for ((r = 0; r < runs; ++r)); do
  run_lagrange >>"$work/lagrange"
  run_casadi >>"$work/casadi"
done

# Both must reach the same optimum before any time means anything; the kite's orbit is
# multi-modal and its optimum decided by round-off along Ipopt's path (docs/benchmarks.md, "a
# kite's power cycle"), so there the two local optima are reported and the time per iteration
# is the figure to compare.
paste -d' ' "$work/lagrange" "$work/casadi" | awk -v kite="$([ "$case" = kite ] && echo 1)" '
  {d = $1 - $7; if (d < 0) d = -d; if (d > 1e-6 * $7) {
     printf "objectives differ: lagrange %s, CasADi %s\n", $1, $7 > "/dev/stderr"; if (!kite) exit 1}}'

echo "$title; median of $runs runs each (A B A B)"
echo "lagrange's tapes: --compile $compile ($("$build/lagrange" optimize "$model" --intervals "$N" \
  --compile "$compile" "${lagrange_args[@]}" | awk '/^  (hessian|residual) +(machine|interpreter)/ {$1 = $1; printf "%s%s", sep, $0; sep = "; "}'))"
echo "load: $(uptime | sed 's/.*load average/load average/')"
paste -d' ' "$work/lagrange" "$work/casadi" | awk -v runs="$runs" '
  function median(a, n,    i, j, t) {
    for (i = 2; i <= n; ++i) for (j = i; j > 1 && a[j - 1] > a[j]; --j) {t = a[j]; a[j] = a[j - 1]; a[j - 1] = t}
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
  }
  # Columns per side: J, iterations, set-up, solve, functions, wall; derived: total, share.
  {
    for (s = 0; s < 2; ++s) {
      o = 6 * s
      v[s, 1, NR] = $(o + 3); v[s, 2, NR] = $(o + 2); v[s, 3, NR] = $(o + 4)
      v[s, 4, NR] = $(o + 3) + $(o + 4); v[s, 5, NR] = $(o + 5); v[s, 6, NR] = $(o + 5) / $(o + 4)
      v[s, 7, NR] = $(o + 6); v[s, 8, NR] = $(o + 1); v[s, 9, NR] = 1000 * $(o + 5) / $(o + 2)
      v[s, 10, NR] = 1000 * $(o + 4) / $(o + 2)
    }
  }
  END {
    split("set-up s|Ipopt iterations|solve s|total (set-up + solve) s|time in NLP functions s|functions / solve|whole process wall s|objective|functions per iteration ms|solve per iteration ms", name, "|")
    printf "| %-26s | %10s | %10s | %16s |\n", "figure", "lagrange", "CasADi", "lagrange/CasADi"
    printf "|%s|%s|%s|%s|\n", "----------------------------", "------------", "------------", "------------------"
    for (f = 1; f <= 10; ++f) {
      for (r = 1; r <= NR; ++r) {a[r] = v[0, f, r]; b[r] = v[1, f, r]; q[r] = b[r] != 0 ? a[r] / b[r] : 0}
      ma = median(a, NR); mb = median(b, NR); mq = median(q, NR)
      if (f == 8) printf "| %-26s | %10.6f | %10.6f | %16s |\n", name[f], ma, mb, ""
      else if (f == 2) printf "| %-26s | %10d | %10d | %16.2f |\n", name[f], ma, mb, mq
      else printf "| %-26s | %10.4f | %10.4f | %16.2f |\n", name[f], ma, mb, mq
    }
  }'
