"""Design-space atlases (docs/atlas.md): a space of designs swept on Dask into a
Zarr store that xarray opens, resumable, the same bit for bit whatever the
workers, the order or the interruptions.

>>> from phedra import atlas
>>> summary = atlas.sweep("space.json", "space.zarr")          # doctest: +SKIP
>>> best = atlas.query("space.zarr", ["poisson.nu_12<=-0.5"])   # doctest: +SKIP

The command: ``python3 -m phedra.atlas SPACE.json -o ATLAS.zarr [--scheduler
ADDRESS] [--workers N]``, ``python3 -m phedra.atlas query ATLAS.zarr TARGET...``
and ``python3 -m phedra.atlas plot ATLAS.zarr X Y -o F.png``.
"""

import hashlib
import json
import math
import os
import sys
import time

import numpy as np

from .. import _core
from .._core import FileError, InputError
from . import _evaluate
from ._space import Space, input_error
from ._store import Store, same_space

__all__ = ["Space", "sweep", "query", "parse_target", "distances", "preset", "design", "open_atlas", "plot",
           "Interrupted", "SweepFailed"]


class Interrupted(KeyboardInterrupt):
    """The sweep was interrupted (Ctrl-C): the chunks written are whole; the same
    call continues where it stopped."""


class SweepFailed(_core.Error):
    """A chunk's task failed on the cluster (not a design: those are recorded)."""


def default_chunk(designs):
    """Rows a chunk (a task and a Zarr chunk): about 64 chunks of 16 to 250 rows;
    fixed by the number of designs alone, so the store is the same whatever the
    workers."""
    return max(min(16, designs), min(250, math.ceil(designs / 64)))


def _space_key(space_json):
    return hashlib.sha1(json.dumps(space_json, sort_keys=True).encode()).hexdigest()[:16]


class _Progress:
    """designs done, designs/s and the time left, on stderr (a line rewritten on
    a terminal, a line every 10 % otherwise)."""

    def __init__(self, total, done, enabled):
        self.total, self.start_done, self.done = total, done, done
        self.enabled = enabled
        self.start = time.monotonic()
        self.tty = sys.stderr.isatty()
        self.last_tenth = done * 10 // max(total, 1)

    def add(self, n):
        self.done += n
        if not self.enabled:
            return
        tenth = self.done * 10 // max(self.total, 1)
        if not self.tty and tenth == self.last_tenth and self.done < self.total:
            return
        self.last_tenth = tenth
        elapsed = max(time.monotonic() - self.start, 1e-9)
        rate = (self.done - self.start_done) / elapsed
        left = (self.total - self.done) / rate if rate > 0 else math.inf
        line = (f"atlas: {self.done}/{self.total} designs ({100.0 * self.done / self.total:.0f} %), "
                f"{rate:.1f} designs/s, {_duration(left)} left")
        sys.stderr.write(("\r" + line + "\033[K") if self.tty else line + "\n")
        if self.tty and self.done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def _duration(seconds):
    if not math.isfinite(seconds):
        return "? s"
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def _open_or_create(output, space, chunk):
    if os.path.exists(output):
        try:
            store = Store(output)
        except InputError:
            raise
        except Exception:
            raise input_error("output", f"{output} exists and is not a phedra atlas: choose another output") from None
        if not same_space(store.space, space):
            raise input_error("output", f"{output} is an atlas of another space: remove it, or choose another output "
                                        "(the same space continues it)")
        return store, False
    if chunk is None:
        chunk = default_chunk(space.designs)
    elif not (isinstance(chunk, int) and chunk > 0):
        raise input_error("chunk", f"must be a positive whole number (got {chunk!r})")
    values = space.values()
    space.check_not_all_invalid(values)
    return Store.create(output, space, values, chunk), True


def sweep(space, output, *, scheduler=None, workers=None, chunk=None, progress=True):
    """Sweep `space` (a SPACE.json path, a dict or a Space) into the Zarr atlas
    `output`; an existing atlas of the same space is continued (only the chunks
    not yet done are computed). `scheduler`: a Dask scheduler's address
    ("tcp://HOST:8786") or a distributed.Client; default a LocalCluster of
    `workers` workers (default one per core); `workers=0`: no Dask, this
    process. `chunk`: rows a task (default default_chunk(designs); an existing
    atlas keeps its own). Returns a summary dict."""
    if not isinstance(space, Space):
        space = Space(space)
    store, created = _open_or_create(output, space, chunk)
    pending = store.pending()
    summary = {"output": output, "designs": store.designs, "chunks": store.chunks, "chunk": store.chunk,
               "created": created, "computed_chunks": 0, "seconds": 0.0}
    start = time.monotonic()
    bar = _Progress(store.designs, store.designs - sum(b - a for a, b in map(store.rows, pending)),
                    progress and bool(pending))
    setup = {"base": store.space["base"], "paths": [p["path"] for p in store.space["parameters"]],
             "figures": store.space["figures"], "options": store.space["options"]}
    key = _space_key(store.space)
    try:
        if pending:
            if workers == 0 and scheduler is None:
                for k in pending:
                    store.write(k, _evaluate.evaluate_chunk(setup, key, store.values(k)))
                    summary["computed_chunks"] += 1
                    bar.add(store.rows(k)[1] - store.rows(k)[0])
            else:
                summary["computed_chunks"] = _on_dask(store, pending, setup, key, scheduler, workers, bar)
    except KeyboardInterrupt:
        raise Interrupted(f"interrupted: {store.chunks - len(store.pending())} of {store.chunks} chunks done; the "
                          "same command continues") from None
    summary["seconds"] = time.monotonic() - start
    summary.update(_counts(store))
    if summary["computed_chunks"]:
        summary["designs_per_second"] = (sum(b - a for a, b in map(store.rows, pending)) / summary["seconds"])
    return summary


def _counts(store):
    g = store.group
    valid = g["valid"][:]
    out = {"valid": int(valid.sum()), "done": int(g["done"][:].sum())}
    if "buildable" in g:
        out["buildable"] = int(g["buildable"][:].sum())
    return out


def _on_dask(store, pending, setup, key, scheduler, workers, bar):
    from distributed import Client, LocalCluster, as_completed

    own = None
    if scheduler is None:
        import logging
        n = workers if workers is not None else (os.cpu_count() or 1)
        if not (isinstance(n, int) and n > 0):
            raise input_error("workers", f"must be a whole number, 0 or more (got {workers!r})")
        own = LocalCluster(n_workers=n, threads_per_worker=1, processes=False, dashboard_address=None,
                           silence_logs=logging.ERROR)
        client = Client(own)
    elif isinstance(scheduler, str):
        try:
            client = Client(scheduler, timeout="20s")
        except OSError as e:
            raise input_error("scheduler", f"cannot reach the Dask scheduler at {scheduler} ({e})") from None
    else:
        client = scheduler
    computed = 0
    futures = None
    try:
        threads = max(sum(client.nthreads().values()), 1)
        window = max(4 * threads, 8)
        # A task's result, not scattered data (_evaluate.shared_setup): recomputed
        # when the worker holding it dies.
        remote_setup = client.submit(_evaluate.shared_setup, setup, key=f"phedra-atlas-setup-{key}", pure=False)
        queue = list(pending)

        def submit(k):
            f = client.submit(_evaluate.evaluate_chunk, remote_setup, key, store.values(k),
                              key=f"phedra-atlas-{key}-{k}", retries=2)
            f.chunk_index = k
            return f

        futures = as_completed([submit(k) for k in queue[:window]])
        queue = queue[window:]
        for future in futures:
            k = future.chunk_index
            try:
                results = future.result()
            except Exception as e:
                raise SweepFailed(f"chunk {k} (designs {store.rows(k)[0]} to {store.rows(k)[1] - 1}) failed on the "
                                  f"cluster: {type(e).__name__}: {e}; the chunks done are kept, the same command "
                                  "continues") from None
            store.write(k, results)
            future.release()
            computed += 1
            a, b = store.rows(k)
            bar.add(b - a)
            if queue:
                futures.add(submit(queue.pop(0)))
    finally:
        if futures is not None:
            for f in list(futures.futures):
                f.cancel()
        if scheduler is None or isinstance(scheduler, str):
            client.close()
        if own is not None:
            own.close()
    return computed


# -- using an atlas ------------------------------------------------------------

def plot(atlas, x, y, output):
    """Draw variable y against x (figures or parameters) over the atlas's valid
    designs to a .png, .svg or .pdf: buildable ones filled, the others hollow,
    the base design a star."""
    from ._plot import plot as draw
    draw(atlas, x, y, output)


def open_atlas(atlas):
    """The atlas as an xarray.Dataset (dimension `design`); a path or a Dataset."""
    import xarray
    if isinstance(atlas, xarray.Dataset):
        return atlas
    if not os.path.exists(os.path.join(str(atlas), ".zgroup")):
        raise FileError(f"{atlas}: not a Zarr atlas (no such store)")
    return xarray.open_zarr(str(atlas), chunks=None)  # numpy arrays read when used (no dask graph)


def _stored_space(ds):
    space = ds.attrs.get("space")
    if space is None:
        raise input_error("atlas", "not a phedra atlas (no space in its attributes)")
    return space


def preset(atlas, row):
    """The preset (a dict) of the atlas's design `row`, rebuilt from its parameters."""
    ds = open_atlas(atlas)
    space = _stored_space(ds)
    if not (0 <= row < space["designs"]):
        raise input_error("row", f"must be in [0, {space['designs'] - 1}] (got {row})")
    values = {p["path"]: float(ds[p["path"]].values[row]) for p in space["parameters"]}
    return _core.with_fields(space["base"], values)


def design(atlas, row):
    """The phedra.Design of the atlas's design `row`."""
    return _core.load(preset(atlas, row))


def distances(atlas):
    """Each design's distance from the base, as phedra repair measures it:
    lengths over the base's model size, turns in radians, Euclidean."""
    ds = open_atlas(atlas)
    space = _stored_space(ds)
    size = _core.load(space["base"]).info()["model_size"]
    total = np.zeros(space["designs"])
    for p in space["parameters"]:
        start = _core.preset_field(space["base"], p["path"], p["path"])
        scale = 180.0 / math.pi if p["path"].endswith(".turn") else size
        total += ((ds[p["path"]].values - start) / scale) ** 2
    return np.sqrt(total)


def parse_target(text, field="target"):
    """'poisson.nu_12=-0.8' -> (name, '=', -0.8), as phedra optimize --target
    reads it ('NAME>=V', 'NAME<=V'; 'mechanics.bistable' alone: (name, '>=', 1))."""
    if text == "mechanics.bistable":
        return text, ">=", 1.0
    for kind in (">=", "<=", "="):
        name, sep, value = text.partition(kind)
        if sep:
            break
    else:
        raise input_error(field, f"\"{text}\": expected NAME=VALUE, NAME>=VALUE or NAME<=VALUE")
    try:
        number = float(value)
    except ValueError:
        number = math.nan
    if not math.isfinite(number):
        raise input_error(field, f"\"{text}\": the value \"{value}\" is not a number")
    return name, kind, number


def query(atlas, targets, *, tol=0.02, limit=None):
    """The designs of the atlas meeting every target (phedra optimize's syntax:
    'poisson.nu_12=-0.8' within max(tol x |value|, 0.01), 'flexion_width>=0.5',
    'mechanics.bistable'), nearest to the base first: an xarray.Dataset over
    `design` (the rows' own numbers kept) with a `distance` variable."""
    ds = open_atlas(atlas)
    space = _stored_space(ds)
    if isinstance(targets, str):
        targets = [targets]
    keep = ds["done"].values & ds["valid"].values
    for i, text in enumerate(targets):
        name, kind, value = parse_target(text, f"targets[{i}]")
        if name not in space["figures"]:
            raise input_error(f"targets[{i}]", f"the atlas has no figure {name} (its figures: "
                                               f"{', '.join(space['figures'])})")
        column = ds[name].values.astype(float)
        with np.errstate(invalid="ignore"):
            if name == "mechanics.bistable":
                met = column == 1.0
            elif kind == "=":
                met = np.abs(column - value) <= max(tol * abs(value), 0.01)
            elif kind == ">=":
                met = column >= value
            else:
                met = column <= value
        keep &= met
    rows = np.flatnonzero(keep)
    d = distances(ds)[rows]
    order = rows[np.argsort(d, kind="stable")]
    if limit is not None:
        order = order[:limit]
    out = ds.isel(design=order).compute()
    out["distance"] = ("design", distances(ds)[order])
    return out.assign_coords(design=order)
