#!/usr/bin/env python3
"""Where a run's fastest particles are and where they come from (issue 15: the spray that sets
DFSPH's time step at 10M).

Reads binary PLY frames (weir run --format ply) of a box-shaped container and prints, per frame:
the largest speed and the 99.99th percentile; how many particles move faster than FAST (default
1.5 sqrt(2 g H)); for those, their distance to the nearest container plane in particle spacings,
their summed density over rho0, their height; and, for the ones that became fast since the frame
before, what they were then (speed, density, wall distance, and which plane was nearest).

usage: dfsph_spray.py FRAMES_DIR --box X0 Y0 Z0 X1 Y1 Z1 --spacing D [--height H] [--fast V]
"""
import argparse
import glob
import math
import re

import numpy as np

TYPES = {"float": "<f4", "double": "<f8", "int": "<i4", "uint": "<u4", "uchar": "u1"}


def read_ply(path):
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                raise SystemExit(f"{path}: no end_header")
            header += line
        text = header.decode()
        n = int(re.search(r"element vertex (\d+)", text).group(1))
        props = re.findall(r"property (\w+) (\w+)", text)
        dtype = np.dtype([(name, TYPES[t]) for t, name in props])
        return np.frombuffer(f.read(n * dtype.itemsize), dtype=dtype, count=n)


PLANES = ["x-", "y-", "z-", "x+", "y+", "z+"]


def wall_distance(a, box):
    lo, hi = np.array(box[:3]), np.array(box[3:])
    x = np.stack([a["x"], a["y"], a["z"]], axis=1)
    d = np.concatenate([x - lo, hi - x], axis=1)
    return d.min(axis=1), d.argmin(axis=1)


def describe(label, values, fmt="%.2f"):
    if len(values) == 0:
        return f"{label} -"
    q = np.percentile(values, [0, 50, 100])
    return f"{label} " + "/".join(fmt % v for v in q)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("frames")
    ap.add_argument("--box", type=float, nargs=6, required=True)
    ap.add_argument("--spacing", type=float, required=True)
    ap.add_argument("--height", type=float, default=0.6, help="column height H (m)")
    ap.add_argument("--rho0", type=float, default=1000.0)
    ap.add_argument("--fast", type=float, default=None, help="m/s; default 1.5 sqrt(2 g H)")
    args = ap.parse_args()
    u = math.sqrt(2 * 9.81 * args.height)
    fast = args.fast if args.fast is not None else 1.5 * u
    print(f"U = sqrt(2 g H) = {u:.2f} m/s; fast: above {fast:.2f} m/s; d = {args.spacing} m")
    files = sorted(glob.glob(args.frames + "/frame_*.ply"))
    before = None
    for path in files:
        a = read_ply(path)
        speed = np.sqrt(a["vx"] ** 2 + a["vy"] ** 2 + a["vz"] ** 2)
        dist, plane = wall_distance(a, args.box)
        is_fast = speed > fast
        line = (f"{path.split('/')[-1]}: max {speed.max():.2f} m/s, 99.99% "
                f"{np.percentile(speed, 99.99):.2f}; fast {int(is_fast.sum())}")
        if is_fast.any():
            planes = np.bincount(plane[is_fast], minlength=6)
            near = ",".join(f"{PLANES[k]}:{planes[k]}" for k in range(6) if planes[k])
            line += (f" | {describe('wall/d', dist[is_fast] / args.spacing)}"
                     f" {describe('rho/rho0', a['density'][is_fast] / args.rho0, '%.3f')}"
                     f" {describe('y', a['y'][is_fast])} {describe('x', a['x'][is_fast])}"
                     f" nearest {near}")
        print(line)
        if before is not None and is_fast.any():
            prev_ids, prev_fast = before
            new_ids = np.setdiff1d(a["id"][is_fast], prev_fast)
            if len(new_ids):
                order = np.argsort(prev_ids["id"])
                k = order[np.searchsorted(prev_ids["id"], new_ids, sorter=order)]
                p = prev_ids[k]
                ps = np.sqrt(p["vx"] ** 2 + p["vy"] ** 2 + p["vz"] ** 2)
                pd, pp = wall_distance(p, args.box)
                planes = np.bincount(pp, minlength=6)
                near = ",".join(f"{PLANES[j]}:{planes[j]}" for j in range(6) if planes[j])
                print(f"    {len(new_ids)} newly fast; a frame before: {describe('speed', ps)}"
                      f" {describe('rho/rho0', p['density'] / args.rho0, '%.3f')}"
                      f" {describe('wall/d', pd / args.spacing)} nearest {near}")
        before = (a[["id", "x", "y", "z", "vx", "vy", "vz", "density"]].copy(), a["id"][is_fast])


if __name__ == "__main__":
    main()
