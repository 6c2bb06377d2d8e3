#!/usr/bin/env bash
# Device call 3 (2026-12-04): build; then side by side: every GPU test, and weir validate at the
# converged resolutions with Monaghan's tensile correction (Lobovsky 30-240, tank 48, Martin &
# Moyce 20-160, viscous, channels 40, Taylor-Green 32-128).
set -u
OUT0=$OUT
export OUT=/tmp/res3
rm -rf "$OUT"; mkdir -p "$OUT"
start=$(date +%s)
PARTS="build" TARGETS="weir weir_tests" bash bench/gpu_waves.sh > "$OUT/build.log" 2>&1 || { tail -40 "$OUT/build.log"; tar czf "$OUT0/res.tgz" -C /tmp res3; exit 1; }
echo "built in $(( $(date +%s) - start )) s"
(PARTS="test" TEST_TIMEOUT=420 bash bench/gpu_waves.sh > "$OUT/test-part.log" 2>&1) &
(PARTS="validate" VALIDATE_TIMEOUT=400 OUT=$OUT/lob VALIDATIONS=$'lobovsky-240|--cases lobovsky --lobovsky-resolution 240\nlobovsky-120|--cases lobovsky --lobovsky-resolution 120\nlobovsky-60|--cases lobovsky --lobovsky-resolution 60\nlobovsky-30|--cases lobovsky --lobovsky-resolution 30' bash bench/gpu_waves.sh > "$OUT/lob-part.log" 2>&1) &
(PARTS="validate" VALIDATE_TIMEOUT=400 OUT=$OUT/rest VALIDATIONS=$'hydro|--cases hydrostatic --tank-resolution 48\ndam-break|--cases dam-break --column-resolution 20,40,80,160\nviscous|--cases viscous --column-resolution 40\nchannels|--cases channels --channel-resolution 40\ntgv|--cases taylor-green --taylor-green-resolution 32,64,128' bash bench/gpu_waves.sh > "$OUT/rest-part.log" 2>&1) &
wait
echo "all done at $(( $(date +%s) - start )) s"
cat "$OUT/test-part.log" "$OUT/lob-part.log" "$OUT/rest-part.log" | grep -v "Clocks\|Counters\|: 0 us\|Sparse\|^name\|^NVIDIA"
find "$OUT" -name "*.vtu" -delete
tar czf "$OUT0/res.tgz" -C /tmp res3
ls -la "$OUT0"
