#!/usr/bin/env python3
"""Counts the functions of src/ longer than 60 and 100 lines (from the `fn` line to its closing brace).

Usage: scripts/long-functions.py [--list N] [DIR]   (DIR defaults to src/ beside this script)
Braces inside string literals, char literals and comments are skipped."""
import re
import sys
from pathlib import Path

FN = re.compile(r"^\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?(extern\s+\"[^\"]*\"\s+)?fn\s+(\w+)")


def code_chars(text):
    """The text with comments, strings and char literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c == "r" and re.match(r'r#*"', text[i:i + 10]) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            hashes = re.match(r'r(#*)"', text[i:]).group(1)
            end = '"' + hashes
            j = text.find(end, i + len(hashes) + 2)
            j = n if j < 0 else j + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            out.append(re.sub(r"[^\n]", " ", text[i:j + 1])); i = j + 1
        elif c == "'" and re.match(r"'(\\.|[^\\'])'|'\\u\{[0-9a-fA-F]+\}'|'\\x[0-9a-fA-F]{2}'", text[i:i + 12]):
            m = re.match(r"'(\\.|[^\\'])'|'\\u\{[0-9a-fA-F]+\}'|'\\x[0-9a-fA-F]{2}'", text[i:i + 12])
            out.append(" " * len(m.group(0))); i += len(m.group(0))
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(path):
    lines = code_chars(path.read_text()).split("\n")
    for k, line in enumerate(lines):
        m = FN.match(line)
        if not m:
            continue
        depth, started = 0, False
        for j in range(k, len(lines)):
            for ch in lines[j]:
                if ch == "{":
                    depth += 1; started = True
                elif ch == "}":
                    depth -= 1
                elif ch == ";" and not started and depth == 0:
                    break  # a declaration without body
            else:
                if started and depth == 0:
                    yield m.group(7), k + 1, j - k + 1
                    break
                continue
            break


def main():
    args = sys.argv[1:]
    show = 0
    if args[:1] == ["--list"]:
        show, args = int(args[1]), args[2:]
    root = Path(args[0]) if args else Path(__file__).resolve().parent.parent / "src"
    found = [(n, f"{p}:{line}", name) for p in sorted(root.rglob("*.rs")) for name, line, n in functions(p)]
    found.sort(reverse=True)
    print(f"functions: {len(found)}, over 60 lines: {sum(n > 60 for n, _, _ in found)}, "
          f"over 100 lines: {sum(n > 100 for n, _, _ in found)}")
    for n, where, name in found[:show]:
        print(f"{n:5} {name} {where}")


main()
