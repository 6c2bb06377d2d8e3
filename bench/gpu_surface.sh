#!/usr/bin/env bash
# One device-machine session for surface reconstruction (issue 22, part 5) and frame output
# (issue 17, part 2): build, the GPU tests of the surface and the step, weir_surface_bench on
# synthetic frames (1M, 10M, 1e8 particles) and on real dam-break frames, frame output timed
# against frames off, the GPU reference step in the same call, throttling checked before and
# after ("suite" runs the whole ctest suite instead of "test"'s GPU tests). Results under $OUT (or ./gpu-out; the device tool brings back a few files only, so
# send OUT=/tmp/x and tar it into the tool's $OUT). PARTS picks what runs (default all of
# "build test synthetic real frames reference").
# Usage: PARTS="build synthetic" bash bench/gpu_surface.sh [reference-dir]
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
reference=${1:-.device/gpu-reference}
parts=" ${PARTS:-build test synthetic real frames reference} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.sm,clocks.max.sm --format=csv \
    | tee "$out/gpu.txt"
nvidia-smi -q -d PERFORMANCE >"$out/performance-before.txt"
nproc >"$out/cores.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" weir weir_tests weir_surface_bench >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
bench=./build-gpu/weir_surface_bench
if has suite; then  # the whole suite, GPU tests included
    (cd build-gpu && OMP_NUM_THREADS=4 timeout "${SUITE_SECONDS:-400}" ctest -j6 \
        --output-on-failure >"$out/ctest.log" 2>&1)
    tail -5 "$out/ctest.log"
fi
if has test; then
    ./build-gpu/weir_tests --gtest_filter='*Cuda*:*cuda*:*Gpu*:SparseLattice*:Surface*:Anisotrop*:Sliver*:MarchingCubes*:DocCommands.*:FrameOutput*:MeshCli*' \
        >"$out/gpu-tests.log" 2>&1
    grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST" "$out/gpu-tests.log" | head -40
fi
surface() {  # name, then weir_surface_bench arguments
    local name=$1
    shift
    timeout 240 "$bench" "$@" --json "$out/surface-$name.json" >/dev/null 2>"$out/surface-$name.log"
    echo "== $name (exit $?): $(python3 -c "import json,sys; d=json.load(open('$out/surface-$name.json')); print(d['particles'], 'particles', round(d['total_ms_median'],1), 'ms', '%.3g/s' % d['particles_per_second'], d['triangles'], 'triangles', {k: round(v,1) for k,v in d['stage_ms_median'].items()})" 2>&1)"
}
if has synthetic; then
    surface iso-1M --particles 1000000 --backend cuda --repeats 5
    surface aniso-1M --particles 1000000 --backend cuda --surface-field anisotropic --repeats 5
    surface iso-10M --particles 10000000 --backend cuda --repeats 5
    surface aniso-10M --particles 10000000 --backend cuda --surface-field anisotropic --repeats 5
    surface iso-100M --particles 100000000 --backend cuda --repeats 3
    surface aniso-100M --particles 100000000 --backend cuda --surface-field anisotropic --repeats 3
    surface cpu-iso-1M --particles 1000000 --backend cpu --repeats 3
fi
if has real; then
    # A dam break just after the front hits the far wall (frame 12 at 30 frames per second).
    timeout 200 ./build-gpu/weir run dam_break --particles 1000000 --frames 12 --format ply -q \
        -o /tmp/db1M >"$out/run-1M.log" 2>&1
    frame=$(ls /tmp/db1M/frame_*.ply | tail -1)
    spacing=$(python3 -c "import json; print(json.load(open('/tmp/db1M/frames.json'))['spacing'])")
    surface real-iso-1M --frame "$frame" --spacing "$spacing" --backend cuda --repeats 5
    surface real-aniso-1M --frame "$frame" --spacing "$spacing" --backend cuda \
        --surface-field anisotropic --repeats 5
    surface real-cpu-iso-1M --frame "$frame" --spacing "$spacing" --backend cpu --repeats 3
    ls -la /tmp/db1M | head -20 >"$out/run-1M-files.txt"
fi
if has frames; then
    OUTDIR=/tmp/fo timeout 300 bash bench/frame_output.sh build-gpu/weir "${FRAME_REPEATS:-3}" \
        dam_break --particles 1000000 --frames 30 2>&1 | tee "$out/frame-output-vtu.txt"
    if [ -z "${FRAME_REPEATS:-}" ]; then
        OUTDIR=/tmp/fo timeout 120 bash bench/frame_output.sh build-gpu/weir 1 dam_break \
            --particles 1000000 --frames 30 --format ply 2>&1 | tee "$out/frame-output-ply.txt"
        OUTDIR=/tmp/fo timeout 120 bash bench/frame_output.sh build-gpu/weir 1 dam_break \
            --particles 1000000 --frames 30 --format csv 2>&1 | tee "$out/frame-output-csv.txt"
    fi
fi
if has reference && [ -d "$reference" ]; then
    bash "$reference/run.sh" 1000000 10000000 2>&1 | tee "$out/reference.txt"
fi
nvidia-smi -q -d PERFORMANCE >"$out/performance-after.txt"
grep -A12 "Clocks Event Reasons" "$out/performance-after.txt" | head -14
