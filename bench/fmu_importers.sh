#!/bin/sh
# FMUs from `lagrange export --fmu` run by two importers no one here wrote (docs/fmu.md,
# "Checked by importers no one here wrote"): the FMI Compliance Checker and fmusim.
#
#   bench/fmu_importers.sh LAGRANGE WORKDIR [MODEL...]
#
# Both are built here from their public sources, which are git checkouts given by
#   FMUCHK_SRC  github.com/modelica-tools/FMUComplianceChecker at c704b98 (its last release branch
#               head, October 2023; development has stopped);
#   FMIL_SRC    github.com/modelon-community/fmi-library at tag 2.0.3 (the FMI Library the
#               checker's own CMakeLists.txt fetches);
#   REFFMUS_SRC github.com/modelica/Reference-FMUs at c8d4e6d, the last commit that has fmusim/
#               (7b3fc08, July 2026, removed it).
# When one is not set the script clones it at that commit (this needs network; CI has none, so the
# script is run by hand). fmusim is built against Debian's SUNDIALS 6 (libsundials-dev), libxml2,
# zlib and minizip (libminizip-dev): SUN_COMM_NULL, which SUNDIALS 7 introduced, is defined as NULL
# (SUNDIALS 6's SUNContext_Create takes a void* communicator).
#
# For each model (default: the six of docs/fmu.md and bench/models/falling_ball.yaml, whose
# stop_when condition is an event indicator) it exports the FMU, runs the checker in Co-Simulation
# and Model Exchange, fmusim in Co-Simulation and Model Exchange (CVODE at two tolerances), and
# compares each result with `lagrange simulate` on the model's own grid (bench/fmu_compare_csv.py).
# The FMU's logging is on: a stop_when condition that fires is logged (category logEvents).
set -eu
if [ $# -lt 2 ]; then
  sed -n '2,20p' "$0"
  exit 2
fi
LAGRANGE=$(realpath "$1")
WORK=$(realpath -m "$2")
shift 2
HERE=$(dirname "$(realpath "$0")")
ROOT=$(dirname "$HERE")
PY=${PYTHON:-/usr/bin/python3}
mkdir -p "$WORK/bin" "$WORK/fmus" "$WORK/results"

checkout() { # checkout VAR URL COMMIT DIR: the source directory, cloned when VAR is unset
  eval "src=\${$1:-}"
  if [ -z "$src" ]; then
    src="$WORK/src/$4"
    if [ ! -d "$src" ]; then
      git clone -q "$2" "$src"
      git -C "$src" checkout -q "$3"
    fi
  fi
  echo "$src"
}

# --- fmusim (Reference-FMUs c8d4e6d) ---------------------------------------------------------
if [ ! -x "$WORK/bin/fmusim" ]; then
  R=$(checkout REFFMUS_SRC https://github.com/modelica/Reference-FMUs.git \
    c8d4e6d90fa14be49d7622badf30e38eebea5e0a Reference-FMUs)
  cc -O2 -w -o "$WORK/bin/fmusim" -I "$R/fmusim" -I "$R/include" -I /usr/include/libxml2 \
    -I /usr/include/minizip -DSUN_COMM_NULL=NULL '-DFMUSIM_VERSION="c8d4e6d"' \
    "$R"/fmusim/*.c "$R/src/FMI.c" "$R/src/FMI1.c" "$R/src/FMI2.c" "$R/src/FMI3.c" \
    "$R/src/structured_variable_name.yy.c" "$R/src/structured_variable_name.tab.c" \
    -lminizip -lxml2 -lz -lsundials_cvode -lsundials_nvecserial -lsundials_sunmatrixdense \
    -lsundials_sunlinsoldense -ldl -lm
fi

# --- the FMI Compliance Checker (c704b98) with the FMI Library 2.0.3 -------------------------
if [ ! -x "$WORK/bin/fmuCheck.linux64" ]; then
  L=$(checkout FMIL_SRC https://github.com/modelon-community/fmi-library.git 2.0.3 fmi-library)
  C=$(checkout FMUCHK_SRC https://github.com/modelica-tools/FMUComplianceChecker.git \
    c704b983b979f57681a5322889360b7688248088 FMUComplianceChecker)
  # The FMI Library as the checker's CMakeLists.txt configures it (static, FMI 2.0 headers of
  # its ThirdParty/FMI/default), built out of tree.
  cmake -Wno-dev -S "$L" -B "$WORK/fmil-build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-w \
    -DFMILIB_INSTALL_PREFIX="$WORK/fmil" -DFMILIB_BUILD_STATIC_LIB=ON \
    -DFMILIB_BUILD_SHARED_LIB=OFF -DFMILIB_BUILD_TESTS=OFF -DFMILIB_GENERATE_DOXYGEN_DOC=OFF \
    -DFMILIB_FMI_STANDARD_HEADERS="$L/ThirdParty/FMI/default" >"$WORK/fmil-build.log" 2>&1
  cmake --build "$WORK/fmil-build" -j1 --target install >>"$WORK/fmil-build.log" 2>&1
  # The checker's one executable, compiled as its CMakeLists.txt does (its ExternalProject would
  # clone the FMI Library itself); the version header it generates is written here.
  mkdir -p "$WORK/fmuchk-build"
  printf '#define FMUCHK_VERSION "c704b98"\n#define FMIL_VERSION "2.0.3"\n' \
    >"$WORK/fmuchk-build/fmu_checker_version.h"
  cc -O2 -w -DFMI_PLATFORM='"linux64"' -o "$WORK/bin/fmuCheck.linux64" \
    -I "$WORK/fmil/include" -I "$C/include" -I "$WORK/fmuchk-build" \
    "$C/src/Common/fmuChecker.c" "$C"/src/FMI1/*.c "$C"/src/FMI2/*.c \
    "$WORK/fmil/lib/libfmilib.a" -ldl -lm
fi

# --- the runs ----------------------------------------------------------------------------------
[ $# -gt 0 ] || set -- examples/pendulum.yaml examples/cartesian_pendulum.yaml examples/crane.yaml \
  examples/heavy_top.yaml examples/figure_eight.yaml examples/robots/ur5.urdf \
  bench/models/falling_ball.yaml
for model in "$@"; do
  case $model in /*) ;; *) model="$ROOT/$model" ;; esac
  name=$(basename "$model" | sed 's/\.[a-z]*$//')
  fmu="$WORK/fmus/$name.fmu"
  out="$WORK/results/$name"
  "$LAGRANGE" export "$model" --fmu "$fmu" >/dev/null
  "$LAGRANGE" simulate "$model" -o "$out.simulate.csv" >"$out.simulate.log"
  echo "== $name"
  grep 'stopped at' "$out.simulate.log" || true
  # The checker's Model Exchange is explicit Euler at a fixed step (-h; by default the stop time
  # over 500): the heavy top's 200 rad/s spin needs h ω well below 1, and the kite diverges at
  # its default 0.24 s (a singular KKT matrix at t = 1.44 s, reported as fmi2Error).
  for kind in cs me; do
    status=0
    case $kind:$name in
      me:heavy_top) euler="-h 1e-5" ;;
      me:figure_eight) euler="-h 1e-3" ;;
      *) euler="" ;;
    esac
    # shellcheck disable=SC2086
    "$WORK/bin/fmuCheck.linux64" -k $kind $euler -l 3 -t "$WORK" -o "$out.fmuCheck.$kind.csv" \
      -e "$out.fmuCheck.$kind.log" "$fmu" || status=$?
    echo "fmuCheck -k $kind $euler: exit $status," \
      "$(grep -c 'ERROR' "$out.fmuCheck.$kind.log" || true) errors," \
      "$(grep -c 'WARNING' "$out.fmuCheck.$kind.log" || true) warnings"
    grep -E 'ERROR|WARNING' "$out.fmuCheck.$kind.log" | sed 's/^/  /' | head -20 || true
  done
  for run in "cs" "me --solver cvode --tolerance 1e-6" "me --solver cvode --tolerance 1e-10"; do
    kind=$(echo "$run" | sed "s/ --solver cvode --tolerance /./")
    status=0
    # shellcheck disable=SC2086
    "$WORK/bin/fmusim" --interface-type $run --logging-on \
      --output-file "$out.fmusim.$kind.csv" "$fmu" >"$out.fmusim.$kind.log" 2>&1 || status=$?
    echo "fmusim --interface-type $run: exit $status, $(wc -l <"$out.fmusim.$kind.log") log lines"
    sed 's/^/  /' "$out.fmusim.$kind.log" | head -20
    [ $status -ne 0 ] || "$PY" "$HERE/fmu_compare_csv.py" "$out.simulate.csv" "$out.fmusim.$kind.csv"
  done
  "$PY" "$HERE/fmu_compare_csv.py" "$out.simulate.csv" "$out.fmuCheck.cs.csv" || true
done
