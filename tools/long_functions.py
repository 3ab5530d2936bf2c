#!/usr/bin/env python3
"""Lists the functions over N lines (default 100) in src/, outside tests.

Usage: tools/long_functions.py [N]   (from anywhere)

A function runs from its `fn` line to its closing brace (brace matching that skips strings,
chars and comments). Files named tests.rs and `#[cfg(test)]` modules are left out.
"""
import pathlib
import re
import sys

LIMIT = int(sys.argv[1]) if len(sys.argv) > 1 else 100
ROOT = pathlib.Path(__file__).resolve().parent.parent / "src"
FN = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)")


def code_only(text):
    """The text with string, char and comment contents blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == '"' or text.startswith('r"', i) or text.startswith("r#", i):
            m = re.match(r'r(#*)"', text[i:])
            if m:
                end = '"' + m.group(1)
                j = text.find(end, i + len(m.group(0)))
                j = n if j < 0 else j + len(end)
            else:
                j = i + 1
                while j < n and text[j] != '"':
                    j += 2 if text[j] == "\\" else 1
                j += 1
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "'":
            m = re.match(r"'(\\.[^']*|[^\\'])'", text[i:])
            if m:
                out.append(" " * len(m.group(0)))
                i += len(m.group(0))
            else:
                out.append(c)
                i += 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    lines = code_only(path.read_text()).split("\n")
    skip_until = -1
    found = []
    for k, line in enumerate(lines):
        if k <= skip_until:
            continue
        if line.strip() == "#[cfg(test)]":
            end = block_end(lines, k + 1)
            skip_until = k + 1 if end is None else end
            continue
        m = FN.match(line)
        if not m:
            continue
        end = block_end(lines, k)
        if end is None:
            continue
        found.append((end - k + 1, m.group(6), k + 1))
    return found


def block_end(lines, start):
    depth, opened = 0, False
    for k in range(start, len(lines)):
        for c in lines[k]:
            if c == "{":
                depth, opened = depth + 1, True
            elif c == "}":
                depth -= 1
                if opened and depth == 0:
                    return k
            elif c == ";" and not opened and depth == 0:
                return None
    return None


rows = []
for path in sorted(ROOT.rglob("*.rs")):
    if path.name == "tests.rs" or "tests" in path.relative_to(ROOT).parts[:-1]:
        continue
    for length, name, line in functions(path):
        if length > LIMIT:
            rows.append((length, f"{path.relative_to(ROOT.parent)}:{line}", name))
for length, where, name in sorted(rows, reverse=True):
    print(f"{length:5}  {where}  {name}")
print(f"{len(rows)} functions over {LIMIT} lines")
