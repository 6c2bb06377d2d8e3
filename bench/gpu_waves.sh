#!/usr/bin/env bash
# Small waves on the GPU (issue 14): the piston wave flume of bench/wave_flume.py in variants
# (slab width, spacing, smoothing ratio h/d, particle shifting), each run to 4 s with binary PLY
# frames and its probes' wave heights; then weir validate runs (VALIDATIONS: lines of
# name|options) and the dam break's step timed at the ratios in BENCH_RATIOS beside the
# reference. Results under $OUT (default gpu-out).
# Usage: FLUMES="0.03:0.005:2:0 ..." VALIDATIONS=$'a|--cases ...\nb|...' bash bench/gpu_waves.sh
#   each flume width:spacing:ratio:shifting[:periodic 0|1[:duration s]]; PARTS picks build, flumes, validate, bench.
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build flumes validate bench} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
py=python3
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt"
if has build; then
    targets=${TARGETS:-weir}
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    # shellcheck disable=SC2086
    ninja -C build-gpu -j"$(nproc)" $targets >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has test; then
    OMP_NUM_THREADS=16 timeout "${TEST_TIMEOUT:-300}" ./build-gpu/weir_tests \
        --gtest_filter="${TEST_FILTER:-*Cuda*:*cuda*:*Gpu*}" >"$out/gpu-tests.log" 2>&1
    grep -E "^\[ +(FAILED|SKIPPED) |Failure|PASSED|FAILED TEST|piston wave maker" "$out/gpu-tests.log" | head -40
fi
if has flumes; then
    for f in ${FLUMES:-0.03:0.005:2:0}; do
        IFS=: read -r width spacing ratio shifting periodic duration <<<"$f"
        name="flume-w${width}-d${spacing}-r${ratio}-s${shifting}$([ "${periodic:-0}" = 1 ] && echo -periodic)"
        $py bench/wave_flume.py scene "/tmp/$name.json" --width "$width" --spacing "$spacing" \
            --ratio "$ratio" --shifting "$shifting" --duration "${duration:-4}" \
            $([ "${periodic:-0}" = 1 ] && echo --periodic-z)
        cp "/tmp/$name.json" "$out/"
        timeout "${FLUME_TIMEOUT:-240}" ./build-gpu/weir run "/tmp/$name.json" --format ply \
            --overwrite -o "/tmp/$name" >"$out/$name.log" 2>&1
        echo "== $name (exit $?): $(grep -E "^weir: done" "$out/$name.log")"
        $py bench/wave_flume.py heights "/tmp/$name" --spacing "$spacing" >"$out/$name-heights.txt"
        grep -E "^H@" "$out/$name-heights.txt" | tr '\n' ' '
        echo
        rm -rf "/tmp/$name"
    done
fi
if has validate; then
    # Each entry name|weir validate options (commas inside options are the ladders').
    while IFS='|' read -r name opts; do
        [ -z "$name" ] && continue
        echo "== validate-$name: $opts"
        # shellcheck disable=SC2086
        timeout "${VALIDATE_TIMEOUT:-300}" ./build-gpu/weir validate --backend cuda --no-plot \
            $opts -o "$out/validate-$name" >"$out/validate-$name.txt" 2>&1
        grep -E "PASS|FAIL|error|front RMS|decay" "$out/validate-$name.txt" | cut -c1-150
    done <<<"${VALIDATIONS:-dam-break-r3|--smoothing-ratio 3 --cases dam-break --column-resolution 20,40,80,160}"
fi
if has bench; then
    # The dam break timed by weir bench at each ratio in BENCH_RATIOS (delta-SPH), then the
    # reference step in the same call.
    for r in ${BENCH_RATIOS:-2 3}; do
        $py - "$r" <<'PY'
import json, sys
s = json.load(open("scenes/dam_break.json"))
s.setdefault("particles", {})["smoothingRatio"] = float(sys.argv[1])
s["name"] = "dam_break_r" + sys.argv[1]
json.dump(s, open("/tmp/dam_break_r%s.json" % sys.argv[1], "w"))
PY
        ./build-gpu/weir bench "/tmp/dam_break_r$r.json" --model delta-sph --sizes "${BENCH_SIZES:-100k,1M}" \
            --backends cuda-dense --steps 30 --no-plot --no-render -o "$out/bench-r$r" \
            >"$out/bench-r$r.txt" 2>&1
        echo "== bench ratio $r"; grep -E "full step|simulated second|particles" "$out/bench-r$r.txt" | head -12
    done
    [ -d .device/gpu-reference ] && bash .device/gpu-reference/run.sh 100000 1000000 2>&1 | tee "$out/reference.txt" | tail -4
fi
nvidia-smi -q -d PERFORMANCE | grep -A12 "Clocks Event Reasons" | grep -v "Not Active" >"$out/throttle.txt"
cat "$out/throttle.txt"
