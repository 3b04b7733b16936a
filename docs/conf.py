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

extensions = ["myst_parser", "sphinx.ext.autodoc", "lagrange_cli"]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]

myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 4  # `[..](model-language.md#rigid-bodies)` links resolve

html_theme = "furo"
html_title = "lagrange manual"
html_static_path = []
html_show_sourcelink = False
pygments_style = "default"

autodoc_member_order = "bysource"
autodoc_typehints = "description"
