"""Design-space atlases (issue 37, docs/atlas.md): sweeps on a real Dask cluster
with a worker killed, interrupted and resumed sweeps, faults recorded, rows
re-checked by the command, and every bad space refused before anything is
written. Run as tests/python/test_phedra.py says."""
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

import numpy as np
import pytest
import zarr

import phedra
from phedra import atlas

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PHEDRA = os.environ.get("PHEDRA", os.path.join(ROOT, "build", "bin", "phedra"))


def preset(name):
    return os.path.join(ROOT, "presets", name)


def space(designs=120, figures=("metrics",), base="default.json", **more):
    s = {"base": preset(base),
         "parameters": [{"path": "apex_heights[1]", "range": [0.8, 1.2]},
                        {"path": "apex_heights[3]", "range": [2.0, 2.4]},
                        {"path": "directions[4].turn", "range": [-4.0, 4.0]}],
         "designs": designs, "seed": 3, "figures": list(figures)}
    s.update(more)
    return s


def arrays(path):
    g = zarr.open_group(path, mode="r")
    return {k: g[k][:] for k in g.array_keys()}


def assert_same_atlas(a, b):
    x, y = arrays(a), arrays(b)
    assert sorted(x) == sorted(y)
    for k in x:
        if x[k].dtype == object:
            assert list(x[k]) == list(y[k]), k
        else:
            assert x[k].tobytes() == y[k].tobytes(), k
    assert zarr.open_group(a, mode="r").attrs.asdict() == zarr.open_group(b, mode="r").attrs.asdict()


def run_atlas(*args, **kw):
    return subprocess.run([sys.executable, "-m", "phedra.atlas", *args], capture_output=True, text=True, **kw)


@pytest.fixture
def work():
    with tempfile.TemporaryDirectory() as d:
        yield d


def write_space(folder, s, name="space.json"):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        json.dump(s, f)
    return path


# -- the cluster ---------------------------------------------------------------

def wait_for(condition, seconds, what):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"timed out waiting for {what}")


def test_a_sweep_on_a_dask_cluster_with_a_worker_killed_equals_one_process(work):
    """2,000 designs on dask-scheduler and two dask-worker processes on
    127.0.0.1, one worker killed in the middle, then the other, a third one
    started after: complete, equal bit for bit to a run in one process; random
    rows re-checked with phedra metrics. (A scattered setup was lost with the
    last worker holding it, and every chunk cancelled: Dask's memory manager keeps
    one replica; the setup is now a task's result, recomputed.)"""
    s = space(designs=2000)
    single = os.path.join(work, "single.zarr")
    atlas.sweep(s, single, workers=0, chunk=10, progress=False)

    file = os.path.join(work, "scheduler.json")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))  # the workers import phedra as we do
    procs = [subprocess.Popen(["dask-scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                               "--scheduler-file", file], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        wait_for(lambda: os.path.exists(file) and os.path.getsize(file) > 0, 60, "the scheduler")
        with open(file) as f:
            address = json.load(f)["address"]
        def start_worker():
            procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                                           "--nthreads", "1", "--no-dashboard", "--host", "127.0.0.1"],
                                          env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        for _ in range(2):
            start_worker()
        from distributed import Client
        with Client(address) as client:
            client.wait_for_workers(2, timeout=60)
        out = os.path.join(work, "cluster.zarr")
        result = {}
        thread = threading.Thread(target=lambda: result.update(atlas.sweep(s, out, scheduler=address, chunk=10,
                                                                           progress=False)))
        thread.start()

        def done_rows():
            try:
                return int(zarr.open_group(out, mode="r")["done"][:].sum())
            except Exception:
                return 0
        wait_for(lambda: done_rows() >= 300 or not thread.is_alive(), 120, "a part of the sweep")
        killed_at = done_rows()
        procs[1].kill()
        wait_for(lambda: done_rows() >= killed_at + 300 or not thread.is_alive(), 120, "the sweep on one worker")
        last_killed_at = done_rows()
        procs[2].kill()  # no worker left: the chunks wait, the setup is gone with it
        start_worker()
        thread.join(300)
        assert not thread.is_alive()
        assert last_killed_at < 2000, "the sweep ended before the second worker was killed"
        assert result["done"] == 2000 and result["computed_chunks"] == 200
        assert_same_atlas(single, out)
    finally:
        for p in reversed(procs):
            p.kill()
            p.wait()

    # Rows rebuilt from the atlas give the command's own figures.
    ds = atlas.open_atlas(out)
    for row in np.random.default_rng(5).choice(2000, 3, replace=False):
        path = os.path.join(work, f"row{row}.json")
        with open(path, "w") as f:
            json.dump(atlas.preset(out, int(row)), f)
        run = subprocess.run([PHEDRA, "metrics", path, "--json"], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        figures = json.loads(run.stdout)["figures"]
        for name, value in figures.items():
            stored = float(ds[name].values[row])
            assert (value is None and np.isnan(stored)) or value == stored, (row, name)


def test_the_default_local_cluster_gives_the_atlas_of_one_process(work):
    s = space(designs=64)
    atlas.sweep(s, os.path.join(work, "one.zarr"), workers=0, progress=False)
    summary = atlas.sweep(s, os.path.join(work, "local.zarr"), workers=2, progress=False)
    assert summary["computed_chunks"] == 4
    assert_same_atlas(os.path.join(work, "one.zarr"), os.path.join(work, "local.zarr"))


# -- resuming --------------------------------------------------------------------

def test_an_interrupted_sweep_resumed_equals_an_uninterrupted_one(work):
    s = space(designs=120, figures=["metrics", "buildability"])
    path = write_space(work, s)
    whole = os.path.join(work, "whole.zarr")
    atlas.sweep(path, whole, workers=0, chunk=8, progress=False)

    out = os.path.join(work, "resumed.zarr")
    p = subprocess.Popen([sys.executable, "-m", "phedra.atlas", path, "-o", out, "--workers", "0", "--chunk", "8"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)

    def done_rows():
        try:
            return int(zarr.open_group(out, mode="r")["done"][:].sum())
        except Exception:
            return 0
    wait_for(lambda: done_rows() >= 32, 120, "a part of the sweep")
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(60)
    assert p.returncode == 130, err
    assert "the same command continues" in err
    assert re.search(r"atlas: \d+/120 designs \(\d+ %\), [0-9.]+ designs/s, \d+ s left\n", err), err  # progress
    before = done_rows()
    assert 32 <= before < 120
    g = zarr.open_group(out, mode="r")
    done = g["done"][:]
    assert all(done[k:k + 8].all() or not done[k:k + 8].any() for k in range(0, 120, 8)), "a chunk half done"

    run = run_atlas(path, "-o", out, "--workers", "0", "--json")
    assert run.returncode == 0, run.stderr
    summary = json.loads(run.stdout)
    assert summary["computed_chunks"] == 15 - before // 8  # none computed twice, none missing
    assert_same_atlas(whole, out)

    again = run_atlas(path, "-o", out, "--workers", "0")
    assert again.returncode == 0 and "already complete" in again.stdout


# -- faults ----------------------------------------------------------------------

def test_a_design_past_the_time_limit_is_recorded_and_the_sweep_goes_on(work):
    s = space(designs=3, figures=["metrics"], options={"time_limit": 1e-4})
    out = os.path.join(work, "slow.zarr")
    summary = atlas.sweep(s, out, workers=0, progress=False)
    ds = atlas.open_atlas(out)
    assert summary["done"] == 3
    assert all("longer than the time limit of 0.0001 s (options.time_limit)" in e for e in ds["error"].values)
    assert not ds["valid"].values.any()


def test_a_design_that_ends_its_process_is_recorded_and_the_sweep_goes_on(work):
    s = space(designs=100, figures=["metrics", "buildability"])
    out = os.path.join(work, "crash.zarr")
    killed = []

    def kill_a_child():
        # the child evaluating designs, once it has answered a few
        def child():
            return next((c.process for c in list(atlas._evaluate._children.values())
                         if c.process is not None and c.process.poll() is None), None)
        wait_for(lambda: child() is not None, 120, "the child")
        time.sleep(0.5)  # a few designs in (one chunk: the child works through all 100, ~2 s)
        p = child()
        p.kill()
        killed.append(p.pid)
    killer = threading.Thread(target=kill_a_child)
    killer.start()
    summary = atlas.sweep(s, out, workers=0, chunk=100, progress=False)
    killer.join()
    assert killed and summary["done"] == 100
    errors = [e for e in atlas.open_atlas(out)["error"].values if e]
    assert errors == ["its evaluation ended the process evaluating it (killed by SIGKILL)"]
    assert summary["valid"] == 99


# -- bad spaces --------------------------------------------------------------------

@pytest.mark.parametrize("change, field, words", [
    ({"parameters": [{"path": "apex_heights[9]", "range": [0, 1]}]}, "parameters[0].path", "no such field"),
    ({"parameters": [{"path": "apex_heights[1]", "range": [1.2, 1.2]}]}, "parameters[0].range", "is empty"),
    ({"base": preset("helix-tube.json"), "parameters": [{"path": "tube.apex_heights[1]", "range": [0.8, 1.2]},
                                                       {"path": "trajectory.helix.radius", "range": [-2, 0]}]},
     "parameters[1].range", "every design tried with trajectory.helix.radius in [-2, 0] is invalid (at -2: "
                            "trajectory.helix.radius: must be positive, got -2)"),
    ({"figures": ["poisson"]}, "figures[0]", "unknown figure"),
    ({"sampling": "random"}, "sampling", "must be one of"),
    ({"designs": 0}, "designs", "positive whole number"),
    ({"bounds": {}}, "bounds", "unknown key"),
])
def test_a_bad_space_is_refused_naming_its_field_and_nothing_is_written(work, change, field, words):
    s = space()
    s.update(change)
    out = os.path.join(work, "bad.zarr")
    with pytest.raises(phedra.InputError) as e:
        atlas.sweep(s, out, workers=0, progress=False)
    assert e.value.field == field and words in str(e.value), str(e.value)
    assert os.listdir(work) == []


def test_the_command_exits_2_for_a_bad_space_and_3_for_an_unwritable_output(work):
    bad = write_space(work, space(parameters=[{"path": "grid.u_heights[1]", "range": [0, 1]}]))
    run = run_atlas(bad, "-o", os.path.join(work, "a.zarr"))
    assert run.returncode == 2 and "parameters[0].path: \"grid.u_heights[1]\": the preset has no such field" in run.stderr
    good = write_space(work, space(designs=4), "good.json")
    blocked = os.path.join(work, "a-file")  # a file where the atlas's folder should be (root writes anywhere else)
    open(blocked, "w").close()
    run = run_atlas(good, "-o", os.path.join(blocked, "a.zarr"), "--workers", "0")
    assert run.returncode == 3 and "cannot write the atlas" in run.stderr, run.stderr
    assert sorted(os.listdir(work)) == ["a-file", "good.json", "space.json"]
    other = write_space(work, space(designs=4, seed=4), "other.json")
    assert run_atlas(good, "-o", os.path.join(work, "a.zarr"), "--workers", "0", "--quiet").returncode == 0
    run = run_atlas(other, "-o", os.path.join(work, "a.zarr"), "--workers", "0")
    assert run.returncode == 2 and "an atlas of another space" in run.stderr


# -- using an atlas --------------------------------------------------------------------

def test_query_plot_and_the_fields(work):
    out = os.path.join(work, "a.zarr")
    atlas.sweep(space(designs=64, figures=["metrics", "buildability"]), out, workers=0, progress=False)
    ds = atlas.open_atlas(out)
    found = atlas.query(out, ["poisson.nu_12>=0", "buildable_fraction>=0.5"])
    assert found.sizes["design"] > 0
    assert (np.diff(found["distance"].values) >= 0).all()
    for row in found["design"].values:
        assert ds["poisson.nu_12"].values[row] >= 0 and ds["buildable_fraction"].values[row] >= 0.5
    everyone = ds["valid"].values & (ds["poisson.nu_12"].values >= 0) & (ds["buildable_fraction"].values >= 0.5)
    assert found.sizes["design"] == everyone.sum()
    with pytest.raises(phedra.InputError, match="the atlas has no figure mechanics.gap"):
        atlas.query(out, "mechanics.gap<=2")
    picture = os.path.join(work, "p.png")
    run = run_atlas("plot", out, "poisson.nu_12", "apex_heights[1]", "-o", picture)
    assert run.returncode == 0, run.stderr
    assert os.path.getsize(picture) > 10000
    with pytest.raises(phedra.InputError, match="X: the atlas has no variable 'poisson.nu_99'"):
        atlas.plot(out, "poisson.nu_99", "apex_heights[1]", picture)


def test_field_paths_set_what_they_name():
    d = phedra.load(preset("anti-parallelogram-tube.json"))
    p = d.preset
    q = phedra._core.with_fields(p, {"tube.apex_heights[0]": -1.0})
    assert q["tube"]["apex_heights"] == [-1.0, 0.5, 1.7, -1.0 + 1.7 - 0.5]  # its symmetry follows
    with pytest.raises(phedra.InputError, match="follows tube.apex_heights\\[0\\] \\+ tube.apex_heights\\[2\\] - "):
        phedra._core.preset_field(p, "tube.apex_heights[3]")
    g = phedra.load(preset("default.json")).preset
    turned = phedra._core.with_fields(g, {"directions[4].turn": 90.0})["directions"][4]
    assert np.dot(turned, g["directions"][4]) == pytest.approx(0.0, abs=1e-12)
    assert phedra._core.with_fields(g, {"directions[4].turn": 0.0}) == g  # bit for bit
    assert phedra._core.with_fields(g, {"trajectory[2][1]": 1.5})["trajectory"][2][1] == 1.5


def test_optimize_starts_from_the_atlas_best_rows(work):
    """phedra optimize --start ATLAS.zarr (and Python's start=): the search
    begins at the atlas's row nearest the target, which the command reads
    from the Zarr store itself."""
    out = os.path.join(work, "a.zarr")
    atlas.sweep(space(designs=64, figures=["metrics", "buildability"]), out, workers=0, progress=False)
    ds = atlas.open_atlas(out)
    ok = ds["valid"].values & ds["buildable"].values
    row = int(np.flatnonzero(ok)[np.argmax(ds["poisson.nu_12"].values[ok])])  # the atlas's extreme
    target = f"poisson.nu_12={ds['poisson.nu_12'].values[row]:.6f}"
    result = os.path.join(work, "opt.json")
    run = subprocess.run([PHEDRA, "optimize", preset("default.json"), "--target", target, "-o", result,
                          "--start", out, "--max-seconds", "20", "--json"], capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    report = json.loads(run.stdout)
    value = ds["poisson.nu_12"].values[row]
    meeting = {f"atlas row {k}" for k in np.flatnonzero(ok & (np.abs(ds["poisson.nu_12"].values - value)
                                                               <= max(0.02 * abs(value), 0.01)))}
    assert report["reached"] and report["started_from"] in meeting, (report["started_from"], meeting)
    _, r = phedra.load(preset("default.json")).optimize(target, start=out, max_seconds=20)
    assert r["reached"] and r["started_from"] == report["started_from"]

    bad = subprocess.run([PHEDRA, "optimize", preset("default.json"), "--target", target, "-o", result,
                          "--start", work], capture_output=True, text=True)
    assert bad.returncode == 2 and "--start: " + work + ": not an atlas" in bad.stderr, bad.stderr
    bad = subprocess.run([PHEDRA, "optimize", preset("default.json"), "--target", "mechanics.gap>=3", "-o", result,
                          "--start", out], capture_output=True, text=True)
    assert bad.returncode == 2 and "the atlas has none of the targets' figures (mechanics.gap)" in bad.stderr
    grid = subprocess.run([PHEDRA, "optimize", preset("grid-3x3.json"), "--target", target, "-o", result,
                           "--start", out], capture_output=True, text=True)
    assert grid.returncode == 2 and "not variations of it" in grid.stderr, grid.stderr


def test_the_example_spaces_of_the_docs_are_valid():
    spaces = {name: atlas.Space(os.path.join(ROOT, "examples", "atlas", name))
              for name in ("default-space.json", "grid-3x3-space.json")}
    assert spaces["default-space.json"].designs == 512
    grid = spaces["grid-3x3-space.json"]
    assert grid.designs == 16 * 16 * 4 and "thickest_at_t_star" in grid.figures
    values = grid.values()
    assert values.shape == (1024, 3) and values[0, 0] == -1.7 and values[-1, 0] == -1.1  # ends exact
