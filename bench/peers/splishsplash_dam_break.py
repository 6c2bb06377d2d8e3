"""SPlisHSPlasH (pip install pysplishsplash) on its dam break, for weir's CPU comparisons.

Usage: python splishsplash_dam_break.py RADIUS DURATION OUT_JSON [dfsph|wcsph]
Runs SPlisHSPlasH's DamBreakModel layout (a 1 m cube of water at one end of a 4 x 3 x 1.5 m
box) at particle radius RADIUS with Akinci et al. 2012 boundary particles (as weir's walls),
under DFSPH (the default; weir's default tolerances: mean density error 0.01%, divergence error
0.1%) or WCSPH (SPlisHSPlasH's defaults: stiffness 50000, exponent 7; its CFL step on the
largest speed, at most 0.5 ms, where weir's follows a speed of sound), and writes to
OUT_JSON the stepping wall time, steps, and every frame's (1/30 s) mean and largest compression
max(rho / rho0 - 1, 0) over the particles. Its own per-stage summary (iterations) goes to
stdout. The wheel's bundled GL libraries clash with Debian's libGLX at import: run it with
LD_PRELOAD=/lib/x86_64-linux-gnu/libGLdispatch.so.0 (bench/peers/compare_dfsph_cpu.sh does).
"""
import json
import os
import sys
import tempfile
import time

import numpy as np
import pysplishsplash as sph

radius, duration, out_path = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
method = sys.argv[4] if len(sys.argv) > 4 else "dfsph"
work = tempfile.mkdtemp(prefix="splish-")
with open(os.path.join(work, "UnitBox.obj"), "w") as f:
    # A unit cube centred at the origin, faces wound outwards (the scene inverts it: the fluid
    # lives inside).
    f.write("""v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 7 3
f 4 8 7
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
""")
scene = {
    "Configuration": {
        "particleRadius": radius,
        "simulationMethod": 4 if method == "dfsph" else 0,  # DFSPH or WCSPH
        "gravitation": [0, -9.81, 0],
        "timeStepSize": 0.001 if method == "dfsph" else 0.0005,
        "cflMethod": 1,
        "cflFactor": 1,
        "cflMaxTimeStepSize": 0.005 if method == "dfsph" else 0.0005,
        "boundaryHandlingMethod": 0,  # Akinci et al. 2012 boundary particles
        "DFSPH": {"minIterations": 2, "maxIterations": 100, "maxError": 0.01,
                  "maxIterationsV": 100, "maxErrorV": 0.1, "enableDivergenceSolver": True},
    },
    "Materials": [{"id": "Fluid", "density0": 1000, "viscosityMethod": 1,
                   "Standard viscosity": {"viscosity": 0.01}}],
    "RigidBodies": [{"geometryFile": os.path.join(work, "UnitBox.obj"), "translation": [0, 1.5, 0],
                     "rotationAxis": [1, 0, 0], "rotationAngle": 0, "scale": [4, 3, 1.5],
                     "isDynamic": False, "isWall": True, "mapInvert": True,
                     "mapThickness": 0.0, "mapResolution": [40, 30, 15]}],
    "FluidBlocks": [{"denseMode": 0, "start": [-0.5, 0.0, -0.5], "end": [0.5, 1.0, 0.5],
                     "translation": [-1.45, 0.05, 0.0], "scale": [1, 1, 1]}],
}
scene_path = os.path.join(work, "dam_break.json")
with open(scene_path, "w") as f:
    json.dump(scene, f)

base = sph.Exec.SimulatorBase()
base.init(["splishsplash", "--no-gui", "--stopAt", str(duration), "--output-dir",
           os.path.join(work, "out"), scene_path], "SPlisHSPlasH")
state = {"frames": [], "steps": 0, "measuring": 0.0, "next": 1.0 / 30}


def after_step():
    # Called by SPlisHSPlasH after every step: each frame's compression, its cost kept apart.
    state["steps"] += 1
    clock = sph.TimeManager.getCurrent()
    if clock.getTime() < state["next"] - 1e-9:
        return
    start = time.perf_counter()
    fluid = sph.Simulation.getCurrent().getFluidModel(0)
    n = fluid.numActiveParticles()
    rho = np.fromiter((fluid.getDensity(i) for i in range(n)), dtype=np.float64, count=n)
    excess = np.maximum(rho / fluid.getDensity0() - 1, 0)
    state["frames"].append({"t": clock.getTime(), "meanCompression": float(excess.mean()),
                            "maxCompression": float(excess.max())})
    state["next"] += 1.0 / 30
    state["particles"] = n
    state["measuring"] += time.perf_counter() - start


base.setTimeStepCB(after_step)
start = time.perf_counter()
base.run()
wall = time.perf_counter() - start
with open(out_path, "w") as f:
    json.dump({"code": "SPlisHSPlasH " + getattr(sph, "__version__", "2.19.0"), "method": method,
               "particles": state.get("particles", 0), "radius": radius,
               "duration": duration, "steps": state["steps"],
               "steppingSeconds": wall - state["measuring"], "frames": state["frames"]},
              f, indent=1)
