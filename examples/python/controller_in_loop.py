"""A controller written in Python flies the figure-eight kite at 20 Hz.

examples/figure_eight.yaml steers its kite by a roll law written in the file. Here the roll is an
external input (`roll_cmd: {value: 0, external: true}`) and the same law runs in Python, reading
the kite's azimuth, elevation and heading from the stepper every 0.05 s and holding the roll
until the next sample. The orbit it flies is compared with the file's own law.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/controller_in_loop.py [SECONDS]
"""

import math
import pathlib
import sys
import time

import lagrange

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
T_END = float(sys.argv[1]) if len(sys.argv) > 1 else 30.0
PERIOD = 0.05  # 20 Hz

text = (EXAMPLES / "figure_eight.yaml").read_text()
law_start = text.index("    roll: >-")
law_end = text.index("simulate:")
in_loop = (text[:law_start] + "    roll: roll_cmd\n" + text[law_end:]).replace(
    "coordinates:", "inputs:\n  roll_cmd: {value: 0, external: true}\ncoordinates:", 1)
model = lagrange.loads(in_loop, label="figure_eight in the loop")
p = model.parameters


def roll_law(azimuth, elevation, heading):
    """The file's law: loops beyond |azimuth| > a0, heading control on the straight legs."""
    turn = (1 + math.tanh((abs(azimuth) - p["a0"]) / 0.02)) / 2
    loop = p["K_loop"] * math.tanh(azimuth / 0.02)
    aim = math.tanh(heading / 0.05) * (math.pi / 2 + p["gamma0"] + p["k_e"] * (elevation - p["el0"]))
    return turn * loop + (1 - turn) * p["K_h"] * (heading - aim)


stepper = model.stepper(t_end=T_END)
start = time.process_time()
for _ in range(round(T_END / PERIOD)):
    out = stepper.outputs
    roll = roll_law(out["wing.azimuth"], out["wing.elevation"], out["wing.heading"])
    stepper.step(PERIOD, inputs={"roll_cmd": roll})
cpu = time.process_time() - start
run = stepper.trajectory()

reference = lagrange.load(str(EXAMPLES / "figure_eight.yaml")).simulate(t_end=T_END,
                                                                        output_step=PERIOD)
azimuth, ref_azimuth = run["wing.azimuth"], reference["wing.azimuth"]
print(f"{len(run.t) - 1} control steps of {PERIOD} s, {T_END:g} s flown in {cpu:.2f} s CPU "
      f"({T_END / cpu:.0f}x real time), {run.stats['rhs_evals']} evaluations")
print(f"azimuth range: Python law {azimuth.min():.3f} .. {azimuth.max():.3f} rad, "
      f"file's law {ref_azimuth.min():.3f} .. {ref_azimuth.max():.3f} rad")
print(f"largest difference in azimuth: {abs(azimuth - ref_azimuth).max():.3g} rad")
