#!/usr/bin/python3
"""Checks the layering of railcontact's sources (docs/ARCHITECTURE.md).

Usage: /usr/bin/python3 scripts/check_layers.py [PROJECT_ROOT]

Reads the #include lines of src/**, include/railcontact/*.hpp and app/** and fails (exit 1,
one line per offender, file:line) when
  - a library file in src/<stage>/ includes a header of a higher layer: an internal header
    src/<stage>/... or a public header railcontact/<stage header>; the umbrella header
    railcontact/railcontact.hpp is not allowed in src/ at all; nor are application headers;
  - a library file lies in a folder of src/ that is not a layer;
  - a public header includes anything but public headers, or a public header of a higher layer;
  - an application file (app/) includes anything of the project but public headers
    (railcontact/...) and application headers (case/..., study/..., cli/...).
Includes in <...> of other libraries (the standard library, Eigen, fmt, ...) are not checked.
Standard library only; a run takes well under a second.
"""
import os
import re
import sys

# The layers, lowest first (docs/ARCHITECTURE.md). A file of layer k may include headers of
# layers <= k only.
STAGE_LAYERS = {
    "support": 0,
    "mesh": 1,
    "hertz": 2,
    "kalker": 3,
    "geometry": 4,
    "elastic": 5,
    "normal": 6,
    "tangential": 7,
    "wheel_rail": 8,
    "flexibility_table": 9,
}
UMBRELLA = "railcontact.hpp"
UMBRELLA_LAYER = max(STAGE_LAYERS.values()) + 1
PUBLIC_LAYERS = {
    "error.hpp": 0,
    "contact_patch.hpp": 1,
    "hertz.hpp": 2,
    "kalker.hpp": 3,
    "geometry.hpp": 4,
    "wheelset_geometry.hpp": 4,
    "normal.hpp": 6,
    "tangential.hpp": 7,
    "wheel_rail.hpp": 8,
    "wheelset.hpp": 8,
    "text_file.hpp": 0,
    "flexibility_table.hpp": 9,
    UMBRELLA: UMBRELLA_LAYER,
}
APP_FOLDERS = ("case", "study", "cli")
SOURCE_EXTENSIONS = (".cpp", ".hpp", ".h", ".cc", ".hh", ".inl")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^">]+)[">]')


def layer_name(layer):
    for stage, k in STAGE_LAYERS.items():
        if k == layer:
            return f"{layer} ({stage})"
    return f"{layer} (umbrella)" if layer == UMBRELLA_LAYER else str(layer)


def sources_under(root, folder):
    base = os.path.join(root, folder)
    found = []
    for directory, subdirs, files in os.walk(base):
        subdirs[:] = sorted(d for d in subdirs if not d.startswith("."))
        found += [os.path.join(directory, f) for f in sorted(files) if f.endswith(SOURCE_EXTENSIONS)]
    return found


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1), m.group(2).strip()


def classify(target):
    """('public', name) | ('stage', stage) | ('app', folder) | None for other libraries."""
    first, _, rest = target.partition("/")
    if first == "railcontact" and rest:
        return "public", rest
    if first in STAGE_LAYERS and rest:
        return "stage", first
    if first in APP_FOLDERS and rest:
        return "app", first
    return None


def check(root):
    problems = []
    counts = {"src": [0, 0], "include": [0, 0], "app": [0, 0]}

    def report(path, number, message):
        problems.append(f"{os.path.relpath(path, root)}:{number}: {message}")

    # The library, src/<stage>/...
    for path in sources_under(root, "src"):
        rel = os.path.relpath(path, os.path.join(root, "src")).split(os.sep)
        counts["src"][0] += 1
        if len(rel) < 2 or rel[0] not in STAGE_LAYERS:
            report(path, 1, f"src/{rel[0]}/ is not a layer of the library ({', '.join(STAGE_LAYERS)})")
            continue
        own = STAGE_LAYERS[rel[0]]
        for number, bracket, target in includes(path):
            kind = classify(target)
            if kind is None:
                if bracket == '"' and not os.path.exists(os.path.join(os.path.dirname(path), target)):
                    report(path, number, f'#include "{target}": not a header of the project '
                                         "(use src/<stage>/... or railcontact/...)")
                else:
                    counts["src"][1] += bracket == '"'
                continue
            counts["src"][1] += 1
            what, name = kind
            if what == "app":
                report(path, number, f"#include {target}: the library may not include the applications (app/)")
            elif what == "public":
                if name == UMBRELLA:
                    report(path, number, f"#include {target}: the umbrella header is not allowed in src/")
                elif name not in PUBLIC_LAYERS:
                    report(path, number, f"#include {target}: not a public header of the layer table")
                elif PUBLIC_LAYERS[name] > own:
                    report(path, number, f"#include {target}: layer {layer_name(PUBLIC_LAYERS[name])} "
                                         f"above this file's layer {layer_name(own)}")
            elif STAGE_LAYERS[name] > own:
                report(path, number, f"#include {target}: layer {layer_name(STAGE_LAYERS[name])} "
                                     f"above this file's layer {layer_name(own)}")

    # The public headers, include/railcontact/*.hpp
    public_dir = os.path.join(root, "include", "railcontact")
    for name in sorted(os.listdir(public_dir)) if os.path.isdir(public_dir) else []:
        path = os.path.join(public_dir, name)
        if not name.endswith(SOURCE_EXTENSIONS) or not os.path.isfile(path):
            continue
        counts["include"][0] += 1
        if name not in PUBLIC_LAYERS:
            report(path, 1, f"public header {name} is not in the layer table (scripts/check_layers.py)")
            continue
        own = PUBLIC_LAYERS[name]
        for number, bracket, target in includes(path):
            kind = classify(target)
            if kind is None and bracket == "<":
                continue  # another library
            counts["include"][1] += 1
            if kind is None or kind[0] != "public":
                report(path, number, f"#include {target}: a public header may include public headers only")
            elif kind[1] not in PUBLIC_LAYERS:
                report(path, number, f"#include {target}: not a public header of the layer table")
            elif kind[1] == UMBRELLA:
                report(path, number, f"#include {target}: only applications may include the umbrella header")
            elif PUBLIC_LAYERS[kind[1]] > own:
                report(path, number, f"#include {target}: layer {layer_name(PUBLIC_LAYERS[kind[1]])} "
                                     f"above this header's layer {layer_name(own)}")

    # The applications, app/**
    for path in sources_under(root, "app"):
        counts["app"][0] += 1
        for number, bracket, target in includes(path):
            kind = classify(target)
            if kind is None and bracket == "<":
                continue
            counts["app"][1] += 1
            if kind is None:
                report(path, number, f'#include "{target}": applications include railcontact/... and '
                                     "case/..., study/..., cli/... only")
            elif kind[0] == "stage":
                report(path, number, f"#include {target}: an application may not include the library's "
                                     "internals (src/); use the public API railcontact/...")
    return problems, counts


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    if not os.path.isdir(os.path.join(root, "src")):
        print(f"check_layers: {root} has no src/ folder", file=sys.stderr)
        return 2
    problems, counts = check(root)
    for line in problems:
        print(line)
    summary = (f"check_layers: {sum(c[0] for c in counts.values())} files, "
               f"{sum(c[1] for c in counts.values())} project includes checked "
               f"(src/ {counts['src'][0]} files in {len(STAGE_LAYERS)} layers, "
               f"include/railcontact/ {counts['include'][0]} public headers, app/ {counts['app'][0]} files)")
    if problems:
        print(f"{summary}: {len(problems)} violation{'s' if len(problems) != 1 else ''}")
        return 1
    print(f"{summary}: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
