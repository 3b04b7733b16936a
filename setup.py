"""`pip install .` from a checkout (docs/python.md, "pip install"): builds the extension
`lagrange._lagrange` with the project's CMake and installs it with the package's Python files.

Without settings it configures build-pip-<python>/ in the checkout (Release, no tests, no
benchmarks, for the Python that runs pip) and builds the `_lagrange` target there. It sits beside
build/, at the same depth: the compiler sees the same relative paths, so that ccache, when the
machine has it, serves what a build in build/ compiled.
LAGRANGE_BUILD_DIR=DIR uses an existing build directory instead (configured for this Python's
version): `cmake --build DIR --target _lagrange` then has nothing to do when the module is built,
and setuptools' own files go to DIR/pip. CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs.
"""

import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
GIVEN = os.environ.get("LAGRANGE_BUILD_DIR")
OWN_DIR = ROOT / f"build-pip-{sys.implementation.cache_tag}"
CMAKE_DIR = pathlib.Path(GIVEN).resolve() if GIVEN else OWN_DIR
# setuptools' build tree (build/lib…, build/bdist…): not the project's own build/ directory.
BUILD_BASE = CMAKE_DIR / "pip"


def run(command):
    print("setup.py:", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True)


class BuildWithCMake(build_ext):
    """Builds `lagrange._lagrange` with CMake and copies it where setuptools expects it."""

    def build_extension(self, ext):
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        build = CMAKE_DIR
        if GIVEN:
            if not (build / "CMakeCache.txt").is_file():
                sys.exit(f"setup.py: LAGRANGE_BUILD_DIR={GIVEN} is not a configured CMake build "
                         "directory (cmake -S . -B build -DCMAKE_BUILD_TYPE=Release)")
        else:
            run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DLAGRANGE_BUILD_TESTS=OFF", "-DLAGRANGE_BUILD_BENCH=OFF",
                 "-DLAGRANGE_BUILD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"])
        run(["cmake", "--build", build, "--target", "_lagrange"])
        built = build / "python" / "lagrange" / f"_lagrange{suffix}"
        if not built.is_file():
            sys.exit(f"setup.py: {built} was not built: {build} is configured for another Python "
                     f"than {sys.executable} (its module has another suffix than {suffix})")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    packages=["lagrange"],
    package_dir={"lagrange": "python/lagrange"},
    package_data={"lagrange": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("lagrange._lagrange", sources=[])],
    cmdclass={"build_ext": BuildWithCMake},
    options={"build": {"build_base": str(BUILD_BASE)},
             "egg_info": {"egg_base": str(BUILD_BASE)}},
    zip_safe=False,
)
