#!/usr/bin/env bash
# Sets up and builds weir, then runs the whole test suite through CTest.
# CUDA tests skip themselves where no GPU is visible.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
cd "$root/build"
ctest --output-on-failure -j "$(nproc)" "$@"
