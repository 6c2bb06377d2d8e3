#!/usr/bin/env bash
# weir's DFSPH against SPlisHSPlasH's on the CPU: SPlisHSPlasH's DamBreakModel layout (a cube of
# water, 5 cm off the floor and the wall, in a 4 x 3 x 1.5 m box) at the same particle radius, the
# same tolerances (mean density error 0.01%, divergence 0.1%), the same OpenMP threads; each
# frame's mean and largest compression measured the same way from the particles' densities, the
# steps, and the wall seconds per simulated second.
# Usage: bash bench/peers/compare_dfsph_cpu.sh [radius] [duration] [threads] [out-dir]
# Needs a build (build/weir) and a Python with pysplishsplash and numpy (PYTHON=...; default
# build/python-env/bin/python, which scripts/setup.sh makes; pip install pysplishsplash into it).
set -euo pipefail
source "$(dirname "$0")/peer_common.sh" dfsph 0.5 bench-out/dfsph-cpu-peers "$@"

# weir, the same layout: the cube's side a whole number of spacings (SPlisHSPlasH seeds
# floor(1 m / 2r) - 1 a side), shifted into weir's box at the origin.
d=$("$python" -c "print(2 * $radius)")
side=$("$python" -c "import math; n = math.floor(1 / (2 * $radius) + 1e-9) - 1; print(n * 2 * $radius)")
cat >"$out/dam_break.json" <<JSON
{"name": "splishsplash_dam_break", "solver": "dfsph",
 "container": {"min": [0, 0, 0], "max": [4, 3, 1.5]},
 "blocks": [{"min": [0.05, 0.05, 0.25], "max": [$("$python" -c "print(0.05 + $side)"), $("$python" -c "print(0.05 + $side)"), $("$python" -c "print(0.25 + $side)")]}],
 "fluid": {"preset": "water"},
 "particles": {"spacing": $d},
 "dfsph": {"densityError": 0.01, "divergenceError": 0.1},
 "time": {"duration": $duration, "frameRate": 30}}
JSON
start=$(date +%s.%N)
"$weir" run "$out/dam_break.json" --format ply --overwrite -o "$out/weir-frames" \
    >"$out/weir.log" 2>&1
end=$(date +%s.%N)

"$python" - "$out" "$start" "$end" <<'PY'
import glob, json, re, sys
import numpy as np
out, start, end = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
def read(path):
    with open(path, 'rb') as f:
        names, n = [], 0
        while True:
            line = f.readline().decode().strip()
            if line.startswith('element vertex'): n = int(line.split()[-1])
            if line.startswith('property'): names.append((line.split()[1], line.split()[-1]))
            if line == 'end_header': break
        dtype = [(name, '<f4' if kind == 'float' else '<i4') for kind, name in names]
        return np.frombuffer(f.read(), dtype=dtype, count=n)
frames = []
for path in sorted(glob.glob(out + "/weir-frames/frame_*.ply"))[1:]:
    p = read(path)
    excess = np.maximum(p['density'] / 998.0 - 1, 0)
    frames.append({"meanCompression": float(excess.mean()), "maxCompression": float(excess.max())})
log = open(out + "/weir.log").read()
steps = int(re.search(r"(\d+) steps in", log).group(1))
sweeps = re.findall(r"density solve ([\d.]+) sweeps a step", log)
splish = json.load(open(out + "/splishsplash.json"))
slog = open(out + "/splishsplash.log").read()
its = re.search(r"Average number: DFSPH - iterations: ([\d.]+)", slog)
itsv = re.search(r"Average number: DFSPH - iterationsV: ([\d.]+)", slog)
weir = {"code": "weir", "particles": int(len(read(sorted(glob.glob(out + "/weir-frames/frame_*.ply"))[0]))),
        "steps": steps, "wallSeconds": end - start, "frames": frames,
        "densitySweepsPerStepByFrame": [float(s) for s in sweeps]}
summary = {"weir": weir, "splishsplash": splish,
           "splishsplashIterations": float(its.group(1)) if its else None,
           "splishsplashIterationsV": float(itsv.group(1)) if itsv else None}
json.dump(summary, open(out + "/summary.json", "w"), indent=1)
dur = splish["duration"]
for name, r, secs in (("weir", weir, weir["wallSeconds"]), ("SPlisHSPlasH", splish, splish["steppingSeconds"])):
    mean = max(f["meanCompression"] for f in r["frames"]) * 100
    peak = max(f["maxCompression"] for f in r["frames"]) * 100
    print(f"{name:13s} {r['particles']:7d} particles  {r['steps']:5d} steps  {secs:8.1f} s wall  "
          f"{secs / dur:8.1f} s per simulated s  worst frame: mean compression {mean:.4f}%, "
          f"largest {peak:.3f}%")
print(f"SPlisHSPlasH sweeps a step: density {summary['splishsplashIterations']}, divergence {summary['splishsplashIterationsV']}")
print(f"weir density sweeps a step by frame: {weir['densitySweepsPerStepByFrame']}")
PY
