#!/usr/bin/env bash
# Rendering on a GPU machine that has the NVIDIA driver but no OpenGL userland (the lent Ubuntu
# 24.04 H100/H200 machines): unpacks the .deb files of .gl/ (scripts/fetch_gl_runtime.sh), then
# times, with the GPU simulation's frames of the dam break at 100k and 1M particles:
#   weir render (particles, 1280x720, EGL on the NVIDIA driver), weir render --surface,
#   weir mesh --backend cuda (and cpu at 100k), weir render --look water (WATER_SAMPLES paths per
#   pixel, default 64), and weir view under Xvfb (GLX on NVIDIA; VIEW_FRAMES=0 leaves it out).
# Prints a summary table; $OUT (default ./gpu-render-out) gets summary.txt, logs.tar.gz and a few
# images. Every step has a time limit and a failure does not stop the others: about 2-4 minutes
# on an H100.
#
# Usage, from the repository root, with .gl/ and build-kit/weir carried:
#   bash bench/gpu_render.sh
# Environment: WEIR (binary, default build-kit/weir), BACKEND (cuda), SIZES (particles:frames,
#   default "100000:5 1000000:3"), VIEW_FRAMES (300), BUDGET (450 s in all), GL_ROOT
#   (/opt/weir-gl), WORK (/tmp/weir-gpu-render: frames, images, meshes; only logs come back).
#
# What goes where: GLVND's loaders (libglvnd0 libegl1 libopengl0 libgl1 libglx0 libgles2) are
# unpacked into / as the device README says; every other package into $GL_ROOT, whose library
# folders come after the system's in /etc/ld.so.conf.d/zz-weir-gl.conf, so no library of the
# machine is replaced. Xvfb finds swrast_dri.so and xkbcomp only at its built-in paths
# (/usr/lib/x86_64-linux-gnu/dri, /usr/bin): those two get symbolic links where nothing is.
set -uo pipefail
weir=${WEIR:-build-kit/weir}
sizes=${SIZES:-100000:5 1000000:3}
view_frames=${VIEW_FRAMES:-300}
backend=${BACKEND:-cuda}  # cpu only to try the script on a machine without a GPU
budget=${BUDGET:-450}  # seconds for the whole script: later steps are cut short or skipped
R=${GL_ROOT:-/opt/weir-gl}
work=${WORK:-/tmp/weir-gpu-render}
out=$(realpath -m "${OUT:-gpu-render-out}")
logs=$work/logs
rm -rf "$work"
mkdir -p "$out" "$logs"
summary=$out/summary.txt
: >"$summary"
say() { echo "$*" | tee -a "$summary"; }
rows=()
row() { rows+=("$(printf '%-44s %s' "$1" "$2")"); say "  -> $1: $2"; }
now() { date +%s.%N; }
ms_per() { awk -v a="$1" -v b="$2" -v n="$3" 'BEGIN { if (n > 0) printf "%.0f", (b - a) * 1000 / n; else print "?" }'; }

# --- 0. the machine --------------------------------------------------------------------------
say "== machine"
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>&1 | tee -a "$summary"
grep PRETTY_NAME /etc/os-release | tee -a "$summary"

# --- 1. unpack ---------------------------------------------------------------------------------
say "== unpacking .gl ($(ls .gl/*.deb 2>/dev/null | wc -l) packages)"
loaders=" libglvnd0 libegl1 libopengl0 libgl1 libglx0 libgles2 "
mkdir -p "$R"
for f in .gl/*.deb; do
    name=$(basename "$f"); name=${name%%_*}
    if [[ "$loaders" == *" $name "* ]]; then dpkg -x "$f" /; else dpkg -x "$f" "$R"; fi
done
{
    echo "$R/usr/lib/x86_64-linux-gnu"
    echo "$R/lib/x86_64-linux-gnu"
    echo "$R/usr/lib/x86_64-linux-gnu/weir-gl-stubs"  # empty libz3/libxml2 for LLVM, last
} >/etc/ld.so.conf.d/zz-weir-gl.conf
# The NVIDIA driver's GL libraries, if they are not on the loader's path yet.
for lib in libEGL_nvidia.so.0 libGLX_nvidia.so.0; do
    if ! ldconfig -p | grep -q "$lib"; then
        found=$(find /usr/local/nvidia /usr/lib /usr/lib64 -name "$lib" 2>/dev/null | head -1)
        [ -n "$found" ] && dirname "$found" >>/etc/ld.so.conf.d/zz-weir-gl.conf
    fi
done
ldconfig
ldconfig -p | grep -E "libEGL_nvidia|libGLX_nvidia|libEGL.so.1|libGL.so.1|libglfw" | tee -a "$summary"
if [ -e "$R/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so" ] &&
   [ ! -e /usr/lib/x86_64-linux-gnu/dri/swrast_dri.so ]; then
    mkdir -p /usr/lib/x86_64-linux-gnu/dri
    ln -s "$R/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so" /usr/lib/x86_64-linux-gnu/dri/
fi
[ -e /usr/bin/xkbcomp ] || ln -s "$R/usr/bin/xkbcomp" /usr/bin/xkbcomp
# EGL vendor: the driver's JSON, when GLVND's own folders hold none for NVIDIA.
if ! grep -qs nvidia /usr/share/glvnd/egl_vendor.d/*.json /etc/glvnd/egl_vendor.d/*.json; then
    json=$(find /usr/local/nvidia /usr/share /etc -name '10_nvidia.json' -path '*egl_vendor.d*' \
           2>/dev/null | head -1)
    [ -n "$json" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$json
fi
say "__EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-(unset: the GLVND folders)}"

# --- 2. the binary -----------------------------------------------------------------------------
say "== ldd $weir"
ldd "$weir" 2>&1 | tee "$logs/ldd-weir.txt" | tee -a "$summary"
if ldd "$weir" | grep -q "not found"; then say "!! weir misses libraries (above)"; fi
timeout 60 "$weir" info >"$logs/info.txt" 2>&1; tail -15 "$logs/info.txt" | tee -a "$summary"

# step NAME LIMIT CMD...: runs CMD with a time limit, its output in $logs/NAME.log; sets $t0 $t1
# and $rc, and says how it ended.
step() {
    local name=$1 limit=$2; shift 2
    echo ">> $*" >"$logs/$name.log"
    local left=$((budget - SECONDS))
    if [ "$left" -lt 10 ]; then
        rc=125 t0=0 t1=0
        say "-- $name: skipped, the script's $budget s are spent"
        return 0
    fi
    [ "$limit" -gt "$left" ] && limit=$left
    t0=$(now)
    timeout -k 5 "$limit" "$@" >>"$logs/$name.log" 2>&1
    rc=$?
    t1=$(now)
    say "-- $name: rc=$rc, $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s: $*"
    [ $rc -eq 124 ] && say "   (timed out after $limit s)"
    grep -E "^weir: (rendering|viewing|view closed|error)|GLFW error|BLEW UP" "$logs/$name.log" |
        head -4 | sed 's/^/   /' | tee -a "$summary"
    [ $rc -ne 0 ] && tail -5 "$logs/$name.log" | sed 's/^/   | /' | tee -a "$summary"
    return 0
}
# weir's own figure from its closing line: "; weir: 319 ms per image to draw and write".
own() {
    local figure
    figure=$(grep -oE "[0-9]+ ms per (image|mesh)[^)]*" "$logs/$1.log" | head -1 |
             sed -E 's/, [0-9:]+ in all//')
    [ -n "$figure" ] && echo "; weir: $figure"
}
count() { find "$1" -maxdepth 1 -name "*$2" 2>/dev/null | wc -l; }

# --- 3. simulate, render, mesh -----------------------------------------------------------------
for size in $sizes; do
    n=${size%%:*}; frames=${size##*:}; d=$work/r$n
    say "== $n particles, $frames frames"
    step "run-$n" 240 "$weir" run dam_break --backend "$backend" --particles "$n" --frames "$frames" \
        --format ply -q -o "$d"
    written=$(count "$d" .ply)
    row "run $n ($backend, $written frames)" "$(ms_per "$t0" "$t1" "$written") ms/frame wall (incl. setup)"
    [ "$written" -gt 0 ] || continue

    step "render-$n" 120 "$weir" render "$d" --scene dam_break -o "$d/images"
    k=$(count "$d/images" .png)
    row "render $n 1280x720 particles ($k img)" "$(ms_per "$t0" "$t1" "$k") ms/image$(own "render-$n")"
    step "render-surface-$n" 180 "$weir" render "$d" --scene dam_break --surface --backend "$backend" \
        -o "$d/surface"
    k=$(count "$d/surface" .png)
    row "render --surface $n, $backend ($k img)" "$(ms_per "$t0" "$t1" "$k") ms/image$(own "render-surface-$n")"
    step "mesh-cuda-$n" 180 "$weir" mesh "$d" --backend "$backend" --format ply -q -o "$d/mesh-cuda"
    k=$(count "$d/mesh-cuda" .ply)
    row "mesh $n $backend, ply ($k frames)" "$(ms_per "$t0" "$t1" "$k") ms/frame$(own "mesh-cuda-$n")"
    # The water look (path traced on the backend, no OpenGL), WATER_SAMPLES paths per pixel.
    step "render-water-$n" 240 "$weir" render "$d" --scene dam_break --look water \
        --backend "$backend" --samples "${WATER_SAMPLES:-64}" -o "$d/water"
    k=$(count "$d/water" .png)
    row "render --look water $n, $backend, ${WATER_SAMPLES:-64} paths ($k img)" "$(ms_per "$t0" "$t1" "$k") ms/image$(own "render-water-$n")"
    cp "$d/water/$(ls "$d/water" 2>/dev/null | tail -1)" "$out/water.png" 2>/dev/null
    if [ "$n" -le 100000 ]; then
        step "mesh-cpu-$n" 180 "$weir" mesh "$d" --backend cpu --format ply -q -o "$d/mesh-cpu"
        k=$(count "$d/mesh-cpu" .ply)
        row "mesh $n cpu ($(nproc) cores), ply ($k frames)" "$(ms_per "$t0" "$t1" "$k") ms/frame$(own "mesh-cpu-$n")"
    fi
    # The last frame of each image kind comes back, of the largest size that got there ($OUT
    # takes at most 8 files).
    cp "$d/images/$(ls "$d/images" 2>/dev/null | tail -1)" "$out/render.png" 2>/dev/null
    cp "$d/surface/$(ls "$d/surface" 2>/dev/null | tail -1)" "$out/surface.png" 2>/dev/null
done

# --- 4. weir view under Xvfb -------------------------------------------------------------------
say "== weir view under Xvfb"
xvfb_ok=0
if [ "$view_frames" -gt 0 ] && [ -x "$R/usr/bin/Xvfb" ]; then
    ldd "$R/usr/bin/Xvfb" | grep "not found" | sed 's/^/   Xvfb: /' | tee -a "$summary"
    "$R/usr/bin/Xvfb" :99 -screen 0 1920x1080x24 -nolisten tcp -xkbdir "$R/usr/share/X11/xkb" \
        >"$logs/xvfb.log" 2>&1 &
    xvfb_pid=$!
    for _ in $(seq 50); do
        [ -e /tmp/.X11-unix/X99 ] && { xvfb_ok=1; break; }
        kill -0 "$xvfb_pid" 2>/dev/null || break
        sleep 0.2
    done
    grep -E "GLX|EE|rror" "$logs/xvfb.log" | head -6 | sed 's/^/   xvfb: /' | tee -a "$summary"
else
    say "!! no Xvfb in .gl (run scripts/fetch_gl_runtime.sh)"
fi
view() {  # view NAME VENDOR N FRAMES
    DISPLAY=:99 __GLX_VENDOR_LIBRARY_NAME=$2 step "$1" 150 "$weir" view dam_break \
        --backend "$backend" --particles "$3" --max-frames "$4" --screenshot "$work/$1.png"
    line=$(grep "view closed after" "$logs/$1.log" | head -1)
    fps=$(echo "$line" | grep -oE '[0-9.]+ frames/s' | head -1)
    renderer=$(sed -n 's/.*drawn by \(.*\), particles by.*/\1/p' "$logs/$1.log" | head -1)
    row "view $3 GLX $2 ($4 frames)" "${fps:-failed (rc=$rc)}${renderer:+ [$renderer]}"
    if [ -n "$renderer" ] && [ "$2" = nvidia ] && [[ "$renderer" != *NVIDIA* ]]; then
        say "   !! GLX did not draw on the NVIDIA driver (GLVND fell back to the server's vendor)"
    fi
    [ -n "$line" ] && say "   ${line#*last lines: }"
    grep -oE "particles by [^)]*\)?" "$logs/$1.log" | head -1 | sed 's/^/   /' | tee -a "$summary"
    cp "$work/$1.png" "$out/$1.png" 2>/dev/null
}
if [ "$view_frames" -le 0 ]; then
    say "   (VIEW_FRAMES=0: not measured)"
elif [ $xvfb_ok = 1 ]; then
    first=""
    for size in $sizes; do
        n=${size%%:*}
        first=${first:-$n}
        view "view-$n-nvidia" nvidia "$n" "$view_frames"
        # Drawing on the CPU (llvmpipe) would take minutes for 300 frames of 1M particles.
        grep -q "drawn by NVIDIA" "$logs/view-$n-nvidia.log" || view_frames=30
    done
    if ! grep -q "view closed after" "$logs/view-$first-nvidia.log"; then
        say "   GLX on NVIDIA failed; Mesa's GLX (llvmpipe: drawing on the CPU) to compare:"
        view "view-$first-mesa" mesa "$first" 60
    fi
    kill "$xvfb_pid" 2>/dev/null
else
    say "!! Xvfb did not start: weir view not measured (see xvfb.log in logs.tar.gz)"
    tail -5 "$logs/xvfb.log" 2>/dev/null | sed 's/^/   | /' | tee -a "$summary"
fi

# --- 5. summary --------------------------------------------------------------------------------
say ""
say "== summary ($(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1))"
for r in "${rows[@]}"; do say "$r"; done
say "(render: wall time of the whole command over its images: frame reading, drawing, PNG"
say " writing; mesh: including the PLY files; view: frames/s of weir's own count)"
tar -czf "$out/logs.tar.gz" -C "$work" logs
