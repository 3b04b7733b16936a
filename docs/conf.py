# Sphinx configuration of the lagrange manual: `make docs` builds it into build/docs/html.
# Debian's Sphinx, furo and myst-parser (scripts/install-deps.sh, LAGRANGE_DOCS=1); offline.
import os
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
root = here.parent
sys.path.insert(0, str(here / "_ext"))

# The build tree whose `lagrange` prints the command-line reference and whose Python module
# documents the API (LAGRANGE_BUILD, default build/).
build = Path(os.environ.get("LAGRANGE_BUILD", "build"))
build = (build if build.is_absolute() else root / build).resolve()
lagrange_binary = str(build / "lagrange")
if (build / "python" / "lagrange" / "__init__.py").exists():
    sys.path.insert(0, str(build / "python"))

project = "lagrange"
author = "the lagrange authors"
copyright = "the lagrange authors"

extensions = ["myst_parser", "sphinx.ext.autodoc", "lagrange_cli", "lagrange_notebooks", "lagrange_cpp"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**/.ipynb_checkpoints"]

myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 4  # `[..](model-language.md#rigid-bodies)` links resolve

html_theme = "furo"
html_title = "lagrange manual"
html_static_path = []
html_show_sourcelink = False
pygments_style = "default"

# The notebooks (docs/notebooks, docs/_ext/lagrange_notebooks.py) run against this build's module.
lagrange_build = str(build)

autodoc_member_order = "bysource"
autodoc_typehints = "description"


# Debian's furo (2022.12.07+dfsg) expects a web server: its stylesheet imports normalize.css from
# /javascript/ (Debian's libjs-normalize.css, served by Apache's javascript-common), and its
# script is an ES module that imports gumshoe. Opened from the disk, or served from any directory,
# the page then lacks both, with console errors. Once the site is written, the stylesheet imports
# a copy beside it and the script carries gumshoe inline, so that every page works offline.
def _furo_offline(app, exception):
    import shutil

    if exception is not None or app.builder.format != "html":
        return
    static = Path(app.outdir) / "_static"
    css = static / "styles" / "furo.css"
    absolute = "url(/javascript/normalize.css/normalize.css)"
    normalize = Path("/usr/share/javascript/normalize.css/normalize.css")
    if css.exists() and absolute in css.read_text() and normalize.exists():
        shutil.copy(normalize, static / "styles" / "normalize.css")
        css.write_text(css.read_text().replace(absolute, "url(normalize.css)"))
    script, gumshoe = static / "scripts" / "furo.js", static / "scripts" / "gumshoe-patched.js"
    importing = 'import Gumshoe from "./gumshoe-patched.js";'
    if script.exists() and gumshoe.exists() and script.read_text().startswith(importing):
        script.write_text(gumshoe.read_text() + "\n" + script.read_text()[len(importing):])


def setup(app):
    app.connect("build-finished", _furo_offline)
