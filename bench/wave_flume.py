#!/usr/bin/env python3
"""A piston wave flume (issue 14/18): write its scene, or measure the wave heights of a run.

  wave_flume.py scene OUT.json --width 0.03 [--spacing 0.005] [--ratio 2] [--shifting 0]
                               [--periodic-z]
  wave_flume.py heights RUN_DIR [--spacing 0.005]

The flume: 4 m long, water 0.3 m deep, a piston 4 cm thick at its left end (clear of the wall by
1.5 cm) driven 1 cm either way at a period of 1 s (stroke S = 2 cm, ramped in over a period), the
slab `width` across between free-slip side walls. Linear wave-maker theory (Dean & Dalrymple
1991) gives H = 2.6 cm. `heights` reads the run's binary PLY frames and prints each probe's
water-surface height per frame (the highest particle within half a spacing of the probe's x),
then the crest-to-trough height from 2.5 s on.
"""
import argparse
import json
import math
import sys

import numpy as np

PROBES = [0.1, 0.5, 1.0, 1.55, 2.5]
DEPTH, PERIOD, STROKE = 0.3, 1.0, 0.02


def theory_height():
    omega = 2 * math.pi / PERIOD
    k = omega * omega / 9.81
    for _ in range(100):  # dispersion: omega^2 = g k tanh(k h)
        k = omega * omega / (9.81 * math.tanh(k * DEPTH))
    kh2 = 2 * k * DEPTH
    return STROKE * 2 * (math.cosh(kh2) - 1) / (math.sinh(kh2) + kh2), omega / k


def scene(args):
    w = args.width
    s = {
        "name": "wave_flume",
        "fluid": {"preset": "water"},
        "container": {"min": [0, 0, 0], "max": [4.0, 0.45, w]},
        "blocks": [{"min": [0.06, 0, 0], "max": [4.0, DEPTH, w]}],
        "bodies": [{"box": {"min": [0.015, 0, 0], "max": [0.055, 0.42, w]},
                    "motion": {"oscillate": {"amplitude": [STROKE / 2, 0, 0], "period": PERIOD,
                                             "ramp": PERIOD}}}],
        "walls": {"slip": "free-slip"},
        "particles": {"spacing": args.spacing, "smoothingRatio": args.ratio},
        "time": {"duration": args.duration, "frameRate": 10},
    }
    if args.shifting:
        s["fluid"]["shifting"] = args.shifting
    if args.periodic_z:
        s["container"]["periodic"] = [False, False, True]
    json.dump(s, open(args.out, "w"), indent=1)


def heights(args):
    frames = json.load(open(args.run + "/frames.json"))["frames"]
    half = args.spacing
    dt = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("r", "<f4", 5), ("id", "<i4")])
    rows = []
    for f in frames:
        raw = open(args.run + "/" + f["file"], "rb").read()
        header_end = raw.index(b"end_header\n") + len(b"end_header\n")
        header = raw[:header_end].decode()
        props = [l.split()[-1] for l in header.splitlines() if l.startswith("property")]
        if len(props) != 9:
            sys.exit(f"{f['file']}: expected x y z + 5 floats + id, got {props}")
        a = np.frombuffer(raw[header_end:], dtype=dt)
        row = [float(a["y"][np.abs(a["x"] - p) < half].max()) if (np.abs(a["x"] - p) < half).any()
               else float("nan") for p in PROBES]
        rows.append((f["time"], row))
        print(f"{f['time']:.2f} " + " ".join(f"{v:.4f}" for v in row))
    H, c = theory_height()
    print(f"linear theory: H = {H * 1000:.1f} mm, phase speed {c:.3f} m/s")
    for i, p in enumerate(PROBES[:4]):
        tops = [r[i] for t, r in rows if t >= 2.5]
        if not tops:
            print(f"H@{p}: the run ends before 2.5 s")
            continue
        print(f"H@{p} = {(max(tops) - min(tops)) * 1000:.1f} mm (t >= 2.5 s)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    sub = ap.add_subparsers(dest="what", required=True)
    s = sub.add_parser("scene")
    s.add_argument("out")
    s.add_argument("--width", type=float, default=0.03)
    s.add_argument("--spacing", type=float, default=0.005)
    s.add_argument("--ratio", type=float, default=2.0)
    s.add_argument("--shifting", type=float, default=0.0)
    s.add_argument("--duration", type=float, default=4.0)
    s.add_argument("--periodic-z", action="store_true")
    h = sub.add_parser("heights")
    h.add_argument("run")
    h.add_argument("--spacing", type=float, default=0.005)
    args = ap.parse_args()
    scene(args) if args.what == "scene" else heights(args)


if __name__ == "__main__":
    main()
