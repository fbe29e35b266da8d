# Imports the modes glTF of `phedra mechanics -o modes.glb` into Blender
# (headless) and plays it: the shape keys are the file's morph targets by name
# ("mode 1 +", "mode 1 -", ...), the action lasts one oscillation a field, and
# at a quarter and three quarters of field k the mesh Blender shows is the
# basis plus and minus that field's shape key, the other keys at rest.
#
# usage: blender -b --factory-startup --python tests/blender/check_modes.py -- FILE.glb
# Prints one JSON line starting with "phedra-blender-modes:"; exits 1 when a check fails.
import json
import sys

import warnings
import numpy
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    if "bool" not in numpy.__dict__:  # Debian's Blender 3.4 importer and bookworm's numpy
        numpy.bool = bool

import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path)
scene = bpy.context.scene
failures = []
info = scene["phedra"].to_dict() if "phedra" in scene.keys() else {}
if not info:
    failures.append("no 'phedra' scene property (scenes[0].extras)")
meshes = [o for o in scene.objects if o.type == "MESH"]
if len(meshes) != 1 or not meshes[0].data.shape_keys:
    failures.append(f"{len(meshes)} meshes, shape keys {bool(meshes and meshes[0].data.shape_keys)}")
    print("phedra-blender-modes: " + json.dumps({"file": path, "failures": failures}))
    sys.exit(1)
mesh = meshes[0]
keys = mesh.data.shape_keys.key_blocks
names = [k.name for k in keys[1:]]
fields = len(names) // 2
modes = len(info.get("eigenvalues", []))
expected = [f"mode {k + 1} {s}" for k in range(modes) for s in "+-"]
if names[:2 * modes] != expected:
    failures.append(f"shape keys {names[:4]}...")
fps = scene.render.fps / scene.render.fps_base
seconds = info.get("seconds_per_field", 2.0)
worst = 0.0
for k in range(fields):
    for phase, key in ((0.25, 2 * k + 1), (0.75, 2 * k + 2)):
        scene.frame_set(0)
        frame = (k + phase) * seconds * fps
        scene.frame_set(int(frame), subframe=frame - int(frame))
        for j, block in enumerate(keys[1:], start=1):
            if abs(block.value - (1.0 if j == key else 0.0)) > 1e-4:
                failures.append(f"field {k} at {phase}: key {block.name} = {block.value}")
        graph = bpy.context.evaluated_depsgraph_get()
        shown = mesh.evaluated_get(graph).to_mesh()
        for v, basis, target in zip(shown.vertices, keys[0].data, keys[key].data):
            worst = max(worst, (v.co - target.co).length)
        mesh.evaluated_get(graph).to_mesh_clear()
size = info.get("model_size", 1.0)
if worst > 1e-5 * size:
    failures.append(f"shown {worst} from the shape key")
print("phedra-blender-modes: " + json.dumps({"file": path, "vertices": len(mesh.data.vertices), "fields": fields,
                                             "largest_deviation": worst / size, "failures": failures[:5]}))
sys.exit(1 if failures else 0)
