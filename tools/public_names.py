#!/usr/bin/env python3
"""Public names: how wide the library's public API is, measured two ways.

1. The items rustdoc lists for the crate, by kind, read from `target/doc/haphe/all.html`
   (build it first: `cargo doc -p haphe --no-deps`; this script builds nothing). Items
   behind `#[doc(hidden)]` are not listed there.
2. The names re-exported by `pub use` lines of the crate's source (`crates/haphe/src`),
   leaving out the ones marked `#[doc(hidden)]` and test code. A `pub use a::{B, C};`
   counts 2; a glob counts 1.

    python3 tools/public_names.py [--doc DIR] [--src DIR] [--names] [--max N]

`--names` lists the names as well. It exits 1 when rustdoc lists more than `--max` items
(default 135, the bound ARCHITECTURE.md states), or when a documented page links to an
item rustdoc does not list (a `#[doc(hidden)]` one: the link would lead nowhere); CI runs
it after building the docs.
"""

import argparse
import html
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from import_cycles import expand_use  # noqa: E402
from long_functions import blank_code, test_module_spans  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The most items rustdoc may list for the crate (ARCHITECTURE.md, "A public name").
MAX_ITEMS = 135


def rustdoc_items(all_html):
    """{kind heading: [item path, ...]} from rustdoc's all.html."""
    with open(all_html, encoding="utf-8") as f:
        text = f.read()
    kinds = {}
    # Each kind: <h3 id="structs">Structs</h3><ul class="all-items"><li><a ...>path</a></li>...
    for m in re.finditer(r'<h3 id="([^"]+)">(.*?)</h3>\s*<ul class="all-items">(.*?)</ul>', text, re.S):
        heading = html.unescape(re.sub(r"<[^>]+>", "", m.group(2))).strip()
        names = [html.unescape(re.sub(r"<[^>]+>", "", a)).strip() for a in re.findall(r"<a [^>]*>(.*?)</a>", m.group(3), re.S)]
        kinds[heading] = names
    return kinds


def links_to_hidden(doc):
    """[(page, target)] of the links in the crate's pages that rustdoc left as a Rust path
    (`super::X`, `crate::m::X`): it does so for an intra-doc link to an item it does not
    list (one under `#[doc(hidden)]`), which then leads nowhere."""
    found = []
    for dirpath, dirnames, filenames in os.walk(doc):
        dirnames.sort()
        for name in sorted(filenames):
            if not name.endswith(".html"):
                continue
            path = os.path.join(dirpath, name)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for target in re.findall(r'href="((?:crate|super|self)::[^"]*)"', text):
                found.append((os.path.relpath(path, doc), html.unescape(target)))
    return found


def reexports(src):
    """[(file, line, name)] of the names in `pub use` lines not marked `#[doc(hidden)]`."""
    found = []
    for dirpath, dirnames, filenames in os.walk(src):
        dirnames.sort()
        for name in sorted(filenames):
            if not name.endswith(".rs") or name == "tests.rs":
                continue
            path = os.path.join(dirpath, name)
            with open(path, encoding="utf-8") as f:
                code = blank_code(f.read())
            for a, b in test_module_spans(code):
                code = code[:a] + "".join("\n" if c == "\n" else " " for c in code[a : b + 1]) + code[b + 1 :]
            for m in re.finditer(r"((?:#\[[^\]]*\]\s*)*)\bpub\s+use\s+([^;]*);", code):
                attributes = m.group(1)
                if re.search(r"#\[\s*doc\s*\(\s*hidden\s*\)\s*\]", attributes):
                    continue
                # An attribute line right above (outside the match) counts too.
                before = code[: m.start()].rstrip()
                if before.endswith("]") and re.search(r"#\[\s*doc\s*\(\s*hidden\s*\)\s*\]\s*$", before):
                    continue
                line = code.count("\n", 0, m.start(2)) + 1
                for segments, bound in expand_use(m.group(2).replace("\n", " ")):
                    found.append((os.path.relpath(path, ROOT), line, bound or "::".join(segments) + "::*"))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--doc", default=os.path.join(ROOT, "target", "doc", "haphe"), help="rustdoc output folder of the crate")
    parser.add_argument("--src", default=os.path.join(ROOT, "crates", "haphe", "src"), help="the crate's source folder")
    parser.add_argument("--names", action="store_true", help="list the names too")
    parser.add_argument("--max", type=int, default=MAX_ITEMS, help=f"exit 1 when rustdoc lists more items than this (default {MAX_ITEMS})")
    args = parser.parse_args()

    all_html = os.path.join(args.doc, "all.html")
    if not os.path.isfile(all_html):
        sys.exit(f"public_names.py: no {all_html}; run `cargo doc -p haphe --no-deps` first")
    kinds = rustdoc_items(all_html)
    total = sum(len(v) for v in kinds.values())
    print(f"rustdoc items listed in {os.path.relpath(all_html, ROOT)}: {total}")
    for kind, names in kinds.items():
        print(f"  {len(names):4}  {kind}")
        if args.names:
            for n in names:
                print(f"          {n}")

    names = reexports(args.src)
    print(f"names in `pub use` lines without #[doc(hidden)] in {os.path.relpath(args.src, ROOT)}: {len(names)}")
    by_module = {}
    for file, _, _ in names:
        rel = os.path.relpath(os.path.join(ROOT, file), args.src).split(os.sep)
        top = rel[0] if len(rel) > 1 else rel[0][:-3]
        by_module[top] = by_module.get(top, 0) + 1
    for top, n in sorted(by_module.items()):
        print(f"  {n:4}  {top}")
    if args.names:
        for file, line, name in names:
            print(f"  {file}:{line}  {name}")
    broken = links_to_hidden(args.doc)
    for page, target in broken:
        print(f"public_names.py: {page} links to {target}, which rustdoc does not list (hidden): name it in code quotes instead", file=sys.stderr)
    if broken:
        return 1
    if total > args.max:
        print(
            f"public_names.py: rustdoc lists {total} items, more than {args.max}: a name a "
            "newcomer needs is documented; an internal is pub(crate), or #[doc(hidden)] / "
            "feature `testing` when another crate needs it (ARCHITECTURE.md)",
            file=sys.stderr,
        )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
