"""python3 -m phedra.atlas: sweep a design space, query and plot an atlas
(docs/atlas.md)."""

import argparse
import json
import sys

from .._core import Error, FileError, InputError


def _sweep(argv):
    from . import sweep
    p = argparse.ArgumentParser(prog="python3 -m phedra.atlas",
                                description="Sweep a design space (SPACE.json) into a Zarr atlas on Dask; the same "
                                            "command continues an interrupted sweep. Also: `plot ATLAS X Y -o F.png`, "
                                            "`query ATLAS TARGET...` (docs/atlas.md).")
    p.add_argument("space", metavar="SPACE.json", help="the design space: base, parameters, sampling, designs, seed, "
                                                       "figures, options")
    p.add_argument("-o", "--output", required=True, metavar="ATLAS.zarr", help="the atlas (continued if it exists)")
    p.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://HOST:8786); default a local "
                                                          "cluster")
    p.add_argument("--workers", type=int, metavar="N", help="workers of the local cluster (default one per core; "
                                                            "0: no Dask, this process)")
    p.add_argument("--chunk", type=int, metavar="ROWS", help="designs a task and a stored chunk (default: about 64 "
                                                             "chunks of 16 to 250 rows)")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.add_argument("--json", action="store_true", help="the summary as JSON")
    a = p.parse_args(argv)
    if a.workers is not None and a.scheduler is not None:
        raise _field_error("--workers", "is for the local cluster: a --scheduler has its own workers")
    if a.workers is not None and a.workers < 0:
        raise _field_error("--workers", f"must be a whole number, 0 or more (got {a.workers})")
    if a.chunk is not None and a.chunk <= 0:
        raise _field_error("--chunk", f"must be a positive whole number (got {a.chunk})")
    s = sweep(a.space, a.output, scheduler=a.scheduler, workers=a.workers, chunk=a.chunk, progress=not a.quiet)
    if a.json:
        print(json.dumps(s, indent=2))
    else:
        what = "written" if s["computed_chunks"] else "already complete"
        rate = f", {s['designs_per_second']:.1f} designs/s" if "designs_per_second" in s else ""
        built = f", {s['buildable']} buildable" if "buildable" in s else ""
        print(f"{s['output']}: {s['designs']} designs {what} ({s['valid']} valid{built}; {s['computed_chunks']} of "
              f"{s['chunks']} chunks computed in {s['seconds']:.1f} s{rate})")
    return 0


def _query(argv):
    from . import query
    p = argparse.ArgumentParser(prog="python3 -m phedra.atlas query",
                                description="The atlas's designs meeting every target, nearest to the base first.")
    p.add_argument("atlas", metavar="ATLAS.zarr")
    p.add_argument("targets", nargs="+", metavar="TARGET", help="as phedra optimize --target: NAME=V, NAME>=V, "
                                                                "NAME<=V, mechanics.bistable")
    p.add_argument("--tol", type=float, default=0.02, help="an equality's relative tolerance (default 0.02)")
    p.add_argument("--limit", type=int, default=10, help="rows printed (default 10)")
    p.add_argument("--json", action="store_true")
    a = p.parse_args(argv)
    ds = query(a.atlas, a.targets, tol=a.tol)
    params = [q["path"] for q in ds.attrs["space"]["parameters"]]
    names = sorted({_core_name(t) for t in a.targets})
    rows = []
    for i in range(min(a.limit, ds.sizes["design"])):
        r = {"design": int(ds["design"].values[i]), "distance": float(ds["distance"].values[i])}
        r.update({n: ds[n].values[i].item() for n in params + names})
        rows.append(r)
    if a.json:
        print(json.dumps({"matches": int(ds.sizes["design"]), "rows": rows}, indent=2))
    else:
        print(f"{ds.sizes['design']} designs meet {', '.join(a.targets)}" + (":" if rows else ""))
        for r in rows:
            print("  design " + str(r["design"]) + f" (distance {r['distance']:.4g}): " +
                  ", ".join(f"{k} {v:.6g}" if isinstance(v, float) else f"{k} {v}" for k, v in r.items()
                            if k not in ("design", "distance")))
    return 0


def _core_name(target):
    from . import parse_target
    return parse_target(target)[0]


def _plot(argv):
    from ._plot import plot
    p = argparse.ArgumentParser(prog="python3 -m phedra.atlas plot",
                                description="Draw the atlas's designs in the plane of two variables (figures or "
                                            "parameters): buildable and not told apart, the base design marked.")
    p.add_argument("atlas", metavar="ATLAS.zarr")
    p.add_argument("x", metavar="X")
    p.add_argument("y", metavar="Y")
    p.add_argument("-o", "--output", required=True, metavar="F.png", help=".png, .svg or .pdf")
    a = p.parse_args(argv)
    plot(a.atlas, a.x, a.y, a.output)
    print(f"{a.output}: written")
    return 0


def _field_error(field, message):
    e = InputError(f"{field}: {message}")
    e.field = field
    return e


def main(argv=None):
    from . import Interrupted
    argv = sys.argv[1:] if argv is None else argv
    command = {"plot": _plot, "query": _query}.get(argv[0] if argv else "", None)
    # Exit status by what went wrong: bad input 2, a file 3, interrupted 130, the rest
    # (a task failed on the cluster) 1; the message on one line.
    try:
        return command(argv[1:]) if command else _sweep(argv)
    except (Interrupted, Error) as e:
        print(f"phedra.atlas: {e}", file=sys.stderr)
        return next(code for kind, code in ((Interrupted, 130), (InputError, 2), (FileError, 3), (Error, 1))
                    if isinstance(e, kind))


if __name__ == "__main__":
    sys.exit(main())
