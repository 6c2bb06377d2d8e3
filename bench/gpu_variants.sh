#!/usr/bin/env bash
# A/B timing of speed experiments in one device call: `weir bench` of the dense GPU step once
# per variant (a name and the environment it runs under), then the GPU reference step at the
# same sizes, side by side. Results go to $OUT/variants.txt (one line per variant and size) and
# $OUT/variants.tgz (every bench.json).
# Usage: bash bench/gpu_variants.sh SIZES "name:VAR=1,VAR2=2" "name2:" ...   (after a build)
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
sizes=$1
shift
work=/tmp/weir-variants
rm -rf "$work" && mkdir -p "$work" "$out"
for variant in "$@"; do
    name=${variant%%:*}
    settings=${variant#*:}
    (
        IFS=','
        for setting in $settings; do
            [ -n "$setting" ] && export "${setting?}"
        done
        ./build-gpu/weir bench --backends cuda-dense --sizes "$sizes" --steps 30 --no-plot \
            --no-render -o "$work/$name" >"$work/$name.log" 2>&1
    )
    python3 - "$work/$name/bench.json" "$name" <<'EOF' | tee -a "$out/variants.txt"
import json, sys
runs = json.load(open(sys.argv[1]))["runs"]
for run in runs:
    col = run["columns"]["cuda-dense"]
    stages = " ".join(f"{k} {v:.4f}" for k, v in sorted(col["stages"].items()))
    print(f"{sys.argv[2]:>12} {run['particles']:>10} step {col['stepMs']:.4f} ms ({stages})")
EOF
done
if [ -d .device/gpu-reference ]; then
    counts=$(python3 -c "
import sys
m = {'k': 1000, 'M': 1000000}
print(' '.join(str(int(float(s[:-1]) * m[s[-1]]) if s[-1] in m else int(s)) for s in sys.argv[1].split(',')))" "$sizes")
    bash .device/gpu-reference/run.sh $counts 2>&1 | tee "$out/reference.txt"
fi
tar czf "$out/variants.tgz" -C "$work" .
