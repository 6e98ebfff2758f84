#!/usr/bin/env bash
# Speed-up of the step on 2 threads over 1, Rebound and rapier side by side, on the peer scenes; then the
# cost growth on 2 threads.
#
#   scripts/thread_speedup.sh [ROUNDS] [STEPS] [THREADS]      (defaults: 3 rounds, 600 steps, 2 threads)
#
# Runs `compare --threads 1` and `compare --threads THREADS` (both engines' parallel builds: Rebound with
# `--features parallel`, rapier from benches/peers with its `parallel` feature), then prints per scene each
# engine's ms/step on 1 and THREADS threads, its speed-up (1-thread ms over THREADS-thread ms), Rebound/rapier
# on THREADS threads, and the issue's bounds (speed-up ≥ 1.7 on balls and pyramid, ≥ 1.4 elsewhere;
# Rebound/rapier ≤ 0.7). Then `compare --scaling --threads THREADS` (the cost-growth exponents on the pool).
# These are the tables docs/performance.md records. Wall-clock figures: run it on an otherwise idle machine.
# Needs python3 for the table.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=${1:-3}
steps=${2:-600}
threads=${3:-2}
one=$(mktemp)
many=$(mktemp)
trap 'rm -f "$one" "$many"' EXIT
cargo build --release --features parallel --bin compare >&2
target/release/compare --threads 1 --rounds "$rounds" --steps "$steps" --json >"$one"
target/release/compare --threads "$threads" --rounds "$rounds" --steps "$steps" --json >"$many"
python3 - "$one" "$many" "$threads" <<'PY'
import json, sys
def load(path):
    return {r["scene"]: r for r in map(json.loads, open(path)) if "scene" in r}
one, many, n = load(sys.argv[1]), load(sys.argv[2]), sys.argv[3]
bound = {"balls": 1.7, "pyramid": 1.7}
print(f"Speed-up on {n} threads over 1 (ms/step: median over rounds of each run's median)\n")
print(f"| scene | Rebound 1 thread ms | Rebound {n} threads ms | Rebound speed-up (bound) | rapier 1 thread ms | rapier {n} threads ms | rapier speed-up | Rebound/rapier, {n} threads (bound 0.7) |")
print("|---|---|---|---|---|---|---|---|")
for scene, a in one.items():
    b = many[scene]
    r1, r2 = a["rebound"]["ms_median"], b["rebound"]["ms_median"]
    p1, p2 = a["rapier"]["ms_median"], b["rapier"]["ms_median"]
    s, lim, ratio = r1 / r2, bound.get(scene, 1.4), r2 / p2
    ok = lambda good: "" if good else " ✗"
    print(f"| {scene} | {r1:.3f} | {r2:.3f} | {s:.2f} (≥ {lim}){ok(s >= lim)} | {p1:.3f} | {p2:.3f} | {p1 / p2:.2f} | {ratio:.2f}{ok(ratio <= 0.7)} |")
print()
PY
target/release/compare --scaling --threads "$threads" --rounds 1
