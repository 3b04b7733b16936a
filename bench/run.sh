#!/usr/bin/env bash
# Run the benchmarks and the SymPy peer in the same run and print the comparison table.
#   bench/run.sh BUILD_DIR        (`make bench` builds the `benchmarks` target first)
# Environment:
#   LAGRANGE_BENCH_SYMPY_20=1   also derive N = 20 with SymPy (about a minute more)
#   LAGRANGE_BENCH_OUT=DIR      where the raw results go (default BUILD_DIR/bench-results)
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build=$1
here=$(cd "$(dirname "$0")" && pwd)
python=/usr/bin/python3  # Debian's python3 has sympy and numpy (docs/benchmarks.md, Peers)
out=${LAGRANGE_BENCH_OUT:-$build/bench-results}

for exe in bench_pendulum bench_cartesian_chain bench_tether bench_kite bench_stepper \
  bench_elastic_kite bench_linearize long_run work_precision; do
  if [[ ! -x $build/bench/$exe ]]; then
    echo "$0: $build/bench/$exe not found; build it first: cmake --build $build --target benchmarks" >&2
    exit 1
  fi
done
if ! "$python" -c 'import sympy, numpy' 2>/dev/null; then
  echo "$0: $python lacks sympy or numpy (apt-get install python3-sympy python3-numpy)" >&2
  exit 1
fi
mkdir -p "$out"

sympy_args=()
if [[ ${LAGRANGE_BENCH_SYMPY_20:-0} == 1 ]]; then sympy_args+=(--with-20); fi

echo "== lagrange: N-link pendulum (derive + compile, forward) =="
"$build/bench/bench_pendulum" --benchmark_out="$out/pendulum.json" --benchmark_out_format=json
echo
echo "== lagrange: Cartesian chain (forward with KKT) =="
"$build/bench/bench_cartesian_chain" --benchmark_out="$out/chain.json" --benchmark_out_format=json
echo
echo "== lagrange: tether element (tethered balloon, N = 10 ... 200 segments) =="
"$build/bench/bench_tether" | tee "$out/tether.md"
echo
echo "== lagrange: kite flight (rigid AP2 on a 50-segment tether, logarithmic wind, 60 s) =="
"$build/bench/bench_kite" | tee "$out/kite.md"
echo
echo "== lagrange: a controller in the loop at 20 Hz (figure-eight kite; C++ and Python) =="
"$build/bench/bench_stepper" | tee "$out/stepper.md"
if [[ -d $build/python/lagrange ]]; then
  PYTHONPATH="$build/python" "$python" "$here/python_stepper.py" | tee -a "$out/stepper.md"
else
  echo "(the Python stepper is not measured: build the _lagrange target)"
fi
echo
echo "== linearise and trim: tethers, kite, Panda; the N-link pendulum against SymPy's linearize =="
"$build/bench/bench_linearize" | tee "$out/linearize.md"
"$python" "$here/linearize_vs_sympy.py" --bench "$build/bench/bench_linearize" | tee -a "$out/linearize.md"
echo
echo "== lagrange from Python against sympy.physics.mechanics (N-link pendulum, same run) =="
if [[ -d $build/python/lagrange ]]; then
  PYTHONPATH="$build/python" "$python" "$here/python_vs_sympy.py" | tee "$out/python_sympy.md"
else
  echo "(not measured: build the _lagrange target)"
fi
echo
echo "== lagrange: KPS4-like case (rigid AP2 on a 6-segment elastic Dyneema tether, 60 s) =="
"$build/bench/bench_elastic_kite" | tee "$out/elastic_kite.md"
echo
echo "== lagrange: long run, memory (10^7 right-hand-side evaluations) =="
"$build/bench/long_run" 1e7
echo
if [[ -x $build/bench/forward_speed ]]; then
  echo "== forward dynamics per call: interpreter, machine code, MuJoCo mj_forward (same run) =="
  "$build/bench/forward_speed" "$here/../examples/robots/"*.urdf | tee "$out/forward_speed.md"
else
  echo "(forward_speed not built: MuJoCo, libmujoco-dev, is not installed)"
fi
echo
echo "== forward dynamics per call: Pinocchio 3.7 ABA on the same chains (same run) =="
if "$here/pinocchio.sh" "$build" | tee "$out/pinocchio.md"; then :; else
  echo "(Pinocchio peer skipped: bench/pinocchio.sh needs git or PINOCCHIO_SRC, and libboost-dev)"
fi
echo
echo "== lagrange: accelerations at the benchmark state (cross-check with SymPy) =="
: >"$out/accelerations.txt"
for n in 2 5 8 10; do
  "$build/bench/bench_pendulum" --accelerations "$n" >>"$out/accelerations.txt"
done
echo "written to $out/accelerations.txt"
echo
echo "== SymPy peer (sympy.physics.mechanics LagrangesMethod) =="
"$python" "$here/sympy_lagrange.py" "${sympy_args[@]}" | tee "$out/sympy.jsonl"
echo
"$python" "$here/report.py" "$out" | tee "$out/report.md"
echo
echo "== work-precision: lagrange's integrators, the SciPy and MuJoCo peers (docs/benchmarks.md) =="
"$build/bench/work_precision" "$out" | tee "$out/work_precision.jsonl"
if "$python" -c 'import scipy' 2>/dev/null; then
  "$python" "$here/work_precision.py" "$out" | tee -a "$out/work_precision.jsonl"
else
  echo "$0: $python lacks scipy (apt-get install python3-scipy): SciPy peers skipped" >&2
fi
if [[ -x $build/bench/work_precision_mujoco ]]; then  # built when libmujoco-dev is installed
  "$build/bench/work_precision_mujoco" "$out" | tee -a "$out/work_precision.jsonl"
else
  echo "$0: $build/bench/work_precision_mujoco not built (libmujoco-dev): MuJoCo peer skipped" >&2
fi
"$python" "$here/work_precision_report.py" "$out/work_precision.jsonl" "$out/work_precision.svg" \
  | tee "$out/work_precision.md"
