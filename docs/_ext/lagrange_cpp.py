"""The C++ API reference from the public headers, include/lagrange/*.hpp.

When the build starts, Doxygen (Debian's doxygen) reads the headers' `///` and `///<` comments
into XML beside the doctrees (build/docs/doxygen/xml for `make docs`); breathe (python3-breathe)
renders it where a page says ```{doxygennamespace} lagrange```. A Doxygen warning (a comment
that does not parse) is a Sphinx warning, so `-W` fails on it. In the `///` lines '<', '>' and
'#include' are escaped first: the comments are prose, and Doxygen would otherwise take
`arkode:<table>` or `<math.h>` for HTML and `#include` for a link request.

The directive `lagrange-cpp-headers` lists every header with the comment that opens it, so that
a new header appears in the reference without an edit to the page.
"""
import re
import shutil
import subprocess
from pathlib import Path

from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

ROOT = Path(__file__).resolve().parents[2]
HEADERS = ROOT / "include" / "lagrange"
logger = logging.getLogger(__name__)

# A sed script that escapes '<', '>' and '#include' in the `///` comment lines, never in the code.
FILTER = r"""/^ *\/\/\//{
s/</\&lt;/g
s/>/\&gt;/g
s/#include/\\#include/g
}
"""


def _doxyfile(out):
    return "\n".join([
        "PROJECT_NAME = lagrange",
        f'INPUT = "{HEADERS}"',
        "FILE_PATTERNS = *.hpp",
        f'OUTPUT_DIRECTORY = "{out}"',
        f'STRIP_FROM_PATH = "{ROOT / "include"}"',
        "GENERATE_XML = YES",
        "GENERATE_HTML = NO",
        "GENERATE_LATEX = NO",
        "EXTRACT_ALL = YES",  # a member without a comment is still listed, with its declaration
        "JAVADOC_AUTOBRIEF = NO",  # one paragraph: "e.g." does not end a brief description
        "QUIET = YES",
        "WARN_IF_UNDOCUMENTED = NO",
        "WARN_IF_DOC_ERROR = YES",
        f'WARN_LOGFILE = "{out / "warnings.txt"}"',
        f'INPUT_FILTER = "sed -f {out / "comments.sed"}"',
        "",
    ])


def run_doxygen(app):
    out = Path(app.doctreedir).parent / "doxygen"
    xml = out / "xml"
    if shutil.which("doxygen") is None:
        logger.warning("lagrange_cpp: doxygen is not installed (LAGRANGE_DOCS=1 "
                       "scripts/install-deps.sh); the C++ reference is empty")
        return
    if xml.exists():
        shutil.rmtree(xml)
    out.mkdir(parents=True, exist_ok=True)
    (out / "comments.sed").write_text(FILTER)
    proc = subprocess.run(["doxygen", "-"], input=_doxyfile(out), text=True, cwd=ROOT,
                          capture_output=True)
    if proc.returncode != 0 or not (xml / "index.xml").exists():
        logger.warning(f"lagrange_cpp: doxygen failed ({proc.returncode}): {proc.stderr.strip()}")
        return
    log = out / "warnings.txt"
    for line in (log.read_text().splitlines() if log.exists() else []):
        if line.strip():
            logger.warning(f"doxygen: {line}")


def lead_comment(header):
    """The `//` lines that open a header, after #pragma once, as one sentence or two."""
    lines = []
    for line in header.read_text(encoding="utf-8").splitlines():
        if line.startswith("#pragma"):
            continue
        if line.startswith("//") and not line.startswith("///"):
            lines.append(line[2:].strip())
        elif lines or line.strip():
            break
    return " ".join(lines)


class CppHeaders(SphinxDirective):
    """A list of the public headers, each with its opening comment."""

    def run(self):
        items = nodes.bullet_list()
        for header in sorted(HEADERS.glob("*.hpp")):
            self.env.note_dependency(str(header))
            para = nodes.paragraph()
            para += nodes.literal(text=f"lagrange/{header.name}")
            text = lead_comment(header)
            if text:
                para += nodes.Text(": ")
                # `code` in the comment as code, the rest as text
                for i, part in enumerate(re.split(r"`([^`]+)`", text)):
                    if part:
                        para += nodes.literal(text=part) if i % 2 else nodes.Text(part)
            items += nodes.list_item("", para)
        return [items]


def _projects(app, config):
    xml = Path(app.doctreedir).parent / "doxygen" / "xml"
    config.breathe_projects = {"lagrange": str(xml)}
    config.breathe_default_project = "lagrange"


def setup(app):
    app.setup_extension("breathe")
    app.connect("config-inited", _projects)
    app.connect("builder-inited", run_doxygen)
    app.add_directive("lagrange-cpp-headers", CppHeaders)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
