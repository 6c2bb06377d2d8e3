"""A parameter sweep with weir from Python: Martin & Moyce's dam break (1952) at several
resolutions (or viscosities), its surge front plotted against the experiment.

    python3 examples/python/dam_break_sweep.py                      # 3 resolutions, to T = 3
    python3 examples/python/dam_break_sweep.py --resolutions 8,12 --end-T 2 --out front.png
    python3 examples/python/dam_break_sweep.py --viscosities 0.001,0.1,1 --resolutions 12

The column is a wide, 2a tall and six particles deep with periodic sides (a plane flow, as in
the experiment), water, walls of boundary particles: the case `weir validate` checks. The front
is the furthest particle plus half a spacing, Z = front / a, against T = t sqrt(2 g / a).
(docs/python.md walks through it.)
"""

import argparse
import csv
import math
import pathlib

import weir

HERE = pathlib.Path(__file__).resolve().parent
A = 2.25 * 0.0254  # the column's width a, m (Martin & Moyce's 2.25 in column)
G = 9.81


def column_scene(resolution, end_T, viscosity=None):
    """Martin & Moyce's column of width a and height 2a, `resolution` particles across."""
    d = A / resolution
    height, depth = 2 * A, 6 * d  # a periodic axis at least 2 h long (h = 3 d, the default)
    fluid = {"preset": "water", "restDensity": 1000}
    if viscosity is not None:
        fluid["viscosity"] = viscosity
    time_scale = math.sqrt(2 * G / A)  # T = t sqrt(2 g / a)
    return {
        "name": f"martin_moyce_{resolution}",
        "container": {"min": [0, 0, 0], "max": [A * (1.5 + 1.4 * end_T), 1.5 * height, depth],
                      "periodic": [False, False, True]},
        "blocks": [{"min": [0, 0, 0], "max": [A, height, depth]}],
        "fluid": fluid,
        "particles": {"spacing": d},
        "walls": {"model": "particles"},
        "time": {"duration": end_T / time_scale, "frameRate": time_scale / 0.125},
    }


def surge_front(scene, backend):
    """(T, Z) of the front at every frame, frame 0 included, from one run."""
    sim = weir.Simulation(scene, backend=backend)
    time_scale = math.sqrt(2 * G / A)
    T, Z = [], []

    def record(sim, index, time):
        front = sim.positions()[:, 0].max() + 0.5 * sim.spacing
        T.append(time * time_scale)
        Z.append(front / A)

    sim.run(on_frame=record)  # every frame of the scene's duration
    return sim.particle_count, T, Z


def experiment():
    """Martin & Moyce's measured front, by series (examples/python/martin_moyce_1952_front.csv)."""
    series = {}
    with open(HERE / "martin_moyce_1952_front.csv") as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        for row in rows:
            series.setdefault(row["series"], []).append((float(row["T"]), float(row["Z"])))
    return series


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--resolutions", default="8,12,16",
                        help="particles across the column, comma-separated (default 8,12,16)")
    parser.add_argument("--viscosities", default="",
                        help="dynamic viscosities in Pa s to sweep instead (at the first "
                             "resolution), comma-separated")
    parser.add_argument("--end-T", type=float, default=3.0, help="end time T (default 3)")
    parser.add_argument("--backend", default="auto", help="auto, cpu or cuda")
    parser.add_argument("--out", default="dam_break_front.png", help="the plot (PNG)")
    args = parser.parse_args(argv)

    resolutions = [int(r) for r in args.resolutions.split(",") if r]
    viscosities = [float(v) for v in args.viscosities.split(",") if v]
    runs = []
    if viscosities:
        for mu in viscosities:
            n, T, Z = surge_front(column_scene(resolutions[0], args.end_T, mu), args.backend)
            runs.append((f"mu = {mu:g} Pa s, {resolutions[0]} across ({n} particles)", T, Z))
    else:
        for r in resolutions:
            n, T, Z = surge_front(column_scene(r, args.end_T), args.backend)
            runs.append((f"{r} across ({n} particles)", T, Z))
    for label, T, Z in runs:
        print(f"{label}: front Z = {Z[-1]:.2f} at T = {T[-1]:.2f}")

    import matplotlib

    matplotlib.use("Agg")  # files only, no window
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, T, Z in runs:
        ax.plot(T, Z, "-", label=f"weir, {label}")
    markers = {"MM1952_Table2_a2.25in": "o", "PySPH_Fig3digitised_a2.25in": "s"}
    for name, points in experiment().items():
        shown = [(T, Z) for T, Z in points if T <= args.end_T]
        if name in markers and shown:
            ax.plot(*zip(*shown), markers[name], mfc="none", color="k",
                    label=f"Martin & Moyce 1952 ({name.split('_')[1]})")
    ax.set_xlim(0, args.end_T)
    ax.set_xlabel("T = t sqrt(2 g / a)")
    ax.set_ylabel("Z = front / a")
    ax.set_title("Dam break: surge front, n² = 2")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"plot: {args.out}")
    return runs


if __name__ == "__main__":
    main()
