"""The command-line reference, generated from the program's own --help at build time.

```{lagrange-cli-reference}
```
runs `lagrange --help`, reads its list of subcommands and writes one section per subcommand
holding `lagrange <cmd> --help` verbatim, so that the reference cannot drift from the program.
The binary is conf.py's `lagrange_binary` (LAGRANGE_BUILD/lagrange, default build/lagrange).
"""
import re
import subprocess
from pathlib import Path

from docutils import nodes
from sphinx.errors import ExtensionError
from sphinx.util.docutils import SphinxDirective


def run_help(binary, *args):
    if not Path(binary).is_file():
        raise ExtensionError(
            f"lagrange-cli-reference: no program at {binary}; build it first "
            "(`make docs` does: cmake --build build --target lagrange)")
    out = subprocess.run([binary, *args, "--help"], capture_output=True, text=True, check=True,
                         env={"PATH": "/usr/bin:/bin", "COLUMNS": "100"})
    # Usage lines name argv[0]; the manual names the command as a user types it.
    return out.stdout.replace(binary, "lagrange").rstrip() + "\n"


def subcommands(top_help):
    """The names listed under 'Subcommands:' of `lagrange --help`."""
    names, inside = [], False
    for line in top_help.splitlines():
        if line.startswith("Subcommands:"):
            inside = True
            continue
        if inside:
            m = re.match(r"^  (\S+)\s", line)
            if m:
                names.append(m.group(1))
            elif line.strip() and not line.startswith(" "):
                break
    return names


class CliReference(SphinxDirective):
    has_content = False

    def run(self):
        binary = self.env.config.lagrange_binary
        self.env.note_dependency(binary)
        top = run_help(binary)
        result = [nodes.literal_block(top, top, language="text")]
        for name in subcommands(top):
            text = run_help(binary, name)
            section = nodes.section(ids=[f"lagrange-{name}"], names=[f"lagrange {name}"])
            section += nodes.title(text=f"lagrange {name}")
            section += nodes.literal_block(text, text, language="text")
            self.state.document.note_implicit_target(section)
            result.append(section)
        return result


def setup(app):
    app.add_config_value("lagrange_binary", "build/lagrange", "env")
    app.add_directive("lagrange-cli-reference", CliReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
