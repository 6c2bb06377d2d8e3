#!/usr/bin/env bash
# DFSPH against WCSPH on the device: the shipped dam break at each size, the same simulated time,
# both solvers; the wall time, steps, the density error per frame and DFSPH's sweeps per step
# (its progress lines), for time per simulated second. Needs build-gpu (bench/gpu_run.sh).
# Usage: bash bench/gpu_dfsph.sh [sizes] [frames]   (frames at the scene's 30 per second)
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
sizes=${1:-100000,1000000}
frames=${2:-9}
mkdir -p "$out/dfsph"
nvidia-smi -q -d PERFORMANCE >"$out/dfsph/perf-before.txt" 2>&1
for n in ${sizes//,/ }; do
    for solver in wcsph dfsph; do
        log="$out/dfsph/dam_break-$n-$solver.log"
        start=$(date +%s%N)
        ./build-gpu/weir run dam_break --solver "$solver" --particles "$n" --frames "$frames" \
            --format ply --overwrite -o "/tmp/dfsph-$n-$solver" >"$log" 2>&1
        end=$(date +%s%N)
        echo "wall $(((end - start) / 1000000)) ms" >>"$log"
        echo "== $n $solver: $(grep -E "done|error" "$log" | tail -1); $(tail -1 "$log")"
        grep -E "^frame" "$log" | tail -2
    done
done
nvidia-smi -q -d PERFORMANCE >"$out/dfsph/perf-after.txt" 2>&1
grep -iE "active|throttle" "$out/dfsph/perf-after.txt" | grep -v "Not Active" | head
