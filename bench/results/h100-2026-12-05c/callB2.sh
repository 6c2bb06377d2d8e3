#!/usr/bin/env bash
# Session 2026-12-05c call B2 (33d5b87, H200): the largest DFSPH dam break that fits: weir bench
# at 500M (DFSPH, no settling, 1 warm-up and 2 timed steps; the neighbour lists turn themselves off).
set -uo pipefail
t0=$(date +%s); el() { echo "$(( $(date +%s) - t0 )) s"; }
for n in ${SIZES:-500M}; do
  ( while sleep 20; do nvidia-smi --query-gpu=memory.used --format=csv,noheader; done ) > "$OUT/mem-$n.txt" &
  mon=$!
  timeout ${T:-560} ./build-gpu/weir bench dam_break --model delta-sph --solver dfsph --sizes $n --settle 0 \
      --warmup 1 --steps 2 --budget 550 --backends cuda-dense --no-plot --no-render -o "$OUT/dfsph-$n" >"$OUT/dfsph-$n.log" 2>&1
  echo "dfsph $n exit $? $(el)"; kill $mon; tail -25 "$OUT/dfsph-$n.log"; sort -n "$OUT/mem-$n.txt" | tail -1
done
nvidia-smi -q -d PERFORMANCE | grep -E "Thermal|Power Cap|Braking"
