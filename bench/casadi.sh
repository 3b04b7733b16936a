#!/usr/bin/env bash
# CasADi as the same-run peer of `lagrange optimize` (docs/benchmarks.md, "Optimal control against
# CasADi"): builds CasADi 3.7.2's C++ core and its Ipopt plugin from the public source against
# Debian's Ipopt 3.11.9 and MUMPS (coinor-libipopt-dev, found by pkg-config), then builds and runs
# bench/optimal_control_casadi.cpp. Nothing is added to lagrange's dependencies.
#   bench/casadi.sh BUILD_DIR [N [d]]
# BUILD_DIR holds src/ (the clone), build/ (CasADi's CMake tree) and bench/ (the peer program).
# Environment: CASADI_SRC=DIR  an existing checkout of tag 3.7.2 (else it is cloned).
# Needs git (for the clone), cmake, g++, pkg-config and coinor-libipopt-dev. No patch is needed:
# CasADi's Ipopt interface guards its 3.14-only calls with IPOPT_VERSION_MINOR >= 14.
set -euo pipefail
if [[ $# -lt 1 ]]; then
  echo "usage: $0 BUILD_DIR [N [d]]" >&2
  exit 2
fi
mkdir -p "$1"
build=$(cd "$1" && pwd)
shift
here=$(cd "$(dirname "$0")" && pwd)
tag=3.7.2
src=${CASADI_SRC:-$build/src}
if [[ ! -f $src/casadi/casadi.hpp ]]; then
  git clone --depth 1 --branch "$tag" https://github.com/casadi/casadi "$src"
fi
tree=$build/build
if [[ ! -f $tree/lib/libcasadi_nlpsol_ipopt.so ]]; then
  # Only the core and the Ipopt plugin: every optional interface and bundled solver off.
  launcher=()
  if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  fi
  cmake -S "$src" -B "$tree" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" -DWITH_IPOPT=ON \
    -DWITH_SUNDIALS=OFF -DWITH_BUILD_SUNDIALS=OFF -DWITH_CSPARSE=OFF -DWITH_BUILD_CSPARSE=OFF \
    -DWITH_TINYXML=OFF -DWITH_BUILD_TINYXML=OFF -DWITH_QPOASES=OFF -DWITH_BLOCKSQP=OFF \
    -DWITH_LAPACK=OFF -DWITH_PYTHON=OFF -DWITH_MATLAB=OFF >/dev/null
  (cd "$tree" && nice -n 10 make -j1 casadi_nlpsol_ipopt)
fi
# The peers: the cart-pole (bench/optimal_control_casadi.cpp, run below), the Panda
# (bench/optimal_control_casadi_panda.cpp, run by bench/optimal_control.sh with CASE=panda) and
# the kite's power cycle (bench/optimal_control_casadi_kite.cpp, CASE=kite).
mkdir -p "$build/bench"
for peer in optimal_control_casadi optimal_control_casadi_panda optimal_control_casadi_kite; do
  exe=$build/bench/$peer
  if [[ ! -x $exe || $here/$peer.cpp -nt $exe || $here/casadi_peer.hpp -nt $exe ||
    $here/casadi_expression_reader.hpp -nt $exe ]]; then
    # CasADi's generated headers (casadi/core/casadi_export.h, config.h) are in its build tree.
    g++ -std=c++17 -O3 -DNDEBUG -I "$src" -I "$tree" "$here/$peer.cpp" \
      -L "$tree/lib" -Wl,-rpath,"$tree/lib" -lcasadi -o "$exe"
  fi
done
# The Ipopt plugin is loaded at run time from CASADIPATH.
CASADIPATH=$tree/lib "$build/bench/optimal_control_casadi" "$@"
