#!/usr/bin/env python3
"""Replaces the text between two marker lines of a file with a table (benches/RESULTS.md's tables).

    python3 write_section.py FILE TABLE BEGIN END     TABLE: a file with the new text; BEGIN, END: the markers
"""
import sys

path, table_file, begin, end = sys.argv[1:5]
table = open(table_file).read().strip()
text = open(path).read()
i, j = text.index(begin) + len(begin), text.index(end)
open(path, "w").write(text[:i] + "\n" + table + "\n" + text[j:])
