#!/usr/bin/env bash
# Small waves on the GPU (issue 14): the piston wave flume of bench/wave_flume.py in variants
# (slab width, spacing, smoothing ratio h/d, particle shifting), each run to 4 s with binary PLY
# frames and its probes' wave heights; then, optionally, weir validate's dam-break ladder and
# Lobovsky case at the ratios in RATIOS. Results under $OUT (default gpu-out).
# Usage: FLUMES="0.03:0.005:2:0 ..." RATIOS="3" CASES="dam-break lobovsky" bash bench/gpu_waves.sh
#   each flume width:spacing:ratio:shifting[:periodic]; PARTS picks build, flumes, validate.
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build flumes validate} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
py=python3
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_PYTHON=OFF >/tmp/weir-configure.log 2>&1 ||
        { tail -30 /tmp/weir-configure.log; exit 1; }
    ninja -C build-gpu -j"$(nproc)" weir >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has flumes; then
    for f in ${FLUMES:-0.03:0.005:2:0}; do
        IFS=: read -r width spacing ratio shifting periodic <<<"$f"
        name="flume-w${width}-d${spacing}-r${ratio}-s${shifting}${periodic:+-periodic}"
        $py bench/wave_flume.py scene "/tmp/$name.json" --width "$width" --spacing "$spacing" \
            --ratio "$ratio" --shifting "$shifting" ${periodic:+--periodic-z}
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
    for r in ${RATIOS:-3}; do
        for c in ${CASES:-dam-break}; do
            case $c in
            dam-break) opts=(--column-resolution "${LADDER:-20,40,80,160}") ;;
            lobovsky) opts=(--lobovsky-resolution "${LOBOVSKY:-30}") ;;
            hydrostatic) opts=(--tank-resolution 48) ;;
            *) opts=() ;;
            esac
            name="validate-$c-r$r"
            echo "== $name"
            timeout "${VALIDATE_TIMEOUT:-300}" ./build-gpu/weir validate --backend cuda --no-plot \
                --smoothing-ratio "$r" --cases "$c" "${opts[@]}" -o "$out/$name" \
                >"$out/$name.txt" 2>&1
            grep -E "PASS|FAIL|error|front RMS" "$out/$name.txt" | cut -c1-150
        done
    done
fi
nvidia-smi -q -d PERFORMANCE | grep -A12 "Clocks Event Reasons" | grep -v "Not Active" >"$out/throttle.txt"
cat "$out/throttle.txt"
