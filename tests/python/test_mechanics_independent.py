"""phedra mechanics against an independent bar-and-hinge code (mechanics_reference.py)
that reads the configurations phedra writes: eigenvalues within 1e-6 relative,
alignment and gap within 1e-6, the energy within 1e-9 of its largest value, the
equilibria within 1e-8 of the interval; on shipped presets and on designs made
here by jittering them at random (neither code has seen them).
"""
import json
import os
import subprocess
import tempfile

import numpy as np
import pytest

import mechanics_reference as ref

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PHEDRA = os.environ.get("PHEDRA", os.path.join(ROOT, "build", "bin", "phedra"))


def phedra_json(*args):
    run = subprocess.run([PHEDRA, *args, "--json"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def jittered(name, seed, tmp):
    """A shipped preset with its apex heights and trajectory moved at random (a design
    neither code has seen); None when phedra refuses it (tried again with another seed)."""
    rng = np.random.default_rng(seed)
    doc = json.load(open(os.path.join(ROOT, "presets", name)))
    for _ in range(20):
        d = json.loads(json.dumps(doc))
        if "apex_heights" in d:
            d["apex_heights"] = [h + rng.uniform(-0.05, 0.05) for h in d["apex_heights"]]
        if isinstance(d.get("trajectory"), list):
            d["trajectory"] = [[c + rng.uniform(-0.03, 0.03) for c in p] for p in d["trajectory"]]
        if "grid" in d:
            d["grid"]["u_heights"] = [h + rng.uniform(-0.05, 0.05) for h in d["grid"]["u_heights"]]
        path = os.path.join(tmp, f"{name}-{seed}.json")
        json.dump(d, open(path, "w"))
        if subprocess.run([PHEDRA, "info", path], capture_output=True).returncode == 0:
            return path
    return None


def compare_stiffness(preset, fraction, panels):
    mine = phedra_json("mechanics", preset, "--fraction", repr(fraction), "--panels", panels, "--modes", "4")
    lo, hi = phedra_json("info", preset)["flexion_interval"]
    t, h = mine["t"], 1e-3 * (hi - lo)
    frames, faces, reference = ref.positions(PHEDRA, preset, [t, t - 2 * h, t - h, t + h, t + 2 * h])
    size = ref.bounding_diagonal(reference)
    model = ref.Model(frames[0], faces, size, panels)
    rigid, values, vectors, largest = ref.modes(model, 4)
    assert (len(model.x), len(model.bars), len(model.folds), len(model.bends)) == (
        mine["nodes"], mine["bars"], mine["hinges"]["fold"], mine["hinges"]["bend"])
    assert rigid == mine["rigid_body_modes"] == 6
    assert np.max(np.abs(values - mine["eigenvalues"]) / values) <= 1e-6
    assert abs(largest - mine["largest_eigenvalue"]) <= 1e-6 * largest
    assert abs(values[1] / values[0] - mine["gap"]) <= 1e-6 * mine["gap"]
    v = model.nodes_from_vertices(ref.velocity(frames[1:], h)).ravel()
    q = model.rigid_basis()
    v -= q @ (q.T @ v)
    mode = vectors[:, 0] - q @ (q.T @ vectors[:, 0])
    alignment = abs(mode @ v) / (np.linalg.norm(mode) * np.linalg.norm(v))
    assert abs(alignment - mine["motion_alignment"]) <= 1e-6
    u = v / np.linalg.norm(v)
    assert abs(u @ model.stiffness() @ u - mine["motion_stiffness"]) <= 1e-6 * mine["motion_stiffness"]


CASES = [("default.json", 0.3, "n5b8"), ("default.json", 0.7, "n4b5"), ("parallelogram-tube.json", 0.5, "n5b8"),
         ("edge-sharing-pair.json", 0.4, "n4b5"), ("anti-parallelogram-tube.json", 0.6, "n5b8")]


@pytest.mark.parametrize("name,fraction,panels", CASES)
def test_stiffness_of_shipped_presets_agrees_with_independent_code(name, fraction, panels):
    compare_stiffness(os.path.join(ROOT, "presets", name), fraction, panels)


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_stiffness_of_unseen_designs_agrees_with_independent_code(seed):
    with tempfile.TemporaryDirectory() as tmp:
        name = ["all-plus.json", "parallelogram-tube.json", "all-minus.json"][seed % 3]
        path = jittered(name, seed, tmp)
        assert path, "no valid jittered design"
        compare_stiffness(path, 0.25 + 0.1 * (seed % 5), "n4b5" if seed % 2 else "n5b8")


def test_energy_landscape_and_equilibria_agree_with_independent_code():
    preset = os.path.join(ROOT, "tests", "data", "bistable.json")
    mine = phedra_json("mechanics", preset, "--energy", "--rest-fraction", "0.95", "--samples", "41", "--panels", "n4b5")
    lo, hi = mine["t_lambda"], mine["t_mu"]
    width = hi - lo
    samples = mine["energy"]
    ts = [s["t"] for s in samples]
    frames, faces, reference = ref.positions(PHEDRA, preset, [mine["rest_t"]] + ts)
    size = ref.bounding_diagonal(reference)
    model = ref.Model(frames[0], faces, size, "n4b5")
    rest = [ref.signed_angle(*(model.x[i] for i in h)) for h, _, _ in model.folds]

    def fold_angles(x_vertices, near):
        x = model.nodes_from_vertices(x_vertices)
        return [ref.continuous(ref.signed_angle(*(x[i] for i in h)), n) for (h, _, _), n in zip(model.folds, near)]

    def energy(angles):
        return sum(0.5 * k * L * (a - a0) ** 2 for (_, L, k), a, a0 in zip(model.folds, angles, rest))

    # E at every sample, the angles carried continuously from the rest state outwards.
    order = np.argsort(np.abs(np.array(ts) - mine["rest_t"]))
    angles = {}
    for i in order:
        nearest = min(angles, key=lambda j: abs(ts[j] - ts[i])) if angles else None
        angles[i] = fold_angles(frames[1 + i], rest if nearest is None else angles[nearest])
    largest = max(energy(angles[i]) for i in range(len(ts)))
    assert abs(largest - mine["largest_E"]) <= 1e-9 * largest
    for i, s in enumerate(samples):
        assert abs(energy(angles[i]) - s["E"]) <= 1e-9 * largest

    def rate(t):
        """dE/dt from the written configurations (differences of positions, not of E)."""
        h = 1e-4 * width
        f, _, _ = ref.positions(PHEDRA, preset, [t, t - 2 * h, t - h, t + h, t + 2 * h])
        x = model.nodes_from_vertices(f[0])
        v = model.nodes_from_vertices(ref.velocity(f[1:], h))
        total = 0.0
        for (h_nodes, L, k), a0 in zip(model.folds, rest):
            a = ref.continuous(ref.signed_angle(*(x[i] for i in h_nodes)), a0)
            g = ref.angle_gradient(*(x[i] for i in h_nodes))
            total += k * L * (a - a0) * sum(gi @ v[n] for gi, n in zip(g, h_nodes))
        return total

    for s in samples[5:-5:7]:  # away from the limits, where dE/dt is finite
        r = rate(s["t"])
        assert abs(r - s["dE_dt"]) <= 1e-6 * max(abs(r), 1e-3 * largest / width)
    # Every equilibrium besides the rest state: dE/dt changes sign within 1e-8 of the interval.
    others = [e for e in mine["equilibria"] if not e["rest"]]
    assert len(others) == 2 and mine["bistable"]
    for e in others:
        before, after = rate(e["t"] - 1e-8 * width), rate(e["t"] + 1e-8 * width)
        assert (before < 0 < after) if e["kind"] == "minimum" else (before > 0 > after)


def read_glb(path):
    """The JSON and binary chunks of a .glb."""
    import struct

    data = open(path, "rb").read()
    length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + length])
    start = 20 + length + 8
    return doc, data[start:]


def accessor(doc, blob, index):
    a = doc["accessors"][index]
    view = doc["bufferViews"][a["bufferView"]]
    width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
    dtype = {5126: np.float32, 5125: np.uint32}[a["componentType"]]
    offset = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    return np.frombuffer(blob, dtype=dtype, count=a["count"] * width, offset=offset).reshape(a["count"], width)


def test_the_modes_glb_holds_eigenvectors_of_the_independent_stiffness():
    preset = os.path.join(ROOT, "presets", "parallelogram-tube.json")
    with tempfile.TemporaryDirectory() as tmp:
        glb = os.path.join(tmp, "modes.glb")
        mine = phedra_json("mechanics", preset, "--fraction", "0.4", "--modes", "3", "-o", glb)
        doc, blob = read_glb(glb)
    primitive = doc["meshes"][0]["primitives"][0]
    to_preset = lambda p: np.column_stack([p[:, 0], -p[:, 2], p[:, 1]])  # glTF (x, y, z) = preset (x, z, -y)
    rest = to_preset(accessor(doc, blob, primitive["attributes"]["POSITION"]).astype(float))
    frames, faces, reference = ref.positions(PHEDRA, preset, [mine["t"]])
    model = ref.Model(frames[0], faces, ref.bounding_diagonal(reference), "n5b8")
    # Each mesh vertex is a model node (float32 positions).
    nearest = [int(np.argmin(np.linalg.norm(model.x - p, axis=1))) for p in rest]
    assert sorted(nearest) == list(range(len(model.x)))
    assert np.max(np.linalg.norm(model.x[nearest] - rest, axis=1)) <= 1e-6 * ref.bounding_diagonal(reference)
    K = model.stiffness()
    vectors = []
    for k, value in enumerate(mine["eigenvalues"][:3]):
        d = to_preset(accessor(doc, blob, primitive["targets"][2 * k]["POSITION"]).astype(float))
        phi = np.zeros_like(model.x)
        phi[nearest] = d
        phi = phi.ravel() / np.linalg.norm(phi)
        assert abs(phi @ K @ phi - value) <= 1e-5 * value
        vectors.append(phi)
    gram = np.array(vectors) @ np.array(vectors).T
    assert np.max(np.abs(gram - np.eye(3))) <= 1e-5
