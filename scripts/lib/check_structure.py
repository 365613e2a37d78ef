#!/usr/bin/env python3
"""The house rules that the tree itself can be checked against (scripts/check-structure.sh).

1. Includes run downwards only. The core's folders are ranked (CORE_RANKS, lowest first); a file
   in one may include its own folder and lower-ranked ones, never a higher one. The core includes
   nothing outside itself: no Qt, no VCG, no MeshLab, none of the adapters. Outside the core, each
   top-level folder may include only the folders TOP_LEVEL_MAY_INCLUDE names.
2. Functions fit on a screen: none over MAX_FUNCTION_LINES lines (from the line its signature
   starts on to its closing brace) in the core, the adapters, the CLI, the plugin and eval/.
3. Files are read in one sitting: none over MAX_FILE_LINES lines there.

Usage: check_structure.py [ROOT]   (ROOT: the checkout, default the one this script is in)
Prints every breach as "path:line: what", and exits 1 when there is one.
"""
import os
import re
import sys

CORE = "filter_support_slimming/core"
CORE_RANKS = ["utilities", "platform", "geometry", "print", "rotation", "domain", "solver",
              "support_model", "optimizer", "orientation"]
# Top-level folders (outside the core) and the project folders each may include from.
TOP_LEVEL_MAY_INCLUDE = {
    "vcg_adapters": {"core", "vcg_adapters"},
    "mesh_io": {"core", "vcg_adapters", "mesh_io"},
    "cli": {"core", "mesh_io", "cli"},
    "filter_support_slimming": {"core", "vcg_adapters", "filter_support_slimming"},
    "eval": {"core", "mesh_io", "vcg_adapters", "eval"},
}
CHECKED_FOR_SIZE = [CORE, "vcg_adapters", "mesh_io", "cli", "filter_support_slimming", "eval"]
MAX_FUNCTION_LINES = 80
MAX_FILE_LINES = 400
SOURCE = (".h", ".cpp")
FOREIGN_IN_CORE = re.compile(r"#include\s*<(Q[A-Za-z]+|vcg/|wrap/|common/|meshlab)")
INCLUDE = re.compile(r'#include\s*"([^"]+)"')


def sources(root, folder):
    for base, _, names in os.walk(os.path.join(root, folder)):
        for name in sorted(names):
            if name.endswith(SOURCE):
                yield os.path.relpath(os.path.join(base, name), root)


def core_folder(path):
    """The core folder of a path like core/<folder>/x.h (include) or .../core/<folder>/x.h."""
    parts = path.split("/")
    if "core" not in parts:
        return None
    i = parts.index("core")
    return parts[i + 1] if i + 2 < len(parts) else ""


def include_breaches(root):
    breaches = []
    for path in sources(root, CORE):
        own = core_folder(path)
        if own not in CORE_RANKS:
            breaches.append(f"{path}:1: a core file outside the ranked folders {CORE_RANKS}")
            continue
        for number, line in enumerate(open(os.path.join(root, path), encoding="utf-8"), 1):
            if FOREIGN_IN_CORE.search(line):
                breaches.append(f"{path}:{number}: the core includes Qt, VCG or MeshLab: {line.strip()}")
            m = INCLUDE.search(line)
            if not m:
                continue
            target = m.group(1)
            if not target.startswith("core/"):
                breaches.append(f"{path}:{number}: the core includes {target}, outside the core")
                continue
            other = core_folder(target)
            if other not in CORE_RANKS:
                breaches.append(f"{path}:{number}: {target} is in no ranked core folder")
            elif CORE_RANKS.index(other) > CORE_RANKS.index(own):
                breaches.append(f"{path}:{number}: {own}/ includes {target}, from the higher folder {other}/")
    for top, allowed in TOP_LEVEL_MAY_INCLUDE.items():
        for path in sources(root, top):
            if path.startswith(CORE + "/"):
                continue
            for number, line in enumerate(open(os.path.join(root, path), encoding="utf-8"), 1):
                m = INCLUDE.search(line)
                if not m or "/" not in m.group(1):
                    continue
                folder = m.group(1).split("/")[0]
                known = folder in TOP_LEVEL_MAY_INCLUDE or folder == "core"
                if known and folder not in allowed:
                    breaches.append(f"{path}:{number}: {top}/ includes {m.group(1)} ({folder}/ is not below it)")
    return breaches


def code_only(text):
    """The text with comments, string and character literals and preprocessor lines blanked,
    newlines kept (so line numbers still hold)."""
    out, i, n = [], 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            while i < n and text[i] != "\n":  # a directive, with its continuation lines
                if text[i] == "\\" and i + 1 < n and text[i + 1] == "\n":
                    out.append("\n")
                    i += 2
                    continue
                i += 1
            continue
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                i += 1
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            out.append("\n" * text.count("\n", i, end))
            i = end
            continue
        if text.startswith('R"', i):  # a raw string: R"delim( ... )delim"
            open_paren = text.find("(", i)
            delim = text[i + 2:open_paren]
            end = text.find(")" + delim + '"', open_paren)
            end = n if end < 0 else end + len(delim) + 2
            out.append('""' + "\n" * text.count("\n", i, end))
            i = end
            continue
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + c)
            i = j + 1
            continue
        out.append(c)
        if c == "\n":
            at_line_start = True
        elif not c.isspace():
            at_line_start = False
        i += 1
    return "".join(out)


SCOPE_KEYWORD = re.compile(r"^(template\s*<.*>\s*)?(namespace|extern)\b|\b(class|struct|union|enum)\b[^(]*$", re.S)
# A function body's brace follows its parameter list and any qualifiers or trailing return type.
SIGNATURE_END = re.compile(r"\)\s*(const|noexcept|override|final|mutable|&|->\s*[\w:<>,*&\s]+)*\s*$")
ACCESS_LABEL = re.compile(r"^\s*(public|private|protected)\s*:")


def functions(text):
    """(first line, last line) of every function body at namespace or class scope."""
    code = code_only(text)
    found, stack = [], []  # stack: (kind, first line)
    header_start, line = 0, 1
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
        elif c == "{":
            header = ACCESS_LABEL.sub("", code[header_start:i]).strip()
            if any(kind != "scope" for kind, _ in stack):
                kind = "block"  # a block, lambda or initializer inside a function or initializer
            elif SCOPE_KEYWORD.search(header):
                kind = "scope"
            elif SIGNATURE_END.search(header) and "=" not in header.split("(")[0]:
                kind = "function"
            else:
                kind = "block"  # an initializer, or a brace in a constructor's initializer list
            stack.append((kind, line - header.count("\n")))
            header_start = i + 1
        elif c in "};":
            if c == "}" and stack:
                kind, first = stack.pop()
                if kind == "function":
                    found.append((first, line))
            header_start = i + 1
    return found


def size_breaches(root):
    breaches = []
    for folder in CHECKED_FOR_SIZE:
        for path in sources(root, folder):
            if folder != CORE and path.startswith(CORE + "/"):
                continue  # the core is checked as a folder of its own
            text = open(os.path.join(root, path), encoding="utf-8").read()
            lines = text.count("\n")
            if lines > MAX_FILE_LINES:
                breaches.append(f"{path}:1: {lines} lines, over {MAX_FILE_LINES}")
            for first, last in functions(text):
                if last - first + 1 > MAX_FUNCTION_LINES:
                    breaches.append(f"{path}:{first}: a function of {last - first + 1} lines, over {MAX_FUNCTION_LINES}")
    return breaches


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    if not os.path.isdir(os.path.join(root, CORE)):
        print(f"check-structure: no {CORE} under {root}", file=sys.stderr)
        return 2
    breaches = include_breaches(root) + size_breaches(root)
    for b in breaches:
        print(b)
    if breaches:
        print(f"check-structure: {len(breaches)} breach(es) of the house rules", file=sys.stderr)
        return 1
    print(f"check-structure: includes run downwards; no function over {MAX_FUNCTION_LINES} lines, "
          f"no file over {MAX_FILE_LINES}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
