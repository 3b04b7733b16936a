"""Derive the double pendulum's equations of motion and write them as text and LaTeX.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/derive.py [OUT_DIR]
"""

import pathlib
import sys

import lagrange

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

model = lagrange.load(str(EXAMPLES / "double_pendulum.yaml"))
print(model, "parameters:", model.parameters)
eq = model.derive()
print(eq.text)
(out / "double_pendulum.tex").write_text(eq.latex)
print("wrote", out / "double_pendulum.tex")
