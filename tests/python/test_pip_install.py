"""`pip install --no-build-isolation .` from the checkout (issue 36 item 15, docs/python.md "pip
install"): into a venv made with --system-site-packages (Debian's numpy, setuptools and pip), the
package imports without PYTHONPATH and simulates as the build tree's module does.

LAGRANGE_BUILD_DIR points setup.py at this build's directory, so the module is not compiled a
second time: `cmake --build` finds it up to date and pip only packs and installs it.
"""

import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import lagrange
from conftest import BINARY, SOURCE_DIR

BUILD_DIR = BINARY.resolve().parent


@pytest.mark.skipif(not (BUILD_DIR / "CMakeCache.txt").is_file(),
                    reason="needs the CMake build directory the tests run from")
def test_pip_install_into_a_venv_imports_and_simulates(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                   check=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["LAGRANGE_BUILD_DIR"] = str(BUILD_DIR)
    done = subprocess.run(
        [python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-cache-dir",
         "--disable-pip-version-check", str(SOURCE_DIR)],
        env=env, capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    example = SOURCE_DIR / "examples" / "double_pendulum.yaml"
    code = (
        "import lagrange, numpy\n"
        "print(lagrange.__file__)\n"
        f"run = lagrange.load({str(example)!r}).simulate(t_end=2)\n"
        "numpy.save('installed.npy', run.array)\n"
    )
    env.pop("LAGRANGE_BUILD_DIR")
    ran = subprocess.run([python, "-c", code], env=env, capture_output=True, text=True,
                         cwd=tmp_path)
    assert ran.returncode == 0, ran.stderr
    # Imported from the venv's site-packages, not from the build tree or the checkout.
    installed = pathlib.Path(ran.stdout.splitlines()[0]).resolve()
    assert installed.is_relative_to(venv.resolve()), installed
    assert (installed.parent / "__init__.pyi").is_file()
    assert (installed.parent / "py.typed").is_file()
    # The same numbers as the module of the build tree.
    here = lagrange.load(str(example)).simulate(t_end=2)
    np.testing.assert_array_equal(np.load(tmp_path / "installed.npy"), here.array)
