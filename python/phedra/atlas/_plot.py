"""The property space of an atlas, drawn with matplotlib (docs/atlas.md)."""

import os

import numpy as np

from .. import _core
from .._core import FileError
from ._space import input_error


def _base_value(space, name):
    """The base design's value of a parameter or figure."""
    if name in [p["path"] for p in space["parameters"]]:
        return _core.preset_field(space["base"], name, name)
    o = space["options"]
    value = _core.load(space["base"]).figures([name], samples=o["samples"], axes=o["axes"], thickness=o["thickness"],
                                              max_growth=o["max_growth"], max_panel_ratio=o["max_panel_ratio"])[name]
    return np.nan if value is None else float(value)


def plot(atlas, x, y, output):
    """Draw variable y against x over the atlas's designs done and valid:
    buildable ones filled, the others hollow, the base design a star."""
    from . import open_atlas
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    ds = open_atlas(atlas)
    space = ds.attrs["space"]
    names = [p["path"] for p in space["parameters"]] + list(space["figures"])
    for field, name in (("X", x), ("Y", y)):
        if name not in names:
            raise input_error(field, f"the atlas has no variable {name!r}; it has {', '.join(names)}")
    if os.path.splitext(output)[1].lower() not in (".png", ".svg", ".pdf"):
        raise input_error("--output", f"{output}: the picture must be .png, .svg or .pdf")
    rows = ds["done"].values & ds["valid"].values
    xs = ds[x].values.astype(float)[rows]
    ys = ds[y].values.astype(float)[rows]
    fig, ax = plt.subplots(figsize=(7, 5.5), dpi=120)
    if "buildable" in ds:
        b = ds["buildable"].values[rows]
        ax.scatter(xs[~b], ys[~b], s=9, facecolors="none", edgecolors="#c0504d", linewidths=0.6,
                   label=f"not buildable ({int((~b).sum())})")
        ax.scatter(xs[b], ys[b], s=9, color="#1f5fa8", label=f"buildable ({int(b.sum())})")
    else:
        ax.scatter(xs, ys, s=9, color="#1f5fa8", label=f"valid designs ({rows.sum()})")
    bx, by = _base_value(space, x), _base_value(space, y)
    if np.isfinite(bx) and np.isfinite(by):
        ax.scatter([bx], [by], marker="*", s=220, color="#f2a900", edgecolors="black", linewidths=0.8, zorder=5,
                   label="base design")
    invalid = int(ds["done"].values.sum() - rows.sum())
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    name = space["base"].get("name", "base")
    hidden = f", {invalid} invalid (not shown)" if invalid else ""
    ax.set_title(f"{name}: {int(ds['done'].values.sum())} designs ({space['sampling']}){hidden}")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=9)
    fig.tight_layout()
    try:
        fig.savefig(output)
    except OSError as e:
        raise FileError(f"{output}: cannot write the picture ({e.strerror or e})") from None
    finally:
        plt.close(fig)
