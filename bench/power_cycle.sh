#!/usr/bin/env bash
# A kite's power cycle, timed (issue 35, docs/benchmarks.md "Optimal control: a kite's power
# cycle"): `lagrange optimize` on examples/optimal/power_cycle_pointmass.yaml and
# power_cycle_ap2.yaml at degree 4 and each N given, one whole process per case. Prints per case
# the mean power, Ipopt's iterations per homotopy stage and in all, the set-up, the solve, the
# share of the solve in lagrange's functions, whether the Hessian ran on machine code (run once
# before, to time the cached library) and the whole process's wall and CPU time.
#   bench/power_cycle.sh BUILD_DIR [N...]      (default N: 40 80)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: $0 BUILD_DIR [N...]}" && pwd)
shift
meshes=("$@")
[ ${#meshes[@]} -gt 0 ] || meshes=(40 80)
work=$(mktemp -d /tmp/power-cycle-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT

echo "degree 4, exact Hessian, MUMPS; load: $(uptime | sed 's/.*load average/load average/')"
echo "| case | N | status | mean power, W | iterations per stage | iterations | set-up, s | solve, s | in our functions | Hessian on | wall, s | CPU, s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for example in power_cycle_pointmass power_cycle_ap2; do
  for N in "${meshes[@]}"; do
    out=$work/$example-$N
    /usr/bin/time -f "%e %U %S" -o "$out.time" \
      "$build/lagrange" optimize "$root/examples/optimal/$example.yaml" --intervals "$N" --degree 4 \
      >"$out.log" 2>&1 || true
    # "  stage track  optimal solution found (24 iterations), …", "NAME: STATUS (K iterations)",
    # "  objective  X", "  time  A s set-up (…), B s solve (C s in our functions)"
    awk -v example="$example" -v N="$N" -v times="$(cat "$out.time")" '
      $1 == "stage" {sub(/.*\(/, "", $0); split($0, a, " "); stages = stages (stages ? "+" : "") a[1]; next}
      /^[^ ].*: .*\([0-9]+ iterations\)$/ {
        status = $0; sub(/^[^:]*: /, "", status); sub(/ \([0-9]+ iterations\)$/, "", status)
        it = $0; sub(/.*\(/, "", it); sub(/ iterations\)/, "", it); total = it
        stages = stages (stages ? "+" : "") it
      }
      $1 == "objective" {J = $2}
      $1 == "time" {setup = $2; solve = $8; fn = $11; sub(/\(/, "", fn)}
      $1 == "hessian" {hessian = $0; sub(/^ *hessian +/, "", hessian)}
      END {
        split(times, t, " ")
        n = split(stages, s, "+"); for (i = 1; i < n; ++i) total += s[i]
        printf "| %s | %s | %s | %.1f | %s | %d | %.2f | %.2f | %.0f %% | %s | %.1f | %.1f |\n",
          example, N, status, J, stages, total, setup, solve, 100 * fn / solve, hessian, t[1],
          t[2] + t[3]
      }' "$out.log"
  done
done
