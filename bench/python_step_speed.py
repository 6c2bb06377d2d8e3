"""Time a step from Python against the same step timed by `weir bench` (issue 16: within 2%).

    PYTHONPATH=build/python build/python-env/bin/python bench/python_step_speed.py \
        --weir build/weir --particles 1000000 --backend cuda

Both sides time the same thing, the way `weir bench` times its "full step": the dam break at the
size asked, settled for 0.1 s of simulated time, then 7 blocks of `steps` steps, each block one
call of the engine's advance(steps) followed by a wait for the device; the median block over its
steps. From Python the block is sim.step(steps) (advance plus one read of the fault record).
Also shown: a step(1) loop, which pays a device round trip per step.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import weir


def python_step_ms(args):
    sim = weir.Simulation("dam_break", backend=args.backend, particles=args.particles,
                          model=args.model, neighbours="dense")
    sim.advance_to(args.settle)
    sim.step(3)  # warm-up, as weir bench's --warmup 3
    blocks = []
    for _ in range(7):
        start = time.perf_counter()
        sim.step(args.steps)  # waits: it reads the fault record once the steps are done
        blocks.append((time.perf_counter() - start) * 1000 / args.steps)
    loop = time.perf_counter()
    for _ in range(args.steps):
        sim.step(1)
    loop_ms = (time.perf_counter() - loop) * 1000 / args.steps
    return statistics.median(blocks), loop_ms, sim.particle_count


def cli_step_ms(args, column):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([args.weir, "bench", "dam_break", "--model", args.model, "--sizes",
                        str(args.particles), "--backends", column, "--steps", str(args.steps),
                        "--warmup", "3", "--settle", str(args.settle), "--no-plot",
                        "--no-render", "--out", out], check=True)
        record = json.loads((pathlib.Path(out) / "bench.json").read_text())
    return record["runs"][0]["columns"][column]["stepMs"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--weir", default="build/weir", help="the weir binary")
    parser.add_argument("--particles", type=int, default=1_000_000)
    parser.add_argument("--backend", default="cuda", choices=["cuda", "cpu"])
    parser.add_argument("--model", default="delta-sph")
    parser.add_argument("--steps", type=int, default=200, help="steps per timed block")
    parser.add_argument("--settle", type=float, default=0.1)
    args = parser.parse_args()

    column = f"{args.backend}-dense"
    cli = cli_step_ms(args, column)
    python, loop, n = python_step_ms(args)
    ratio = python / cli
    print(f"{n} particles, {args.backend}, {args.model}: weir bench {cli:.4f} ms/step, "
          f"Python step({args.steps}) {python:.4f} ms/step ({100 * (ratio - 1):+.2f}%), "
          f"a step(1) loop {loop:.4f} ms/step")
    print("within 2%" if ratio <= 1.02 else "MORE than 2% slower")
    return 0 if ratio <= 1.02 else 1


if __name__ == "__main__":
    sys.exit(main())
