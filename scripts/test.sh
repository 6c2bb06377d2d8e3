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
