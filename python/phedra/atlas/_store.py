"""The atlas's Zarr store (docs/atlas.md): one array a variable over the
dimension `design` (xarray.open_zarr opens it), written chunk by chunk, each
chunk whole or not at all: a chunk's arrays first, its `done` flags last (Zarr
writes every chunk file through a temporary file and a rename)."""

import json
import os
import shutil
import uuid

import numcodecs
import numpy as np
import zarr

from .. import __version__
from .._core import FileError
from ._space import BOOLEAN_FIGURES, input_error

FORMAT = "phedra-atlas/1"
COMPRESSOR = numcodecs.Zlib(level=5)


def _array(group, name, values=None, dtype="f8", chunk=1, n=0, fill=np.nan):
    kwargs = {"object_codec": numcodecs.VLenUTF8()} if dtype == object else {}
    a = group.create_dataset(name, shape=(n,), chunks=(chunk,), dtype=dtype, fill_value=fill,
                             compressor=COMPRESSOR, **kwargs)
    a.attrs["_ARRAY_DIMENSIONS"] = ["design"]
    if values is not None:
        a[:] = values
    return a


def figure_dtype(name):
    return bool if name in BOOLEAN_FIGURES else "f8"


class Store:
    """An atlas on disk: its space, its arrays, which chunks are done."""

    def __init__(self, path):
        self.path = path
        self.group = zarr.open_group(path, mode="r+")
        attrs = self.group.attrs.asdict()
        if attrs.get("format") != FORMAT:
            raise input_error("output", f"{path} is not a phedra atlas")
        self.space = attrs["space"]
        self.chunk = attrs["chunk"]
        self.designs = self.space["designs"]

    @staticmethod
    def create(path, space, values, chunk):
        """A new atlas at `path` with the parameters' values, nothing computed:
        made beside it and renamed into place (never half-made)."""
        parent = os.path.dirname(os.path.abspath(path))
        temporary = os.path.join(parent, f".{os.path.basename(path)}.{uuid.uuid4().hex}.partial")
        try:
            os.mkdir(temporary)  # the folder's own error (a missing or read-only parent), before Zarr's KeyError
            group = zarr.open_group(temporary, mode="a")
            n = space.designs
            for k, p in enumerate(space.paths):
                _array(group, p, values[:, k], chunk=chunk, n=n)
            # True/false and text have no missing value xarray reads as such:
            # they are written out whole now (false, ""); numbers start as NaN.
            no = np.zeros(n, dtype=bool)
            for name in space.figures:
                if figure_dtype(name) is bool:
                    _array(group, name, no, dtype=bool, chunk=chunk, n=n, fill=None)
                else:
                    _array(group, name, chunk=chunk, n=n)
            _array(group, "valid", no, dtype=bool, chunk=chunk, n=n, fill=None)
            _array(group, "error", np.full(n, "", dtype=object), dtype=object, chunk=chunk, n=n, fill=None)
            _array(group, "done", no, dtype=bool, chunk=chunk, n=n, fill=None)
            group.attrs.update({"format": FORMAT, "version": __version__, "space": space.to_json(),
                                "base": space.base, "parameters": space.paths, "figures": space.figures,
                                "chunk": chunk, "designs": n,
                                "description": "a phedra design-space atlas (docs/atlas.md): one row a design; "
                                               "NaN marks a figure undefined or not computed; rows count only "
                                               "where done is true"})
            zarr.consolidate_metadata(group.store)
            os.rename(temporary, path)
        except (OSError, KeyError) as e:  # Zarr says KeyError when a file cannot be written
            shutil.rmtree(temporary, ignore_errors=True)
            why = e.strerror if isinstance(e, OSError) and e.strerror else f"{type(e).__name__}: {e}"
            raise FileError(f"{path}: cannot write the atlas ({why})") from None
        except BaseException:
            shutil.rmtree(temporary, ignore_errors=True)
            raise
        return Store(path)

    @property
    def chunks(self):
        return (self.designs + self.chunk - 1) // self.chunk

    def rows(self, k):
        return k * self.chunk, min((k + 1) * self.chunk, self.designs)

    def pending(self):
        """The chunks not done, in order."""
        done = self.group["done"][:]
        return [k for k in range(self.chunks) if not done[slice(*self.rows(k))].all()]

    def values(self, k):
        a, b = self.rows(k)
        return np.stack([self.group[p["path"]][a:b] for p in self.space["parameters"]], axis=1)

    def write(self, k, results):
        """Chunk k's results [(valid, error, figures)], `done` last."""
        a, b = self.rows(k)
        assert len(results) == b - a
        figures = np.array([r[2] for r in results], dtype=float).reshape(b - a, -1)
        for j, name in enumerate(self.space["figures"]):
            column = figures[:, j]
            self.group[name][a:b] = (column == 1.0) if figure_dtype(name) is bool else column
        self.group["valid"][a:b] = np.array([r[0] for r in results], dtype=bool)
        error = np.empty(b - a, dtype=object)
        error[:] = [r[1] for r in results]
        self.group["error"][a:b] = error
        self.group["done"][a:b] = np.ones(b - a, dtype=bool)


def same_space(stored, space):
    """Whether an atlas's stored space is this one (JSON-equal)."""
    return json.dumps(stored, sort_keys=True) == json.dumps(json.loads(json.dumps(space.to_json())), sort_keys=True)
