#!/usr/bin/env bash
# Sets up and builds weir, then simulates the default dam break into out/dam_break/.
# Extra arguments go to `weir run`, e.g. scripts/run.sh drop_into_pool --particles 50000
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
cd "$root"
exec ./build/weir run "$@"
