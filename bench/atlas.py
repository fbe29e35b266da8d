"""The atlas's speed (issue 37, docs/performance.md): designs/s of a plain loop
over the module, and of the sweep with 1 and 2 local workers, on the same space.

    PYTHONPATH=build/python /usr/bin/python3 bench/atlas.py [--preset grid-3x3.json] [--designs 1000]

Prints JSON: seconds and designs/s of each, the sweep's overhead over the loop
(target <= 10 %) and 2 workers over 1 (target >= 1.8 on 2 cores)."""

import argparse
import json
import os
import shutil
import sys
import tempfile
import time

import phedra
from phedra import atlas

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))

PARAMETERS = {
    "grid-3x3.json": [{"path": "grid.u_heights[1]", "range": [-1.6, -1.2]},
                      {"path": "grid.w_heights[2]", "range": [1.6, 2.0]},
                      {"path": "directions[2].turn", "range": [-3.0, 3.0]}],
    "default.json": [{"path": "apex_heights[1]", "range": [0.8, 1.2]},
                     {"path": "apex_heights[3]", "range": [2.0, 2.4]},
                     {"path": "directions[4].turn", "range": [-4.0, 4.0]}],
}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--preset", default="grid-3x3.json", choices=sorted(PARAMETERS))
    p.add_argument("--designs", type=int, default=1000)
    p.add_argument("--figures", default="metrics,buildability")
    p.add_argument("--only", default="loop,1,2", help="loop, 1, 2 (workers), comma-separated")
    a = p.parse_args()
    spec = {"base": os.path.join(ROOT, "presets", a.preset), "parameters": PARAMETERS[a.preset],
            "designs": a.designs, "seed": 1, "figures": a.figures.split(",")}
    space = atlas.Space(spec)
    out = {"preset": a.preset, "designs": a.designs, "figures": space.figures, "cores": os.cpu_count()}
    only = a.only.split(",")
    if "loop" in only:
        values = space.values()
        o = space.options
        start = time.perf_counter()
        for row in values:
            try:
                d = phedra.load(space.preset(row))
                d.figures(space.figures, samples=o["samples"], axes=o["axes"], thickness=o["thickness"],
                          max_growth=o["max_growth"], max_panel_ratio=o["max_panel_ratio"])
            except phedra.Error:
                pass
        out["loop_s"] = time.perf_counter() - start
    work = tempfile.mkdtemp()
    try:
        for n in (1, 2):
            if str(n) not in only:
                continue
            start = time.perf_counter()
            atlas.sweep(space, os.path.join(work, f"w{n}.zarr"), workers=n, progress=False)
            out[f"workers_{n}_s"] = time.perf_counter() - start
    finally:
        shutil.rmtree(work)
    for k in [k for k in out if k.endswith("_s")]:
        out[k.replace("_s", "_designs_per_s")] = a.designs / out[k]
    if "loop_s" in out and "workers_1_s" in out:
        out["overhead_1_worker"] = out["workers_1_s"] / out["loop_s"] - 1.0
    if "workers_1_s" in out and "workers_2_s" in out:
        out["speedup_2_workers"] = out["workers_1_s"] / out["workers_2_s"]
    json.dump(out, sys.stdout, indent=2)
    print()


if __name__ == "__main__":
    main()
