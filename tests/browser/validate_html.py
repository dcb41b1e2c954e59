"""Validates an HTML file with html5lib, an implementation of the WHATWG HTML parsing algorithm: every
parse error the standard defines (a stray end tag, an unclosed element, a bad character reference, an
attribute repeated, a missing doctype, a non-void element written `<x/>` ...) is printed with its line and
column, and the exit status is 1 when there is any. Usage: python3 validate_html.py FILE.html
"""
import sys

import html5lib


def main(path):
    with open(path, "rb") as f:
        data = f.read()
    parser = html5lib.HTMLParser(strict=False, namespaceHTMLElements=False)
    parser.parse(data)
    for (line, col), code, params in parser.errors:
        print(f"{path}:{line}:{col}: {code} {params}")
    if parser.errors:
        return 1
    print(f"{path}: no parse error (html5lib {html5lib.__version__})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
