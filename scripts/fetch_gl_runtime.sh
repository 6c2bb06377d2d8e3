#!/usr/bin/env bash
# Downloads into .gl/ (git-ignored) the amd64 .deb files that a GPU machine without any OpenGL
# userland (no GLVND loaders, no GLFW, no X server: e.g. the lent Ubuntu 24.04 H100/H200
# machines) needs at RUN time for `weir render` (EGL offscreen on the NVIDIA driver) and for
# `weir view` under Xvfb (GLX with __GLX_VENDOR_LIBRARY_NAME=nvidia). bench/gpu_render.sh unpacks
# them there. Run it on a Debian 12 (bookworm) amd64 machine with apt, e.g. the one that builds
# weir; it does not install anything here.
#
# Usage: scripts/fetch_gl_runtime.sh [--no-mesa]
#   --no-mesa  leave out Mesa's software DRI driver (about 30 MiB of the 40): Xvfb then has no
#              GLX provider of its own and `weir view` will probably not open a window.
#
# Groups (bench/gpu_render.sh decides by file name where each goes):
#   loaders  GLVND's libEGL/libOpenGL/libGL/libGLX/libGLESv2: unpacked into / (the machine has
#            none; the NVIDIA driver's vendor libraries plug into them)
#   the rest unpacked into a private root (/opt/weir-gl), found through an ld.so.conf entry that
#            comes after the system's, so no library of the machine is replaced:
#            GLFW and the X11 client libraries it loads; Xvfb with xkbcomp, the XKB data and its
#            libraries; Mesa's swrast_dri.so (Xvfb's own GLX provider, which the GLX visuals and
#            fbconfigs come from) with LLVM 15; Mesa's GLX client (a fallback renderer).
#   stubs    weir-gl-stubs_*.deb, built here: empty libz3.so.4 and libxml2.so.2 that only satisfy
#            libLLVM-15's links (Mesa never calls Z3 or libxml2), saving 17 MiB of Z3 and ICU.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dest=$root/.gl
mesa=1
[ "${1:-}" = "--no-mesa" ] && mesa=0

loaders=(libglvnd0 libegl1 libopengl0 libgl1 libglx0 libgles2)
# GLFW 3.3 links libX11 and dlopens Xrandr, Xinerama, Xcursor, Xi, X11-xcb, Xrender, Xxf86vm.
glfw=(libglfw3 libx11-6 libx11-data libxcb1 libxau6 libxdmcp6 libbsd0 libmd0 libxext6 libxrandr2
      libxrender1 libxcursor1 libxfixes3 libxinerama1 libxi6 libx11-xcb1 libxxf86vm1)
# Xvfb (xserver-common is left out: it is 2.3 MiB of changelog; Xvfb starts without it).
# libaudit1, libgcrypt20, libselinux1, libsystemd0 are in every Ubuntu base image.
xvfb=(xvfb x11-xkb-utils xkb-data libxkbfile1 libxfont2 libfontenc1 libfreetype6 libbrotli1
      libpixman-1-0 libunwind8 libxshmfence1)
mesa_pkgs=(libgl1-mesa-dri libllvm15 libglapi-mesa libdrm2 libdrm-common libdrm-amdgpu1
           libdrm-intel1 libdrm-nouveau2 libdrm-radeon1 libpciaccess0 libsensors5 libelf1 libedit2
           libxcb-dri3-0
           # Mesa's GLX client: only for the fallback run with __GLX_VENDOR_LIBRARY_NAME=mesa
           libglx-mesa0 libxcb-dri2-0 libxcb-glx0 libxcb-present0 libxcb-randr0 libxcb-shm0
           libxcb-sync1 libxcb-xfixes0)
packages=("${loaders[@]}" "${glfw[@]}" "${xvfb[@]}")
[ "$mesa" = 1 ] && packages+=("${mesa_pkgs[@]}")

rm -rf "$dest"
mkdir -p "$dest" /tmp/amd64/partial
o=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64)
apt-get "${o[@]}" update -qq
(cd "$dest" && apt-get "${o[@]}" download "${packages[@]}" 2>&1 | grep -v "unsandboxed" || true)
missing=()
for p in "${packages[@]}"; do
    compgen -G "$dest/${p}_*.deb" >/dev/null || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "fetch_gl_runtime: could not download: ${missing[*]}" >&2
    exit 1
fi

if [ "$mesa" = 1 ]; then
    # Stub libraries for libLLVM-15's NEEDED entries that Mesa never uses: every undefined Z3_*
    # and xml* symbol of libLLVM as an empty function, with libxml2's symbol versions.
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    dpkg -x "$dest"/libllvm15_*.deb "$work/llvm"
    undefined=$(objdump -T "$work"/llvm/usr/lib/x86_64-linux-gnu/libLLVM-15.so.1 | grep '\*UND\*')
    pkg=$work/pkg
    mkdir -p "$pkg/DEBIAN" "$pkg/usr/lib/x86_64-linux-gnu/weir-gl-stubs"
    lib=$pkg/usr/lib/x86_64-linux-gnu/weir-gl-stubs
    echo "$undefined" | awk '{print $NF}' | grep '^Z3_' | sort -u |
        sed 's/.*/void* &(void) { return 0; }/' >"$work/z3.c"
    gcc -shared -fPIC -O1 -Wl,-soname,libz3.so.4 -o "$lib/libz3.so.4" "$work/z3.c"
    echo "$undefined" | grep -E '\(LIBXML2_[0-9.]+\) +xml' | sed -E 's/.*\((LIBXML2_[0-9.]+)\) +(xml[A-Za-z0-9_]+).*/\1 \2/' |
        sort -u >"$work/xml.txt"
    awk '{print "void* " $2 "(void) { return 0; }"}' "$work/xml.txt" >"$work/xml.c"
    # Version nodes in order, each inheriting the previous one, as libxml2 defines them.
    prev=""
    for node in $(awk '{print $1}' "$work/xml.txt" | sort -u -V); do
        echo "$node {"
        echo "  global:"
        awk -v n="$node" '$1 == n {print "    " $2 ";"}' "$work/xml.txt"
        [ -z "$prev" ] && echo "  local: *;"
        echo "}${prev:+ $prev};"
        prev=$node
    done >"$work/xml.map"
    gcc -shared -fPIC -O1 -Wl,-soname,libxml2.so.2 -Wl,--version-script="$work/xml.map" \
        -o "$lib/libxml2.so.2" "$work/xml.c"
    cat >"$pkg/DEBIAN/control" <<EOF
Package: weir-gl-stubs
Version: 1.0
Architecture: amd64
Maintainer: weir
Description: empty libz3.so.4 and libxml2.so.2 for libLLVM-15's links (see scripts/fetch_gl_runtime.sh)
EOF
    dpkg-deb --root-owner-group -Zxz --build "$pkg" "$dest/weir-gl-stubs_1.0_amd64.deb" >/dev/null
fi

echo "fetch_gl_runtime: $(ls "$dest" | wc -l) packages, $(du -sh "$dest" | cut -f1) in $dest"
