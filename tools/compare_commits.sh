#!/usr/bin/env bash
# Compares `haphe bench` between two commits, interleaved and pinned.
#
#   tools/compare_commits.sh [options] A B [-- BENCH_ARGS...]
#
# Builds commits A and B (anything `git rev-parse` takes: hashes, branches, tags), each in a
# detached git worktree of its own with the fully optimised profile (`--profile optimized`,
# fat LTO, feature `bench` of haphe-cli), then runs `haphe bench --quick --json ...` for
# both, pinned to one core with taskset, over several rounds, the order alternating from
# round to round (A B, B A, A B, ...), so that a slow spell of a shared machine falls on
# both alike. It prints, for each (mesh, query, method) that both runs measured, the median
# over the rounds of each commit's p50, p99 and trimmed mean (ns), and B ÷ A; for the
# contact rows also parry ÷ haphe per commit. Every round's figures stay in the work
# folder (one JSON file per round and commit, with the bench's own report beside it).
#
# Options:
#   -n N            rounds (default 3)
#   -c CPU          core to pin to (default 1)
#   -q Q1,Q2,...    queries to print (default: every timed query; e.g. -q contact)
#   -d DIR          work folder (default ${TMPDIR:-/tmp}/haphe-compare): worktrees
#                   wt-<hash>, target folders target-<hash>, binaries bin/haphe-<hash>,
#                   results run-<time>/
#   --shared-target one target folder for every commit (dependencies built once; each
#                   binary is copied out as soon as it is built)
#   --rebuild       build again even when the binary of a commit is already there
#   --build-only    build the two binaries, run nothing
#   -h, --help      this text
#
# After `--`, arguments for `haphe bench` replacing the default `--quick` (e.g.
# `-- --quick --objects 1` to keep the object-count series short, or `-- --sizes 1000`).
# `--json` is always added.
#
# A commit is built once: its binary is kept in DIR/bin, and a re-run with the same
# commits only runs the benches. Commits from before the `optimized` profile existed are
# built with the release profile given the same settings (fat LTO, one codegen unit) through
# CARGO_PROFILE_RELEASE_* variables, and without `--features bench` when haphe-cli has no
# such feature. Needs git, cargo, taskset and python3. The load average is printed before
# and after the rounds: say how loaded the machine was when you quote the figures.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; }

rounds=3
cpu=1
queries=""
dir="${TMPDIR:-/tmp}/haphe-compare"
shared=0
rebuild=0
build_only=0
commits=()
bench_args=()
while (($#)); do
    case "$1" in
    -n) rounds="${2:?-n needs a number}"; shift 2 ;;
    -c) cpu="${2:?-c needs a core}"; shift 2 ;;
    -q) queries="${2:?-q needs query names}"; shift 2 ;;
    -d) dir="${2:?-d needs a folder}"; shift 2 ;;
    --shared-target) shared=1; shift ;;
    --rebuild) rebuild=1; shift ;;
    --build-only) build_only=1; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; bench_args=("$@"); break ;;
    -*) echo "compare_commits.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) commits+=("$1"); shift ;;
    esac
done
if ((${#commits[@]} != 2)); then
    echo "compare_commits.sh: give two commits, A and B (see --help)" >&2
    exit 2
fi
if ! [[ "$rounds" =~ ^[1-9][0-9]*$ ]]; then
    echo "compare_commits.sh: -n: a number of rounds from 1 up, not '$rounds'" >&2
    exit 2
fi
((${#bench_args[@]})) || bench_args=(--quick)
for tool in git cargo taskset python3; do
    command -v "$tool" >/dev/null || { echo "compare_commits.sh: $tool is missing" >&2; exit 2; }
done
taskset -c "$cpu" true 2>/dev/null || {
    echo "compare_commits.sh: -c: cannot pin to core '$cpu'" >&2
    exit 2
}

repo="$(git rev-parse --show-toplevel)"
here="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$dir/bin"
dir="$(cd "$dir" && pwd)"

resolve() {
    git -C "$repo" rev-parse --verify --quiet "$1^{commit}" || {
        echo "compare_commits.sh: '$1' is not a commit of $repo" >&2
        exit 2
    }
}
a="$(resolve "${commits[0]}")"
b="$(resolve "${commits[1]}")"
short() { git -C "$repo" rev-parse --short "$1"; }

# Builds commit $1 unless its binary is there; prints nothing on stdout.
build() {
    local sha="$1" wt="$dir/wt-$1" bin="$dir/bin/haphe-$1" target
    if [[ -x "$bin" && $rebuild == 0 ]]; then
        echo "compare_commits.sh: $(short "$sha"): built already ($bin)" >&2
        return
    fi
    if [[ ! -e "$wt/.git" ]]; then
        git -C "$repo" worktree prune
        git -C "$repo" worktree add --detach --force "$wt" "$sha" >&2
    fi
    git -C "$wt" checkout --quiet --detach "$sha"
    if ((shared)); then target="$dir/target"; else target="$dir/target-$sha"; fi
    local features=() profile=(--profile optimized) out=optimized envs=()
    if grep -q '^bench *=' "$wt/crates/haphe-cli/Cargo.toml"; then
        features=(--features bench)
    fi
    if ! grep -q '^\[profile\.optimized\]' "$wt/Cargo.toml"; then
        profile=(--release)
        out=release
        envs=(CARGO_PROFILE_RELEASE_LTO=fat CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1)
    fi
    echo "compare_commits.sh: $(short "$sha"): building (cargo build ${profile[*]}" \
        "-p haphe-cli ${features[*]}, target $target) ..." >&2
    (cd "$wt" && env CARGO_INCREMENTAL=0 CARGO_TARGET_DIR="$target" "${envs[@]}" \
        cargo build --locked "${profile[@]}" -p haphe-cli "${features[@]}" >&2)
    cp "$target/$out/haphe" "$bin.tmp"
    mv "$bin.tmp" "$bin"
}

build "$a"
build "$b"
((build_only)) && exit 0

run="$dir/run-$(date -u +%Y%m%dT%H%M%S)"
mkdir -p "$run"
load() { cut -d' ' -f1-3 /proc/loadavg; }
echo "compare_commits.sh: A = $(short "$a"), B = $(short "$b"); $rounds round(s) of" \
    "'haphe bench ${bench_args[*]}' pinned to core $cpu; results in $run" >&2
echo "compare_commits.sh: load average before: $(load) ($(nproc) cores)" >&2
load_before="$(load)"
for ((r = 1; r <= rounds; r++)); do
    if ((r % 2)); then order=("$a" "$b"); else order=("$b" "$a"); fi
    for sha in "${order[@]}"; do
        echo "compare_commits.sh: round $r/$rounds: $(short "$sha") ..." >&2
        (cd "$run" && taskset -c "$cpu" "$dir/bin/haphe-$sha" bench "${bench_args[@]}" \
            --json "$run/r$r-$sha.json" >"$run/r$r-$sha.md" 2>"$run/r$r-$sha.log") || {
            echo "compare_commits.sh: the bench of $(short "$sha") failed; see" \
                "$run/r$r-$sha.log" >&2
            exit 1
        }
    done
done
load_after="$(load)"

python3 "$here/compare_commits.py" "$run" "$a" "$b" "$(short "$a")" "$(short "$b")" \
    "$rounds" "$queries" "$load_before" "$load_after" "$(nproc)" "${bench_args[*]}" "$cpu" |
    tee "$run/summary.md"
