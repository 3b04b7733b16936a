#!/usr/bin/env bash
# Pinocchio's ABA as a same-run peer of bench/forward_speed (docs/benchmarks.md): builds
# bench/pinocchio_aba.cpp header-only against Pinocchio 3.7.0's public source — nothing is added
# to lagrange's dependencies — and runs it.
#   bench/pinocchio.sh BUILD_DIR [N ...]
# Environment: PINOCCHIO_SRC=DIR  an existing checkout (else v3.7.0 is cloned into BUILD_DIR);
# needs git (for the clone), g++, Eigen 3 and the Boost headers (libboost-dev).
set -euo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 BUILD_DIR [N ...]" >&2
  exit 2
fi
build=$1
shift
here=$(cd "$(dirname "$0")" && pwd)
src=${PINOCCHIO_SRC:-$build/pinocchio-src}
if [[ ! -f $src/include/pinocchio/algorithm/aba.hpp ]]; then
  git clone --depth 1 --branch v3.7.0 https://github.com/stack-of-tasks/pinocchio "$src"
fi
exe=$build/bench/pinocchio_aba
mkdir -p "$build/bench"
if [[ ! -x $exe || $here/pinocchio_aba.cpp -nt $exe ]]; then
  # Pinocchio's own Release flags (-O3, no -march); its generated config headers are replaced by
  # bench/pinocchio/pinocchio/*.hpp.
  g++ -std=c++17 -O3 -DNDEBUG -I "$here/pinocchio" -I "$src/include" -I "$here" \
    -isystem /usr/include/eigen3 "$here/pinocchio_aba.cpp" "$here/n_link_pendulum.cpp" -o "$exe"
fi
"$exe" "$@"
