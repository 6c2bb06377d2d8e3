#!/usr/bin/env bash
# Is the 10M DFSPH dam break's blow-up at 0.07 s (H100, ab95436, 100 frames/s) a regression since
# 68aab21 (ran to 0.3 s on the H200 at 30 frames/s) or the frame rate? Both builds, both rates.
set -uo pipefail
t0=$(date +%s); el() { echo "$(( $(date +%s) - t0 )) s"; }
D=$(pwd)
nvidia-smi --query-gpu=name,clocks.sm,clocks.max.sm --format=csv,noheader
mkdir -p /tmp/old && tar xzf old.tgz -C /tmp/old
cfg="-G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 -DWEIR_ENABLE_PYTHON=OFF"
(cd /tmp/old && cmake -S . -B b $cfg >/tmp/oc.log 2>&1 && ninja -C b weir >/tmp/ob.log 2>&1; echo "old build $? $(el)") &
(cd tree && cmake -S . -B /tmp/nb $cfg >/tmp/nc.log 2>&1 && ninja -C /tmp/nb weir >/tmp/nbl.log 2>&1; echo "new build $? $(el)") &
wait
tail -3 /tmp/ob.log /tmp/nbl.log | grep -i error
timeout 60 /tmp/nb/weir run $D/slab10m.json --backend cuda --format ply --overwrite -o /tmp/slab >$OUT/slab-gpu.log 2>&1
echo "slab (CPU: +0.59% worst, +0.12% at 0.1 s) on the GPU: exit $? $(el)"; grep -E "^frame|blew|worst" $OUT/slab-gpu.log | cut -c1-150
WEIR_NEIGHBOUR_LISTS=0 timeout 60 /tmp/nb/weir run $D/slab10m.json --backend cuda --format ply --overwrite -o /tmp/slab >$OUT/slab-gpu-nolists.log 2>&1
echo "slab, no lists: exit $? $(el)"; grep -E "blew|worst" $OUT/slab-gpu-nolists.log | cut -c1-150
for pair in "new 100" "old 100" "new 30" "old 30"; do set -- $pair; v=$1; fps=$2
  bin=/tmp/old/b/weir; [ $v = new ] && bin=/tmp/nb/weir

    timeout 60 $bin run $D/dam$fps.json --solver dfsph --particles 10M --format ply --overwrite -o /tmp/r-$v-$fps >$OUT/$v-$fps.log 2>&1
    echo "$v $fps fps exit $? $(el)"; grep -E "^frame|blew" $OUT/$v-$fps.log | cut -c1-200 | tail -4
    rm -rf /tmp/r-$v-$fps
done
nvidia-smi -q -d PERFORMANCE | grep -E "Thermal|Power Cap|Braking"
