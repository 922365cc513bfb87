#!/usr/bin/env python3
"""Import cycles: files of a crate that import each other, directly or through others.

Every path of a file's code that names another part of the crate is an import: `use` trees
and paths in expressions or types starting with `crate::`, `super::`, `self::` or the name
of a child module (`use summary::Summary` in the module that declares `mod summary`). A
path is resolved to a file by descending the crate's modules (`a.rs` or `a/mod.rs`, inline
`mod a { ... }` blocks belong to their file) and then following the names the last module
imports (a `use`, public or not, is seen by its children), so `crate::Surface` re-exported
by `lib.rs` leads to the file that defines `Surface`. Test code (`#[cfg(test)]` modules and
files named `tests.rs`) is left out unless `--with-tests`.

    python3 tools/import_cycles.py [--exclude FOLDER ...] [--with-tests] [--edges] [CRATE_SRC ...]

Without CRATE_SRC it checks the library (crates/haphe/src) and the command
(crates/haphe-cli/src). `--exclude map` leaves out the files under `map/` of each crate
(imports to and from them are dropped). Prints each cycle (a strongly connected group of
files) with the imports that close it, and exits 1 when there is one.
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from long_functions import blank_code, matching_brace, test_module_spans  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_CRATES = ["crates/haphe/src", "crates/haphe-cli/src"]
KEYWORDS = {"crate", "super", "self"}
IDENT = r"[A-Za-z_][A-Za-z0-9_]*"


def module_files(src, with_tests):
    """{module path (tuple): file} for the crate whose root is lib.rs or main.rs in src."""
    modules = {}
    for dirpath, dirnames, filenames in os.walk(src):
        dirnames.sort()
        rel = os.path.relpath(dirpath, src)
        parts = () if rel == "." else tuple(rel.split(os.sep))
        for name in sorted(filenames):
            if not name.endswith(".rs"):
                continue
            if name == "tests.rs" and not with_tests:
                continue
            stem = name[:-3]
            if not parts and stem in ("lib", "main"):
                path = ()
            elif stem == "mod":
                path = parts
            else:
                path = parts + (stem,)
            modules.setdefault(path, os.path.join(dirpath, name))
    return modules


def split_top(text, sep=","):
    """`text` split at `sep` outside braces."""
    out, depth, start = [], 0, 0
    for i, c in enumerate(text):
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
        elif c == sep and depth == 0:
            out.append(text[start:i])
            start = i + 1
    out.append(text[start:])
    return [p.strip() for p in out if p.strip()]


def expand_use(tree, prefix=()):
    """(segments, name bound or None for a glob) of each leaf of a use tree."""
    tree = tree.strip()
    if tree.startswith("::"):
        tree = tree[2:]
    if "{" in tree and tree.endswith("}"):
        head, body = tree[: tree.index("{")], tree[tree.index("{") + 1 : -1]
        head_parts = tuple(s for s in head.split("::") if s)
        for part in split_top(body):
            yield from expand_use(part, prefix + head_parts)
        return
    alias = None
    m = re.match(r"(.*?)\s+as\s+(" + IDENT + r")$", tree)
    if m:
        tree, alias = m.group(1), m.group(2)
    segments = prefix + tuple(s.strip() for s in tree.split("::") if s.strip())
    if not segments:
        return
    if segments[-1] == "*":
        yield segments[:-1], None
    elif segments[-1] == "self":
        yield segments[:-1], alias or segments[-2]
    else:
        yield segments, alias or segments[-1]


class Crate:
    def __init__(self, src, with_tests, exclude):
        self.src = src
        self.modules = module_files(src, with_tests)
        self.file_module = {f: p for p, f in self.modules.items()}
        self.with_tests = with_tests
        self.exclude = [os.path.join(src, e.strip("/")) + os.sep for e in exclude]
        # Per file: its code (comments and strings blanked, test code blanked unless kept),
        # its use statements as (line, segments, bound name) and the names it imports.
        self.code = {}
        self.uses = {}
        self.imported = {}
        self.globs = {}
        for path, file in self.modules.items():
            with open(file, encoding="utf-8") as f:
                code = blank_code(f.read())
            if not with_tests:
                for a, b in test_module_spans(code):
                    code = code[:a] + "".join("\n" if c == "\n" else " " for c in code[a : b + 1]) + code[b + 1 :]
            self.code[file] = code
            uses = []
            for m in re.finditer(r"\buse\s+([^;]*);", code):
                line = code.count("\n", 0, m.start()) + 1
                for segments, name in expand_use(m.group(1).replace("\n", " ")):
                    uses.append((line, m.start(), segments, name))
            self.uses[file] = uses
            self.imported[file] = {n: s for _, _, s, n in uses if n}
            self.globs[file] = [s for _, _, s, n in uses if n is None]

    def excluded(self, file):
        return any(file.startswith(e) for e in self.exclude)

    def inline_module_spans(self, code):
        spans = []
        for m in re.finditer(r"\bmod\s+" + IDENT + r"\s*\{", code):
            brace = m.end() - 1
            spans.append((brace, matching_brace(code, brace)))
        return spans

    def resolve(self, module, segments, depth=0):
        """The file that defines what `segments` names, seen from `module`; None outside
        the crate."""
        if depth > 8 or not segments:
            return self.modules.get(module)
        first, rest = segments[0], list(segments[1:])
        if first == "crate":
            current = ()
        elif first in ("super", "self"):
            current = module
            while first in ("super", "self"):
                if first == "super":
                    current = current[:-1]
                if not rest:
                    return self.modules.get(current)
                first, rest = rest[0], rest[1:]
            rest = [first] + list(rest)
        elif module + (first,) in self.modules:
            current, rest = module, [first] + list(rest)
        else:
            # A name the module imports (`use crate::x::y;` then `y::f`).
            file = self.modules.get(module)
            target = self.imported.get(file, {}).get(first)
            if target is None or target[0] not in KEYWORDS and module + (target[0],) not in self.modules:
                return None
            return self.resolve(module, tuple(target) + tuple(rest), depth + 1)
        while rest and current + (rest[0],) in self.modules:
            current, rest = current + (rest[0],), rest[1:]
        file = self.modules.get(current)
        if rest and file is not None:
            name = rest[0]
            target = self.imported[file].get(name)
            if target is not None and tuple(target) != tuple(segments):
                found = self.resolve(current, tuple(target) + tuple(rest[1:]), depth + 1)
                if found is not None:
                    return found
            if not re.search(r"\b(fn|struct|enum|trait|type|const|static|union|macro_rules!)\s+" + name + r"\b", self.code[file]):
                for glob in self.globs[file]:
                    found = self.resolve(current, tuple(glob) + (name,), depth + 1)
                    if found is not None and found != file:
                        return found
        return file

    def edges(self):
        """{(from file, to file): [line, ...]}."""
        found = {}
        for file, code in self.code.items():
            if self.excluded(file):
                continue
            module = self.file_module[file]
            spans = self.inline_module_spans(code)

            def scope_at(pos):
                # `super::` inside an inline module means the file's own module.
                inner = sum(1 for a, b in spans if a < pos < b)
                return module + ("<inline>",) * inner

            def add(pos, segments):
                scope = scope_at(pos)
                seg = list(segments)
                while scope and scope[-1] == "<inline>" and seg and seg[0] == "super":
                    scope, seg = scope[:-1], seg[1:]
                    seg = ["self"] + seg
                scope = tuple(s for s in scope if s != "<inline>")
                target = self.resolve(scope, tuple(seg))
                if target and target != file and not self.excluded(target):
                    line = code.count("\n", 0, pos) + 1
                    found.setdefault((file, target), []).append(line)

            use_spans = []
            for line, pos, segments, _ in self.uses[file]:
                add(pos, segments)
            for m in re.finditer(r"\buse\s+[^;]*;", code):
                use_spans.append((m.start(), m.end()))
            for m in re.finditer(r"(?<![\w$:])((?:" + IDENT + r")(?:::" + IDENT + r")+)", code):
                if any(a <= m.start() < b for a, b in use_spans):
                    continue
                segments = m.group(1).split("::")
                first = segments[0]
                if first in KEYWORDS or module + (first,) in self.modules or first in self.imported[file]:
                    if first not in KEYWORDS and first in self.imported[file]:
                        target = self.imported[file][first]
                        if not target or (target[0] not in KEYWORDS and module + (target[0],) not in self.modules):
                            continue
                    add(m.start(), segments)
        return found


def cycles(nodes, edges):
    """Strongly connected groups of more than one file (Tarjan)."""
    graph = {n: sorted({b for (a, b) in edges if a == n}) for n in nodes}
    index, low, stack, on, groups = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, []):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    sys.setrecursionlimit(10000)
    for n in sorted(nodes):
        if n not in index:
            visit(n)
    return groups


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exclude", action="append", default=[], help="a folder of each crate's src to leave out (e.g. map)")
    parser.add_argument("--with-tests", action="store_true", help="count test code's imports too")
    parser.add_argument("--edges", action="store_true", help="print every import between files")
    parser.add_argument("crates", nargs="*", help="crate source folders")
    args = parser.parse_args()
    total = 0
    for src in args.crates or DEFAULT_CRATES:
        folder = src if os.path.isabs(src) else os.path.join(ROOT, src)
        if not os.path.isdir(folder):
            sys.exit(f"import_cycles.py: no folder {folder}")
        crate = Crate(folder, args.with_tests, args.exclude)
        edges = crate.edges()
        rel = lambda f: os.path.relpath(f, ROOT)  # noqa: E731
        nodes = [f for f in crate.code if not crate.excluded(f)]
        groups = cycles(nodes, edges)
        total += len(groups)
        excluded = f" (leaving out {', '.join(args.exclude)})" if args.exclude else ""
        print(f"{os.path.relpath(folder, ROOT)}: {len(nodes)} files, {len(edges)} imports between files, {len(groups)} cycles{excluded}")
        if args.edges:
            for (a, b), lines in sorted(edges.items()):
                print(f"  {rel(a)} -> {rel(b)} (line {', '.join(map(str, lines[:5]))})")
        for group in groups:
            print("  cycle: " + " <-> ".join(rel(f) for f in group))
            members = set(group)
            for (a, b), lines in sorted(edges.items()):
                if a in members and b in members:
                    print(f"    {rel(a)}:{lines[0]} imports {rel(b)}")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
