#!/usr/bin/env python3
"""Plots weir_surface_bench results: for each run, the median time per particle of each stage
(surface.h lists them), stacked, with the particles per second at the end of each bar.

Usage: python3 bench/plot_surface.py RESULT.json [MORE.json ...] OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STAGES = [
    ("surface upload", "upload"),
    ("surface bins", "bins"),
    ("surface anisotropy", "anisotropy"),
    ("surface blocks", "blocks"),
    ("surface field", "field"),
    ("surface vertices", "vertices"),
    ("surface triangles", "triangles"),
    ("surface download", "download"),
    ("surface slivers", "sliver cleanup (host)"),
]


def label(result):
    count = result["particles"]
    size = f"{count / 1e6:.0f}M" if count >= 1e6 else f"{count / 1e3:.0f}k"
    source = "dam break" if result["input"] != "synthetic" else "synthetic"
    return f"{result['backend']} {result['field']} {size} ({source})"


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    results = [json.load(open(path)) for path in sys.argv[1:-1]]
    fig, ax = plt.subplots(figsize=(10, 0.45 * len(results) + 1.6))
    colours = plt.get_cmap("tab10").colors
    for row, result in enumerate(results):
        left = 0.0
        for k, (stage, name) in enumerate(STAGES):
            ms = result["stage_ms_median"].get(stage, 0.0)
            width = ms * 1e6 / result["particles"]  # ns per particle
            ax.barh(row, width, left=left, color=colours[k % len(colours)],
                    label=name if row == 0 or stage == "surface anisotropy" else None)
            left += width
        rate = result["particles_per_second"]
        ax.text(left, row, f"  {rate / 1e6:.0f}M particles/s", va="center", fontsize=8)
    ax.set_yticks(range(len(results)), [label(r) for r in results])
    ax.invert_yaxis()
    ax.set_xlabel("ns per particle (median of the repeats), stages stacked")
    handles, names = ax.get_legend_handles_labels()
    unique = dict(zip(names, handles))
    ax.legend(unique.values(), unique.keys(), fontsize=8, loc="lower right")
    ax.set_xlim(0, ax.get_xlim()[1] * 1.25)
    fig.tight_layout()
    fig.savefig(sys.argv[-1], dpi=110)


if __name__ == "__main__":
    main()
