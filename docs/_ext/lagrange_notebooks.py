"""Executed notebooks in the manual: every docs/notebooks/*.ipynb is run when the manual is built,
on a fresh Jupyter kernel (Debian's python3-ipykernel, through nbclient, as `jupyter nbconvert
--execute` runs it) in the notebook's own directory, with the built module on PYTHONPATH. Its
cells and outputs become MyST Markdown (code blocks, text, tables, figures as data URIs), so a
notebook is a page like any other. A cell that raises fails the build with the cell and its
traceback; tests/docs/run_notebooks.py runs the same execution as a test.

Debian has neither nbsphinx nor myst-nb; this is the part of them the manual needs.
"""
import base64
import os
import re
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


class NotebookFailed(RuntimeError):
    pass


def execute(path, python_path=None, timeout=300):
    """Runs the notebook at `path` in its directory on a fresh python3 kernel and returns it with
    its outputs (an nbformat NotebookNode). `python_path` (the build's python/ directory) goes in
    front of PYTHONPATH. Raises NotebookFailed naming the cell when a cell raises."""
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    path = Path(path).resolve()
    nb = nbformat.read(str(path), as_version=4)
    env = dict(os.environ)
    if python_path:
        env["PYTHONPATH"] = os.pathsep.join(
            p for p in (str(Path(python_path).resolve()), env.get("PYTHONPATH", "")) if p)
    env.pop("MPLBACKEND", None)  # the kernel's inline backend draws the figures
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3",
                            resources={"metadata": {"path": str(path.parent)}})
    # What the kernel process prints outside the notebook is kept, and shown when the kernel
    # fails. (debugpy's four-line note on frozen modules, at each kernel start, still reaches the
    # terminal: it is harmless, and Debian's kernel spec gives no place for -Xfrozen_modules=off.)
    with tempfile.TemporaryFile(mode="w+") as console:
        try:
            client.execute(env=env, stdout=console, stderr=console)
        except CellExecutionError as e:
            text = re.sub(r"\x1b\[[0-9;]*m", "", str(e))  # IPython's colours
            raise NotebookFailed(f"{_name(path)}: a cell raised\n{text}") from None
        except Exception as e:
            console.seek(0)
            raise NotebookFailed(f"{_name(path)}: {type(e).__name__}: {e}\n"
                                 f"the kernel printed:\n{console.read()}") from None
    return nb


def _name(path):
    return path.relative_to(ROOT) if path.is_relative_to(ROOT) else path


def _fence(text, info):
    """A fenced block that no run of backticks in `text` can close."""
    ticks = "```"
    while ticks in text:
        ticks += "`"
    return f"{ticks}{info}\n{text.rstrip()}\n{ticks}\n"


def _output(out):
    kind = out.get("output_type")
    if kind == "stream":
        return _fence(out["text"], "none")
    if kind in ("display_data", "execute_result"):
        data = out.get("data", {})
        if "text/html" in data:
            return _fence(data["text/html"], "{raw} html")
        for mime in ("image/png", "image/jpeg"):
            if mime in data:
                payload = "".join(data[mime].split())
                base64.b64decode(payload, validate=True)
                return f"![figure](data:{mime};base64,{payload})\n"
        if "image/svg+xml" in data:
            return _fence(data["image/svg+xml"], "{raw} html")
        if "text/plain" in data:
            return _fence(data["text/plain"], "none")
    return ""


def to_markdown(nb):
    """The executed notebook as MyST Markdown: Markdown cells as they are, code cells as Python
    blocks, each followed by its outputs."""
    parts = []
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            parts.append(cell.source.rstrip() + "\n")
        elif cell.cell_type == "code" and cell.source.strip():
            parts.append(_fence(cell.source, "python"))
            parts.extend(p for p in map(_output, cell.get("outputs", [])) if p)
    return "\n".join(parts)


def _python_path(app):
    python = Path(app.config.lagrange_build) / "python"
    return python if (python / "lagrange" / "__init__.py").exists() else None


def setup(app):
    from myst_parser.parsers.sphinx_ import MystParser
    from sphinx.errors import ExtensionError
    from sphinx.util import logging

    logger = logging.getLogger(__name__)

    from sphinx.parsers import Parser

    class NotebookParser(Parser):
        supported = ("jupyter_notebook",)

        def parse(self, inputstring, document):
            path = Path(document["source"])
            start = time.monotonic()
            try:
                nb = execute(path, _python_path(self._app))
            except NotebookFailed as e:
                raise ExtensionError(str(e)) from None
            logger.info(f"notebook {path.name}: executed in {time.monotonic() - start:.1f} s")
            myst = MystParser()
            myst.set_application(self._app)
            myst.parse(to_markdown(nb), document)

    app.add_config_value("lagrange_build", str(ROOT / "build"), "env")
    app.add_source_suffix(".ipynb", "jupyter_notebook")
    app.add_source_parser(NotebookParser)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
