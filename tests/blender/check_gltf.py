# Imports a phedra glTF into Blender (headless) and checks that it plays the
# exact motion: at every keyframe, and at every whole frame between (24 fps),
# every vertex Blender shows is within the tolerance of `phedra sample` at the
# same t.
# Also reads the scene metadata and times the import and a frame change.
#
# usage: blender -b --factory-startup --python tests/blender/check_gltf.py -- \
#            PHEDRA_BINARY PRESET FILE.glb [--max-import-seconds S] [--max-frame-seconds S] [--poses N] \
#            [PRESET FILE.glb [options]]...
# Each file in turn in one Blender (its start takes seconds; the scene is reset
# between files). Prints one JSON line a file starting with "phedra-blender:";
# exits 1 when a check fails.
import json
import subprocess
import sys
import time

# Debian's Blender 3.4 importer still uses numpy.bool, which bookworm's numpy
# removed: give it back before the importer runs (a packaging mismatch).
import warnings
import numpy
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    if "bool" not in numpy.__dict__:
        numpy.bool = bool

import bpy
from mathutils import Vector, kdtree



def check(phedra, preset, path, options):
    """Imports `path` into an empty scene and checks it against `phedra sample` of `preset`; prints the report."""
    bpy.ops.wm.read_factory_settings(use_empty=True)  # no default cube
    failures = []
    started = time.perf_counter()
    bpy.ops.import_scene.gltf(filepath=path)
    import_seconds = time.perf_counter() - started
    scene = bpy.context.scene

    # Blender keeps scenes[0].extras as the scene's custom properties.
    if "phedra" not in scene.keys():
        failures.append("the scene has no 'phedra' custom property (scenes[0].extras)")
        info = {}
    else:
        info = scene["phedra"].to_dict()
    size = info.get("model_size", 1.0)
    ts = list(info.get("keyframe_t", []))
    tolerance = info.get("vertex_tolerance", 0.0) / size

    # Keyframe frames: those of the first animation curve (every curve has all of
    # them: one per shape key, or per node rotation channel).
    curves = [c for a in bpy.data.actions for c in a.fcurves]
    frames = [p.co.x for p in curves[0].keyframe_points] if curves else []
    if ts and len(frames) != len(ts):
        failures.append(f"{len(frames)} keyframe frames in Blender, {len(ts)} keyframes in the file")

    # Shape keys named by t (meshes[].extras.targetNames).
    names = [k.name for o in scene.objects if o.type == "MESH" and o.data.shape_keys for k in o.data.shape_keys.key_blocks[1:]]
    if info.get("representation") == "morph targets" and ts and not all(n.startswith("t=") for n in names):
        failures.append(f"shape keys not named by t: {names[:3]}")

    depsgraph = bpy.context.evaluated_depsgraph_get()
    meshes = [o for o in scene.objects if o.type == "MESH"]


    def shown():
        """Every vertex Blender shows, world space (shape keys and node transforms applied)."""
        out = []
        graph = bpy.context.evaluated_depsgraph_get()
        for o in meshes:
            e = o.evaluated_get(graph)
            m = e.to_mesh()
            w = e.matrix_world
            out.extend(w @ v.co for v in m.vertices)
            e.to_mesh_clear()
        return out


    def blender_to_preset(v):
        # Blender imports glTF Y-up as Z-up: Blender (x, y, z) = glTF (x, -z, y) = preset (x, y, z).
        return Vector((v.x, v.y, v.z))


    # The poses: every keyframe (exact, up to float32), and every whole frame a
    # user plays (24 fps), whose t the file's time map gives (extras time_map:
    # linear in t but within ease seconds of a flexion limit, docs/formats.md);
    # those are mostly between keyframes and must be within the file's vertex tolerance.
    def eased_fraction(phi, e0, e1):
        phi = min(max(phi, 0.0), 1.0)
        k = 1.0 / (1.0 - 0.5 * e0 - 0.5 * e1)
        if phi < e0:
            return k * phi * phi / (2.0 * e0)
        if phi > 1.0 - e1:
            return 1.0 - k * (1.0 - phi) * (1.0 - phi) / (2.0 * e1)
        return k * (phi - 0.5 * e0)


    def t_at(seconds):
        for s in info["time_map"]["segments"]:
            (start, end), (t0, t1), (e0, e1) = s["seconds"], s["t"], s["ease_seconds"]
            if seconds <= end:
                d = end - start
                g = eased_fraction((seconds - start) / d, e0 / d, e1 / d) if d > 0 else 1.0
                return t1 if g >= 1.0 else t0 + g * (t1 - t0)
        return info["time_map"]["segments"][-1]["t"][1]


    forward = [0]
    for k in range(1, len(ts)):
        if ts[k] <= ts[k - 1]:
            break
        forward.append(k)
    poses = [(frames[k], ts[k], 2e-5) for k in forward]
    if len(forward) > 1:
        if "time_map" not in info:
            failures.append("the file has no time_map in its extras")
        else:
            f0, f1 = frames[0], frames[forward[-1]]
            last = info["time_map"]["segments"][-1]["seconds"][1]
            for frame in range(int(f0 // 1) + 1, int(f1 // 1)):
                poses.append((float(frame), t_at((frame - f0) / (f1 - f0) * last), tolerance + 2e-5))
    if options["--poses"] and len(poses) > options["--poses"]:
        step = len(poses) / options["--poses"]
        poses = [poses[int(i * step)] for i in range(int(options["--poses"]))]

    worst_key = worst_between = 0.0
    frame_seconds = []
    if poses:
        args = [phedra, "sample", preset]
        for _, t, _ in poses:
            args += ["--t", repr(t)]
        sample = json.loads(subprocess.run(args, check=True, capture_output=True).stdout)
        # Which phedra vertex each Blender vertex is: nearest at the first pose (a
        # keyframe, where the file is exact), then kept.
        exact = [Vector(p) for p in sample["samples"][0]["vertices"]]
        tree = kdtree.KDTree(len(exact))
        for i, p in enumerate(exact):
            tree.insert(p, i)
        tree.balance()
        for p, (frame, t, limit) in enumerate(poses):
            whole, sub = int(frame // 1), frame % 1
            began = time.perf_counter()
            scene.frame_set(whole, subframe=sub)
            vertices = [blender_to_preset(v) for v in shown()]
            frame_seconds.append(time.perf_counter() - began)
            if p == 0:
                match = [tree.find(v)[1] for v in vertices]
            expected = sample["samples"][p]["vertices"]
            here = max((v - Vector(expected[i])).length for v, i in zip(vertices, match)) / size
            if limit == 2e-5:
                worst_key = max(worst_key, here)
            else:
                worst_between = max(worst_between, here)
            if here > limit:
                failures.append(f"t = {t}: a vertex {here:.3e} of the model size from phedra sample (limit {limit:.1e})")
                if len(failures) > 5:
                    break

    # A frame change on its own (no Python vertex copies): the median of a few.
    change = []
    if frames:
        for k in range(min(8, len(frames))):
            f = frames[(k * 7) % len(frames)]
            began = time.perf_counter()
            scene.frame_set(int(f))
            bpy.context.evaluated_depsgraph_get().update()
            change.append(time.perf_counter() - began)
    frame_change = sorted(change)[len(change) // 2] if change else 0.0

    if import_seconds > options["--max-import-seconds"]:
        failures.append(f"import took {import_seconds:.2f} s (limit {options['--max-import-seconds']} s)")
    if frame_change > options["--max-frame-seconds"]:
        failures.append(f"a frame change took {frame_change * 1000:.1f} ms (limit {options['--max-frame-seconds'] * 1000:.0f} ms)")

    report = {
        "file": path, "representation": info.get("representation"), "panels": info.get("panels"),
        "objects": len(meshes), "keyframes": len(ts), "shape_keys": len(names), "import_seconds": round(import_seconds, 3),
        "frame_change_ms": round(frame_change * 1000, 2), "poses_checked": len(poses),
        "worst_at_keyframes": worst_key, "worst_between": worst_between, "tolerance": tolerance,
        "failures": failures,
    }
    print("phedra-blender: " + json.dumps(report), flush=True)
    return not failures


def jobs(argv):
    """PHEDRA then (PRESET FILE [--option VALUE]...)...: the checks, each with its options."""
    out, k = [], 1
    while k < len(argv):
        preset, path, k = argv[k], argv[k + 1], k + 2
        # Time limits are off unless given (bench/blender.sh gives the targets:
        # speed is measured by benchmarks, not by tests).
        options = {"--max-import-seconds": float("inf"), "--max-frame-seconds": float("inf"), "--poses": 0}
        while k < len(argv) and argv[k].startswith("--"):
            options[argv[k]] = float(argv[k + 1])
            k += 2
        out.append((preset, path, options))
    return out


argv = sys.argv[sys.argv.index("--") + 1:]
passed = [check(argv[0], preset, path, options) for preset, path, options in jobs(argv)]
sys.exit(0 if all(passed) else 1)
