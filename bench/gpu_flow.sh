#!/usr/bin/env bash
# One device-machine session for emitters and sinks (issue 18): build, the GPU tests (every CUDA
# test, the emitter and sink tests), the shipped hose at 1M particles (its count grows from 0 on
# the device), the dam break at 1M with and without a sink that takes nothing (what the
# reservoir's bookkeeping costs a step), a dam break that drains, and the stability sweep of the
# hose on the GPU; throttling checked before and after. Results under $OUT (or ./gpu-out; send
# OUT=/tmp/x and tar it into the device tool's $OUT). PARTS picks what runs (default all of
# "build test scenes sweep").
# Usage: PARTS="build scenes" bash bench/gpu_flow.sh
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build test scenes sweep} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv \
    | tee "$out/gpu.txt"
nvidia-smi -q -d PERFORMANCE >"$out/performance-before.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" weir weir_tests >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has test; then
    OMP_NUM_THREADS=16 timeout 400 ./build-gpu/weir_tests \
        --gtest_filter='*Cuda*:*cuda*:*Gpu*:InflowOutflow*:FrameWriter*:ParticleIds*' \
        >"$out/gpu-tests.log" 2>&1
    grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST" "$out/gpu-tests.log" | head -40
fi
# A scene at `count` particles for `frames` frames at its frame rate, frames off: the run's own
# summary lines.
scene() {  # name, scene, frames, count
    local name=$1 file=$2 frames=$3 count=${4:-1000000}
    WEIR_FRAME_OUTPUT=off timeout 300 ./build-gpu/weir run "$file" --particles "$count" \
        --frames "$frames" --overwrite -o "/tmp/run-$name" >"$out/run-$name.log" 2>&1
    echo "== $name (exit $?): $(grep -E "^weir: done|on cuda|warning" "$out/run-$name.log" | tr '\n' ' ')"
    tr '\r' '\n' <"$out/run-$name.log" | grep -E "^frame" | tail -2
}
if has scenes; then
    python3 - <<'PY'
import json
scene = json.load(open("scenes/dam_break.json"))
# A sink high in the far corner that the water does not reach in 1 s: the reservoir's cost alone.
scene["name"] = "dam_break_idle_sink"
scene["sinks"] = [{"min": [scene["container"]["max"][0] - 0.05, scene["container"]["max"][1] - 0.05,
                           scene["container"]["min"][2]],
                   "max": scene["container"]["max"]}]
json.dump(scene, open("/tmp/dam_break_idle_sink.json", "w"))
# A drain along the far wall's foot: the count shrinks on the device.
scene["name"] = "dam_break_drain"
x1 = scene["container"]["max"][0]
scene["sinks"] = [{"min": [x1 - 0.1, scene["container"]["min"][1], scene["container"]["min"][2]],
                   "max": [x1, scene["container"]["min"][1] + 0.05, scene["container"]["max"][2]]}]
json.dump(scene, open("/tmp/dam_break_drain.json", "w"))
PY
    scene dam-break-1M dam_break 30
    scene dam-break-idle-sink-1M /tmp/dam_break_idle_sink.json 30
    scene dam-break-drain-1M /tmp/dam_break_drain.json 60
    scene hose-1M hose_filling_glass 120
fi
if has sweep; then
    WEIR_SWEEP_SIZES=${SWEEP_SIZES:-100000} WEIR_SWEEP_BACKEND=cuda WEIR_SWEEP_MODELS=delta-sph \
        timeout 400 ./build-gpu/weir_tests --gtest_filter='*hose_filling_glass*' \
        >"$out/sweep.log" 2>&1
    grep -E "^sweep|FAILED|OK \]" "$out/sweep.log" | head -30
fi
nvidia-smi -q -d PERFORMANCE >"$out/performance-after.txt"
grep -A12 "Clocks Event Reasons" "$out/performance-after.txt" | grep -v "Not Active" | head -8
