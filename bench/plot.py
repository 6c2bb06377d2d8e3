#!/usr/bin/env python3
"""Plots weir bench results: ms per step against particle count, log-log, one line per column,
with the paper's GTX 280 / Core 2 Duo figures (Tables 1-3) beside them.

Usage: python3 bench/plot.py BENCH.json [MORE.json ...] OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Paper §8, Tables 1-3: total ms per step (pressure + force + displacement + point sprites).
PAPER = {
    "CPU (paper, Core 2 Duo E7500)": ([10000, 50000, 100000], [1253.13, 27401.09, 123438.9]),
    "GPU (paper, GTX 280)": ([10000, 50000, 100000], [21.24, 264.31, 1212.76]),
    "Optimized GPU (paper, GTX 280)": ([10000, 50000, 100000], [4.898, 10.137, 21.241]),
}
STYLE = {"cpu-brute": ("C0", "o"), "cpu-grid": ("C2", "o"), "cpu-dense": ("C4", "^"),
         "cuda-brute": ("C1", "o"), "cuda-grid": ("C3", "o"), "cuda-dense": ("C5", "^")}


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    inputs, out = argv[1:-1], argv[-1]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    titles = []
    for path in inputs:
        with open(path) as f:
            record = json.load(f)
        device = record["gpu"] if record["gpu"] != "none" else record["cpu"]
        titles.append(device.split(",")[0])
        series = {}
        for run in record["runs"]:
            for name, result in run["columns"].items():
                if "totalMs" in result:
                    series.setdefault(name, ([], [], result["title"]))
                    series[name][0].append(run["particles"])
                    series[name][1].append(result["totalMs"])
        for name, (xs, ys, title) in sorted(series.items()):
            color, marker = STYLE.get(name, (None, "o"))
            ax.loglog(xs, ys, marker + "-", color=color, label=f"{title} ({name}, weir)")
    for (label, (xs, ys)), color in zip(PAPER.items(), ["C0", "C1", "C3"]):
        ax.loglog(xs, ys, "s--", color=color, alpha=0.5, label=label)
    ax.set_xlabel("particles")
    ax.set_ylabel("ms per step (median)")
    ax.set_title("weir bench, dam break: " + ", ".join(sorted(set(titles))))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main(sys.argv)
