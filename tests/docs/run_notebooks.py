#!/usr/bin/env python3
"""Executes every notebook of the manual (docs/notebooks/*.ipynb) on a fresh Jupyter kernel with
the built module, as `make docs` does (docs/_ext/lagrange_notebooks.py): a cell that raises, and
so each notebook's assert on its physical number, fails the test.

usage: run_notebooks.py --source SRC --python-path BUILD/python [NOTEBOOK...]
Exit 77 (ctest: skipped) when Debian's python3-nbclient, python3-nbformat or python3-ipykernel is
not installed (LAGRANGE_DOCS=1 scripts/install-deps.sh installs them).
"""
import argparse
import importlib.util
import sys
import time
from pathlib import Path


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
    sys.path.insert(0, str(src / "docs" / "_ext"))
    import lagrange_notebooks

    notebooks = [Path(n) for n in a.notebooks] or sorted((src / "docs" / "notebooks").glob("*.ipynb"))
    if not notebooks:
        print(f"FAIL no notebooks in {src / 'docs' / 'notebooks'}")
        return 1
    failed = 0
    for path in notebooks:
        start = time.monotonic()
        try:
            nb = lagrange_notebooks.execute(path, a.python_path)
        except lagrange_notebooks.NotebookFailed as e:
            print(f"FAIL {e}")
            failed += 1
            continue
        cells = sum(1 for c in nb.cells if c.cell_type == "code")
        print(f"ok   {path.name}: {cells} cells in {time.monotonic() - start:.1f} s")
    print(f"{len(notebooks) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
