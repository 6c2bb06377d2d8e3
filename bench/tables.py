#!/usr/bin/env python3
"""Prints weir bench results (bench.json) as Markdown tables in the paper's layout.

Usage: python3 bench/tables.py BENCH.json
"""
import json
import sys

ROWS = [("grid", "Grid construction"), ("density", "Pressure computation"),
        ("force", "Force computation"), ("integrate", "Displacement computation")]


def main(path):
    record = json.load(open(path))
    print(f"Device: {record['gpu']}; CPU: {record['cpu']}; commit {record['commit']}; "
          f"{record['steps']} timed steps after {record['warmupSteps']} warm-up steps, from a fluid "
          f"settled for {record['settleSeconds']} s.")
    for run in record["runs"]:
        cols = list(run["columns"])
        nb = run.get("neighboursPerParticle")
        start = f"{nb:.1f} neighbours per particle" if nb is not None else "from the initial lattice"
        print(f"\n**{run['particles']:,} particles** ({start}, h = {run['smoothingRatio']} d), "
              f"ms per step:\n")
        print("| Operation | " + " | ".join(f"{run['columns'][c]['title']} (`{c}`)" for c in cols) + " |")
        print("|---|" + "---:|" * len(cols))

        def cell(c, key=None, stage=None):
            x = run["columns"][c]
            if "skipped" in x:
                return "skipped"
            if stage:
                return f"{x['stages'][stage]:.4g}"
            return f"{x[key]:.4g}" if key in x else "-"

        for stage, title in ROWS:
            print(f"| {title} | " + " | ".join(cell(c, stage=stage) for c in cols) + " |")
        if "pointSpriteMs" in run:
            print("| Point sprite rendering (1280x720, same for every column) | " +
                  " | ".join(f"{run['pointSpriteMs']:.4g}" for c in cols) + " |")
        print("| **Total** (sum of stage medians) | " + " | ".join(cell(c, "totalMs") for c in cols) + " |")
        print("| Full step, no events (median) | " + " | ".join(cell(c, "stepMs") for c in cols) + " |")
        base = run["columns"].get("cpu-brute", {}).get("totalMs")
        print("| Speedup over CPU | " + " | ".join(
            f"{base / run['columns'][c]['totalMs']:.0f}" if base and "totalMs" in run["columns"][c] else "-"
            for c in cols) + " |")
        print("| Bytes per particle | " + " | ".join(
            f"{run['columns'][c]['bytesPerParticle']:.0f}" if "bytesPerParticle" in run["columns"][c] else "-"
            for c in cols) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
