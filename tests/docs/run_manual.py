#!/usr/bin/env python3
"""Runs what the manual and the README show (issue 39): a documentation change that breaks an
example fails the test suite.

- ```console blocks: each `$ lagrange …` (or `$ cc …`, `$ ./out/…`) line is run (lagrange = the built program) and every
  output line the page shows must appear, in order, in what the program prints; `...` inside a
  line stands for any text (timings), and output lines not shown may lie between. Equations
  match when equal as expressions (GiNaC's term order varies). The exit code must be 0, or
  the N of a shown `(exit N)` line.
- ```python blocks: each page's blocks run in order in one fresh interpreter with the built
  module on PYTHONPATH (skipped when the module is not built). They check their own numbers.
- ```yaml blocks whose first line is `# PATH.yaml`: the block must be an excerpt of that file
  (its lines in the file's order), and `lagrange check` must accept the file.
- {literalinclude} of a .yaml file: `lagrange check` must accept the file. (Each tutorial's
  transcripts then simulate it and compare the numbers the page states.)

- The command line cannot drift from the manual: the reference page is generated from --help
  (docs/_ext/lagrange_cli.py), and every option some `lagrange COMMAND --help` lists must be
  described in docs/manual/reference/options.md, which must name no option the program lacks.

Commands run in a scratch directory that sees the repository's examples/ and docs/, so `-o out/…`
writes nowhere in the source tree.

usage: run_manual.py --lagrange BUILD/lagrange [--python-path BUILD/python] --source SRC [PAGE …]
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FENCE = re.compile(r"^(`{3,}|:{3,})\s*(\{?[\w-]+\}?)?[ \t]*(.*)$")


def blocks(text):
    """(language, argument, body lines, first line number) of each fenced block."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if m and m.group(2):
            fence, lang, arg = m.group(1), m.group(2), m.group(3)
            start = i + 1
            j = start
            while j < len(lines) and lines[j].strip() != fence:
                j += 1
            yield lang, arg.strip(), lines[start:j], start
            i = j + 1
        else:
            i += 1


def line_pattern(shown):
    parts = [re.escape(p) for p in shown.rstrip().split("...")]
    return re.compile("^" + ".*".join(parts) + r"\s*$")


def same_equation(shown, printed):
    """`lagrange derive` prints sums and products in GiNaC's order, which can differ from one
    process to the next: an equation line matches when its left-hand name is the same and the
    two sides are equal as expressions (SymPy)."""
    if " = " not in shown or "..." in shown or " = " not in printed:
        return False
    a, b = shown.strip().split(" = ", 1), printed.strip().split(" = ", 1)
    try:
        import sympy
        def parse(e):
            return sympy.sympify(e.replace("^", "**").replace("lambda", "lambda_"))
        if a[0] != b[0]:
            if sympy.simplify(parse(a[0]) - parse(b[0])) != 0:
                return False
        return sympy.simplify(parse(a[1]) - parse(b[1])) == 0
    except Exception:
        return False


def check_transcript(page, lineno, body, env, cwd, lagrange, failures):
    commands = []
    for k, line in enumerate(body):
        if line.startswith("$ "):
            commands.append((lineno + k, line[2:], []))
        elif commands:
            commands[-1][2].append(line)
    for at, command, shown in commands:
        command = re.sub(r"#.*$", "", command).strip()
        if not re.match(r"^(lagrange|cc|\./out/)", command):
            continue  # only the program, the C compiler and what they built run here
        argv = shlex.split(command)
        if argv[0] == "lagrange":
            argv[0] = lagrange
        proc = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=120)
        out = (proc.stdout + proc.stderr).split("\n")
        k = 0
        code = 0
        for expect in (s for s in shown if s.strip() and s.strip() != "..."):
            m = re.match(r"^\(exit (\d+)\)$", expect.strip())
            if m:  # `(exit N)` shown after the output: the exit code the command must give
                code = int(m.group(1))
                continue
            pattern = line_pattern(expect)
            while k < len(out) and not (pattern.match(out[k].rstrip())
                                        or same_equation(expect, out[k])):
                k += 1
            if k == len(out):
                failures.append(f"{page}:{at}: `{command}` did not print\n    {expect}\n"
                                f"  it printed (exit {proc.returncode}):\n    "
                                + "\n    ".join(out))
                break
            k += 1
        else:
            if proc.returncode != code:
                failures.append(f"{page}:{at}: `{command}` exited {proc.returncode}, not {code}:\n"
                                + proc.stdout + proc.stderr)


def excerpt_of(body, path):
    """The block's lines appear in the file in the same order (the first line, naming the
    file, may be the block's own)."""
    if not path.exists():
        return False
    lines = path.read_text().split("\n")
    k = 0
    for i, line in enumerate(body):
        while k < len(lines) and lines[k] != line:
            k += 1
        if k == len(lines):
            if i == 0:  # the heading comment, not in the file
                k = 0
                continue
            return False
        k += 1
    return True


def check_model(path, rel, lineno, lagrange, cwd, env, failures):
    proc = subprocess.run([lagrange, "check", str(path)], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=60)
    if proc.returncode != 0:
        failures.append(f"{rel}:{lineno}: lagrange check {path}: {proc.stdout}{proc.stderr}")


# Options of other programs that options.md quotes (git describe, mpirun).
FOREIGN_OPTIONS = {"--always", "--dirty", "--oversubscribe", "--allow-run-as-root"}


def check_options(lagrange, page, failures):
    def help_of(*args):
        return subprocess.run([lagrange, *args, "--help"], capture_output=True, text=True,
                              check=True).stdout
    top = help_of()
    program = set(re.findall(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", top, re.M))
    commands = re.findall(r"^  (\S+)\s", top.split("Subcommands:")[1], re.M)
    for command in commands:
        program |= set(re.findall(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", help_of(command), re.M))
    described = set(re.findall(r"(--[a-z][a-z0-9-]*)", page.read_text())) - FOREIGN_OPTIONS
    for option in sorted(program - described):
        failures.append(f"{page.name}: the program has {option}, which the page does not describe")
    for option in sorted(described - program):
        failures.append(f"{page.name}: the page describes {option}, which no command has")
    return len(commands), len(program)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lagrange", required=True)
    ap.add_argument("--python-path")
    ap.add_argument("--source", required=True)
    ap.add_argument("pages", nargs="*")
    a = ap.parse_args()
    src = Path(a.source).resolve()
    lagrange = str(Path(a.lagrange).resolve())
    pages = [Path(p).resolve() for p in a.pages] or (
        [src / "README.md"] + sorted((src / "docs" / "manual").rglob("*.md")))
    python_ok = a.python_path and (Path(a.python_path) / "lagrange" / "__init__.py").exists()
    failures, counts = [], {"console": 0, "python": 0, "yaml": 0, "include": 0}
    with tempfile.TemporaryDirectory(prefix="lagrange-manual-") as tmp:
        cwd = Path(tmp)
        for name in ("examples", "docs"):
            (cwd / name).symlink_to(src / name)
        env = dict(os.environ, LAGRANGE_CACHE_DIR=str(cwd / ".cache"), COLUMNS="100")
        env["PATH"] = str(Path(lagrange).parent) + os.pathsep + env.get("PATH", "")
        if python_ok:
            env["PYTHONPATH"] = str(Path(a.python_path).resolve())
        timings = []
        for page in pages:
            started = time.monotonic()
            rel = page.relative_to(src)
            text = page.read_text()
            python = []
            for lang, arg, body, lineno in blocks(text):
                if lang == "console":
                    counts["console"] += 1
                    check_transcript(rel, lineno, body, env, cwd, lagrange, failures)
                elif lang == "python":
                    python.append("\n".join(body))
                elif lang == "yaml" and body and re.match(r"^# (\S+\.yaml)\b", body[0]):
                    counts["yaml"] += 1
                    path = src / re.match(r"^# (\S+\.yaml)\b", body[0]).group(1)
                    if not excerpt_of(body, path):
                        failures.append(f"{rel}:{lineno}: the block is not an excerpt of "
                                        f"{path.relative_to(src)}: a line differs or is missing")
                    else:
                        check_model(path, rel, lineno, lagrange, cwd, env, failures)
                elif lang == "{literalinclude}" and arg.endswith(".yaml"):
                    counts["include"] += 1
                    check_model((page.parent / arg).resolve(), rel, lineno, lagrange, cwd, env,
                                failures)
            if python and python_ok:
                counts["python"] += len(python)
                proc = subprocess.run([sys.executable, "-c", "\n\n".join(python)], cwd=cwd,
                                      env=env, capture_output=True, text=True, timeout=120)
                if proc.returncode != 0:
                    failures.append(f"{rel}: its Python blocks failed:\n{proc.stdout}{proc.stderr}")
            timings.append((time.monotonic() - started, str(rel)))
    options_page = src / "docs" / "manual" / "reference" / "options.md"
    if not a.pages:
        commands, options = check_options(lagrange, options_page, failures)
        print(f"checked the {options} options of {commands} commands against {options_page.name}")
    print(f"checked {len(pages)} pages: {counts['console']} transcripts, {counts['python']} "
          f"Python blocks{'' if python_ok else ' (skipped: no module)'}, {counts['yaml']} "
          f"YAML blocks, {counts['include']} included model files")
    for seconds, rel in timings:
        if seconds >= 0.05:
            print(f"  {seconds:5.2f} s  {rel}")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
