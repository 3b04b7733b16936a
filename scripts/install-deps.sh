#!/usr/bin/env bash
# Installs exactly the Debian packages lagrange needs that are not yet present.
# Idempotent: when everything is installed it only runs dpkg-query and exits.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libginac-dev libcln-dev libeigen3-dev libsundials-dev libyaml-cpp-dev
  libcli11-dev libfmt-dev nlohmann-json3-dev libtinyxml2-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox python3 python3-sympy
)
if [ "${LAGRANGE_FUZZ:-0}" = 1 ]; then packages+=(clang libclang-rt-14-dev); fi
# The benchmarks' peers (bench/work_precision.py): SciPy's solve_ivp, Debian's build.
if [ "${LAGRANGE_BENCH:-0}" = 1 ]; then packages+=(python3-numpy python3-scipy); fi
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
