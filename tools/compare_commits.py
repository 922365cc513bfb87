#!/usr/bin/env python3
"""The summary of tools/compare_commits.sh: the rounds' `haphe bench --json` records of two
commits, as one markdown table (medians over the rounds, and B ÷ A).

    compare_commits.py RUN_DIR A B A_NAME B_NAME ROUNDS QUERIES LOAD_BEFORE LOAD_AFTER
                       CORES BENCH_ARGS CPU

Reads RUN_DIR/r<round>-<commit>.json. QUERIES is a comma-separated list of query names to
print, or empty for every timed query.
"""

import json
import statistics
import sys
from pathlib import Path

# The timed queries, in the order of the bench's report (build, decode and zones are whole
# operations, not ticks; they are left out).
TIMED = ["free_space", "segment", "segment_random", "inside", "inside_random", "walk",
         "floor", "contact"]


def load(run: Path, sha: str, rounds: int) -> list[dict]:
    """One dict per round: (mesh, query, method) -> record."""
    out = []
    for r in range(1, rounds + 1):
        path = run / f"r{r}-{sha}.json"
        records = json.loads(path.read_text())
        out.append({(x["mesh"], x["query"], x["method"]): x for x in records})
    return out


def median(rounds: list[dict], key, field: str):
    values = [r[key][field] for r in rounds if key in r and r[key][field] is not None]
    return statistics.median(values) if values else None


def fmt(x, digits=0):
    return "–" if x is None else f"{x:,.{digits}f}".replace(",", " ")


def ratio(b, a):
    return None if a is None or b is None or a <= 0 else b / a


def main() -> int:
    (run, a, b, a_name, b_name, rounds, queries, load_before, load_after, cores, bench_args,
     cpu) = sys.argv[1:13]
    run, rounds = Path(run), int(rounds)
    wanted = [q for q in queries.split(",") if q] or TIMED
    unknown = [q for q in wanted if q not in TIMED]
    if unknown:
        print(f"compare_commits: unknown query {', '.join(unknown)} (one of "
              f"{', '.join(TIMED)})", file=sys.stderr)
        return 2
    ra, rb = load(run, a, rounds), load(run, b, rounds)
    keys = [k for k in ra[0] if k in rb[0] and k[1] in wanted]
    keys.sort(key=lambda k: (TIMED.index(k[1]), k[2] != "haphe", k[2],
                             ra[0][k]["family"], ra[0][k]["triangles"]))
    print(f"# haphe bench: {a_name} (A) against {b_name} (B)\n")
    print(f"`haphe bench {bench_args}`, pinned to core {cpu}, {rounds} round(s), order "
          f"alternating (A B, B A, ...). Medians over the rounds, ns. Load average "
          f"(1, 5, 15 min) before {load_before}, after {load_after}, on {cores} core(s).\n")
    print(f"| mesh | query | method | A p50 | B p50 | B÷A p50 | A p99 | B p99 | B÷A p99 "
          f"| A mean | B mean | B÷A mean |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for key in keys:
        mesh, query, method = key
        cells = []
        for field in ["p50_ns", "p99_ns", "trimmed_mean_ns"]:
            x, y = median(ra, key, field), median(rb, key, field)
            cells += [fmt(x), fmt(y), fmt(ratio(y, x), 2)]
        print(f"| {mesh} | {query} | {method} | " + " | ".join(cells) + " |")

    contact = [k for k in keys if k[1] == "contact" and k[2] == "haphe"]
    if contact:
        print("\nContact p50, each round (A / B, ns), and parry ÷ haphe (medians over the "
              "rounds; at least 1.3 means haphe is 1.3x ahead):\n")
        print("| mesh | " + " | ".join(f"round {r}" for r in range(1, rounds + 1))
              + " | parry÷A | parry÷B |")
        print("|---|" + "---:|" * (rounds + 2))
        for key in contact:
            each = [f"{fmt(x[key]['p50_ns'])} / {fmt(y[key]['p50_ns'])}"
                    for x, y in zip(ra, rb)]
            parry = (key[0], "contact", "parry")
            vs = []
            for rr in (ra, rb):
                vs.append(fmt(ratio(median(rr, parry, "p50_ns"), median(rr, key, "p50_ns")),
                              2))
            print(f"| {key[0]} | " + " | ".join(each) + f" | {vs[0]} | {vs[1]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
