"""The early surge front of two dam-break experiments and of weir, in one set of units.

Martin & Moyce (1952; a column a wide, 2a high) and Lobovsky et al. (2014; 2H long, H high)
measured the front of a collapsing water column. Early on (before the rarefaction from the
released face reaches the back wall, tau = t sqrt(g / H) < ~0.5) the flow is the corner flow
at the foot of the released face, which scales with H alone. This prints, against tau, the
front's travel from the released face over H: weir's runs of both columns (committed results of
`weir validate` on an H200: Martin & Moyce at 160 across, Lobovsky at 240 over H, delta-SPH,
h = 3 d), and both experiments (shared/data). Usage: python bench/front_origins.py [DATA_DIR]
"""
import csv
import pathlib
import sys

import numpy as np

root = pathlib.Path(__file__).resolve().parents[1]
data = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else root.parent / "shared" / "data")
results = root / "bench" / "results"


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


mm_sim = [r for r in rows(results / "h200-2026-12-03-waves/validate-ratio3/validate-dam-break-r3/dam_break.csv")
          if r["fluid"] == "water" and r["resolution"] == "160"]
# Martin & Moyce: T = t sqrt(2 g / a), Z = z / a with H = 2 a, so tau = T / 2, x / H = (Z - 1) / 2.
mm_sim_tau = np.array([float(r["T"]) / 2 for r in mm_sim])
mm_sim_x = np.array([(float(r["Z"]) - 1) / 2 for r in mm_sim])
lob_sim = rows(results / "h200-2026-12-04-bodies-tensile/lob/validate-lobovsky-240/lobovsky_front.csv")
lob_sim_tau = np.array([float(r["tau"]) for r in lob_sim])
lob_sim_x = np.array([float(r["x_over_H"]) for r in lob_sim])
lob_exp = rows(data / "lobovsky2014_front_H300.csv")
lob_exp_tau = np.array([float(r["tau"]) for r in lob_exp])
lob_exp_x = np.array([float(r["x_over_H"]) for r in lob_exp])
mm_exp = [r for r in rows(data / "martin_moyce_1952_front_n2eq2.csv") if r["series"].startswith("MM1952")]
mm_exp_tau = np.array([float(r["T"]) / 2 for r in mm_exp])
mm_exp_x = np.array([(float(r["Z"]) - 1) / 2 for r in mm_exp])

print("front travel / H from the released face")
print(" tau | weir, M&M column | weir, Lobovsky column | Lobovsky et al. 2014 | Martin & Moyce 1952")
for tau in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0):
    print(f"{tau:4.1f} | {np.interp(tau, mm_sim_tau, mm_sim_x):16.3f} | "
          f"{np.interp(tau, lob_sim_tau, lob_sim_x):21.3f} | "
          f"{np.interp(tau, lob_exp_tau, lob_exp_x):20.3f} | {np.interp(tau, mm_exp_tau, mm_exp_x):19.3f}")
