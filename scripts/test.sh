#!/usr/bin/env bash
# Sets up and builds weir, then runs the whole test suite through CTest.
# CUDA tests skip themselves where no GPU is visible.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
cd "$root/build"
# Tests run side by side, each with OpenMP threads on every core: threads that spin at barriers
# would then wait for descheduled ones (a step can take 10x longer), so waiting threads sleep.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
ctest --output-on-failure -j "$(nproc)" "$@"

# The Python module's tests (src/python/*_test.py, pytest): the module as built in the build
# folder (build/python/weir), compared with the weir binary beside it; the CUDA and DLPack-on-GPU
# tests skip without a GPU. CI does not also run `pip install .` or `pip wheel .`: scikit-build-core
# builds in a folder of its own, which would compile the engine a second time (several minutes of
# CI's two cores), for the same CMake target that is built and tested here.
if [ "${WEIR_PYTHON:-1}" != 0 ]; then
    PYTHONPATH="$root/build/python" WEIR_BINARY="$root/build/weir" \
        "$root/build/python-env/bin/python" -m pytest -q -p no:cacheprovider "$root/src/python"
fi

# Fuzzing as a habit (fuzz/README.md): every reader of outside input (scenes, OBJ/STL meshes,
# VTU/PLY/CSV frames) under libFuzzer with address, undefined-behaviour and float-cast-overflow
# sanitizers, WEIR_FUZZ_SECONDS each (default 30). A step of its own after ctest rather than a
# ctest test: it needs its own clang build (build-fuzz; the main build stays g++), and as a test
# it would compete for the two cores with the suite's timing-sensitive tests. It replays the
# seed corpora first, and runs the io and mesh-file unit tests built with the same sanitizers
# (fuzz/CMakeLists.txt): that is CI's sanitizer run, a subset, because a sanitize build of the
# whole suite takes about as long as the rest of CI on two cores. Cost: the clang build of the
# readers' libraries (estimated 4-5 minutes on two idle cores), 6 x 30 s of fuzzing, 5 s of
# tests. WEIR_FUZZ_SECONDS=0 skips it.
if [ "${WEIR_FUZZ_SECONDS:-30}" != 0 ]; then
    bash "$root/fuzz/run.sh" "${WEIR_FUZZ_SECONDS:-30}"
fi
