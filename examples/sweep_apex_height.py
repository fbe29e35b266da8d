"""Sweep one apex height of the 3 x 3 grid and plot its Poisson's ratio nu_12
(axis 2, across the tubes, against axis 1, along them) at t* against it, marking which designs can be built (docs/python.md).

    PYTHONPATH=build/python python3 examples/sweep_apex_height.py [-o nu12.png] [--steps N]

Uses Debian's python3 with python3-numpy and python3-matplotlib (scripts/setup.sh).
"""
import argparse
import copy
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files, no window
import matplotlib.pyplot as plt
import numpy as np

import phedra

HERE = os.path.dirname(os.path.abspath(__file__))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--preset", default=os.path.join(HERE, "..", "presets", "grid-3x3.json"))
    parser.add_argument("--field", default="u_heights", help="the grid's height list to sweep (u_heights or w_heights)")
    parser.add_argument("--index", type=int, default=1)
    parser.add_argument("--span", type=float, default=0.3, help="the height moves by up to this much either way")
    parser.add_argument("--steps", type=int, default=13)
    parser.add_argument("-o", "--output", default="nu12-sweep.png")
    args = parser.parse_args()

    base = phedra.load(args.preset).preset
    start = base["grid"][args.field][args.index]
    heights, nu12, buildable = [], [], []
    for h in np.linspace(start - args.span, start + args.span, args.steps):
        preset = copy.deepcopy(base)
        preset["grid"][args.field][args.index] = float(h)
        try:
            design = phedra.load(preset)
        except phedra.InputError as e:  # a height that breaks an assumption: say which, go on
            print(f"height {h:.4f}: {e}", file=sys.stderr)
            continue
        value = design.metrics(samples=11)["at_t_star"]["poisson"]["nu_12"]
        if value is None:
            continue
        heights.append(h)
        nu12.append(value)
        buildable.append(design.buildability()["buildable"])
        print(f"{args.field}[{args.index}] = {h:.4f}: nu_12 = {value:.4f}, buildable: {buildable[-1]}")

    if not heights:
        print("no design in the sweep could be built", file=sys.stderr)
        return 1
    heights, nu12, buildable = map(np.asarray, (heights, nu12, buildable))
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(heights, nu12, color="0.6", zorder=1)
    ax.scatter(heights[buildable], nu12[buildable], color="tab:blue", label="buildable", zorder=2)
    ax.scatter(heights[~buildable], nu12[~buildable], color="tab:red", marker="x", label="not buildable", zorder=2)
    ax.axvline(start, color="0.3", linestyle=":", label="as shipped")
    ax.set_xlabel(f"grid.{args.field}[{args.index}]")
    ax.set_ylabel("nu_12 at t*")
    ax.set_title(f"{base.get('name', 'design')}: Poisson's ratio against one apex height")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
