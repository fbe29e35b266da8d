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

from ._core import Design, Error, FileError, InputError, load  # noqa: F401
from ._core import __version__  # noqa: F401

__all__ = ["Design", "Error", "FileError", "InputError", "load", "__version__"]
