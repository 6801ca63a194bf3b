#!/usr/bin/python3
"""Checks that the project's documentation references resolve inside the project.

Usage: /usr/bin/python3 scripts/check_docs.py [--basic] [PROJECT_ROOT]

Scans the project's files (those git tracks plus new ones it does not ignore; without git,
the tree minus build folders) named *.md, *.cpp, *.hpp, *.h, *.py, *.toml, *.txt or Makefile,
and fails (exit 1, one line per offender: file:line: rule: what) on
  (a) a markdown link [text](target) whose relative target does not exist or lies outside the
      project (http(s), mailto and anchor-only links are not checked; in *.md files code spans
      and fenced code blocks are skipped; in other files only targets that look like paths);
  (b) a file name ending in .md whose name is not the name of a project file (summary.md,
      which the studies write into their output folders, is allowed);
  (c) a path into the folder shared between projects, or up into a reference or data folder
      next to the project: the project must not depend on, or refer to, anything outside its
      own tree;
and, unless --basic is given,
  (d) a path starting with a top-level folder of the project (src/, include/, app/, docs/,
      tests/, bench/, scripts/, data/, examples/, cmake/) that matches no file or folder
      ({a,b} alternatives and * globs are expanded; a placeholder such as src/<stage>/ is
      checked up to the placeholder), or an include-style path of a C++ file that matches no
      file: railcontact/<name>.hpp (in include/), <stage>/<name>.hpp (in src/) and
      case/..., study/..., cli/... (in app/);
  (e) a C++ source or header name (*.cpp, *.hpp, also <name>.{hpp,cpp}) outside #include lines
      that is the name of no project file, nor of another library's header the project includes
      with #include <...> (generated files: kalker_table_data.cpp);
  (f) a section of docs/METHOD.md cited as "METHOD.md §N", "METHOD §N.M" (also "…, §K" lists)
      that has no heading "## N." / "### N.M" there.
Standard library only; a run takes a fraction of a second.
"""
import glob
import os
import re
import subprocess
import sys

EXTENSIONS = (".md", ".cpp", ".hpp", ".h", ".py", ".toml", ".txt")
PLAIN_NAMES = ("Makefile",)
BUILD_PREFIXES = ("build", "railcontact-out", "out")
ALLOWED_MD = {"summary.md"}
GENERATED_SOURCES = {"kalker_table_data.cpp"}
TOP_FOLDERS = ("src", "include", "app", "docs", "tests", "bench", "scripts", "data", "examples", "cmake")

LINK = re.compile(r"\[([^\]\n]*)\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
URL = re.compile(r"[a-zA-Z][a-zA-Z0-9+.-]*://[^\s)>\]\"'`]+")
MD_NAME = re.compile(r"(?<![\w.-])([\w][\w.-]*\.md)\b")
OUTSIDE = re.compile(r"(?<![\w.-])" + "shared" + r"/|\.\./" + r"(?:reference|data)\b")
PROJECT_PATH = re.compile(r"(?<![\w./$}*@:-])((?:" + "|".join(TOP_FOLDERS) + r")/[\w./{},*+-]*)")
STAGES = ("support", "mesh", "hertz", "kalker", "geometry", "elastic", "normal", "tangential", "wheel_rail",
          "flexibility_table")
APP_FOLDERS = ("case", "study", "cli")
INCLUDE_STYLE_PATH = re.compile(r"(?<![\w./$}*@:-])((railcontact|" + "|".join(STAGES + APP_FOLDERS)
                                + r")/[\w./{},*-]*\.(?:hpp|cpp|h))\b")
SOURCE_NAME = re.compile(r"(?<![\w./$}*@:<-])([\w-]+\.(?:cpp|hpp))\b")
SOURCE_NAMES = re.compile(r"(?<![\w./$}*@:<-])([\w-]+)\.\{((?:cpp|hpp)(?:,(?:cpp|hpp))*)\}")
INCLUDE_LINE = re.compile(r"^\s*#\s*include\b")
EXTERNAL_INCLUDE = re.compile(r"^\s*#\s*include\s*<([^>]+)>")
METHOD_REF = re.compile(r"\bMETHOD(?:\.md)?\s*§\s*(\d+(?:\.\d+)?)((?:\s*(?:,|and)\s*§\s*\d+(?:\.\d+)?)*)")
METHOD_HEADING = re.compile(r"^#{2,4}\s+(\d+(?:\.\d+)?)\.?\s")
FENCE = re.compile(r"^\s*(```|~~~)")
CODE_SPAN = re.compile(r"(`+)(.+?)\1")


def project_files(root):
    """Relative paths (with /) of the files to scan and to resolve names against."""
    try:
        out = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             cwd=root, capture_output=True, check=True).stdout.decode("utf-8", "replace")
        names = {f for f in out.split("\0") if f}
    except (OSError, subprocess.CalledProcessError):
        names = set()
        for directory, subdirs, files in os.walk(root):
            rel_dir = os.path.relpath(directory, root)
            subdirs[:] = [d for d in subdirs if not d.startswith(".")
                          and not (rel_dir == "." and d.startswith(BUILD_PREFIXES))]
            names |= {os.path.normpath(os.path.join(rel_dir, f)).replace(os.sep, "/") for f in files}
    return sorted(f for f in names if os.path.isfile(os.path.join(root, f)))


def scanned(path):
    name = path.rsplit("/", 1)[-1]
    return name.endswith(EXTENSIONS) or name in PLAIN_NAMES


def blank_code(lines):
    """Markdown lines with fenced code blocks and code spans replaced by blanks (same numbering)."""
    out, fenced = [], False
    for line in lines:
        if FENCE.match(line):
            fenced = not fenced
            out.append("")
        elif fenced:
            out.append("")
        else:
            out.append(CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line))
    return out


def expand_braces(path):
    m = re.search(r"\{([^{}]*)\}", path)
    if not m:
        return [path]
    return [p for alt in m.group(1).split(",") for p in expand_braces(path[:m.start()] + alt + path[m.end():])]


def path_exists(root, path):
    """A project path (relative to root) with optional {a,b} and * globs: does anything match?"""
    for candidate in expand_braces(path):
        full = os.path.join(root, candidate)
        if any(c in candidate for c in "*?["):
            if glob.glob(full, recursive=True):
                continue
            return False
        if not os.path.exists(full):
            return False
    return True


def clean_path(token):
    token = token.rstrip(".,;:")
    # A path ends before a placeholder or an unbalanced brace left by the sentence.
    while token.count("{") < token.count("}") or token.endswith(("{", ",")):
        token = token[:-1]
    return token


def check(root, basic=False):
    files = project_files(root)
    basenames = {f.rsplit("/", 1)[-1] for f in files}
    problems = []
    checked = 0
    method_sections = set()
    method = os.path.join(root, "docs", "METHOD.md")
    if os.path.isfile(method):
        with open(method, encoding="utf-8", errors="replace") as f:
            method_sections = {m.group(1) for m in map(METHOD_HEADING.match, f) if m}

    texts = {}
    for rel in files:
        if not scanned(rel):
            continue
        try:
            with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
                texts[rel] = f.read().split("\n")
        except OSError as error:
            problems.append(f"{rel}:1: unreadable: {error}")
    # Headers of other libraries the project includes may be named in comments (rule e).
    external = {m.group(1).strip().rsplit("/", 1)[-1] for lines in texts.values() for line in lines
                for m in [EXTERNAL_INCLUDE.match(line)] if m}

    for rel, lines in texts.items():
        is_md = rel.endswith(".md")
        link_lines = blank_code(lines) if is_md else lines
        directory = os.path.dirname(rel)
        for number, (line, link_line) in enumerate(zip(lines, link_lines), 1):
            where = f"{rel}:{number}"
            # (a) markdown links
            for m in LINK.finditer(link_line):
                target = m.group(2)
                if not is_md:
                    before = link_line[m.start() - 1] if m.start() > 0 else " "
                    if before.isalnum() or before in "_])" or not re.fullmatch(r"[\w./#-]+", target) \
                            or not ("/" in target or re.search(r"\.\w+(#|$)", target)):
                        continue
                if re.match(r"[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("#"):
                    continue
                checked += 1
                path = target.split("#", 1)[0]
                resolved = os.path.normpath(path.lstrip("/") if path.startswith("/") else os.path.join(directory, path))
                if resolved == ".." or resolved.startswith(".." + os.sep):
                    problems.append(f"{where}: (a) link target outside the project: {target}")
                elif not os.path.exists(os.path.join(root, resolved)):
                    problems.append(f"{where}: (a) link target does not exist: {target}")
            without_urls = URL.sub(" ", line)
            # (b) a .md name that is not the name of a project file
            for m in MD_NAME.finditer(without_urls):
                checked += 1
                name = m.group(1)
                if name not in basenames and name not in ALLOWED_MD:
                    problems.append(f"{where}: (b) no project file is named {name}")
            # (c) paths outside the project
            for m in OUTSIDE.finditer(line):
                checked += 1
                start = max(0, m.start() - 20)
                problems.append(f"{where}: (c) refers outside the project: ...{line[start:m.end() + 30].strip()}")
            if basic:
                continue
            # (d) project paths that match nothing
            for m in INCLUDE_STYLE_PATH.finditer(without_urls):
                if INCLUDE_LINE.match(line):
                    break
                token, first = m.group(1), m.group(2)
                base = "include" if first == "railcontact" else "app" if first in APP_FOLDERS else "src"
                checked += 1
                if token.count("{") == token.count("}") and not path_exists(root, f"{base}/{token}"):
                    problems.append(f"{where}: (d) no such file: {token} ({base}/{token})")
            for m in PROJECT_PATH.finditer(without_urls):
                token = clean_path(m.group(1))
                if token.count("{") != token.count("}"):
                    continue
                checked += 1
                if not path_exists(root, token):
                    problems.append(f"{where}: (d) no such file or folder: {token}")
            # (f) sections of docs/METHOD.md
            if method_sections:
                for m in METHOD_REF.finditer(line):
                    for section in [m.group(1)] + re.findall(r"§\s*(\d+(?:\.\d+)?)", m.group(2)):
                        checked += 1
                        if section not in method_sections:
                            problems.append(f"{where}: (f) docs/METHOD.md has no section {section}")
            # (e) C++ file names that are no project file
            if INCLUDE_LINE.match(line):
                continue
            names = [m.group(1) for m in SOURCE_NAME.finditer(without_urls)]
            names += [f"{m.group(1)}.{ext}" for m in SOURCE_NAMES.finditer(without_urls) for ext in m.group(2).split(",")]
            for name in names:
                checked += 1
                if name not in basenames and name not in GENERATED_SOURCES and name not in external:
                    problems.append(f"{where}: (e) no project file is named {name}")
    return problems, sum(1 for f in files if scanned(f)), checked


def main(argv):
    args = argv[1:]
    basic = "--basic" in args
    args = [a for a in args if a != "--basic"]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    problems, scanned_files, checked = check(root, basic)
    for line in problems:
        print(line)
    rules = "(a)-(c)" if basic else "(a)-(f)"
    summary = f"check_docs: {scanned_files} files, {checked} references checked, rules {rules}"
    if problems:
        print(f"{summary}: {len(problems)} dangling reference{'s' if len(problems) != 1 else ''}")
        return 1
    print(f"{summary}: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
