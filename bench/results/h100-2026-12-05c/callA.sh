#!/usr/bin/env bash
# Session 2026-12-05c call A (33d5b87): build; the 10M DFSPH dam break to 0.1 s with the
# worst-particle bound (d784914); every CUDA test; DFSPH and WCSPH bench with the reference beside.
set -uo pipefail
t0=$(date +%s); el() { echo "$(( $(date +%s) - t0 )) s"; }
PARTS="build" OUT=$OUT bash bench/gpu_pending.sh 2>&1 | grep -v "^ \|Clocks" | tail -3; echo "built $(el)"
timeout 110 ./build-gpu/weir run ../dam100.json --solver dfsph --particles 10M --format ply --overwrite -o /tmp/r10 >"$OUT/head-10m-100fps.log" 2>&1
echo "10M dam break, bound 1%: exit $? $(el)"; grep -E "^frame|blew|done" "$OUT/head-10m-100fps.log" | cut -c1-260
rm -rf /tmp/r10
OMP_NUM_THREADS=16 timeout 170 ./build-gpu/weir_tests --gtest_filter='*Cuda*:*cuda*:*Gpu*' >"$OUT/gpu-tests.log" 2>&1
echo "tests exit $? $(el)"; grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST|tests ran" "$OUT/gpu-tests.log" | head -20
timeout 80 ./build-gpu/weir bench dam_break --model delta-sph --solver dfsph --sizes 100k,1M \
    --backends cuda-dense --no-plot --no-render -o "$OUT/dfsph" >"$OUT/dfsph.log" 2>&1
echo "dfsph bench exit $? $(el)"; grep -E "cuda-dense:" "$OUT/dfsph.log"
timeout 60 ./build-gpu/weir bench dam_break --model delta-sph --sizes 100k,1M --backends cuda-dense --no-plot --no-render -o "$OUT/wcsph" >"$OUT/wcsph.log" 2>&1
echo "wcsph bench exit $? $(el)"; grep -E "cuda-dense:" "$OUT/wcsph.log"
timeout 60 ./build-gpu/weir bench dam_break --sizes 100k,1M --backends cuda-dense --no-plot --no-render -o "$OUT/paper" >"$OUT/paper.log" 2>&1
echo "paper-model bench exit $? $(el)"; grep -E "cuda-dense:" "$OUT/paper.log"
timeout 60 bash ../gpu-reference/run.sh 100000 1000000 >"$OUT/reference.txt" 2>&1; echo "reference exit $? $(el)"; tail -6 "$OUT/reference.txt"
nvidia-smi -q -d PERFORMANCE | grep -E "Thermal|Power Cap|Braking"
cd "$OUT" && tar czf /tmp/logs.tgz * 2>/dev/null; rm -rf "$OUT"/*; mv /tmp/logs.tgz "$OUT"/
