#!/usr/bin/env python3
"""Shallow contact unchanged: the proxy's path now against its path at an earlier commit.

Builds `crates/haphe/examples/09_proxy_paths.rs` in this checkout and in a worktree of BASE
(default 07cd5f6, the commit before the proxy first held beyond the saturation depth),
writes the proxy suites' device paths once, runs both proxies along them and compares
every tick before the first on which either proxy's penetration passes the saturation
depth (F_max / k, 3.3 N over the material's stiffness); on a path that never gets that
deep, every tick. Prints one line per path and a summary; exit 1 when a compared tick
differs by 1e-9 m or more.

    python3 tools/shallow_contact.py [BASE]
"""

import glob
import os
import shutil
import struct
import subprocess
import sys
import tempfile

EXAMPLE = "crates/haphe/examples/09_proxy_paths.rs"
TOLERANCE_M = 1e-9


def build(checkout, target):
    env = dict(os.environ, CARGO_TARGET_DIR=target, CARGO_INCREMENTAL="0")
    subprocess.run(
        ["cargo", "build", "-q", "-p", "haphe", "--example", "09_proxy_paths"],
        cwd=checkout, env=env, check=True)
    return os.path.join(target, "debug", "examples", "09_proxy_paths")


def ticks(path):
    data = open(path, "rb").read()
    return [struct.unpack_from("<7d", data, 56 * i) for i in range(len(data) // 56)]


def main():
    base = sys.argv[1] if len(sys.argv) > 1 else "07cd5f6"
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    scratch = tempfile.mkdtemp(prefix="haphe-shallow-")
    worktree = os.path.join(scratch, "base")
    try:
        subprocess.run(["git", "worktree", "add", "-q", "--detach", worktree, base],
                       cwd=root, check=True)
        source = open(os.path.join(root, EXAMPLE)).read()
        shapes = open(os.path.join(worktree, "crates/haphe/src/mesh/shapes/mod.rs")).read()
        if "Catalog" not in shapes:  # before the shape catalogue was renamed
            source = source.replace("shapes::Catalog;", "shapes::Shape as Catalog;")
        open(os.path.join(worktree, EXAMPLE), "w").write(source)
        new = build(root, os.path.join(root, "target"))
        old = build(worktree, os.path.join(scratch, "target"))
        paths = os.path.join(scratch, "paths")
        os.makedirs(paths)
        subprocess.run([new, "paths", paths], check=True)
        subprocess.run([new, "run", paths, os.path.join(scratch, "new")], check=True)
        subprocess.run([old, "run", paths, os.path.join(scratch, "old")], check=True)
        compared = total = whole = 0
        worst = 0.0
        for out in sorted(glob.glob(os.path.join(scratch, "new", "*.out"))):
            name = os.path.basename(out)
            a, b = ticks(os.path.join(scratch, "old", name)), ticks(out)
            saturation = 3.3 / (2000.0 if "-m2." in name else 500.0)
            n = len(b)
            first = next((i for i in range(n) if a[i][3] > saturation or b[i][3] > saturation), n)
            gap = max((sum((a[i][j] - b[i][j]) ** 2 for j in range(3)) ** 0.5
                       for i in range(first)), default=0.0)
            touching = sum(1 for i in range(first) if b[i][3] >= 0.0)
            print(f"{name:28s} {n:5d} ticks, {first:5d} compared ({touching:5d} in contact), "
                  f"largest gap {gap:.3e} m")
            total += n
            compared += first
            whole += first == n
            worst = max(worst, gap)
        print(f"{total} ticks; {compared} before the first beyond the saturation depth "
              f"compared; {whole} paths never went beyond; largest gap {worst:.3e} m")
        return 0 if worst < TOLERANCE_M else 1
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", worktree], cwd=root)
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
