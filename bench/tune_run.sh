#!/usr/bin/env bash
# TEMPORARY: A/B timing of tuning knobs on the device machine (not for commit).
set -uo pipefail
out=${OUT:-/tmp/tune}
mkdir -p "$out"
PARTS="build" bash bench/gpu_run.sh >/dev/null 2>&1 || { tail -20 /tmp/weir-build.log; exit 1; }
./build-gpu/weir_tests --gtest_filter='*Cuda*:*Dense*:NeighbourMask*:Solver*' 2>&1 > "$out/tests.log"
grep -E "^\[ +(FAILED|PASSED|SKIPPED) |Failure" "$out/tests.log" | head -20
for v in plain bounded; do
    if [ $v = bounded ]; then export WEIR_TUNE_BOUNDED=1; else unset WEIR_TUNE_BOUNDED; fi
    ./build-gpu/weir bench --backends cuda-dense --sizes ${SIZES:-100k,1M,10M} --steps 20 --no-plot \
        -o "$out/bench-$v" > "$out/bench-$v.txt" 2>&1
    echo "== $v"; grep -E "cuda-dense:|Grid construction|Pressure computation|Force computation" "$out/bench-$v.txt"
done
unset WEIR_TUNE_BOUNDED
ncu=$(command -v ncu || ls /usr/local/cuda/bin/ncu 2>/dev/null || true)
echo "ncu: ${ncu:-none}"
if [ -n "$ncu" ]; then
    for v in plain bounded; do
        if [ $v = bounded ]; then export WEIR_TUNE_BOUNDED=1; else unset WEIR_TUNE_BOUNDED; fi
        timeout 120 "$ncu" --kernel-name-base demangled --kernel-name regex:'accelerateAndIntegrate|computeDensity' \
            --launch-skip 10 --launch-count 2 --section SpeedOfLight --section Occupancy \
            --section WarpStateStats --section LaunchStats --section ComputeWorkloadAnalysis \
            ./build-gpu/weir run --particles 1000000 --frames 1 -q -o /tmp/ncu$v > "$out/ncu-$v.txt" 2>&1
        echo "== ncu $v"; grep -E "Duration|Registers Per|Achieved Occupancy|Theoretical Occupancy|Compute \(SM\) Throughput|Memory Throughput|L1/TEX Cache Throughput|L2 Cache Throughput|Issue Slots Busy|Executed Ipc A|Avg. Active Threads Per Warp|Warp Cycles Per Issued" "$out/ncu-$v.txt" | head -40
    done
    unset WEIR_TUNE_BOUNDED
fi
bash .device/gpu-reference/run.sh 100000 1000000 10000000 2>&1 | grep untuned | tee "$out/reference.txt"
