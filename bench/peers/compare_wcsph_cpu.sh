#!/usr/bin/env bash
# weir's WCSPH against SPlisHSPlasH's on the CPU, per core: SPlisHSPlasH's DamBreakModel layout
# (a 1 m cube of water, 5 cm off the floor and the wall, in a 4 x 3 x 1.5 m box) at the same
# particle radius and OpenMP threads, both with Akinci et al. 2012 boundary particles. What is
# compared is the cost of a step per particle (particle-steps per second per core, from each code's
# own stepping time) and the wall seconds per simulated second; the codes choose their steps
# differently (weir: a speed of sound 10 times sqrt(2 g H); SPlisHSPlasH: its CFL step on the
# largest speed, at most 0.5 ms), so the second also says what each time step buys.
# weir runs twice: at SPlisHSPlasH's support (h = 2 d: its cubic kernel reaches 4 r = 2 d) and at
# its own default (h = 3 d).
# Usage: bash bench/peers/compare_wcsph_cpu.sh [radius] [duration] [threads] [out-dir]
# Needs a build (build/weir) and a Python with pysplishsplash and numpy (PYTHON=...; default
# build/python-env/bin/python; pip install pysplishsplash into it).
set -euo pipefail
source "$(dirname "$0")/peer_common.sh" wcsph 0.1 bench-out/wcsph-cpu-peers "$@"

d=$("$python" -c "print(2 * $radius)")
side=$("$python" -c "import math; n = math.floor(1 / (2 * $radius) + 1e-9) - 1; print(n * 2 * $radius)")
hi=$("$python" -c "print(0.05 + $side)")
hiz=$("$python" -c "print(0.25 + $side)")
for ratio in 2 3; do
    cat >"$out/dam_break_h$ratio.json" <<JSON
{"name": "splishsplash_dam_break", "solver": "wcsph",
 "container": {"min": [0, 0, 0], "max": [4, 3, 1.5]},
 "blocks": [{"min": [0.05, 0.05, 0.25], "max": [$hi, $hi, $hiz]}],
 "fluid": {"preset": "water"},
 "particles": {"spacing": $d, "smoothingRatio": $ratio},
 "time": {"duration": $duration, "frameRate": 30}}
JSON
    WEIR_FRAME_OUTPUT=off "$weir" run "$out/dam_break_h$ratio.json" --overwrite \
        -o "$out/weir-h$ratio" >"$out/weir-h$ratio.log" 2>&1
done

"$python" - "$out" "$threads" <<'PY'
import json, re, sys
out, threads = sys.argv[1], int(sys.argv[2])
splish = json.load(open(out + "/splishsplash.json"))
rows = []
for ratio in (2, 3):
    log = open(f"{out}/weir-h{ratio}.log").read()
    done = re.search(r"(\d+) steps in (\d+):(\d+)(?::(\d+))? \(([\d.]+) steps/s\)", log)
    steps, rate = int(done.group(1)), float(done.group(5))
    n = int(re.search(r"(\d+) particles", log).group(1))
    neighbours = re.search(r"([\d.]+) neighbours", log)
    rows.append((f"weir, h = {ratio} d", n, steps, steps / rate, neighbours.group(1) if neighbours else "?"))
rows.append(("SPlisHSPlasH", splish["particles"], splish["steps"], splish["steppingSeconds"], "~30"))
dur = splish["duration"]
summary = []
for name, n, steps, secs in ((r[0], r[1], r[2], r[3]) for r in rows):
    per_core = n * steps / secs / threads
    summary.append({"code": name, "particles": n, "steps": steps, "steppingSeconds": secs,
                    "particleStepsPerSecondPerCore": per_core, "wallSecondsPerSimulatedSecond": secs / dur})
    print(f"{name:18s} {n:7d} particles {steps:6d} steps {secs:8.1f} s stepping  "
          f"{per_core / 1e6:6.3f} M particle-steps/s per core  {secs / dur:8.1f} s per simulated s")
json.dump({"threads": threads, "duration": dur, "rows": summary}, open(out + "/summary.json", "w"), indent=1)
PY
