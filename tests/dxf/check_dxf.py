#!/usr/bin/env python3
"""The DXF cut sheets as a laser's CAM software reads them, through ezdxf
(Debian's python3-ezdxf): the file audits clean (DXF R2000, millimetres);
CUT holds closed LWPOLYLINEs only, one a piece, the inner ones before the
outer; the frame, the labels and the key (the legend's samples, the scale bar)
are on layers of their own; plates' hinge lines on HINGE.
usage: check_dxf.py PHEDRA PRESETS_DIR"""
import os
import re
import subprocess
import sys
import tempfile

import ezdxf

phedra, presets = sys.argv[1], sys.argv[2]
cases = [
    ("parallelogram-tube.json", ["--thickness-mm", "3", "--kerf", "0.2"]),  # plates
    ("grid-3x3.json", ["--pieces", "strips"]),                                # card strips with tabs
    ("default.json", ["--pieces", "panels", "--page", "letter"]),
]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def area(points):
    return 0.5 * abs(sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1])))


with tempfile.TemporaryDirectory() as scratch:
    for preset, options in cases:
        out = os.path.join(scratch, preset.replace(".json", ".dxf"))
        run = subprocess.run([phedra, "outlines", os.path.join(presets, preset), "-o", out, *options],
                             capture_output=True, text=True)
        check(run.returncode == 0, f"{preset}: outlines exited {run.returncode}: {run.stderr}")
        if run.returncode:
            continue
        pieces = int(re.search(r"(\d+) pieces", run.stdout).group(1))
        pages = int(re.search(r"(\d+) pages?", run.stdout).group(1)) if re.search(r"(\d+) pages? of", run.stdout) else 1
        doc = ezdxf.readfile(out)
        auditor = doc.audit()
        check(not auditor.has_errors, f"{preset}: ezdxf's audit: {[str(e.message) for e in auditor.errors][:5]}")
        check(doc.dxfversion == "AC1015", f"{preset}: DXF version {doc.dxfversion}")
        check(doc.header.get("$INSUNITS") == 4, f"{preset}: $INSUNITS {doc.header.get('$INSUNITS')} (4: mm)")
        msp = doc.modelspace()
        cut = [e for e in msp if e.dxf.layer == "CUT"]
        kinds = {e.dxftype() for e in cut}
        check(kinds == {"LWPOLYLINE"}, f"{preset}: CUT holds {kinds}")
        check(all(e.closed for e in cut if e.dxftype() == "LWPOLYLINE"), f"{preset}: an open polyline on CUT")
        check(len(cut) == pieces, f"{preset}: {len(cut)} outlines on CUT for {pieces} pieces")
        # Inner before outer: on each page (pages side by side), by area, smallest first.
        by_page = {}
        width = None
        frames = [e for e in msp if e.dxf.layer == "FRAME"]
        check(len(frames) >= 1 and all(e.dxftype() == "LWPOLYLINE" and e.closed for e in frames), f"{preset}: the page frames")
        if frames:
            xs = [p[0] for p in frames[0].get_points("xy")]
            width = max(xs) - min(xs) + 10.0
        for e in cut:
            points = [tuple(p) for p in e.get_points("xy")]
            by_page.setdefault(int(min(x for x, _ in points) // width), []).append(area(points))
        for page, areas in by_page.items():
            check(areas == sorted(areas), f"{preset}: page {page + 1}: the outlines are not in order of area")
        key = [e for e in msp if e.dxf.layer == "KEY"]
        check(len(key) >= 4 and all(e.dxftype() == "LINE" for e in key), f"{preset}: {len(key)} key lines")
        # Each sample in the colour of the lines it stands for (a mountain fold's red, 1; a valley's blue, 5).
        if "--pieces" in options and "strips" in options:
            check({1, 5} <= {e.dxf.color for e in key}, f"{preset}: the key's samples in colours {sorted({e.dxf.color for e in key})}")
        check(any(e.dxftype() == "TEXT" and e.dxf.layer == "LABELS" for e in msp), f"{preset}: no labels")
        layers = {e.dxf.layer for e in msp}
        check(layers <= {"CUT", "HINGE", "MOUNTAIN", "VALLEY", "FLAT", "TAB_FOLD", "AXIS", "FRAME", "LABELS", "KEY"},
              f"{preset}: layers {layers}")
        if "--thickness-mm" in options:
            check(any(e.dxf.layer == "HINGE" for e in msp), f"{preset}: no hinge lines on HINGE")
        print(f"{preset}: {len(cut)} closed outlines on CUT for {pieces} pieces, {len(key)} key lines, audit clean")

for f in failures:
    print("FAIL:", f, file=sys.stderr)
sys.exit(1 if failures else 0)
