#!/usr/bin/python3
"""Runs the complete examples of the docs (ctest docs.examples): every ```c block of
docs/C_API.md, compiled with -std=c11 -Wall -Wextra -Werror against the build's headers and
librailcontact.so, and the ```python block under "## Example" of docs/PYTHON.md, run with
Debian's /usr/bin/python3 on the build's module. Each must exit 0; a failure names the doc and
the line of its block.

Usage: run_doc_examples.py SOURCE_DIR BUILD_DIR GENERATED_INCLUDE_DIR C_COMPILER
"""
import os
import re
import subprocess
import sys
import tempfile


def blocks(path, language, under=None):
    """(line, code) of each fenced block of `language`, only under the heading `under` if given."""
    found, heading, inside, start, lines = [], None, False, 0, []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if not inside and line.startswith("#"):
                heading = line.strip("# \n")
            if not inside and line.rstrip() == "```" + language:
                inside, start, lines = True, number, []
            elif inside and line.rstrip() == "```":
                inside = False
                if under is None or heading == under:
                    found.append((start, "".join(lines)))
            elif inside:
                lines.append(line)
    return found


def main():
    source, build, generated, cc = sys.argv[1:5]
    failures = 0
    with tempfile.TemporaryDirectory(prefix="railcontact_doc_examples_") as work:
        c_api = os.path.join(source, "docs", "C_API.md")
        for line, code in blocks(c_api, "c"):
            program = os.path.join(work, f"c_api_{line}.c")
            with open(program, "w") as f:
                f.write(code)
            binary = program[:-2]
            compile = [cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-I", os.path.join(source, "include"), "-I",
                       generated, program, "-L", build, "-lrailcontact", f"-Wl,-rpath,{build}", "-lm", "-o", binary]
            for command, what in ((compile, "compile"), ([binary], "run")):
                r = subprocess.run(command, capture_output=True, text=True, timeout=300)
                if r.returncode != 0:
                    print(f"docs/C_API.md:{line}: the C example does not {what} (exit {r.returncode}):\n{r.stdout}{r.stderr}")
                    failures += 1
                    break
            else:
                print(f"docs/C_API.md:{line}: ok")
        python_doc = os.path.join(source, "docs", "PYTHON.md")
        examples = blocks(python_doc, "python", under="Example")
        if not examples:
            print("docs/PYTHON.md: no ```python block under '## Example'")
            failures += 1
        for line, code in examples:
            env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"), PYTHONDONTWRITEBYTECODE="1")
            r = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True, timeout=300, env=env,
                               cwd=work)
            if r.returncode != 0:
                print(f"docs/PYTHON.md:{line}: the Python example fails (exit {r.returncode}):\n{r.stdout}{r.stderr}")
                failures += 1
            else:
                print(f"docs/PYTHON.md:{line}: ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
