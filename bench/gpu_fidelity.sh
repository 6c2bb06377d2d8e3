#!/usr/bin/env bash
# The fidelity checks of issue 14 on a GPU at converged resolutions: weir validate (delta-SPH, the
# default model) over resolution ladders, each case's results and plots under $OUT/validate-*.
# Expects build-gpu/ from bench/gpu_run.sh (PARTS=build). Usage: bash bench/gpu_fidelity.sh
# [cases], cases a comma list of tgv, hydrostatic, dam-break, lobovsky, viscous, channels.
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
cases=",${1:-tgv,hydrostatic,dam-break,lobovsky},"
has() { [[ "$cases" == *",$1,"* ]]; }
weir=./build-gpu/weir
mkdir -p "$out"
validate() {  # name, then weir validate's options
    local name=$1
    shift
    echo "== validate $name: $*"
    "$weir" validate --backend cuda --no-plot -o "$out/validate-$name" "$@" 2>&1 |
        tee "$out/validate-$name.txt" | grep -E "PASS|FAIL|error|front|decay|particles"
}
has tgv && validate taylor-green --cases taylor-green --taylor-green-resolution 32,64,128,256
has hydrostatic && validate hydrostatic --cases hydrostatic --tank-resolution 48
has dam-break && validate dam-break --cases dam-break --column-resolution 20,40,80,160
has lobovsky && for r in 30 60; do validate "lobovsky-$r" --cases lobovsky --lobovsky-resolution "$r"; done
has viscous && validate viscous --cases viscous --column-resolution 40
has channels && validate channels --cases channels --channel-resolution 40
nvidia-smi -q -d PERFORMANCE | grep -A12 "Clocks Event Reasons" >"$out/throttle.txt" 2>&1
true
