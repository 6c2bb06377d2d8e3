#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang, address and undefined-behaviour sanitizers) in build-fuzz
# and runs each for a while from its seed corpus; fails if any harness finds a crash, a hang, an
# uncaught exception, a sanitizer report, an input running 30 s or an allocation past 2 GB.
# Usage: fuzz/run.sh [seconds-per-target] [target ...]   (default: 60 s, every target:
#        scene obj stl vtu ply csv). WEIR_FUZZ_BUILD=DIR builds elsewhere.
# What a run finds is kept in build-fuzz/: new inputs in corpus/TARGET/, reproducers in
# crashes/TARGET-*; replay one with build-fuzz/fuzz/fuzz_TARGET FILE.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene obj stl vtu ply csv)
build=${WEIR_FUZZ_BUILD:-$root/build-fuzz}

# Debian's clang brings libFuzzer; libomp-dev is OpenMP for clang (the libraries use OpenMP).
missing=()
command -v clang++ >/dev/null 2>&1 || missing+=(clang)
dpkg-query -W -f='${Status}' libomp-dev 2>/dev/null | grep -q "install ok installed" ||
    missing+=(libomp-dev)
if [ ${#missing[@]} -gt 0 ]; then
    echo "weir fuzz: installing ${missing[*]}"
    sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWEIR_FUZZ=ON -DWEIR_ENABLE_CUDA=OFF \
        -DWEIR_ENABLE_MPI=OFF -DWEIR_ENABLE_RENDER=OFF -DWEIR_BUILD_TESTS=OFF >/dev/null
fi
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}" weir_reader_tests

# Leaks are reported (and fail the run); one OpenMP thread, the readers do not need more.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMP_NUM_THREADS=1
failed=()
# The readers' unit tests, built with the same sanitizers.
if ! "$build/fuzz/weir_reader_tests" --gtest_brief=1 >"$build/reader_tests.log" 2>&1; then
    echo "weir fuzz: the sanitized reader tests FAILED (log: $build/reader_tests.log)"
    grep -E "FAILED|ERROR|runtime error|SUMMARY" "$build/reader_tests.log" | head -20 || true
    failed+=(reader_tests)
fi
for target in "${targets[@]}"; do
    corpus=$build/corpus/$target  # new inputs land here; the seeds in fuzz/corpus stay as they are
    mkdir -p "$corpus" "$build/crashes"
    log=$build/fuzz_$target.log
    echo "weir fuzz: $target for ${seconds} s"
    if "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 \
        -max_len=16384 -print_final_stats=1 -artifact_prefix="$build/crashes/$target-" \
        "$corpus" "$root/fuzz/corpus/$target" >"$log" 2>&1; then
        grep -E "^Done [0-9]+ runs" "$log" | sed "s/^/weir fuzz: $target: /" || true
    else
        echo "weir fuzz: $target FAILED (log: $log; reproducer: $build/crashes/$target-*)"
        grep -E "ERROR|runtime error|terminate|SUMMARY|==[0-9]+==" "$log" | head -20 || true
        failed+=("$target")
    fi
done
if [ ${#failed[@]} -gt 0 ]; then
    echo "weir fuzz: failed: ${failed[*]}"
    exit 1
fi
echo "weir fuzz: every target ran ${seconds} s without a fault"
