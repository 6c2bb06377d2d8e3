#!/usr/bin/env bash
# What writing frames costs a run (issue 17): the same `weir run` with frames written in the
# background (the default), in the foreground (WEIR_FRAME_OUTPUT=foreground, as before issue 17)
# and not at all (WEIR_FRAME_OUTPUT=off), REPEATS times each in turn; prints each run's wall time
# and the run's own account of downloading and writing, then the median of each and the ratios to
# frames off. Then dd writes as many bytes as one run's frames into the same folder, through the
# page cache and to the disk (fdatasync), for the disk's speed beside the writer's.
# Usage: bash bench/frame_output.sh WEIR REPEATS [weir run arguments...]
#   e.g. bash bench/frame_output.sh build-gpu/weir 3 dam_break --particles 1000000 --frames 30
# OUTDIR (default /tmp/weir-frame-output) is where the frames go.
set -euo pipefail
weir=$(realpath "$1")
repeats=$2
shift 2
dir=${OUTDIR:-/tmp/weir-frame-output}
mkdir -p "$dir"
declare -A walls
for ((r = 1; r <= repeats; ++r)); do
    for mode in off foreground background; do
        rm -rf "$dir/$mode"
        start=$(date +%s.%N)
        WEIR_FRAME_OUTPUT=$mode "$weir" run "$@" --quiet --out "$dir/$mode" >"$dir/$mode.log" 2>&1 ||
            { cat "$dir/$mode.log"; exit 1; }
        wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}')
        walls[$mode]+="$wall "
        printf '%-10s run %d: %6.2f s wall; %s\n' "$mode" "$r" "$wall" \
            "$(grep -E '^weir: (done|frames downloaded)' "$dir/$mode.log" | tr '\n' ' ')"
    done
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
off=$(echo "${walls[off]}" | median)
for mode in off foreground background; do
    m=$(echo "${walls[$mode]}" | median)
    printf 'median %-10s %6.2f s  (%.3f x frames off)\n' "$mode" "$m" \
        "$(awk -v a="$m" -v b="$off" 'BEGIN {print a / b}')"
done
bytes=$(du -sb "$dir/background" | cut -f1)
mb=$(( (bytes + 1048575) / 1048576 ))
echo "one run's frames: $bytes bytes; dd of $mb MiB into $dir:"
dd if=/dev/zero of="$dir/dd.bin" bs=1M count="$mb" 2>&1 | tail -1 | sed 's/^/  page cache: /'
dd if=/dev/zero of="$dir/dd.bin" bs=1M count="$mb" conv=fdatasync 2>&1 | tail -1 |
    sed 's/^/  fdatasync:  /'
rm -f "$dir/dd.bin"
