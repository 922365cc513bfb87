#!/usr/bin/env python3
"""Long functions: the Rust functions over N lines, per crate, tests left out.

Counts each function from the line of its `fn` to the line of its closing brace (both
included; the doc comment and attributes above it are not counted). Left out: files named
`tests.rs` or under a `tests/` folder, and modules marked `#[cfg(test)]`. Closures and
nested functions count as part of the function that holds them; a nested `fn` is also
listed on its own.

    python3 tools/long_functions.py [--over N] [--check LIB,CLI] [CRATE_SRC ...]

Without CRATE_SRC it measures the library (crates/haphe/src) and the command
(crates/haphe-cli/src). `--over` is 100 by default. `--check 3,2` exits 1 when more than 3
library functions or more than 2 command functions are over N lines (the limits of
issue 35, acceptance 4).
"""

import argparse
import os
import signal
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_CRATES = [("library", "crates/haphe/src"), ("command", "crates/haphe-cli/src")]


def blank_code(text):
    """The text with comments, strings and character literals replaced by spaces
    (newlines kept), so that braces and keywords are only those of the code."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            depth, j = 1, i + 2
            while j < n and depth:
                if text.startswith("/*", j):
                    depth, j = depth + 1, j + 2
                elif text.startswith("*/", j):
                    depth, j = depth - 1, j + 2
                else:
                    j += 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "rb" and _raw_string_at(text, i):
            j = _raw_string_end(text, i)
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == '"':
            j = i + 1
            while j < n and text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            j += 1
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c == "'":
            # A character literal ('a', '\n', '\u{1F}', '{') or a lifetime ('a).
            if i + 2 < n and text[i + 1] == "\\":
                j = text.find("'", i + 2) + 1
            elif i + 2 < n and text[i + 2] == "'":
                j = i + 3
            else:
                out.append(c)
                i += 1
                continue
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def _raw_string_at(text, i):
    j = i + 1 if text[i] == "r" else (i + 2 if text.startswith("br", i) else -1)
    if j < 0 or (i > 0 and (text[i - 1].isalnum() or text[i - 1] == "_")):
        return False
    while j < len(text) and text[j] == "#":
        j += 1
    return j < len(text) and text[j] == '"' and (text[i] == "r" or text[i + 1] == "r")


def _raw_string_end(text, i):
    j = i + (1 if text[i] == "r" else 2)
    hashes = 0
    while text[j] == "#":
        hashes, j = hashes + 1, j + 1
    end = text.find('"' + "#" * hashes, j + 1)
    return len(text) if end < 0 else end + 1 + hashes


def matching_brace(code, open_at):
    depth = 0
    for j in range(open_at, len(code)):
        if code[j] == "{":
            depth += 1
        elif code[j] == "}":
            depth -= 1
            if depth == 0:
                return j
    return len(code) - 1


def is_word_at(code, i, word):
    end = i + len(word)
    return (
        code.startswith(word, i)
        and (i == 0 or not (code[i - 1].isalnum() or code[i - 1] == "_"))
        and (end >= len(code) or not (code[end].isalnum() or code[end] == "_"))
    )


def test_module_spans(code):
    """The character spans of `#[cfg(test)] mod name { ... }` blocks."""
    spans = []
    at = 0
    while True:
        k = code.find("#[cfg(test)]", at)
        if k < 0:
            return spans
        j = k + len("#[cfg(test)]")
        rest = code[j:].lstrip()
        j = len(code) - len(rest)
        if rest.startswith("pub(crate) "):
            rest = rest[len("pub(crate) "):].lstrip()
            j = len(code) - len(rest)
        if is_word_at(code, j, "mod"):
            brace, semi = code.find("{", j), code.find(";", j)
            if brace >= 0 and (semi < 0 or brace < semi):
                spans.append((k, matching_brace(code, brace)))
        at = j


def functions(path):
    """(name, first line, line count) of every function with a body in the file."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    code = blank_code(text)
    skipped = test_module_spans(code)
    found = []
    i = code.find("fn")
    while i >= 0:
        if is_word_at(code, i, "fn") and not any(a <= i <= b for a, b in skipped):
            j = i + 2
            while j < len(code) and code[j].isspace():
                j += 1
            k = j
            while k < len(code) and (code[k].isalnum() or code[k] == "_"):
                k += 1
            name = code[j:k]
            # The body opens at the first `{` outside the signature's brackets, unless a `;`
            # (a declaration without body, in a trait or extern block) comes first.
            depth, m = 0, k
            while m < len(code):
                ch = code[m]
                if ch in "([<":
                    depth += 1
                elif ch in ")]>" and not (ch == ">" and code[m - 1] == "-"):
                    depth = max(depth - 1, 0)
                elif ch == ";" and depth == 0:
                    m = -1
                    break
                elif ch == "{" and depth == 0:
                    break
                m += 1
            if name and 0 <= m < len(code):
                end = matching_brace(code, m)
                first = code.count("\n", 0, i) + 1
                last = code.count("\n", 0, end) + 1
                found.append((name, first, last - first + 1))
        i = code.find("fn", i + 2)
    return found


def crate_files(src):
    for dirpath, dirnames, filenames in os.walk(src):
        dirnames[:] = sorted(d for d in dirnames if d != "tests")
        for name in sorted(filenames):
            if name.endswith(".rs") and name != "tests.rs":
                yield os.path.join(dirpath, name)


def main():
    # Piped into `head`: stop quietly.
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--over", type=int, default=100, help="lines (default 100)")
    parser.add_argument("--check", help="LIB,CLI: the most functions allowed over N lines")
    parser.add_argument("crates", nargs="*", help="crate source folders")
    args = parser.parse_args()
    crates = [(c, c) for c in args.crates] or DEFAULT_CRATES
    counts = []
    for label, src in crates:
        folder = src if os.path.isabs(src) else os.path.join(ROOT, src)
        if not os.path.isdir(folder):
            sys.exit(f"long_functions.py: no folder {folder}")
        long = []
        for path in crate_files(folder):
            for name, line, length in functions(path):
                if length > args.over:
                    long.append((length, os.path.relpath(path, ROOT), line, name))
        long.sort(key=lambda x: (-x[0], x[1], x[2]))
        print(f"{label} ({src}): {len(long)} functions over {args.over} lines")
        for length, path, line, name in long:
            print(f"  {length:4d}  {path}:{line}  {name}")
        counts.append(len(long))
    if args.check:
        limits = [int(x) for x in args.check.split(",")]
        over = [(c, lim) for c, lim in zip(counts, limits) if c > lim]
        if over:
            sys.exit(f"long_functions.py: over the limit: {over} (count, limit)")


if __name__ == "__main__":
    main()
