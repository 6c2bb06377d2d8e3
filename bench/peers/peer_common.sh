# What both CPU peer comparisons do first (sourced by compare_dfsph_cpu.sh and
# compare_wcsph_cpu.sh): their arguments, then SPlisHSPlasH's run of its DamBreakModel layout.
# Usage: source peer_common.sh METHOD DEFAULT_DURATION DEFAULT_OUT [radius] [duration] [threads] [out]
# Sets root, radius, duration, threads, out, python, weir; exports OMP_NUM_THREADS.
# REUSE_PEER=1 keeps an earlier run's SPlisHSPlasH results in the out-dir (to re-measure weir alone).
peer_method=$1
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
radius=${4:-0.0125}
duration=${5:-$2}
threads=${6:-2}
out=$(realpath -m "${7:-$3}")
python=${PYTHON:-$root/build/python-env/bin/python}
weir=${WEIR:-$root/build/weir}
mkdir -p "$out"
export OMP_NUM_THREADS=$threads

# SPlisHSPlasH (its wheel's bundled GL libraries clash with Debian's libGLX at import).
if [ -z "${REUSE_PEER:-}" ] || [ ! -f "$out/splishsplash.json" ]; then
    LD_PRELOAD=/lib/x86_64-linux-gnu/libGLdispatch.so.0 \
        "$python" "$root/bench/peers/splishsplash_dam_break.py" "$radius" "$duration" \
        "$out/splishsplash.json" "$peer_method" >"$out/splishsplash.log" 2>&1
fi
