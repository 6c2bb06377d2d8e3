#!/usr/bin/env bash
# A/B timing of two builds of weir in one device call: the dense GPU step of build A (a baseline
# tree, e.g. the commit before a refactor, built into build-base) and of this tree (build-gpu),
# run in turns A B A B so that drift or throttling shows in both, then the GPU reference step at
# the same sizes. One line per run and size in $OUT/ab.txt, every bench.json in $OUT/ab.tgz.
# Usage: bash bench/gpu_ab.sh SIZES BASELINE_DIR [rounds]   (after both builds)
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
sizes=$1
baseline=$2
rounds=${3:-2}
work=/tmp/weir-ab
rm -rf "$work" && mkdir -p "$work" "$out"
for round in $(seq 1 "$rounds"); do
    for side in A B; do
        binary=./build-gpu/weir
        [ "$side" = A ] && binary=$baseline/build-base/weir
        name=$side$round
        "$binary" bench --backends cuda-dense --sizes "$sizes" --steps 30 --no-plot --no-render \
            -o "$work/$name" >"$work/$name.log" 2>&1 || tail -5 "$work/$name.log"
        python3 - "$work/$name/bench.json" "$name" <<'PY' | tee -a "$out/ab.txt"
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
for run in runs:
    col = run["columns"]["cuda-dense"]
    stages = " ".join(f"{k} {v:.4f}" for k, v in sorted(col["stages"].items()))
    print(f"{sys.argv[2]:>4} {run['particles']:>10} step {col['stepMs']:.4f} ms ({stages})")
PY
    done
done
if [ -d .device/gpu-reference ]; then
    counts=$(python3 -c "
import sys
m = {'k': 1000, 'M': 1000000}
print(' '.join(str(int(float(s[:-1]) * m[s[-1]]) if s[-1] in m else int(s)) for s in sys.argv[1].split(',')))" "$sizes")
    bash .device/gpu-reference/run.sh $counts 2>&1 | tee "$out/reference.txt"
fi
tar czf "$out/ab.tgz" -C "$work" .
