#!/usr/bin/env python3
"""Plots weir validate results: hydrostatic pressure profile and Martin & Moyce surge front.

Usage: python3 plot.py DIR   (reads DIR/*.csv, writes DIR/hydrostatic.png, dam_break.png, viscous_dam_break.png, channels.png, lobovsky.png, taylor_green.png)
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path) as f:
        return [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]


def main(d):
    h = rows(os.path.join(d, "hydrostatic.csv"))
    if h:
        y = [float(r["y"]) for r in h]
        p = [float(r["pressure"]) for r in h]
        ref = [float(r["reference"]) for r in h]
        tol = [float(r["tolerance"]) for r in h]
        fig, ax = plt.subplots(figsize=(5, 5))
        ax.fill_betweenx(y, [a - t for a, t in zip(ref, tol)], [a + t for a, t in zip(ref, tol)],
                         color="C0", alpha=0.2, label="tolerance")
        ax.plot(ref, y, "C0-", label="rho0 g depth")
        ax.plot(p, y, "C3o", label="weir (layer means)")
        ax.set_xlabel("pressure [Pa]")
        ax.set_ylabel("height above floor [m]")
        ax.set_title("Hydrostatic tank")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(d, "hydrostatic.png"), dpi=120)

    ref = rows(os.path.join(d, "martin_moyce_1952.csv"))
    rt = [float(r["T"]) for r in ref]

    def fronts(name):
        runs = {}
        for r in rows(os.path.join(d, name)):
            runs.setdefault((r["fluid"], int(r["resolution"]), int(r["particles"])), []).append(
                (float(r["T"]), float(r["Z"])))
        return runs

    for name, title, key in (("dam_break", "Dam break: surge front, resolution ladder", "res"),
                             ("viscous_dam_break", "Dam break: water, oil and honey", "fluid")):
        runs = fronts(name + ".csv")
        if not runs:
            continue
        fig, ax = plt.subplots(figsize=(6, 4.5))
        ax.fill_between(rt, [float(r["band_low"]) for r in ref],
                        [float(r["band_high"]) for r in ref], color="C0", alpha=0.15,
                        label="Martin & Moyce +- 15%")
        ax.plot(rt, [float(r["Z"]) for r in ref], "C0s", label="Martin & Moyce 1952, n^2 = 2")
        tmax = zmax = 0
        for k, ((fluid, res, n), pts) in enumerate(sorted(runs.items(), key=lambda kv: kv[0][1])):
            label = ("%d across (%d particles)" % (res, n)) if key == "res" else fluid
            ax.plot([0] + [p[0] for p in pts], [1] + [p[1] for p in pts], "C%d-" % (k + 1),
                    label="weir, " + label)
            tmax = max(tmax, pts[-1][0])
            zmax = max(zmax, max(p[1] for p in pts))
        ax.set_xlim(0, tmax + 0.5)
        ax.set_ylim(0, zmax + 1.5)
        ax.set_xlabel("T = t sqrt(2 g / a)")
        ax.set_ylabel("Z = z / a")
        ax.set_title(title)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(d, name + ".png"), dpi=120)

    ch = rows(os.path.join(d, "channels.csv"))
    if ch:
        fig, axes = plt.subplots(1, 2, figsize=(10, 4.5))
        for ax, flow, scale in zip(axes, ("poiseuille", "couette"), ("u_max", "V0")):
            pts = [r for r in ch if r["flow"] == flow]
            for k, theta in enumerate(sorted({float(r["theta"]) for r in pts})):
                sel = [r for r in pts if float(r["theta"]) == theta]
                eta = [float(r["eta"]) for r in sel]
                ax.plot([float(r["u_series"]) for r in sel], eta, "C%d-" % k,
                        label="series, theta = %g" % theta)
                ax.plot([float(r["u"]) for r in sel], eta, "C%do" % k, ms=4)
            ax.set_xlabel("u / " + scale)
            ax.set_ylabel("y / L")
            ax.set_title("Start-up %s flow (dots: weir)" % flow.capitalize())
            ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "channels.png"), dpi=120)

    lf = rows(os.path.join(d, "lobovsky_front.csv"))
    if lf:
        ref = [(0.2859, 0.1995), (0.4765, 0.3815), (0.6671, 0.5529), (0.8578, 0.7349),
               (1.0484, 0.9729), (1.2390, 1.2214), (1.4296, 1.4926), (1.6202, 1.7656),
               (1.8108, 2.0561), (2.0014, 2.3675), (2.1921, 2.6895), (2.3827, 3.0062),
               (2.5733, 3.3658)]
        lp = rows(os.path.join(d, "lobovsky_pressure.csv"))
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
        axes[0].plot([r[0] for r in ref], [r[1] for r in ref], "C0s",
                     label="Lobovsky et al. 2014, H = 300 mm")
        axes[0].plot([float(r["tau"]) for r in lf], [float(r["x_over_H"]) for r in lf], "C3-",
                     label="weir")
        axes[0].set_xlim(0, 3)
        axes[0].set_xlabel("tau = t sqrt(g / H)")
        axes[0].set_ylabel("(front - gate) / H")
        axes[0].set_title("Lobovsky dam break: front (no time shift)")
        axes[0].legend()
        for k, (name, band) in enumerate((("sensor2", (1.7710, 2.0316)),
                                          ("sensor3", (1.3338, 1.6494)),
                                          ("sensor4", (0.7388, 1.1484)))):
            axes[1].plot([float(r["tau"]) for r in lp], [float(r[name]) for r in lp],
                         "C%d-" % k, lw=0.7, label="weir, " + name)
            axes[1].axhspan(band[0], band[1], color="C%d" % k, alpha=0.15)
        axes[1].set_xlabel("tau")
        axes[1].set_ylabel("p / (rho g H)")
        axes[1].set_title("Impact wall pressure (bands: measured peak, 2.5-97.5%)")
        axes[1].legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "lobovsky.png"), dpi=120)

    tg = rows(os.path.join(d, "taylor_green.csv"))
    if tg:
        fig, ax = plt.subplots(figsize=(6, 4.5))
        runs = sorted({int(r["resolution"]) for r in tg})
        for k, n in enumerate(runs):
            sel = [r for r in tg if int(r["resolution"]) == n]
            ax.semilogy([float(r["t"]) for r in sel], [float(r["energy"]) for r in sel],
                        "C%do-" % (k + 1), ms=3, label="weir, %d across" % n)
        sel = [r for r in tg if int(r["resolution"]) == runs[-1]]
        ax.semilogy([float(r["t"]) for r in sel], [float(r["energy_analytic"]) for r in sel],
                    "k--", label="analytic exp(-16 pi^2 t / Re)")
        ax.set_xlabel("t U / L")
        ax.set_ylabel("kinetic energy per particle / U^2")
        ax.set_title("Taylor-Green vortex, Re = 100")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(d, "taylor_green.png"), dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
