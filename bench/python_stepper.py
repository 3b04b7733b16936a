"""A controller written in Python in the loop at 20 Hz: the figure-eight kite (issue 23).

The same three runs as bench/bench_stepper.cpp, from Python, CPU time:
- one run: m.simulate(t_end, output_step=0.05) with the roll law written in the file;
- stepped: s.step(0.05) from a Python loop with no input set (the same integration, rows
  compared bit for bit): the difference is the cost of the Python loop and the binding;
- in the loop: the roll an external input set every step from the file's law evaluated in Python
  on s.outputs (zero-order hold, examples/python/controller_in_loop.py); its extra evaluations
  (steps landing on each control instant) are integration the held input makes necessary.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_stepper.py [SECONDS]
"""

import math
import pathlib
import sys
import time

import numpy as np

import lagrange

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"
T_END = float(sys.argv[1]) if len(sys.argv) > 1 else 60.0
PERIOD = 0.05
STEPS = round(T_END / PERIOD)


def best_of(repeats, fn):
    best, result = math.inf, None
    for _ in range(repeats):
        start = time.process_time()
        result = fn()
        best = min(best, time.process_time() - start)
    return best, result


text = (EXAMPLES / "figure_eight.yaml").read_text()
law_start, law_end = text.index("    roll: >-"), text.index("simulate:")
in_loop_text = (text[:law_start] + "    roll: roll_cmd\n" + text[law_end:]).replace(
    "coordinates:", "inputs:\n  roll_cmd: {value: 0, external: true}\ncoordinates:", 1)
file_model = lagrange.loads(text, label="figure_eight.yaml")
loop_model = lagrange.loads(in_loop_text, label="figure_eight in the loop")
p = loop_model.parameters


def one():
    return file_model.simulate(t_end=T_END, output_step=PERIOD, compile="off")


def stepped():
    s = file_model.stepper(t_end=T_END, compile="off")
    for _ in range(STEPS):
        s.step(PERIOD)
    return s.trajectory()


def in_the_loop():
    s = loop_model.stepper(t_end=T_END, compile="off")
    for _ in range(STEPS):
        out = s.outputs
        azimuth, elevation, heading = out["wing.azimuth"], out["wing.elevation"], out["wing.heading"]
        turn = (1 + math.tanh((abs(azimuth) - p["a0"]) / 0.02)) / 2
        aim = math.tanh(heading / 0.05) * (math.pi / 2 + p["gamma0"]
                                           + p["k_e"] * (elevation - p["el0"]))
        s.step(PERIOD, inputs={"roll_cmd": turn * p["K_loop"] * math.tanh(azimuth / 0.02)
                               + (1 - turn) * p["K_h"] * (heading - aim)})
    return s.trajectory()


# one run and the Python loop alternate, each first in every other pair; the overhead is the
# median of the pairs' ratios
REPEATS = 11
ratios, t_one, t_step = [], math.inf, math.inf
for r in range(REPEATS):
    pair = [best_of(1, one), best_of(1, stepped)] if r % 2 == 0 else \
        list(reversed([best_of(1, stepped), best_of(1, one)]))
    (a, run_one), (b, run_step) = pair
    ratios.append(b / a)
    t_one, t_step = min(t_one, a), min(t_step, b)
overhead = sorted(ratios)[REPEATS // 2] - 1
t_loop, run_loop = best_of(REPEATS, in_the_loop)
identical = np.array_equal(run_one.array, run_step.array)
print(f"\nfrom Python: figure-eight kite, {T_END:g} s flown at 20 Hz ({STEPS} control steps), "
      f"CPU s (best of {REPEATS})\n")
print("| run | CPU s | evaluations | real-time factor | overhead per control step |")
print("|---|---|---|---|---|")
print(f"| m.simulate | {t_one:.4f} | {run_one.stats['rhs_evals']} | {T_END / t_one:.0f}× | — |")
print(f"| s.step loop, no input set (rows {'bit-identical' if identical else 'DIFFER'}) | "
      f"{t_step:.4f} | {run_step.stats['rhs_evals']} | {T_END / t_step:.0f}× | "
      f"{100 * overhead:.2f} % ({1e6 * overhead * t_one / STEPS:.1f} µs; median of {REPEATS} pairs) |")
evals_up = 100 * (run_loop.stats["rhs_evals"] / run_one.stats["rhs_evals"] - 1)
print(f"| Python law in the loop, roll set every step | {t_loop:.4f} | "
      f"{run_loop.stats['rhs_evals']} ({evals_up:+.1f} %) | {T_END / t_loop:.0f}× | "
      f"the hold's extra evaluations |")
print(f"\npython_stepper_overhead_percent = {100 * overhead:.2f}")
