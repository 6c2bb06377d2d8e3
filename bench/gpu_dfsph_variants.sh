#!/usr/bin/env bash
# DFSPH settings compared on the device: the shipped dam break at one size, each variant a label,
# environment settings and a JSON merge patch of the scene; wall time, steps, sweeps a step and the
# density error of each (progress lines kept in $OUT/dfsph-variants/). Needs build-gpu.
# Usage: bash bench/gpu_dfsph_variants.sh N FRAMES "label|ENV=1 ENV2=2|{json patch}" ...
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")/dfsph-variants
mkdir -p "$out"
n=$1
frames=$2
shift 2
for variant in "$@"; do
    IFS='|' read -r label envs patch <<<"$variant"
    scene="$out/$label.json"
    python3 - "$patch" "$scene" <<'PY'
import json, sys
base = json.load(open("scenes/dam_break.json"))
def merge(a, b):
    for k, v in b.items():
        a[k] = merge(a.get(k, {}), v) if isinstance(v, dict) and isinstance(a.get(k), dict) else v
    return a
base = merge(base, json.loads(sys.argv[1] or "{}"))
base["name"] = "dam_break"
json.dump(base, open(sys.argv[2], "w"))
PY
    log="$out/$n-$label.log"
    start=$(date +%s%N)
    env $envs ./build-gpu/weir run "$scene" --particles "$n" --frames "$frames" --format ply \
        --overwrite -o "/tmp/variant-$label" >"$log" 2>&1
    end=$(date +%s%N)
    echo "wall $(((end - start) / 1000000)) ms" >>"$log"
    echo "== $n $label [$envs] $patch: $(grep -E "done|error" "$log" | tail -1 | cut -c1-160); $(tail -1 "$log")"
    grep -E "^frame" "$log" | sed -n '3p;$p' | sed 's/.*elapsed/  elapsed/' | cut -c1-200
done
