#!/usr/bin/env bash
# One device-machine session for rigid bodies (issue 18): build, the GPU tests (the CUDA tests,
# the rigid-body tests, the piston wave maker against linear theory), the shipped body scenes at
# 1M particles with and without their bodies (the bodies' cost per step), the stability sweep of
# the body scenes on the GPU, throttling checked before and after. Results under $OUT (or
# ./gpu-out; send OUT=/tmp/x and tar it into the device tool's $OUT). PARTS picks what runs
# (default all of "build test scenes sweep").
# Usage: PARTS="build scenes" bash bench/gpu_bodies.sh
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build test scenes sweep} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv \
    | tee "$out/gpu.txt"
nvidia-smi -q -d PERFORMANCE >"$out/performance-before.txt"
git log -1 --format=%H >"$out/commit.txt" 2>/dev/null
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" weir weir_tests >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has test; then
    OMP_NUM_THREADS=16 ./build-gpu/weir_tests \
        --gtest_filter='*Cuda*:*cuda*:*Gpu*:RigidBodies*:FrameWriter*' >"$out/gpu-tests.log" 2>&1
    grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST|piston wave|floating box" \
        "$out/gpu-tests.log" | head -40
fi
# A scene at 1M particles for `seconds` simulated, frames off: the run's own summary line.
scene() {  # name, scene, seconds
    local name=$1 file=$2 seconds=$3
    WEIR_FRAME_OUTPUT=off timeout 300 ./build-gpu/weir run "$file" --particles 1000000 \
        --frames "$seconds" --overwrite -o "/tmp/run-$name" >"$out/run-$name.log" 2>&1
    echo "== $name (exit $?): $(grep -E "^weir: done|on cuda" "$out/run-$name.log" | tr '\n' ' ')"
}
if has scenes; then
    for s in floating_boxes piston_wave_maker; do
        python3 - "$s" <<'PY'
import json, sys
name = sys.argv[1]
scene = json.load(open(f"scenes/{name}.json"))
scene["bodies"] = []
scene["name"] = name + "_without_bodies"
json.dump(scene, open(f"/tmp/{name}_without_bodies.json", "w"))
PY
    done
    scene floating-1M floating_boxes 30
    scene floating-1M-without /tmp/floating_boxes_without_bodies.json 30
    scene piston-1M piston_wave_maker 30
    scene piston-1M-without /tmp/piston_wave_maker_without_bodies.json 30
fi
if has sweep; then
    WEIR_SWEEP_SIZES=${SWEEP_SIZES:-100000} WEIR_SWEEP_BACKEND=cuda WEIR_SWEEP_MODELS=delta-sph \
        timeout 400 ./build-gpu/weir_tests --gtest_filter='*floating_boxes*:*piston_wave_maker*' \
        >"$out/sweep.log" 2>&1
    grep -E "^sweep|FAILED|OK \]" "$out/sweep.log" | head -30
fi
nvidia-smi -q -d PERFORMANCE >"$out/performance-after.txt"
grep -A12 "Clocks Event Reasons" "$out/performance-after.txt" | grep -v "Not Active" | head -8
