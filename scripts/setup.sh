#!/usr/bin/env bash
# Installs what weir needs on Debian 12 / Ubuntu (if missing), then configures and builds it.
# Usage: scripts/setup.sh [build-dir]   (default: build). Safe to run again: it only adds.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}

packages=(cmake ninja-build g++ pkg-config libgtest-dev libbenchmark-dev nlohmann-json3-dev
          libcli11-dev
          # rendering (weir render / view, optional at build time): OpenGL through GLVND, EGL,
          # GLFW, libpng; Mesa's software renderer for machines without a GPU; Xvfb for the
          # window test; ffmpeg for videos
          libglfw3-dev libegl-dev libgl-dev libgl1-mesa-dri libegl-mesa0 libpng-dev xvfb xauth
          ffmpeg
          # distributed runs (mpirun -n R weir run): OpenMPI
          libopenmpi-dev openmpi-bin
          # the Python module (import weir): headers and venv; nanobind, NumPy, pytest and
          # matplotlib come from PyPI into a virtual environment (below)
          python3-dev python3-venv)
# Optional: OpenVDB output (--format vdb; docs/pipeline.md), whose CMake module needs
# Boost.Iostreams besides. A machine that cannot install them builds without it.
optional=(libopenvdb-dev libboost-iostreams-dev)
missingFrom() {
    local p
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
    done
}
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
mapfile -t missing < <(missingFrom "${packages[@]}")
if [ ${#missing[@]} -gt 0 ]; then
    echo "weir setup: installing ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
mapfile -t missing < <(missingFrom "${optional[@]}")
if [ ${#missing[@]} -gt 0 ]; then
    echo "weir setup: installing ${missing[*]} (optional: OpenVDB output)"
    if ! { $sudo apt-get update -qq &&
           DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null; }
    then
        echo "weir setup: could not install ${missing[*]}; building without OpenVDB"
    fi
fi
# Optional, for the tests only: Debian's Blender, which src/python/blender_test.py runs headless
# to load a weir run and render it in Cycles (docs/pipeline.md); the test skips without it. About
# 30 s and 420 MB (77 packages, none of them Python). WEIR_BLENDER=0 leaves it out.
if [ "${WEIR_BLENDER:-1}" != 0 ] && [ -n "$(missingFrom blender)" ]; then
    echo "weir setup: installing blender (optional: the Blender test)"
    if ! { $sudo apt-get update -qq &&
           DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq blender >/dev/null; }; then
        echo "weir setup: could not install blender; the Blender test will skip"
    fi
fi

# CUDA is optional: use nvcc if it is on PATH or in the usual place.
if ! command -v nvcc >/dev/null 2>&1 && [ -x /usr/local/cuda/bin/nvcc ]; then
    export PATH=/usr/local/cuda/bin:$PATH
fi
if command -v nvcc >/dev/null 2>&1; then
    echo "weir setup: CUDA backend with $(nvcc --version | tail -1)"
else
    echo "weir setup: no nvcc found, building the CPU backend only"
fi

# The Python module (src/python/, docs/python.md) builds against a virtual environment in the
# build folder, which holds what it needs from PyPI: nanobind (the bindings), NumPy, pytest and
# matplotlib (its tests and worked example), scikit-build-core (pip install .). A venv rather than
# pip --user: Debian 12's pip refuses to install into the system's Python (PEP 668).
# WEIR_PYTHON=0 builds without it.
python_args=()
if [ "${WEIR_PYTHON:-1}" != 0 ]; then
    venv=$build/python-env
    if [ ! -x "$venv/bin/python" ]; then
        mkdir -p "$build"
        python3 -m venv --system-site-packages "$venv"
    fi
    if ! "$venv/bin/python" -c "import nanobind, numpy, pytest, matplotlib, scikit_build_core" \
            2>/dev/null; then
        echo "weir setup: installing nanobind, numpy, pytest, matplotlib, scikit-build-core" \
             "into $venv"
        "$venv/bin/python" -m pip install -q --disable-pip-version-check \
            nanobind==3.1.0 numpy pytest matplotlib scikit-build-core
    fi
    # usd-core (Pixar's USD for Python) reads back the .usda stages weir writes, in the tests;
    # apart, so that a Python it has no wheel for only skips those tests.
    if ! "$venv/bin/python" -c "import pxr.Usd" 2>/dev/null; then
        echo "weir setup: installing usd-core into $venv"
        "$venv/bin/python" -m pip install -q --disable-pip-version-check usd-core ||
            echo "weir setup: usd-core is not available here; the USD read-back test will skip"
    fi
    python_args=(-DPython_EXECUTABLE="$venv/bin/python")
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        ${python_args[@]+"${python_args[@]}"}
elif [ ${#python_args[@]} -gt 0 ] &&
        ! grep -q "^Python_EXECUTABLE:[A-Z]*=$venv/bin/python\$" "$build/CMakeCache.txt"; then
    cmake "$build" "${python_args[@]}" >/dev/null  # a build folder from before the module
fi
cmake --build "$build" -j "$(nproc)"

# Install the binary so that `weir` is on PATH: into /usr/local/bin as root (or with sudo that
# needs no password), else into ~/.local/bin; WEIR_PREFIX=DIR installs into DIR/bin instead.
install_with=()
if [ -n "${WEIR_PREFIX:-}" ]; then
    prefix=$WEIR_PREFIX
elif [ "$(id -u)" -eq 0 ]; then
    prefix=/usr/local
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    prefix=/usr/local
    install_with=(sudo)
else
    prefix=$HOME/.local
fi
${install_with[@]+"${install_with[@]}"} cmake --install "$build" --prefix "$prefix" >/dev/null
echo "weir setup: installed $prefix/bin/weir"
case ":$PATH:" in
    *":$prefix/bin:"*) ;;
    *) echo "weir setup: $prefix/bin is not on PATH; add it, e.g. in ~/.bashrc:" \
            "export PATH=\"$prefix/bin:\$PATH\"" ;;
esac
