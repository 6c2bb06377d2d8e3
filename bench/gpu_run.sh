#!/usr/bin/env bash
# One device-machine session: build for the GPU, run every test, time the dam break, run weir
# bench and the GPU reference step side by side, and collect logs and results under $OUT (or
# ./gpu-out). PARTS picks what runs (default: all of "build test runs bench reference"; "huge"
# adds the largest dam break, HUGE particles, 1B by default), so a long session can be split over
# calls that reuse the build.
# Usage: WEIR_COMMIT=<commit, named on the machine that sends the tree: the copy's .git there can
#        be stale> PARTS="build test" bash bench/gpu_run.sh [sizes] [reference-dir]
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
sizes=${1:-10k,50k,100k,1M,10M}
reference=${2:-.device/gpu-reference}
parts=" ${PARTS:-build test runs bench reference} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv \
    | tee "$out/gpu.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        >/tmp/weir-configure.log 2>&1 || { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has test; then
    (cd build-gpu && OMP_NUM_THREADS=4 ctest -j4 --output-on-failure >"$out/ctest.log" 2>&1)
    tail -4 "$out/ctest.log"
    ./build-gpu/weir_tests --gtest_filter='*Cuda*:*cuda*:*Gpu*' 2>&1 | tee "$out/gpu-tests.log" |
        grep -E "^\[ +(OK|FAILED|SKIPPED) |Failure|Expected|actual|Which is|error|PASSED" | head -60
    ./build-gpu/weir info | tee "$out/info.txt"
fi
if has runs; then
    # Steps per second of whole runs (frames written), per neighbour search; the paper's fluid
    # model, as the figures in NOTES.md (MODEL=delta-sph for weir's default model).
    for run in "100000 dense 3" "100000 grid 3" "100000 brute 1" "1000000 dense 3" \
               "1000000 grid 3"; do
        set -- $run
        echo "== $1 particles, $2 neighbours"
        ./build-gpu/weir run --model "${MODEL:-paper}" --particles "$1" --neighbours "$2" \
            --frames "$3" -q -o "/tmp/run$1$2" \
            2>&1 | tail -1
    done | tee "$out/runs.txt"
fi
if has bench; then
    # BENCH_WEIR: a binary with rendering built in (build-kit/weir with the GL runtime of
    # bench/gpu_render.sh unpacked) adds the point-sprite row.
    "${BENCH_WEIR:-./build-gpu/weir}" bench --sizes "$sizes" --steps 20 --budget "${BUDGET:-30}" -o "$out/bench" \
        2>&1 | tee "$out/bench.txt"
fi
if has huge; then
    # The largest dam break: seeded on the GPU, timed from the lattice, no frames written.
    nvidia-smi --query-gpu=memory.used,memory.total --format=csv | tee "$out/huge-memory-before.txt"
    ./build-gpu/weir bench --backends cuda-dense --sizes "${HUGE:-1B}" --steps 10 --warmup 2 \
        --budget 300 --no-plot -o "$out/huge" 2>&1 | tee "$out/huge.txt"
fi
if has reference && [ -d "$reference" ]; then
    bash "$reference/run.sh" 100000 1000000 10000000 2>&1 | tee "$out/reference.txt"
fi
