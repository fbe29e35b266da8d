# Imports a thick-plate STL (`phedra generate --thickness T -o FILE.stl`) into
# Blender (headless) and checks what a user gets: one closed, outward-oriented
# solid per plate, and the volume phedra reports.
#
# STL has no connectivity and Blender's importers weld exactly equal points, so
# plates that meet at a hinge come in as one loose part. The importer's welds
# are undone first: faces sharing an edge with exactly 2 faces are one solid,
# and at a hinge edge (4 faces) the faces are paired around the edge by angle
# and normal, as outward solids meeting there (plates_of); each solid gets its
# own points. Then the mesh is separated by loose parts (Mesh > Separate > By
# Loose Parts). Each part, on its own, is merged by distance (1e-6 of the model
# size: merging across parts would join plates at their hinges again) and must
# be a closed manifold (every edge has exactly 2 faces, every point one fan),
# consistently wound (the 2 faces of every edge run it in opposite directions)
# and outward (signed volume > 0). The part count must be the plate count, the
# total volume within 1e-4 (relative) of the expected, and Blender must keep
# every triangle of the file (its importers drop repeated ones silently).
# Every STL importer this Blender has is checked (3.4: import_mesh.stl, the
# add-on, and wm.stl_import, the built-in one that replaces it in 4.x).
#
# usage: blender -b --factory-startup --python-exit-code 1 -P tests/blender/stl_in_blender.py -- \
#            FILE.stl PLATES VOLUME [FILE.stl PLATES VOLUME ...]
# Prints one line per file and importer starting with "phedra-stl:"; exits 1
# (after the "FAILED:" lines) when a check fails.
import math
import os
import sys
import time

import bmesh
import bpy
from mathutils import Vector

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if not argv or len(argv) % 3:
    print("usage: blender -b --factory-startup --python-exit-code 1 -P stl_in_blender.py -- "
          "FILE.stl PLATES VOLUME [FILE.stl PLATES VOLUME ...]", flush=True)
    sys.exit(2)

RELATIVE_VOLUME_TOLERANCE = 1e-4
# Of the model size (bounding-box diagonal): points closer are one, and so are
# faces around a hinge (float32 coordinates: about 1e-7).
MERGE_DISTANCE = 1e-6

importers = []
if "stl_import" in dir(bpy.ops.wm):
    importers.append(("wm.stl_import", lambda path: bpy.ops.wm.stl_import(filepath=path)))
if "stl" in dir(bpy.ops.import_mesh):
    importers.append(("import_mesh.stl", lambda path: bpy.ops.import_mesh.stl(filepath=path)))


def triangles_in(path):
    """The triangle count of an STL file (binary or ASCII)."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) >= 84 and len(data) == 84 + 50 * int.from_bytes(data[80:84], "little"):
        return int.from_bytes(data[80:84], "little")
    return sum(1 for line in data.splitlines() if line.strip().startswith(b"facet"))


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def plates_of(bm, touching):
    """The faces of each solid: face lists, and the count of edges whose faces do not pair up.

    Faces sharing an edge with exactly 2 faces are in one solid. At an edge
    with more (a hinge, welded by the importer), the faces are placed by angle
    around it: an outward solid fills the wedge from a face whose normal points
    backwards (against the turn) to the next face whose normal points forwards;
    those two faces are paired. A face that the turn reaches within `touching`
    (a distance) is a neighbour folded flat onto the face it starts from, not
    a wedge of nothing. Faces of an edge that do not pair up so (an inverted or
    overlapping plate) are left unpaired, to fail below.
    Computed in double precision (mathutils rounds to single).
    """
    bm.faces.ensure_lookup_table()
    parent = list(range(len(bm.faces)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    def join(a, b):
        parent[root(a.index)] = root(b.index)

    unpaired = 0
    for e in bm.edges:
        faces = list(e.link_faces)
        if len(faces) == 2:
            join(*faces)
        elif len(faces) > 2:
            p, q = (tuple(v.co) for v in e.verts)
            axis = sub(q, p)
            axis = tuple(x / math.sqrt(dot(axis, axis)) for x in axis)
            ref = None
            starts, ends = [], []
            for f in faces:
                corners = [tuple(v.co) for v in f.verts]
                normal = (0.0, 0.0, 0.0)
                for k in range(len(corners)):
                    normal = tuple(map(sum, zip(normal, cross(corners[k], corners[(k + 1) % len(corners)]))))
                # The face's direction from the edge (across it), and its reach.
                out = [sub(c, p) for c in corners]
                out = [sub(o, tuple(x * dot(o, axis) for x in axis)) for o in out]
                reach = max(math.sqrt(dot(o, o)) for o in out)
                r = tuple(map(sum, zip(*out)))
                r = tuple(x / math.sqrt(dot(r, r)) for x in r)
                if ref is None:
                    ref = r
                angle = math.atan2(dot(axis, cross(ref, r)), dot(ref, r))
                (ends if dot(normal, cross(axis, r)) > 0 else starts).append((angle, reach, f))
            chosen = []
            for angle, reach, f in starts:
                best = None
                for b, reach_b, g in ends:
                    turn = (b - angle) % math.tau
                    if turn * min(reach, reach_b) < touching:
                        turn += math.tau
                    if best is None or turn < best[0]:
                        best = (turn, g)
                chosen.append(best and best[1])
            if len(starts) != len(ends) or len(set(chosen)) != len(chosen):
                unpaired += 1
                continue
            for (_, _, f), g in zip(starts, chosen):
                join(f, g)
    groups = {}
    for f in bm.faces:
        groups.setdefault(root(f.index), []).append(f)
    return list(groups.values()), unpaired


def unwelded(groups, mesh):
    """Writes the solids to mesh, each with its own points (loose parts); returns the faces it could not
    write (a face repeated in a solid)."""
    out = bmesh.new()
    repeated = 0
    for faces in groups:
        copies = {}
        for f in faces:
            verts = []
            for v in f.verts:
                if v not in copies:
                    copies[v] = out.verts.new(v.co)
                verts.append(copies[v])
            try:
                out.faces.new(verts)
            except ValueError:
                repeated += 1
    out.to_mesh(mesh)
    out.free()
    return repeated


def check(path, plates, expected_volume, importer_name, run_import):
    failures = []
    bpy.ops.wm.read_factory_settings(use_empty=True)  # no default cube, nothing from the last file
    began = time.perf_counter()
    try:
        result = run_import(path)
    except RuntimeError as error:
        return [f"{importer_name} failed: {str(error).strip().splitlines()[-1]}"], {}
    import_seconds = time.perf_counter() - began
    meshes = [o for o in bpy.context.scene.objects if o.type == "MESH"]
    if "FINISHED" not in result or len(meshes) != 1 or not meshes[0].data.vertices:
        return [f"{importer_name} made {len(meshes)} mesh objects, "
                f"{sum(len(m.data.vertices) for m in meshes)} points ({result})"], {}
    obj = meshes[0]
    triangles = len(obj.data.polygons)

    began = time.perf_counter()
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.transform(obj.matrix_world)
    obj.matrix_world.identity()
    low = [min(v.co[k] for v in bm.verts) for k in range(3)]
    high = [max(v.co[k] for v in bm.verts) for k in range(3)]
    size = math.dist(low, high)
    groups, unpaired = plates_of(bm, MERGE_DISTANCE * size)
    repeated = unwelded(groups, obj.data)
    bm.free()

    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.mesh.separate(type="LOOSE")
    bpy.ops.object.mode_set(mode="OBJECT")
    parts = [o for o in bpy.context.scene.objects if o.type == "MESH"]

    total = 0.0
    smallest = math.inf
    bad = {"open": [], "miswound": [], "inward": []}
    for part in parts:
        bm = bmesh.new()
        bm.from_mesh(part.data)
        bm.transform(part.matrix_world)
        where = sum((v.co for v in bm.verts), Vector()) / max(len(bm.verts), 1)
        name = "({:.3g}, {:.3g}, {:.3g})".format(*where)
        bmesh.ops.remove_doubles(bm, verts=list(bm.verts), dist=MERGE_DISTANCE * size)
        if any(len(e.link_faces) != 2 for e in bm.edges) or not all(v.is_manifold for v in bm.verts):
            bad["open"].append(name)
        elif not all(e.is_contiguous for e in bm.edges):
            bad["miswound"].append(name)
        volume = bm.calc_volume(signed=True)
        if volume <= 0:
            bad["inward"].append(f"{name} (volume {volume:.3g})")
        total += volume
        smallest = min(smallest, volume)
        bm.free()
    check_seconds = time.perf_counter() - began

    if triangles != triangles_in(path):
        failures.append(f"{triangles} triangles in Blender, {triangles_in(path)} in the file "
                        "(the importer drops repeated and degenerate triangles)")
    if len(parts) != plates:
        failures.append(f"{len(parts)} loose parts, {plates} plates expected")
    if repeated:
        failures.append(f"{repeated} triangles repeat another of their solid")
    if unpaired:
        failures.append(f"at {unpaired} edges shared by more than 2 faces, the faces do not pair up as "
                        "outward solids meeting there (an inverted, open or overlapping plate)")
    if bad["open"]:
        failures.append(f"{len(bad['open'])} parts not closed manifolds (an edge without exactly 2 faces, or "
                        f"shells touching at a point), centred at {', '.join(bad['open'][:5])}")
    if bad["miswound"]:
        failures.append(f"{len(bad['miswound'])} parts with inconsistent normals (faces of an edge wound "
                        f"the same way), centred at {', '.join(bad['miswound'][:5])}")
    if bad["inward"]:
        failures.append(f"{len(bad['inward'])} parts with volume <= 0 (inside out), centred at "
                        f"{', '.join(bad['inward'][:5])}")
    difference = abs(total - expected_volume) / abs(expected_volume) if expected_volume else math.inf
    if not difference <= RELATIVE_VOLUME_TOLERANCE:
        failures.append(f"total volume {total:.6g}, expected {expected_volume:.6g} "
                        f"(relative difference {difference:.2e} > {RELATIVE_VOLUME_TOLERANCE:g})")
    summary = {"parts": len(parts), "triangles": triangles, "volume": total, "difference": difference,
               "smallest": smallest, "import_seconds": import_seconds, "check_seconds": check_seconds}
    return failures, summary


all_failures = []
if not importers:
    all_failures.append("this Blender has no STL importer (neither wm.stl_import nor import_mesh.stl)")
for k in range(0, len(argv), 3):
    path = argv[k]
    name = os.path.basename(path)
    try:
        plates, expected_volume = int(argv[k + 1]), float(argv[k + 2])
    except ValueError:
        all_failures.append(f"{name}: PLATES '{argv[k + 1]}' and VOLUME '{argv[k + 2]}' must be numbers")
        continue
    if not os.path.isfile(path):
        all_failures.append(f"{path}: no such file")
        continue
    for importer_name, run_import in importers:
        failures, s = check(path, plates, expected_volume, importer_name, run_import)
        if s:
            print(f"phedra-stl: {name} via {importer_name}: {s['parts']} parts ({plates} plates expected), "
                  f"{s['triangles']} triangles, volume {s['volume']:.6g} (expected {expected_volume:.6g}, "
                  f"relative difference {s['difference']:.1e}), smallest part {s['smallest']:.3g}, "
                  f"import {s['import_seconds']:.3f} s, checks {s['check_seconds']:.3f} s: "
                  f"{'FAILED' if failures else 'ok'}", flush=True)
        all_failures += [f"{name} via {importer_name}: {f}" for f in failures]

for f in all_failures:
    print(f"FAILED: {f}", flush=True)
sys.exit(1 if all_failures else 0)
