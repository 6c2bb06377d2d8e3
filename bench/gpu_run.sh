#!/usr/bin/env bash
# One device-machine session: build for the GPU, run every test, run weir bench and the GPU
# reference step side by side, and collect logs and results under $OUT (or ./gpu-out).
# Usage: bash bench/gpu_run.sh [sizes] [reference-dir]
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
sizes=${1:-10k,50k,100k,1M,10M}
reference=${2:-.device/gpu-reference}
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv \
    | tee "$out/gpu.txt"
cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
    >/tmp/weir-configure.log 2>&1 || { tail -30 /tmp/weir-configure.log; exit 1; }
ninja -C build-gpu -j"$(nproc)" >/tmp/weir-build.log 2>&1 || { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
(cd build-gpu && OMP_NUM_THREADS=4 ctest -j4 --output-on-failure >"$out/ctest.log" 2>&1); tail -4 "$out/ctest.log"
./build-gpu/weir_tests --gtest_filter='Cuda*' 2>&1 | grep -E "^\[ +(OK|FAILED|SKIPPED) |Failure|Expected|actual|Which is|error" | head -60
./build-gpu/weir info
for n in 20000 100000 1000000; do
    ./build-gpu/weir run --particles $n --frames 3 -q -o /tmp/run$n 2>&1 | tail -1
done | tee "$out/runs.txt"
./build-gpu/weir bench --sizes "$sizes" --steps 20 --budget "${BUDGET:-30}" -o "$out/bench" 2>&1 | tee "$out/bench.txt"
if [ -d "$reference" ]; then
    bash "$reference/run.sh" 100000 1000000 10000000 2>&1 | tee "$out/reference.txt"
fi
