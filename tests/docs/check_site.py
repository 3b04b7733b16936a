#!/usr/bin/env python3
"""Builds the manual as `make docs` does, into a scratch directory, and checks the site (issue 39):
no Sphinx warning (-W), every internal link and anchor of the built pages resolves (no network),
the search index sends "Baumgarte" to the model-language page, and, where node, the report's
playwright-core and Debian's chromium are present, headless Chromium opens the start page and a
tutorial without console errors and its search page lists model-language for "Baumgarte"
(tests/docs/site_browser.mjs).

usage: check_site.py --source SRC --build BUILD
Exit 77 (ctest: skipped) when Debian's Sphinx, furo, myst-parser, breathe, doxygen, nbclient,
nbformat, ipykernel or SciPy is not installed (LAGRANGE_DOCS=1 scripts/install-deps.sh installs
them): the build runs the notebooks and Doxygen.
"""
import argparse
import html.parser
import importlib.util
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from urllib.parse import unquote, urlsplit


class Links(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.hrefs = set(), []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "a" and a.get("href"):
            self.hrefs.append(a["href"])
        if tag in ("img", "script") and a.get("src"):
            self.hrefs.append(a["src"])
        if tag == "link" and a.get("href"):
            self.hrefs.append(a["href"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--build", required=True)
    a = ap.parse_args()
    try:
        import sphinx, furo, myst_parser, breathe, nbclient, nbformat, scipy  # noqa: F401
        if importlib.util.find_spec("ipykernel") is None:
            raise ImportError("No module named 'ipykernel'")
        if shutil.which("doxygen") is None:
            raise ImportError("no doxygen")
    except ImportError as e:
        print(f"skipped: {e} (LAGRANGE_DOCS=1 scripts/install-deps.sh)")
        return 77
    src = Path(a.source).resolve()
    failures = []
    with tempfile.TemporaryDirectory(prefix="lagrange-docs-") as tmp:
        out = Path(tmp) / "html"
        start = time.monotonic()
        proc = subprocess.run(
            [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
             "-d", str(Path(tmp) / "doctrees"), str(src / "docs"), str(out)],
            env=dict(os.environ, LAGRANGE_BUILD=str(Path(a.build).resolve())),
            capture_output=True, text=True)
        seconds = time.monotonic() - start
        if proc.returncode != 0:
            print(proc.stdout + proc.stderr)
            print(f"FAIL sphinx -W exited {proc.returncode}")
            return 1
        pages = {p: Links() for p in out.rglob("*.html")}
        for p, parser in pages.items():
            parser.feed(p.read_text(encoding="utf-8"))
        checked = 0
        for p, parser in pages.items():
            for href in parser.hrefs:
                u = urlsplit(href)
                if u.scheme or u.netloc or href.startswith("mailto:"):
                    continue
                target = (p.parent / unquote(u.path)).resolve() if u.path else p
                checked += 1
                if not target.exists():
                    failures.append(f"{p.relative_to(out)}: link to missing {href}")
                elif u.fragment and target.suffix == ".html":
                    if target in pages and unquote(u.fragment) not in pages[target].ids:
                        failures.append(f"{p.relative_to(out)}: link to missing anchor {href}")
        index = (out / "searchindex.js").read_text()
        data = json.loads(re.search(r"Search\.setIndex\((.*)\)\s*$", index, re.S).group(1))
        hits = data["terms"].get("baumgart", [])
        hits = hits if isinstance(hits, list) else [hits]
        if "model-language" not in [data["docnames"][i] for i in hits]:
            failures.append('the search index does not send "Baumgarte" to model-language')
        browser = "not run (no node, web/node_modules or chromium)"
        node = shutil.which("node")
        if node and (src / "web" / "node_modules" / "playwright-core").exists() and \
                Path("/usr/bin/chromium").exists():
            run = subprocess.run([node, str(src / "tests" / "docs" / "site_browser.mjs"), str(out)],
                                 capture_output=True, text=True, timeout=240)
            browser = run.stdout.strip().splitlines()[-1] if run.stdout.strip() else "no output"
            if run.returncode != 0:
                failures.append("headless Chromium: " + run.stdout + run.stderr)
        size = sum(f.stat().st_size for f in out.rglob("*") if f.is_file())
        print(f"built {len(pages)} pages in {seconds:.1f} s ({size / 1e6:.1f} MB); "
              f"checked {checked} internal links and the search for Baumgarte; browser: {browser}")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
