#!/usr/bin/env bash
# What is left to run on a GPU, in parts (PARTS, default all). Updated 2026-12-05 (third session:
# an H100 ran build, test, dfsph, walls, spray and the sweep at ab95436; bench/results/h100-2026-12-05b):
#   build    weir, weir_tests, weir_water_view_bench (Release, sm_90) into build-gpu
#   test     every CUDA test (all 36 passed at ab95436, the graph loops among them)
#   dfsph    DFSPH's step replayed as a graph (the default since it passed there) against the
#            host-polled step (WEIR_DFSPH_GRAPH=0), weir bench at 100k and 1M with WCSPH beside
#   live     weir_water_view_bench at 1M (99 frames/s at fcc5913), then `weir render --look water`
#            timed on a 1M frame; this needs a weir built with rendering: run bench/gpu_render.sh
#            with build-kit/weir and .gl/ carried (see its header) for the offline timings
#   sweep    issue 14: the delta-SPH stability sweep at 1M, h = 3 d, for the scene not yet run
#            there (SWEEP_SCENES: viscous_pour; it needs more than 265 s), then the simple walls
#            at 100k (WEIR_SWEEP_SIMPLE_DELTA; 27 cases, 6 blew up at ab95436)
# Parts not in the default set (a call of their own each):
#   spray    issue 15: the 10M DFSPH dam break to 0.3 s with a ply frame every 0.01 s, then
#            bench/dfsph_spray.py. At 33d5b87 on an H100 it ran (worst +1.61%, 1640 steps; 30
#            particles kicked out at a side wall; bench/results/h100-2026-12-05c)
#   largest  issues 15 and 17: the largest runs with today's physics: weir bench with delta-SPH
#            at 1B (700M if 1B does not fit) and DFSPH at 500M, 2 timed steps each, no settling
#            (an H200's memory; DFSPH at 500M ran on an H100 at 33d5b87: 126 B a particle)
#   walls    issue 15: DFSPH's pushing walls (WEIR_DFSPH_WALLS=extrapolated): the DFSPH CUDA
#            tests with it, the hydrostatic tank on the GPU at 48 and 96 over the depth, and the
#            shipped dam break at 1M to 0.3 s beside the default (at ab95436 the GPU tank at 48
#            blew up at 0.09 s where the CPU passes it)
# Results under $OUT (default gpu-out). Usage: PARTS="build test live" bash bench/gpu_pending.sh
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build test dfsph live sweep} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" weir weir_tests weir_water_view_bench >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
    echo "built at $(date +%T)"
fi
if has test; then
    OMP_NUM_THREADS=16 timeout "${TEST_TIMEOUT:-300}" ./build-gpu/weir_tests \
        --gtest_filter="${TEST_FILTER:-*Cuda*:*cuda*:*Gpu*}" >"$out/gpu-tests.log" 2>&1
    echo "tests exit $?"
    grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST" "$out/gpu-tests.log" | head -40
fi
if has dfsph; then
    for g in 1 0; do
        WEIR_DFSPH_GRAPH=$g timeout 150 ./build-gpu/weir bench dam_break --model delta-sph \
            --solver dfsph --sizes 100k,1M --backends cuda-dense --no-plot --no-render \
            -o "$out/dfsph-graph$g" >"$out/dfsph-graph$g.log" 2>&1
        echo "dfsph bench, graph $g: exit $?"; grep -E "cuda-dense:" "$out/dfsph-graph$g.log"
    done
    timeout 150 ./build-gpu/weir bench dam_break --model delta-sph --sizes 100k,1M \
        --backends cuda-dense --no-plot --no-render -o "$out/wcsph" >"$out/wcsph.log" 2>&1
    echo "wcsph bench: exit $?"; grep -E "cuda-dense:" "$out/wcsph.log"
fi
if has live; then
    timeout 300 ./build-gpu/weir_water_view_bench dam_break --particles 1M --frames 100 \
        --warmup 10 --out "$out/water_view.png" --json "$out/water_view.json" \
        >"$out/water_view.txt" 2>&1
    echo "water view bench exit $?"; tail -n 20 "$out/water_view.txt"
    timeout 200 ./build-gpu/weir run dam_break --particles 1000000 --frames 18 --format ply \
        --overwrite -o /tmp/dam1m >"$out/run-1m.log" 2>&1
    for samples in 32 256; do
        /usr/bin/time -f "%e s" timeout 120 ./build-gpu/weir render /tmp/dam1m --frame 18 \
            --look water --samples "$samples" --out "/tmp/dam1m/water$samples" \
            >"$out/render-water-$samples.log" 2>&1
        echo "render --look water at $samples paths: $(tail -n 1 "$out/render-water-$samples.log")"
    done
    cp /tmp/dam1m/water256/frame_00018.png "$out/dam_break_1m_water.png" 2>/dev/null
fi
if has sweep; then
    scenes=${SWEEP_SCENES:-viscous_pour piston_wave_maker}
    filter=$(for s in $scenes; do printf 'ShippedScenes*/%s*:' "$s"; done)
    WEIR_SWEEP_BACKEND=cuda WEIR_SWEEP_SIZES=1000000 WEIR_SWEEP_RATIOS=3 WEIR_SWEEP_MODELS=delta-sph \
        timeout "${SWEEP_TIMEOUT:-560}" ./build-gpu/weir_tests --gtest_filter="${filter%:}" \
        >"$out/sweep-1M.log" 2>&1
    echo "1M sweep exit $?"; grep -E "^sweep |FAILED  \]" "$out/sweep-1M.log" | cut -c1-220
    WEIR_SWEEP_BACKEND=cuda WEIR_SWEEP_SIZES=100000 WEIR_SWEEP_MODELS=delta-sph WEIR_SWEEP_SIMPLE_DELTA=1 \
        WEIR_SWEEP_RATIOS="${SIMPLE_RATIOS:-1.5,2,3}" \
        timeout "${SWEEP_TIMEOUT:-560}" ./build-gpu/weir_tests --gtest_filter='ShippedScenes*_simple' \
        >"$out/sweep-simple-100k.log" 2>&1
    echo "simple-walls sweep exit $?"; grep -E "^sweep |FAILED  \]" "$out/sweep-simple-100k.log" | cut -c1-220
fi
if has spray; then
    python3 - <<'PY'
import json
s = json.load(open("scenes/dam_break.json"))
s["time"] = {"duration": 0.3, "frameRate": 100}
json.dump(s, open("/tmp/dam_break_100fps.json", "w"))
PY
    timeout 300 ./build-gpu/weir run /tmp/dam_break_100fps.json --solver dfsph --particles 10M \
        --format ply --overwrite -o /tmp/spray10m >"$out/spray10m-run.log" 2>&1
    echo "spray run: exit $?"; grep -E "particles on|^weir: done" "$out/spray10m-run.log"
    n=$(grep -oE "[0-9]+ particles on" "$out/spray10m-run.log" | grep -oE "^[0-9]+")
    spacing=$(python3 -c "print((0.4 * 0.6 * 0.6 / $n) ** (1 / 3))")  # the column's volume
    timeout 200 python3 bench/dfsph_spray.py /tmp/spray10m --box 0 0 0 1.6 1 0.6 \
        --spacing "$spacing" >"$out/spray10m.txt" 2>&1
    echo "spray analysis: exit $?"; head -n 60 "$out/spray10m.txt"
fi
if has walls; then
    WEIR_DFSPH_WALLS=extrapolated ./build-gpu/weir_tests --gtest_filter='DfsphCuda.*:CudaPeriodic.*Dfsph*' \
        >"$out/walls-cuda-tests.log" 2>&1
    echo "pushing walls, CUDA tests: exit $?"; grep -E "OK|FAILED" "$out/walls-cuda-tests.log"
    for r in 48 96; do
        WEIR_DFSPH_WALLS=extrapolated timeout 240 ./build-gpu/weir validate --backend cuda \
            --solver dfsph --cases hydrostatic --tank-resolution $r --no-plot -o "$out/walls-tank-$r" \
            >"$out/walls-tank-$r.log" 2>&1
        echo "pushing walls, tank $r: exit $?"; grep -E "PASS|FAIL" "$out/walls-tank-$r.log"
    done
    for walls in own extrapolated; do
        WEIR_DFSPH_WALLS=$walls timeout 200 ./build-gpu/weir run dam_break --solver dfsph \
            --particles 1M --frames 9 --format ply --overwrite -o /tmp/walls-$walls \
            >"$out/walls-dam-$walls.log" 2>&1
        echo "dam break 1M, walls $walls: exit $?"; grep -E "^weir: done|frame 9/" "$out/walls-dam-$walls.log"
    done
fi

if has largest; then
    big() {  # label, seconds, bench arguments
        local label=$1 limit=$2
        shift 2
        timeout "$limit" ./build-gpu/weir bench dam_break --backends cuda-dense --steps 2 \
            --warmup 1 --settle 0 --budget 400 --no-plot --no-render -o "$out/$label" "$@" \
            >"$out/$label.log" 2>&1
        echo "$label: exit $?"; grep -E "cuda-dense:|rror|memory" "$out/$label.log" | head -5
    }
    big largest-delta-1B 230 --model delta-sph --sizes 1B
    grep -q "cuda-dense:" "$out/largest-delta-1B.log" ||
        big largest-delta-700M 200 --model delta-sph --sizes 700M
    big largest-dfsph-500M 250 --model delta-sph --solver dfsph --sizes 500M
fi
nvidia-smi -q -d PERFORMANCE | grep -A12 "Clocks Event Reasons" | grep -v "Not Active" >"$out/throttle.txt"
cat "$out/throttle.txt"
