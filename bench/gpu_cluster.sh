#!/usr/bin/env bash
# One call on a multi-GPU machine (nvidia-h200-x2): build with MPI and NCCL, run the distributed
# tests (CPU and CUDA, 1-3 ranks), then `weir bench --scaling` (weak and strong, NCCL against
# host staging) and the largest run across the GPUs. Logs and results under $OUT.
# Usage: WEIR_COMMIT=<commit> PARTS="build test scaling largest" bash bench/gpu_cluster.sh
set -uo pipefail
out=$(realpath -m "${OUT:-gpu-out}")
parts=" ${PARTS:-build test scaling largest} "
has() { [[ "$parts" == *" $1 "* ]]; }
mkdir -p "$out"
# NVLink multicast stays off (it can take a shared host's GPUs out of service).
export NCCL_NVLS_ENABLE=0 TORCH_SYMM_MEM_DISABLE_MULTICAST=1 NVSHMEM_DISABLE_NVLS=1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
gpus=$(nvidia-smi -L | wc -l)
nvidia-smi --query-gpu=name,memory.total --format=csv | tee "$out/gpu.txt"
nvidia-smi topo -m > "$out/topology.txt" 2>&1
mpirun --version | head -1 | tee -a "$out/gpu.txt"
if has build; then
    cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
        -DWEIR_ENABLE_RENDER=OFF >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
    grep -E "weir:" "$out/configure.log"
    ninja -C build-gpu -j"$(nproc)" >/tmp/weir-build.log 2>&1 ||
        { grep -E "error" -A3 /tmp/weir-build.log | head -40; exit 1; }
fi
if has test; then
    for ranks in 1 2 3; do
        echo "== weir_mpi_tests, $ranks ranks on $gpus GPUs"
        OMP_NUM_THREADS=4 mpirun -n "$ranks" --oversubscribe --bind-to none \
            -x NCCL_NVLS_ENABLE -x OMP_NUM_THREADS ./build-gpu/weir_mpi_tests 2>&1 |
            tee "$out/mpi-tests-$ranks.log" | grep -E "ranks,|OK|FAILED|Failure|Expected|PASSED|SKIPPED"
    done
fi
if has scaling; then
    mpirun -n "$gpus" --bind-to none -x NCCL_NVLS_ENABLE ./build-gpu/weir bench --scaling \
        --sizes "${SIZES:-1M,4M,10M,30M}" --steps 20 --warmup 5 -o "$out/scaling" 2>&1 |
        tee "$out/scaling.txt"
fi
if has largest; then
    nvidia-smi --query-gpu=memory.used,memory.total --format=csv | tee "$out/largest-memory.txt"
    mpirun -n "$gpus" --bind-to none -x NCCL_NVLS_ENABLE ./build-gpu/weir bench --scaling \
        --sizes "${LARGEST:-1B}" --steps 2 --warmup 1 -o "$out/largest" 2>&1 | tee "$out/largest.txt"
fi
