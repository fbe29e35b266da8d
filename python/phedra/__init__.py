"""phedra: rigid-foldable P-hedra, their tubes and tube arrays, from Python.

The exact one-parameter folding motion in closed form, its flexion interval and
limits, buildability, repair and optimization, the metamaterial figures, the
mechanics (MERLIN2's bar-and-hinge definitions on the exact motion) and the
exports: the library the ``phedra`` command runs, not a re-implementation
(docs/python.md).

>>> import phedra
>>> d = phedra.load("presets/default.json")
>>> d.evaluate(d.t_star).shape            # doctest: +SKIP
(V, 3)

A :class:`Design` pickles by its preset, so it can be sent to other processes
(multiprocessing, Dask).
"""

import numpy as _np

from ._core import Design, Error, FileError, InputError, load  # noqa: F401
from ._core import __version__  # noqa: F401


def _number(value):
    return _np.nan if value is None else value


def _series(samples):
    """The metrics' samples as arrays over t (NaN where a figure is undefined)."""
    def rows(key):
        return _np.array([[_number(v) for v in s[key]] for s in samples], dtype=float).reshape(len(samples), -1)

    out = {"t": _np.array([s["t"] for s in samples], dtype=float)}
    for key in ("length", "bounding_extent", "strain_rate", "member_volume"):
        out[key] = rows(key)
    out["volume"] = _np.array([_number(s["volume"]) for s in samples], dtype=float)
    names = samples[0]["poisson"].keys() if samples else ()
    out["poisson"] = {n: _np.array([_number(s["poisson"][n]) for s in samples], dtype=float) for n in names}
    return out


_core_metrics = Design.metrics


def _metrics(self, samples=101, axes="structural"):
    """Metamaterial figures against t, as phedra metrics --json (a dict), with
    "series": the samples as numpy arrays over t: t (k,), length, bounding_extent
    and strain_rate (k, 3), volume (k,), member_volume (k, members), poisson
    {nu_12, nu_13, nu_23: (k,)}; NaN where a figure is undefined (None in
    "samples")."""
    out = _core_metrics(self, samples, axes)
    out["series"] = _series(out["samples"])
    return out


Design.metrics = _metrics

__all__ = ["Design", "Error", "FileError", "InputError", "load", "__version__"]
