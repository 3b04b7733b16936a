#!/usr/bin/env bash
# Regenerates the README's report screenshots (docs/report_*.png) from real reports: simulates
# each highlighted example with --report and photographs the 3-D view in headless Chromium.
# Usage: scripts/readme-screenshots.sh [BUILD_DIR]   (default build; run `make build` first)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# example@fraction of its run at which the picture is taken
shots=(double_pendulum@0.12 tumbling_brick@0.33 five_bar@0.2 crane_with_cable@0.3 rigid_kite_ap2@0.5
       elbow_manipulator@0.4)
reports=()
for shot in "${shots[@]}"; do
  name="${shot%@*}"
  "$build/lagrange" simulate "$root/examples/$name.yaml" -q --report "$work/report_$name.html"
  reports+=("$work/report_$name.html@${shot#*@}")
done
# A spatial arm: the Panda of examples/robots falling from a bent pose (zero torques), and the
# bead on its turning hoop.
"$build/lagrange" simulate "$root/examples/robots/panda.urdf" -q --t-end 1.5 \
  --initial panda_joint2=-0.6 --initial panda_joint4=-2.2 --initial panda_joint6=1.6 \
  --initial panda_joint1_dot=0.6 --report "$work/report_panda.html"
"$build/lagrange" simulate "$root/examples/bead_on_hoop.yaml" -q --report "$work/report_bead_on_hoop.html"
reports+=("$work/report_panda.html@0.5" "$work/report_bead_on_hoop.html@0.04")
node "$root/web/screenshots.mjs" "$root/docs" "${reports[@]}"
