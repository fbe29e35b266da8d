"""How often `phedra repair` repairs a random unbuildable design (issue 39), as a
user runs it: the command with its defaults (60 s), each result judged by
`phedra check` on the written file, not by what the search believed.

    PYTHONPATH=build/python /usr/bin/python3 bench/repair_rate.py [--designs 20] [--seed 1]
        [--jobs 2] [--keep DIR] [-- REPAIR OPTIONS...]

The designs come from a generator of its own, broader than the tests' (it shares
no code with tests/support/random_input.cpp): open P-hedra of 4-8 strips and 4-7
profile vertices, signs with 0-60 % '-', smooth and irregular trajectories,
some placed on a tilted axis; parallelogram tubes of 4-10 strips; grids of 2x2
to 4x3 cells, rows of cells and edge-sharing pairs on random trajectories.
A design counts when it loads and `phedra check` fails on it (unbuildable).

Prints one line a design and a JSON summary: repaired (exit 0 and `check` passes
on the written file), failed (exit 1: nothing buildable found), the rate, and
any result that `check` refutes (a broken promise: exit 1 of this script)."""

import argparse
import concurrent.futures
import json
import math
import os
import random
import subprocess
import sys
import tempfile
import time

import phedra

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
PHEDRA = os.environ.get("PHEDRA", os.path.join(ROOT, "build", "bin", "phedra"))


def horizontal(angle, length=1.0):
    return [length * math.cos(angle), length * math.sin(angle), 0.0]


def sine_between(a, b):
    return abs(a[0] * b[1] - a[1] * b[0]) / (math.hypot(a[0], a[1]) * math.hypot(b[0], b[1]))


def trajectory_and_directions(rng, strips, smooth):
    """A trajectory rising along z and horizontal profile directions, the apex line the z-axis."""
    v0 = [rng.uniform(1.0, 3.5), 0.0, rng.uniform(-0.5, 0.5)]
    turn = rng.choice([-1, 1]) * rng.uniform(0.12, 0.7)
    v1 = horizontal(turn, v0[0] * rng.uniform(0.6, 1.4))
    v1[2] = v0[2] + rng.uniform(0.15, 0.8)
    points = [v0, v1]
    directions = [[rng.choice([-1.0, 1.0]), 0.0, 0.0], [s * rng.choice([-1.0, 1.0]) for s in horizontal(turn)]]
    heading = turn + math.pi / 2 + rng.uniform(-0.6, 0.6)
    angle = turn
    while len(points) <= strips:
        for _ in range(1000):
            if smooth:
                h = heading + rng.uniform(-0.35, 0.35)
                a = angle + rng.choice([-1, 1]) * rng.uniform(0.08, 0.45)
                step = horizontal(h, rng.uniform(0.35, 0.9))
                step[2] = rng.uniform(0.05, 0.45)
            else:
                h = heading + rng.uniform(-1.3, 1.3)
                a = angle + rng.choice([-1, 1]) * rng.uniform(0.1, 1.6)
                step = horizontal(h, rng.uniform(0.3, 1.1))
                step[2] = rng.uniform(-0.15, 0.7)
            d = horizontal(a)
            if sine_between(d, directions[-1]) >= 0.1 and sine_between(d, step) >= 0.2:
                break
        heading, angle = h, a
        points.append([p + s for p, s in zip(points[-1], step)])
        directions.append([rng.uniform(0.5, 1.5) * c for c in d])
    return points, directions


def distinct_heights(rng, count, spread=3.0, apart=0.15):
    """Heights whose consecutive pairs and triples are distinct (a valid apex polyline)."""
    out = []
    while len(out) < count:
        z = rng.uniform(-spread, spread)
        if all(abs(z - out[-b]) > apart for b in (1, 2) if b <= len(out)):
            out.append(z)
    return out


def tilt(rng, preset):
    """Places a design rigidly on a random axis (the preset's `axis`)."""
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / n for c in q)
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    shift = [rng.uniform(-5, 5) for _ in range(3)]

    def rotate(v):
        return [sum(r[i][j] * v[j] for j in range(3)) for i in range(3)]

    axis = rotate([0.0, 0.0, 1.0])
    preset["axis"] = axis
    preset["trajectory"] = [[a + b for a, b in zip(rotate(p), shift)] for p in preset["trajectory"]]
    preset["directions"] = [rotate(d) for d in preset["directions"]]
    along = sum(a * s for a, s in zip(axis, shift))
    preset["apex_heights"] = [h + along for h in preset["apex_heights"]]
    return preset


def random_design(rng, k):
    """Design k: 60 % open, 15 % parallelogram tubes, 25 % arrays."""
    kind = rng.random()
    smooth = rng.random() < 0.5
    if kind < 0.6:
        strips, n = rng.randint(4, 8), rng.randint(4, 7)
        minus = rng.choice([0.0, 0.2, 0.4, 0.6])
        points, directions = trajectory_and_directions(rng, strips, smooth)
        preset = {"name": f"random-open-{k}", "trajectory": points, "directions": directions,
                  "apex_heights": distinct_heights(rng, n + 1),
                  "signs": "".join("-" if rng.random() < minus else "+" for _ in range(n - 1))}
        return tilt(rng, preset) if rng.random() < 0.3 else preset
    if kind < 0.75:
        points, directions = trajectory_and_directions(rng, rng.randint(4, 10), smooth)
        return {"name": f"random-tube-{k}", "trajectory": points, "directions": directions,
                "tube": {"type": "parallelogram", "apex_heights": distinct_heights(rng, 4, apart=0.3)}}
    points, directions = trajectory_and_directions(rng, rng.randint(6, 10), smooth)
    preset = {"name": f"random-array-{k}", "trajectory": points, "directions": directions}
    which = rng.choice(["grid", "row", "edge"])
    if which == "grid":
        # u heights rising below, w heights falling above: the shipped grid's pattern, disturbed.
        u, w = rng.randint(3, 5), rng.randint(3, 4)
        step = rng.uniform(0.4, 0.9)
        preset["grid"] = {"u_heights": [-2.0 + step * i + rng.uniform(-0.35, 0.35) for i in range(u)],
                          "w_heights": [3.0 - step * i + rng.uniform(-0.35, 0.35) for i in range(w)]}
    else:
        tube = [-2.0, 3.0, -1.4, 2.4]
        preset["tube"] = {"type": "parallelogram", "apex_heights": [h + rng.uniform(-0.4, 0.4) for h in tube]}
        if which == "row":
            preset["row"] = {"side": 1, "free_heights": [-0.8 + 0.6 * i + rng.uniform(-0.4, 0.4)
                                                          for i in range(rng.randint(1, 3))]}
        else:
            preset["couplings"] = [{"type": "edge", "parent": 0, "vertex": 2,
                                    "free_heights": [-0.8 + rng.uniform(-0.5, 0.5), 1.8 + rng.uniform(-0.5, 0.5)]}]
    return preset


def unbuildable_designs(count, seed):
    """`count` designs that load and are not buildable (anti-parallelogram-free: those crossing by kind
    cannot be repaired, MATH.md section 6)."""
    rng = random.Random(seed)
    out, drawn = [], 0
    while len(out) < count:
        preset = random_design(rng, drawn)
        drawn += 1
        try:
            d = phedra.load(preset)
            if d.buildability()["buildable"]:
                continue
        except phedra.Error:
            continue
        out.append(preset)
    return out, drawn


def run(preset, work, options):
    name = preset["name"]
    src, dst = os.path.join(work, name + ".json"), os.path.join(work, name + "-repaired.json")
    with open(src, "w") as f:
        json.dump(preset, f)
    start = time.perf_counter()
    p = subprocess.run([PHEDRA, "repair", src, "-o", dst, "--json", *options], capture_output=True, text=True)
    seconds = time.perf_counter() - start
    row = {"name": name, "exit": p.returncode, "seconds": round(seconds, 1)}
    if p.returncode in (0, 1) and p.stdout:
        report = json.loads(p.stdout)
        row["varied"] = report["varied"]
        row["closest"] = report["closest"]
    else:
        row["stderr"] = p.stderr.strip()[-300:]
    if p.returncode == 0:
        c = subprocess.run([PHEDRA, "check", dst], capture_output=True, text=True)
        row["check"] = c.returncode
        if c.returncode != 0:
            row["check_says"] = c.stdout.strip()[-300:]
    elif os.path.exists(dst):
        row["written_on_failure"] = True
    return row


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--designs", type=int, default=20)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--keep", help="keep the designs and results in this folder")
    p.add_argument("options", nargs="*", help="options for phedra repair (after --)")
    a = p.parse_args()
    designs, drawn = unbuildable_designs(a.designs, a.seed)
    work = a.keep or tempfile.mkdtemp()
    os.makedirs(work, exist_ok=True)
    rows = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        for row in pool.map(lambda d: run(d, work, a.options), designs):
            print(json.dumps(row), flush=True)
            rows.append(row)
    repaired = sum(1 for r in rows if r["exit"] == 0 and r.get("check") == 0)
    refuted = [r["name"] for r in rows if r["exit"] == 0 and r.get("check") != 0 or r.get("written_on_failure")]
    summary = {"designs": len(rows), "drawn": drawn, "seed": a.seed, "repaired": repaired,
               "failed": sum(1 for r in rows if r["exit"] == 1), "other_exits": sum(1 for r in rows if r["exit"] not in (0, 1)),
               "rate": repaired / max(len(rows), 1), "refuted": refuted,
               "mean_s": round(sum(r["seconds"] for r in rows) / max(len(rows), 1), 1), "options": a.options}
    print(json.dumps(summary))
    return 1 if refuted else 0


if __name__ == "__main__":
    sys.exit(main())
