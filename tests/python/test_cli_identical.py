"""Every example simulates from Python with numbers bit-identical to the CLI's CSV.

Both sides run the interpreter (--compile off / compile="off"; machine code gives the same bits,
tests/dynamics) over the first T_END seconds of the file's grid, so the sweep stays short.
"""

import csv
import subprocess

import numpy as np
import pytest

import lagrange
from conftest import SOURCE_DIR

T_END = 0.25
EXAMPLES = sorted(p.name for p in (SOURCE_DIR / "examples").glob("*.yaml"))


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


def test_the_sweep_covers_the_examples():
    assert len(EXAMPLES) >= 20


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_matches_the_cli_bit_for_bit(name, examples_dir, cli, tmp_path):
    path = examples_dir / name
    model = lagrange.load(str(path))
    t_end = T_END
    out = tmp_path / "run.csv"
    subprocess.run(
        [cli, "simulate", str(path), "-o", str(out), "--t-end", repr(t_end), "--compile", "off",
         "-q"],
        check=True, capture_output=True)
    header, table = read_csv(out)
    run = model.simulate(t_end=t_end, compile="off")
    assert run.status == "complete"
    assert run.columns == header == model.columns
    assert run.array.shape == table.shape
    assert run.t[-1] == pytest.approx(t_end)
    # Bit-identical: the CSV's 17 significant digits give back each double exactly.
    same = (run.array == table) | (np.isnan(run.array) & np.isnan(table))
    assert same.all(), f"{name}: first difference at {np.argwhere(~same)[0]}"



def test_max_order_matches_the_cli_bit_for_bit(examples_dir, cli, tmp_path):
    """max_order= reaches CVODE from simulate, the Stepper's settings and a sweep as
    --max-order does from the command line."""
    path = examples_dir / "double_pendulum.yaml"
    model = lagrange.load(str(path))
    out = tmp_path / "run.csv"
    settings = ["--t-end", "1", "--integrator", "cvode", "--rtol", "1e-5", "--compile", "off"]
    subprocess.run([cli, "simulate", str(path), "-o", str(out), "--max-order", "2", "-q"]
                   + settings, check=True, capture_output=True)
    _, table = read_csv(out)
    run = model.simulate(t_end=1, integrator="cvode", rtol=1e-5, compile="off", max_order=2)
    assert (run.array == table).all()
    default = model.simulate(t_end=1, integrator="cvode", rtol=1e-5, compile="off")
    assert not (default.array == table).all()
    frame = lagrange.sweep(model, [{"m1": 1.0}], ["final(theta1)"], t_end=1, integrator="cvode",
                           rtol=1e-5, max_order=2)
    assert frame["final(theta1)"].iloc[0] == run["theta1"][-1]
