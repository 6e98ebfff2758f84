#!/usr/bin/env bash
# Rebound's step time on the peer scenes, this checkout against an earlier commit, in one run on one machine.
#
#   scripts/against.sh REV [ROUNDS] [STEPS]      (defaults: 6 rounds, 600 steps)
#
# Builds `compare` (release, single thread) here and at REV (in a temporary worktree with its own target/),
# then runs `compare --engine rebound --scene S` of both builds back to back, scene by scene, swapping which
# goes first every round, because the shared machine's speed drifts for minutes at a time. Prints per scene
# each build's median ms/step over the rounds, their ratio (this checkout over REV) and every round's own
# ratio. rapier is not run: both builds meet the same rapier, so this ratio is how the Rebound/rapier ratios of
# `compare` moved since REV, without rapier's own run-to-run spread. Wall-clock figures: run it on an
# otherwise idle machine. Needs git and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:?usage: scripts/against.sh REV [ROUNDS] [STEPS]}
rounds=${2:-6}
steps=${3:-600}
old=$(mktemp -d)
log=$(mktemp)
trap 'git worktree remove --force "$old" >/dev/null 2>&1 || rm -rf "$old"; rm -f "$log"' EXIT
git worktree add --detach "$old" "$rev" >/dev/null
cargo build --release --bin compare >&2
(cd "$old" && cargo build --release --bin compare >&2)
for round in $(seq 1 "$rounds"); do
    for scene in balls pyramid chain springs bridge; do
        if [ $((round % 2)) -eq 1 ]; then order="old new"; else order="new old"; fi
        for which in $order; do
            if [ "$which" = old ]; then bin="$old/target/release/compare"; else bin=target/release/compare; fi
            ms=$("$bin" --engine rebound --scene "$scene" --rounds 1 --steps "$steps" |
                awk -F'|' -v s="$scene" '$2 ~ "^ " s " $" { gsub(/ /, "", $4); print $4 }')
            echo "$round $scene $which $ms" >>"$log"
        done
    done
done
python3 - "$log" "$rev" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(lambda: collections.defaultdict(list))
for line in open(sys.argv[1]):
    _, scene, which, ms = line.split()
    runs[scene][which].append(float(ms))
print(f"Rebound ms/step, this checkout against {sys.argv[2]} (median over rounds; ratio = this / {sys.argv[2]})\n")
print(f"| scene | {sys.argv[2]} ms | this ms | ratio | ratio per round |")
print("|---|---|---|---|---|")
for scene, r in runs.items():
    old, new = statistics.median(r["old"]), statistics.median(r["new"])
    per = " ".join(f"{n / o:.3f}" for n, o in zip(r["new"], r["old"]))
    print(f"| {scene} | {old:.3f} | {new:.3f} | {new / old:.3f} | {per} |")
PY
