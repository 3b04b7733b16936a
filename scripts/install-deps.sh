#!/usr/bin/env bash
# Installs exactly the Debian packages lagrange needs that are not yet present (Ninja, ccache and
# mold for fast builds, rebuilds and links, time for the per-stage figures).
# Idempotent: when everything is installed it only runs dpkg-query and exits.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config ccache mold time
  libginac-dev libcln-dev libeigen3-dev libsundials-dev libsuitesparse-dev libyaml-cpp-dev
  libcli11-dev libfmt-dev nlohmann-json3-dev libtinyxml2-dev libssl-dev coinor-libipopt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox python3 python3-sympy
  pybind11-dev python3-dev python3-numpy python3-pytest python3-pandas python3-matplotlib
  libopenmpi-dev openmpi-bin python3-distributed
  chromium
  unzip  # the FMU tests unzip exported FMUs with Info-ZIP, a reader we did not write
)
# node and npm build the report front-end; any install of them will do (Debian's when absent).
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
if [ "${LAGRANGE_FUZZ:-0}" = 1 ]; then packages+=(clang libclang-rt-14-dev); fi
# The benchmarks' peers (bench/work_precision.py): SciPy's solve_ivp, Debian's build.
if [ "${LAGRANGE_BENCH:-0}" = 1 ]; then packages+=(python3-numpy python3-scipy); fi
# The manual (`make docs`): Debian's Sphinx with the furo theme and myst-parser (Markdown pages);
# the notebooks executed on a Jupyter kernel (nbconvert's nbclient, ipykernel; SciPy for the LQR
# and the elliptic integral); the C++ reference from the headers (Doxygen's XML through breathe).
if [ "${LAGRANGE_DOCS:-0}" = 1 ]; then
  packages+=(python3-sphinx furo python3-myst-parser)
  packages+=(python3-nbconvert python3-nbformat python3-nbclient python3-ipykernel python3-scipy)
  packages+=(doxygen python3-breathe)
fi
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [ "$status" = "install ok installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The report front-end's npm packages (three, uPlot, KaTeX, esbuild, playwright-core), pinned by
# web/package-lock.json, when they are missing or older than the lock file.
web="$(cd "$(dirname "$0")/.." && pwd)/web"
if [ ! -f "$web/node_modules/.package-lock.json" ] ||
  [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in web/"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi
