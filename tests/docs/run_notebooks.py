#!/usr/bin/env python3
"""Executes every notebook of the manual (docs/notebooks/*.ipynb) on a fresh Jupyter kernel with
the built module, as `make docs` does (docs/_ext/lagrange_notebooks.py): a cell that raises, and
so each notebook's assert on its physical number, fails the test.

usage: run_notebooks.py --source SRC --python-path BUILD/python [NOTEBOOK...]
Exit 77 (ctest: skipped) when Debian's python3-nbclient, python3-nbformat or python3-ipykernel is
not installed (LAGRANGE_DOCS=1 scripts/install-deps.sh installs them).
"""
import argparse
import concurrent.futures
import importlib.util
import sys
import time
from pathlib import Path


def _run(path, python_path):
    """(True, what ran) or (False, the failure) for one notebook."""
    import lagrange_notebooks

    start = time.monotonic()
    try:
        nb = lagrange_notebooks.execute(path, python_path)
    except lagrange_notebooks.NotebookFailed as e:
        return False, str(e)
    cells = sum(1 for c in nb.cells if c.cell_type == "code")
    return True, f"{cells} cells in {time.monotonic() - start:.1f} s"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--python-path", required=True)
    ap.add_argument("notebooks", nargs="*")
    a = ap.parse_args()
    try:
        import nbclient, nbformat, matplotlib, scipy  # noqa: F401
        if importlib.util.find_spec("ipykernel") is None:
            raise ImportError("No module named 'ipykernel'")
    except ImportError as e:
        print(f"skipped: {e} (LAGRANGE_DOCS=1 scripts/install-deps.sh)")
        return 77
    src = Path(a.source).resolve()
    sys.path.insert(0, str(src / "docs" / "_ext"))  # lagrange_notebooks, as the docs build

    notebooks = ([Path(n) for n in a.notebooks]
                 or sorted((src / "docs" / "notebooks").glob("*.ipynb")))
    if not notebooks:
        print(f"FAIL no notebooks in {src / 'docs' / 'notebooks'}")
        return 1
    # Two at a time (each on its own kernel, in its own process): a kernel's start is most of a
    # notebook's time, and the machine has two cores.
    failed = 0
    with concurrent.futures.ProcessPoolExecutor(min(2, len(notebooks))) as pool:
        runs = [pool.submit(_run, path, a.python_path) for path in notebooks]
        for path, run in zip(notebooks, runs):
            ok, text = run.result()
            print(f"ok   {path.name}: {text}" if ok else f"FAIL {text}")
            failed += not ok
    print(f"{len(notebooks) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
