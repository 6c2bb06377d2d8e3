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
