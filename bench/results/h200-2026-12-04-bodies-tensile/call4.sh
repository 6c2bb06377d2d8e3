#!/usr/bin/env bash
# Device call 4 (2026-12-04, the commit after c1803f9's parent): build; the body GPU tests (piston at
# h = 4 d, tilted mesh body, box and paddle) and the boat example's frames.
set -u
start=$(date +%s)
PARTS="build" TARGETS="weir weir_tests" OUT=/tmp/r4 bash bench/gpu_waves.sh > /tmp/build4.log 2>&1 || { tail -40 /tmp/build4.log; exit 1; }
echo "built in $(( $(date +%s) - start )) s"
(OMP_NUM_THREADS=16 ./build-gpu/weir_tests --gtest_filter='RigidBodiesCuda.*:CudaSolver.BlowUp*' > "$OUT/gpu-tests.log" 2>&1) &
(cd examples && timeout 300 ../build-gpu/weir run boat_in_waves.json -o /tmp/boat --overwrite > "$OUT/boat.log" 2>&1; cp /tmp/boat/frames.json /tmp/boat/frame_00090.vtu /tmp/boat/frame_00150.vtu "$OUT/") &
wait
echo "all done at $(( $(date +%s) - start )) s"
grep -E "OK|FAILED|Failure|piston|PASSED" "$OUT/gpu-tests.log"; grep -E "done|error|particles on" "$OUT/boat.log"
nvidia-smi -q -d PERFORMANCE | grep -A12 "Clocks Event Reasons" | grep -v "Not Active" | head -8
