#!/usr/bin/env bash
# Speed-up of the step on 2 threads over 1, Rebound and rapier side by side, on the peer scenes.
#
#   scripts/thread_speedup.sh [ROUNDS] [STEPS]      (defaults: 3 rounds, 600 steps)
#
# Runs `compare --threads 1` and `compare --threads 2` (both engines' parallel builds: Rebound with
# `--features parallel`, rapier from benches/peers with its `parallel` feature), then prints per scene each
# engine's ms/step on 1 and 2 threads, its speed-up (1-thread ms over 2-thread ms) and Rebound/rapier on
# 2 threads. Wall-clock figures: run it on an otherwise idle machine. Needs python3 for the table.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-3}
steps=${2:-600}
one=$(mktemp)
two=$(mktemp)
trap 'rm -f "$one" "$two"' EXIT
cargo build --release --features parallel --bin compare >&2
for threads in 1 2; do
    out=$one
    [ "$threads" = 2 ] && out=$two
    target/release/compare --threads "$threads" --rounds "$rounds" --steps "$steps" --json >"$out"
done
python3 - "$one" "$two" <<'PY'
import json, sys
def load(path):
    return {r["scene"]: r for r in map(json.loads, open(path)) if "scene" in r}
one, two = load(sys.argv[1]), load(sys.argv[2])
print("| scene | Rebound 1 thread ms | Rebound 2 threads ms | Rebound speed-up | rapier 1 thread ms | rapier 2 threads ms | rapier speed-up | Rebound/rapier, 2 threads |")
print("|---|---|---|---|---|---|---|---|")
for scene, a in one.items():
    b = two[scene]
    r1, r2 = a["rebound"]["ms_median"], b["rebound"]["ms_median"]
    p1, p2 = a["rapier"]["ms_median"], b["rapier"]["ms_median"]
    print(f"| {scene} | {r1:.3f} | {r2:.3f} | {r1 / r2:.2f} | {p1:.3f} | {p2:.3f} | {p1 / p2:.2f} | {r2 / p2:.2f} |")
PY
