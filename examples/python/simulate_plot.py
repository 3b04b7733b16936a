"""Simulate the elastic pendulum for two spring stiffnesses and plot θ(t) into a PNG.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/simulate_plot.py [OUT_DIR]
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402

import lagrange  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

fig, ax = plt.subplots(figsize=(7, 3.5))
for k in (20.0, 40.0):
    model = lagrange.load(str(EXAMPLES / "elastic_pendulum.yaml"), set={"k": k})
    run = model.simulate(t_end=5.0, output_step=0.01)
    energy = run["energy"]
    print(f"k = {k}: {len(run)} samples, energy drift {abs(energy[-1] - energy[0]):.2e}")
    ax.plot(run.t, run["theta"], label=f"k = {k:g}")
ax.set_xlabel("t [s]")
ax.set_ylabel("θ [rad]")
ax.legend()
fig.tight_layout()
fig.savefig(out / "elastic_pendulum.png", dpi=100)
print("wrote", out / "elastic_pendulum.png")
