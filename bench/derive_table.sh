#!/usr/bin/env bash
# `lagrange derive` time and output size per form for the seed arms, the R-R-P arm of issue 20,
# UR5, Panda and N-link spatial chains (issue 20, item 1): one run each, wall and CPU seconds,
# peak memory and bytes of output, as a Markdown table.
#   bench/derive_table.sh BUILD_DIR
set -euo pipefail
if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
lagrange=$1/lagrange
here=$(cd "$(dirname "$0")" && pwd)
examples=$here/../examples
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# An N-link spatial chain: joints alternating about y and x, each link a named mass and length.
chain() {
  local n=$1 file=$scratch/chain_$1.yaml params="g: 9.81" links="" parent=""
  for ((k = 1; k <= n; ++k)); do
    params+=", m$k: 1.0, l$k: 0.3"
    local axis="[0, 1, 0]"
    ((k % 2 == 0)) && axis="[1, 0, 0]"
    local z="l$((k - 1))"
    ((k == 1)) && z="0"
    links+="  link$k: {${parent}joint: {name: q$k, type: revolute, axis: $axis, origin: {xyz: [0, 0, -$z]}, initial: 0.1},
          mass: m$k, com: [0, 0, -l$k], inertia: [0.01, 0.01, 0.002]}
"
    parent="parent: link$k, "
  done
  printf 'name: chain %s\nparameters: {%s}\nlinks:\n%sgravity: [0, 0, -g]\n' "$n" "$params" "$links" > "$file"
  echo "$file"
}

models=("$examples/elbow_manipulator.yaml" "$examples/planar_arm_pd.yaml" "$here/models/rrp_arm.yaml"
  "$examples/robots/ur5.urdf" "$examples/robots/panda.urdf" "$(chain 6)" "$(chain 12)")
echo "| model | form | wall s | CPU s | peak MB | output bytes |"
echo "|---|---|---|---|---|---|"
for model in "${models[@]}"; do
  for form in lagrangian manipulator recursive; do
    args=(derive "$model")
    [[ $form != lagrangian ]] && args+=(--form "$form")
    if /usr/bin/time -o "$scratch/time" -f "%e %U %M" "$lagrange" "${args[@]}" > "$scratch/out" 2> "$scratch/err"; then
      read -r wall cpu rss < "$scratch/time"
      printf '| %s | %s | %s | %s | %.0f | %s |\n' "$(basename "$model")" "$form" "$wall" "$cpu" \
        "$(echo "$rss / 1024" | bc -l)" "$(wc -c < "$scratch/out")"
    else
      echo "| $(basename "$model") | $form | refused: $(head -c 100 "$scratch/err" | tr '\n' ' ') | | | |"
    fi
  done
done
