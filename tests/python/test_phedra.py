"""phedra from Python (issue 26): the module against the command it mirrors.
Run by the README's test command (ctest: python_module), or
    PYTHONPATH=build/python PHEDRA=build/bin/phedra /usr/bin/python3 -m pytest tests/python
or, as the suite runs them, against the package installed into a fresh venv:
    bash tests/python/run_installed.sh build build/bin/phedra
"""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import phedra

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PHEDRA = os.environ.get("PHEDRA", os.path.join(ROOT, "build", "bin", "phedra"))
PRESETS = ["default.json", "parallelogram-tube.json", "grid-3x3.json", "edge-sharing-pair.json", "all-minus.json"]


def preset(name):
    return os.path.join(ROOT, "presets", name)


def cli(*args):
    return subprocess.run([PHEDRA, *args], capture_output=True, text=True, check=False)


@pytest.mark.parametrize("name", PRESETS)
def test_evaluate_equals_phedra_sample(name):
    d = phedra.load(preset(name))
    lo, hi = d.flexion_interval
    ts = [lo, d.t_star, lo + 0.37 * (hi - lo), hi]
    run = cli("sample", preset(name), *sum((["--t", repr(t)] for t in ts), []), "--full-precision")
    assert run.returncode == 0, run.stderr
    doc = json.loads(run.stdout)
    size = d.info()["model_size"]
    for t, s in zip(ts, doc["samples"]):
        x = d.evaluate(t)
        assert x.shape == (len(doc["labels"]), 3) and x.dtype == np.float64
        assert np.max(np.abs(x - np.asarray(s["vertices"]))) <= 1e-12 * size
    assert np.array_equal(d.faces, np.asarray(doc["faces"]))
    assert [list(l) for l in d.labels] == doc["labels"]
    k = d.sample(ts)
    assert k.shape == (len(ts), len(doc["labels"]), 3)
    assert np.array_equal(k[1], d.evaluate(d.t_star))


def test_evaluate_owns_its_array_and_many_calls_agree():
    d = phedra.load(preset("default.json"))
    a = d.evaluate(0.3)
    b = d.evaluate(0.3)
    a[0, 0] = 1e9  # a copy of its own: changing one leaves the other
    assert b[0, 0] != 1e9
    assert np.isfinite(b).all()


def test_load_from_dict_and_json_text_equals_file():
    with open(preset("grid-3x3.json")) as f:
        text = f.read()
    a, b, c = phedra.load(preset("grid-3x3.json")), phedra.load(json.loads(text)), phedra.load(text)
    assert np.array_equal(a.evaluate(a.t_star), b.evaluate(b.t_star))
    assert np.array_equal(a.evaluate(a.t_star), c.evaluate(c.t_star))
    assert a.info()["kind"] == c.info()["kind"] and "grid" in a.info()["kind"]
    assert a.info()["source"].endswith("grid-3x3.json") and b.info()["source"] == "a dict"


def test_reports_match_the_command():
    for name in ["default.json", "grid-3x3.json"]:
        d = phedra.load(preset(name))
        check = json.loads(cli("check", preset(name), "--json").stdout)
        b = d.buildability()
        assert b["summary"] == check["buildability"]["summary"]
        assert b["buildable"] is True
        geometry = d.check()
        assert geometry["passed"] is True and geometry["passed"] == check["geometry_passed"]
        assert geometry["isometry"] == check["isometry"] and geometry["planarity"] == check["planarity"]
        m = d.metrics(samples=11)
        metrics = json.loads(cli("metrics", preset(name), "--samples", "11", "--json").stdout)
        for key, value in metrics["at_t_star"]["poisson"].items():
            assert m["at_t_star"]["poisson"][key] == pytest.approx(value, rel=1e-12)
        assert m["at_t_star"]["length"] == pytest.approx(metrics["at_t_star"]["length"], rel=1e-12)
        assert len(m["samples"]) == len(metrics["samples"])
    partly = phedra.load(os.path.join(ROOT, "tests", "data", "partly-buildable.json"))
    assert partly.buildability()["buildable"] is False
    oversized = phedra.load(os.path.join(ROOT, "tests", "data", "oversized-panels.json"))
    assert oversized.buildability()["oversized"] == 3
    assert oversized.buildability(max_panel_ratio=0)["sliver"] == 3


def test_errors_name_the_field_like_the_command():
    d = phedra.load(preset("default.json"))
    with pytest.raises(phedra.InputError) as e:
        d.evaluate(100.0)
    assert e.value.field == "t" and "outside the flexion interval" in str(e.value)
    with pytest.raises(phedra.FileError) as f:
        phedra.load(os.path.join(ROOT, "no-such-preset.json"))
    assert "cannot open" in str(f.value)
    bad = os.path.join(ROOT, "tests", "data", "bad", "apexes-consecutive-equal.json")
    run = cli("info", bad)
    with pytest.raises(phedra.InputError) as g:
        phedra.load(bad)
    assert run.returncode == 2 and str(g.value) in run.stderr
    with pytest.raises(phedra.InputError):
        phedra.load("{ not json")
    assert issubclass(phedra.InputError, phedra.Error) and issubclass(phedra.FileError, phedra.Error)


def test_repair_gives_a_buildable_design(tmp_path):
    d = phedra.load(os.path.join(ROOT, "tests", "data", "repairable-tube.json"))
    assert d.buildability()["buildable"] is False
    repaired, result = d.repair(max_seconds=30)
    assert result["found"] and repaired is not None
    assert repaired.buildability()["buildable"] is True
    assert result["changes"] and result["nearest_changes"] == len(result["changes"])
    with pytest.raises(phedra.InputError):
        d.repair(vary="heights")
    # Written and checked by the command, not trusted.
    out = tmp_path / "repaired.json"
    out.write_text(json.dumps(repaired.preset))
    assert cli("check", str(out)).returncode == 0
    assert result["closest_design"] is None and result["closest_fraction"] is None
    # Out of time: no result, but the closest design to inspect, said so.
    none, failed = d.repair(max_seconds=1e-6)
    assert none is None and not failed["found"]
    assert "stay not simple" in failed["closest"]
    assert isinstance(failed["closest_design"], phedra.Design) and failed["closest_fraction"] == 0.0
    assert failed["closest_design"].preset["name"] == d.preset["name"] + "-closest"


def test_optimize_reaches_a_target_that_the_command_confirms(tmp_path):
    d = phedra.load(preset("grid-3x3.json"))
    optimized, result = d.optimize("poisson.nu_12=-0.8", max_seconds=300)
    assert result["reached"] and optimized is not None, result["binding"]
    assert result["targets"][0]["met"] and result["binding"] is None
    assert optimized.name == "grid-3x3-optimized"
    # Written and measured by the command, not trusted.
    out = tmp_path / "optimized.json"
    out.write_text(json.dumps(optimized.preset))
    figures = json.loads(cli("metrics", str(out), "--json").stdout)["figures"]
    assert abs(figures["poisson.nu_12"] + 0.8) <= 0.016
    assert cli("check", str(out)).returncode == 0
    # Several targets as a dict of equalities; a bad name raises with the command's message.
    _, both = phedra.load(preset("parallelogram-tube.json")).optimize({"poisson.nu_12": 0.5}, max_seconds=300)
    assert both["reached"]
    with pytest.raises(phedra.InputError, match="unknown figure"):
        d.optimize(["poisson.nu_21=1"])


def test_optimize_fits_points_given_as_an_array():
    d = phedra.load(preset("default.json"))
    target = d.preset
    target["apex_heights"][1] += 0.15
    points = phedra.load(target).evaluate(d.t_star)[::2] + np.array([0.5, -0.2, 0.1])
    fitted, result = d.optimize(fit=points, fit_tol=0.02, vary="apex_heights", max_seconds=300)
    assert result["reached"], result["binding"]
    assert result["targets"][0]["after"] <= 0.02 < result["targets"][0]["before"]
    with pytest.raises(phedra.InputError):
        d.optimize(fit=np.zeros((2, 3)))


def test_export_writes_what_the_command_writes(tmp_path):
    d = phedra.load(preset("parallelogram-tube.json"))
    for ext in ["glb", "gltf", "fold", "json", "obj", "ply"]:
        path = tmp_path / f"tube.{ext}"
        d.export(str(path))
        assert path.stat().st_size > 0
    with open(tmp_path / "tube.json") as f:
        doc = json.load(f)
    assert len(doc["samples"]) == 41
    assert np.max(np.abs(np.asarray(doc["samples"][0]["vertices"]) - d.evaluate(d.flexion_interval[0]))) < 1e-12 * d.info()["model_size"]
    with pytest.raises(phedra.InputError) as e:
        d.export(str(tmp_path / "tube.stl"))
    assert e.value.field == "thickness"
    assert not (tmp_path / "tube.stl").exists()
    with pytest.raises(phedra.InputError) as e:
        d.export(str(tmp_path / "tube.xyz"))
    assert e.value.field == "path"


def test_thick_plates_as_the_command_has_them(tmp_path):
    d = phedra.load(preset("parallelogram-tube.json"))
    report = d.thick(0.08, side="front", hinge_gap=0.02)
    command = json.loads(cli("check", preset("parallelogram-tube.json"), "--thickness", "0.08", "--plate-side", "front",
                             "--hinge-gap", "0.02", "--json").stdout)["thick"]
    assert report["plates"] == command["plates"] == 40
    assert report["thick_interval"] == pytest.approx(command["thick_interval"], abs=1e-12)
    assert report["volume"] == pytest.approx(command["volume"], rel=1e-12)
    assert report["thickest_at_t_star"] == pytest.approx(command["thickest_at_t_star"], rel=1e-12)
    d.export(str(tmp_path / "plates.stl"), thickness=0.08, side="front", hinge_gap=0.02)
    assert cli("generate", preset("parallelogram-tube.json"), "--thickness", "0.08", "--plate-side", "front",
               "--hinge-gap", "0.02", "-o", str(tmp_path / "command.stl")).returncode == 0
    assert (tmp_path / "plates.stl").read_bytes()[80:] == (tmp_path / "command.stl").read_bytes()[80:]
    with pytest.raises(phedra.InputError) as e:
        d.thick(0.08, side="up")
    assert e.value.field == "side" and "--" not in str(e.value)
    with pytest.raises(phedra.InputError) as e:
        d.export(str(tmp_path / "plates.glb"), thickness=0.08)
    assert e.value.field == "thickness"


def test_the_example_sweeps_and_plots(tmp_path):
    out = tmp_path / "nu12.png"
    env = dict(os.environ, MPLBACKEND="Agg")
    run = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "sweep_apex_height.py"), "--steps", "5", "-o", str(out)],
                         capture_output=True, text=True, env=env, check=False)
    assert run.returncode == 0, run.stderr
    assert "nu_12 = " in run.stdout and out.stat().st_size > 1000
    with open(out, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_mechanics_equals_the_command_and_its_arrays_hold_together():
    d = phedra.load(preset("parallelogram-tube.json"))
    m = d.mechanics(fraction=0.4, modes=3, rest_fraction=0.5, samples=21)
    run = cli("mechanics", preset("parallelogram-tube.json"), "--fraction", "0.4", "--modes", "3", "--energy",
              "--rest-fraction", "0.5", "--samples", "21", "--json")
    assert run.returncode == 0, run.stderr
    doc = json.loads(run.stdout)
    for key in ["t", "nodes", "bars", "hinges", "rigid_body_modes", "equilibria", "bistable"]:
        assert m[key] == doc[key], key
    # The eigen-solver's results to rounding: the command may run other BLAS kernels than this process
    # (it chooses OpenBLAS's kernels for the processor: docs/performance.md).
    for key in ["eigenvalues", "gap", "motion_alignment", "motion_stiffness"]:
        assert m[key] == pytest.approx(doc[key], rel=1e-9, abs=0), key
    # K from its COO triplets: the modes are its eigenvectors, the velocity its soft direction.
    n = m["K"]["shape"][0]
    K = np.zeros((n, n))
    np.add.at(K, (m["K"]["row"], m["K"]["col"]), m["K"]["value"])
    assert np.allclose(K, K.T, atol=1e-9 * np.abs(K).max())
    for phi, value in zip(m["modes"], m["eigenvalues"]):
        v = phi.ravel()
        assert np.linalg.norm(K @ v - value * v) <= 1e-8 * np.abs(K).max()
    u = m["velocity"].ravel() / np.linalg.norm(m["velocity"])
    assert abs(u @ K @ u - m["motion_stiffness"]) <= 1e-9 * m["motion_stiffness"]
    # Corner nodes are vertices of evaluate(t); the n5b8 centres are not (-1).
    x = d.evaluate(m["t"])
    corners = m["node_vertex"] >= 0
    assert corners.sum() == m["mobility"]["corner_nodes"]
    assert np.allclose(m["node_positions"][corners], x[m["node_vertex"][corners]], atol=1e-12)
    e = m["energy"]
    assert e["t"].shape == e["E"].shape == e["dE_dt"].shape == (21,)
    assert np.isnan(e["dE_dt"][0]) and np.isnan(e["dE_dt"][-1]) and not np.isnan(e["dE_dt"][1:-1]).any()
    assert np.allclose(e["E"], [s["E"] for s in doc["energy"]], rtol=0, atol=1e-15)


@pytest.mark.parametrize("kwargs,field", [({"bar": -1.0}, "bar"), ({"fold": 0.0}, "fold"), ({"panels": "n6"}, "panels"),
                                          ({"fraction": 1.5}, "fraction"), ({"rest_t": 99.0}, "rest_t"),
                                          ({"modes": 0}, "modes"), ({"material": (1e3, 0.3)}, "thickness"),
                                          ({"material": (1e3, 0.3), "thickness": 0.1, "panels": "n4b5"}, "material")])
def test_mechanics_errors_name_the_keyword(kwargs, field):
    d = phedra.load(preset("parallelogram-tube.json"))
    with pytest.raises(phedra.InputError) as e:
        d.mechanics(**kwargs)
    assert e.value.field == field


def _evaluate_at_t_star(design):
    return design.evaluate(design.t_star)


def test_design_pickles_by_its_preset_and_travels_to_another_process():
    import multiprocessing
    import pickle

    d = phedra.load(preset("grid-3x3.json"))
    copy = pickle.loads(pickle.dumps(d))
    assert copy.preset == d.preset
    assert copy.info()["source"] == d.info()["source"]
    np.testing.assert_array_equal(copy.evaluate(copy.t_star), d.evaluate(d.t_star))
    # A fresh interpreter (spawn) gets it pickled, as Dask's workers do.
    with multiprocessing.get_context("spawn").Pool(1) as pool:
        there = pool.apply(_evaluate_at_t_star, (d,))
    np.testing.assert_array_equal(there, d.evaluate(d.t_star))
    with pytest.raises(Exception):
        phedra.Design.__new__(phedra.Design).__setstate__(("{}",))


def test_version_and_a_docstring_for_everything_public():
    assert re_version.fullmatch(phedra.__version__)
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        assert f"project(phedra VERSION {phedra.__version__} " in f.read()
    assert phedra.__doc__ and "P-hedra" in phedra.__doc__
    for name in phedra.__all__:
        if name == "__version__":
            continue
        assert getattr(phedra, name).__doc__, name
    for name in dir(phedra.Design):
        if name.startswith("_"):
            continue
        assert getattr(phedra.Design, name).__doc__, f"Design.{name}"
    for cls in (phedra.Error, phedra.InputError, phedra.FileError):
        assert issubclass(cls, phedra.Error) and len(cls.__doc__) > 20


re_version = __import__("re").compile(r"[0-9]+\.[0-9]+\.[0-9]+")


def test_fractions_to_t_with_exact_ends_and_array_likes():
    d = phedra.load(preset("default.json"))
    lo, hi = d.flexion_interval
    assert d.t_at_fraction(0.0) == lo and d.t_at_fraction(1.0) == hi
    assert d.t_at_fraction(np.float64(1.0)) == hi
    ts = d.t_at_fraction(np.array([[0.0, 0.5], [0.25, 1.0]]))
    assert ts.shape == (2, 2) and ts[1, 1] == hi and ts[0, 0] == lo
    # a + 1.0 * (b - a) lands past t_mu in floating point; the fraction does not.
    assert d.evaluate(d.t_at_fraction(1.0)).shape == (len(d.labels), 3)
    by_fraction = d.sample(fractions=[0.0, 0.5, 1.0])
    by_t = d.sample(np.array([lo, d.t_at_fraction(0.5), hi]))
    np.testing.assert_array_equal(by_fraction, by_t)
    np.testing.assert_array_equal(d.sample((lo, hi)), d.sample([lo, hi]))
    np.testing.assert_array_equal(d.sample(range(0)), np.zeros((0, len(d.labels), 3)))
    with pytest.raises(phedra.InputError) as e:
        d.t_at_fraction(1.5)
    assert e.value.field == "fraction"
    with pytest.raises(phedra.InputError) as e:
        d.sample(fractions=[0.5, -0.1])
    assert e.value.field == "fractions" and "fractions must be in [0, 1]" in str(e.value)


def test_bad_arguments_are_input_errors_named_by_keyword():
    d = phedra.load(preset("default.json"))
    for bad, field in [((-2.0,), "ts"), ((["a", "b"],), "ts"), (("0.5",), "ts"), ((), "ts"), (([[0.0]],), "ts")]:
        with pytest.raises(phedra.InputError) as e:
            d.sample(*bad)
        assert e.value.field == field, bad
    with pytest.raises(phedra.InputError) as e:
        d.sample([d.t_star], fractions=[0.5])
    assert e.value.field == "fractions"
    with pytest.raises(phedra.InputError) as e:
        phedra.load(np.zeros((3, 3)))
    assert e.value.field == "preset" and "numpy array" in str(e.value)


def test_metrics_series_as_arrays_and_info_with_the_limits():
    d = phedra.load(preset("grid-3x3.json"))
    m = d.metrics(samples=11)
    series = m["series"]
    k = len(m["samples"])
    assert series["t"].shape == (k,) and series["length"].shape == (k, 3) and series["strain_rate"].shape == (k, 3)
    for i, s in enumerate(m["samples"]):
        assert series["t"][i] == s["t"]
        np.testing.assert_array_equal(series["length"][i], s["length"])
        nu = s["poisson"]["nu_12"]
        assert (np.isnan(series["poisson"]["nu_12"][i]) if nu is None else series["poisson"]["nu_12"][i] == nu)
    info = d.info()
    doc = json.loads(cli("info", preset("grid-3x3.json"), "--json").stdout)
    assert info["limits"] == doc["limits"]


def _gltf_json(path):
    import struct
    with open(path, "rb") as f:
        data = f.read()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length])


def test_export_nodes_and_cycle_as_the_command(tmp_path):
    d = phedra.load(preset("parallelogram-tube.json"))
    for kwargs, flag in [({"nodes": True}, "--nodes"), ({"cycle": True}, "--cycle"), ({}, None)]:
        mine, theirs = tmp_path / "py.glb", tmp_path / "cli.glb"
        d.export(str(mine), **kwargs)
        run = cli("generate", preset("parallelogram-tube.json"), "-o", str(theirs), *([flag] if flag else []))
        assert run.returncode == 0, run.stderr
        a, b = _gltf_json(mine), _gltf_json(theirs)
        assert len(a["nodes"]) == len(b["nodes"]), kwargs
        assert [len(x["samplers"]) for x in a["animations"]] == [len(x["samplers"]) for x in b["animations"]], kwargs
        counts = [a["accessors"][s["input"]]["count"] for x in a["animations"] for s in x["samplers"]]
        assert counts == [b["accessors"][s["input"]]["count"] for x in b["animations"] for s in x["samplers"]], kwargs
    assert len(_gltf_json(tmp_path / "py.glb")["nodes"]) < len(d.faces)  # morph targets: one mesh
    for kwargs, field in [({"nodes": True}, "nodes"), ({"cycle": True}, "cycle")]:
        with pytest.raises(phedra.InputError) as e:
            d.export(str(tmp_path / "x.obj"), **kwargs)
        assert e.value.field == field
    with pytest.raises(phedra.InputError) as e:
        d.export(str(tmp_path / "x.glb"), cycle=True, t=d.t_star)
    assert e.value.field == "cycle"
    # count configurations from t_lambda to t_mu exactly (no t an ulp past the interval)
    d.export(str(tmp_path / "x.fold"), count=7)
    frames = json.loads((tmp_path / "x.fold").read_text())["file_frames"]
    assert len(frames) == 7


def test_fit_points_that_span_no_surface_are_refused():
    d = phedra.load(preset("default.json"))
    for points, words in [(np.ones((10, 3)), "all coincide"), (np.outer(np.arange(5.0), [1.0, 2.0, 0.5]), "one line"),
                          (np.zeros((2, 3)), "(k, 3) array with k >= 3")]:
        with pytest.raises(phedra.InputError) as e:
            d.optimize(fit=points, max_seconds=5)
        assert e.value.field == "fit" and words in str(e.value), words


@pytest.mark.parametrize("name", ["default.json", "grid-3x3.json"])
def test_fold_numbering_exposed_and_triangles_flagged(tmp_path, name):
    d = phedra.load(preset(name))
    path = tmp_path / "d.fold"
    d.export(str(path), t=d.t_star)
    fold = json.loads(path.read_text())
    coords = np.array(fold["vertices_coords"])
    x = d.evaluate(d.t_star)
    number = d.fold_vertex
    assert number.shape == (len(x),) and number.min() >= 0 and number.max() == len(coords) - 1
    size = d.info()["model_size"]
    assert np.abs(coords[number] - x).max() <= 1e-12 * size
    faces, triangles = d.faces, d.triangles
    assert triangles.shape == (len(faces),)
    for f, quad in enumerate(faces):
        expected = list(dict.fromkeys(number[quad]))  # its distinct FOLD corners, in order
        assert fold["faces_vertices"][f] == expected
        assert triangles[f] == (len(expected) == 3)
    if name == "default.json":  # faces[6]: vertices 7 and 15 at one point over the whole motion
        assert triangles[6] and number[7] == number[15]


def test_errors_name_python_keywords_not_command_options():
    d = phedra.load(preset("default.json"))
    with pytest.raises(phedra.InputError) as e:
        d.metrics(samples=1)
    assert e.value.field == "samples" and "--" not in str(e.value)
    for kwargs, field in [({"max_growth": -1.0}, "max_growth"), ({"max_panel_ratio": float("nan")}, "max_panel_ratio")]:
        with pytest.raises(phedra.InputError) as e:
            d.buildability(**kwargs)
        assert e.value.field == field and field + ": must be 0 (no bound) or a number, 1 or more" in str(e.value)
