#!/usr/bin/env python3
"""Regenerate (or check) the command outputs shown in README.md and the docs (FILES).

A block of example output is a ```text fence right after a line `<!-- output -->`
(`<!-- output slow -->` for one that takes long). In it, lines starting with `$ ` are
commands; the lines after each, up to the next command, are what it printed. This script
runs the commands of every block, in order, with bash, in a scratch directory holding links
to the repository's `meshes/` and `scenes/` (blocks of one file share it, so a file that
one block writes is there for the next), with `haphe` on the PATH meaning the binary given
by --bin, and writes what they print back into the block. `cargo run --release -p
haphe-cli -- ARGS` in a command runs `haphe ARGS` the same way. Only standard output is
kept (progress bars go to standard error), then `exit code: N` when it is not 0.

A fenced block right after a line `<!-- file NAME -->` (a program shown in the docs, such
as a Python peer) is written to NAME in the scratch directory before the commands that
follow it run, so an output block can run the program exactly as the docs show it.
`python3` in the commands is the interpreter given by --python (default: this one), which
must import the `haphe` package for the docs that use it (CI passes its virtual
environment's).

    python3 tools/guide.py --bin target/release/haphe          # rewrite the outputs
    python3 tools/guide.py --bin target/debug/haphe --check    # CI: do they still hold?

--check compares without rewriting and fails, with a diff, when an output changed; times (a
number with its unit: ns, µs, ms, s), rates of ticks per second, "Nx the asked rate" and the
"seconds" of JSON reports are masked first, since they differ from run to run and between debug and release builds.
--fast skips the blocks marked slow.
"""

import argparse
import difflib
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FILES = ["README.md", "docs/guide.md", "docs/devices.md", "docs/python.md"]
CARGO_RUN = "cargo run --release -p haphe-cli -- "
MARKER = re.compile(r"^<!-- output( slow)? -->$")
FILE_MARKER = re.compile(r"^<!-- file (\S+) -->$")
MASKS = [
    (re.compile(r"\d[\d.]*(e-?\d+)? ?(ns|µs|us|ms|s)\b"), "#time"),
    (re.compile(r"\d[\d.]* ticks/s"), "# ticks/s"),
    (re.compile(r"\d[\d.]*x the asked rate"), "#x the asked rate"),
    (re.compile(r'"seconds":[\d.e-]+'), '"seconds":#'),
]


def mask(text):
    for pattern, repl in MASKS:
        text = pattern.sub(repl, text)
    return text


def run(command, scratch, env):
    """What `command` prints on standard output, and its exit code when not 0."""
    shown = command
    if command.startswith(CARGO_RUN):
        command = "haphe " + command[len(CARGO_RUN):]
        env = dict(env, CARGO_PKG_NAME="haphe-cli")  # as `cargo run` would tell it
    done = subprocess.run(
        ["bash", "-c", command], cwd=scratch, env=env, stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL, text=True, timeout=1800,
    )
    out = done.stdout.rstrip("\n")
    lines = [f"$ {shown}"] + (out.split("\n") if out else [])
    if done.returncode != 0:
        lines += ["", f"exit code: {done.returncode}"]
    return lines


def regenerate(path, scratch, env, fast):
    """The file's text with every block's outputs regenerated (slow ones kept when fast)."""
    lines = path.read_text().split("\n")
    out, i = [], 0
    while i < len(lines):
        line = lines[i]
        out.append(line)
        i += 1
        named = FILE_MARKER.match(line)
        if named:
            if i >= len(lines) or not lines[i].startswith("```"):
                sys.exit(f"{path}:{i}: a file marker must be followed by a fenced block")
            end = lines.index("```", i + 1)
            (Path(scratch) / named.group(1)).write_text("\n".join(lines[i + 1:end]) + "\n")
            continue
        m = MARKER.match(line)
        if not m:
            continue
        if i >= len(lines) or lines[i] != "```text":
            sys.exit(f"{path}:{i}: an output marker must be followed by a ```text fence")
        end = lines.index("```", i + 1)
        block = lines[i + 1:end]
        commands = [l[2:] for l in block if l.startswith("$ ")]
        if not commands:
            sys.exit(f"{path}:{i + 1}: an output block without a `$ ` command")
        out.append("```text")
        if m.group(1) and fast:
            out += block
        else:
            print(f"{path.name}:{i + 1}: {' ; '.join(commands)}", file=sys.stderr)
            for command in commands:
                out += run(command, scratch, env)
        out.append("```")
        i = end + 1
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bin", default="target/release/haphe", help="the haphe binary")
    parser.add_argument("--check", action="store_true", help="compare, do not rewrite")
    parser.add_argument("--fast", action="store_true", help="skip blocks marked slow")
    parser.add_argument("--python", default=sys.executable,
                        help="the interpreter `python3` means in the commands")
    args = parser.parse_args()
    binary = (ROOT / args.bin).resolve() if not Path(args.bin).is_absolute() else Path(args.bin)
    if not binary.is_file():
        sys.exit(f"{binary}: no such binary (build it first)")
    failed = False
    for name in FILES:
        path = ROOT / name
        with tempfile.TemporaryDirectory(prefix="haphe-guide-") as scratch:
            bindir = Path(scratch) / ".bin"
            bindir.mkdir()
            (bindir / "haphe").symlink_to(binary)
            # A script, not a link: a virtual environment is found from the path it runs as.
            shim = bindir / "python3"
            shim.write_text(f'#!/bin/sh\nexec "{Path(args.python).absolute()}" "$@"\n')
            shim.chmod(0o755)
            for linked in ["meshes", "scenes"]:
                (Path(scratch) / linked).symlink_to(ROOT / linked)
            env = {k: v for k, v in os.environ.items() if not k.startswith("CARGO")}
            env["PATH"] = f"{bindir}:{env.get('PATH', '')}"
            old = path.read_text()
            new = regenerate(path, scratch, env, args.fast)
        if args.check:
            if mask(old) != mask(new):
                failed = True
                diff = difflib.unified_diff(
                    mask(old).split("\n"), mask(new).split("\n"),
                    f"{name} (as written)", f"{name} (as the commands print now)", lineterm="",
                )
                print("\n".join(diff))
        elif new != old:
            path.write_text(new)
            print(f"{name}: rewritten", file=sys.stderr)
    if failed:
        sys.exit("outputs changed: run `python3 tools/guide.py` (see CONTRIBUTING.md)")


if __name__ == "__main__":
    main()
