#!/usr/bin/env bash
# Session 2026-12-05c call B1 (33d5b87, H200): build weir; weir bench at 10M, DFSPH and WCSPH
# (delta-SPH, each at its default smoothing ratio): wall seconds per simulated second.
set -uo pipefail
t0=$(date +%s); el() { echo "$(( $(date +%s) - t0 )) s"; }
nvidia-smi --query-gpu=name,clocks.sm,clocks.max.sm,memory.total --format=csv,noheader | tee "$OUT/gpu.txt"
cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 -DWEIR_ENABLE_PYTHON=OFF >/tmp/c.log 2>&1
ninja -C build-gpu weir >/tmp/b.log 2>&1; echo "built $? $(el)"
timeout 200 ./build-gpu/weir bench dam_break --model delta-sph --solver dfsph --sizes 10M --budget 180 \
    --backends cuda-dense --no-plot --no-render -o "$OUT/dfsph10m" >"$OUT/dfsph10m.log" 2>&1
echo "dfsph 10M bench exit $? $(el)"; grep -E "cuda-dense:|solve|list" "$OUT/dfsph10m.log"
left=$(( 590 - ($(date +%s) - t0) ))
timeout $left ./build-gpu/weir bench dam_break --model delta-sph --sizes 10M --budget $((left - 10)) \
    --backends cuda-dense --no-plot --no-render -o "$OUT/wcsph10m" >"$OUT/wcsph10m.log" 2>&1
echo "wcsph 10M bench exit $? $(el)"; grep -E "cuda-dense:" "$OUT/wcsph10m.log"
nvidia-smi -q -d PERFORMANCE | grep -E "Thermal|Power Cap|Braking" | tee "$OUT/throttle.txt"
