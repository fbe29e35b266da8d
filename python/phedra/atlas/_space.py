"""A design space (SPACE.json, docs/atlas.md): the base preset, the parameters
with their ranges, the sampling and the figures wanted; checked whole before
anything is written, every error naming its field."""

import json
import math
import os
import warnings

import numpy as np

from .. import _core
from .._core import FileError, InputError

SAMPLINGS = ("sobol", "lhs", "grid")

#: Names that stand for several figures.
FIGURE_GROUPS = {
    "metrics": [n for n in _core.figure_names() if not n.startswith("mechanics.") and n not in
                ("buildable", "buildable_fraction", "thickest_at_t_star")],
    "buildability": ["buildable", "buildable_fraction"],
    "mechanics": [n for n in _core.figure_names() if n.startswith("mechanics.")],
}

#: Figures stored as true/false; every other one is a float64 (NaN: undefined).
BOOLEAN_FIGURES = ("buildable", "mechanics.bistable")

DEFAULT_OPTIONS = {"samples": 101, "axes": "structural", "thickness": None, "max_growth": 10.0,
                   "max_panel_ratio": 100.0, "time_limit": 60.0}

KEYS = ("base", "parameters", "sampling", "designs", "seed", "figures", "options", "description")


def input_error(field, message):
    """phedra.InputError naming `field`, as the command's errors read."""
    error = InputError(f"{field}: {message}")
    error.field = field
    return error


def _number(value, field, *, whole=False, positive=False, minimum=None):
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    if ok and whole:
        ok = float(value).is_integer()
    if ok and positive:
        ok = value > 0
    if ok and minimum is not None:
        ok = value >= minimum
    if not ok:
        what = "a whole number" if whole else "a number"
        if positive:
            what = "a positive " + what[2:]
        elif minimum is not None:
            what += f", {minimum} or more"
        raise input_error(field, f"must be {what} (got {json.dumps(value)})")
    return int(value) if whole else float(value)


class Space:
    """A checked design space. `Space(spec, folder)`: spec a dict (or a path to
    SPACE.json); a base given as a path is read relative to `folder` (the
    SPACE file's folder)."""

    def __init__(self, spec, folder="."):
        if isinstance(spec, (str, os.PathLike)):
            folder = os.path.dirname(os.path.abspath(spec))
            spec = read_json(spec, "space")
        if not isinstance(spec, dict):
            raise input_error("space", "must be a JSON object {base, parameters, sampling, designs, seed, figures}")
        unknown = sorted(set(spec) - set(KEYS))
        if unknown:
            raise input_error(unknown[0], f"unknown key; a space has {', '.join(KEYS)}")
        self.base = self._base(spec.get("base"), folder)
        self.parameters = self._parameters(spec.get("parameters"))
        self.sampling = spec.get("sampling", "sobol")
        if self.sampling not in SAMPLINGS:
            raise input_error("sampling", f"must be one of {', '.join(SAMPLINGS)} (got {json.dumps(self.sampling)})")
        self.seed = _number(spec.get("seed", 0), "seed", whole=True, minimum=0)
        self.designs = self._designs(spec.get("designs"))
        self.figures = self._figures(spec.get("figures", ["metrics", "buildability"]))
        self.options = self._options(spec.get("options", {}))
        self.description = spec.get("description", "")

    # -- reading ---------------------------------------------------------------

    def _base(self, base, folder):
        if base is None:
            raise input_error("base", "missing: the base preset (a path or a preset object)")
        if isinstance(base, str):
            base = read_json(base if os.path.isabs(base) else os.path.join(folder, base), "base")
        if not isinstance(base, dict):
            raise input_error("base", "must be a preset file's path or a preset object")
        try:
            design = _core.load(base)
        except InputError as e:
            raise input_error("base", f"not a valid design: {e}") from None
        self.model_size = design.info()["model_size"]
        return design.preset

    def _parameters(self, parameters):
        if not isinstance(parameters, list) or not parameters:
            raise input_error("parameters", "must be a non-empty list of {path, range}")
        out, seen = [], set()
        for i, p in enumerate(parameters):
            field = f"parameters[{i}]"
            if not isinstance(p, dict) or not isinstance(p.get("path"), str):
                raise input_error(field, "must be an object {\"path\": FIELD, \"range\": [LOW, HIGH]}")
            unknown = sorted(set(p) - {"path", "range", "steps"})
            if unknown:
                raise input_error(f"{field}.{unknown[0]}", "unknown key; a parameter has path, range, steps")
            path = p["path"]
            if path in seen:
                raise input_error(f"{field}.path", f"\"{path}\" is already a parameter")
            seen.add(path)
            _core.preset_field(self.base, path, f"{field}.path")
            r = p.get("range")
            if not isinstance(r, list) or len(r) != 2:
                raise input_error(f"{field}.range", f"must be [LOW, HIGH] (got {json.dumps(r)})")
            low = _number(r[0], f"{field}.range")
            high = _number(r[1], f"{field}.range")
            if not low < high:
                raise input_error(f"{field}.range", f"[{r[0]}, {r[1]}] is empty: LOW must be below HIGH")
            steps = None
            if "steps" in p:
                steps = _number(p["steps"], f"{field}.steps", whole=True, minimum=2)
            out.append({"path": path, "range": [low, high], "steps": steps})
        return out

    def _designs(self, designs):
        if self.sampling == "grid":
            steps = [p["steps"] for p in self.parameters]
            if all(s is not None for s in steps):
                n = math.prod(steps)
                if designs is not None and _number(designs, "designs", whole=True, positive=True) != n:
                    raise input_error("designs", f"{designs} is not the grid's {' x '.join(map(str, steps))} = {n}: "
                                                 "leave it out or make it equal")
                return n
            if any(s is not None for s in steps):
                raise input_error("parameters", "a grid needs steps on every parameter, or on none (then "
                                                "designs = steps ** parameters)")
            n = _number(designs, "designs", whole=True, positive=True)
            k = round(n ** (1.0 / len(self.parameters)))
            if k ** len(self.parameters) != n or k < 2:
                raise input_error("designs", f"a grid of {len(self.parameters)} parameters needs designs = steps ** "
                                             f"{len(self.parameters)} with steps >= 2 (got {n}); or give each "
                                             "parameter its steps")
            for p in self.parameters:
                p["steps"] = k
            return n
        if any(p["steps"] is not None for p in self.parameters):
            raise input_error("parameters", f"steps are for the grid sampling, not {self.sampling}")
        if designs is None:
            raise input_error("designs", "missing: how many designs to sample")
        return _number(designs, "designs", whole=True, positive=True)

    def _figures(self, figures):
        if not isinstance(figures, list) or not figures:
            raise input_error("figures", "must be a non-empty list of figure names or groups")
        known = _core.figure_names()
        out = []
        for i, name in enumerate(figures):
            names = FIGURE_GROUPS.get(name, [name])
            if name == "thickest_plate":
                names = ["thickest_at_t_star"]
            for n in names:
                if n not in known:
                    raise input_error(f"figures[{i}]", f"unknown figure {json.dumps(name)}; known: the groups "
                                                       f"{', '.join(FIGURE_GROUPS)}, thickest_plate, and "
                                                       f"{', '.join(known)}")
                if n not in out:
                    out.append(n)
        return out

    def _options(self, options):
        if not isinstance(options, dict):
            raise input_error("options", "must be an object")
        unknown = sorted(set(options) - set(DEFAULT_OPTIONS))
        if unknown:
            raise input_error(f"options.{unknown[0]}", f"unknown option; the options are {', '.join(DEFAULT_OPTIONS)}")
        out = dict(DEFAULT_OPTIONS)
        out.update(options)
        out["samples"] = _number(out["samples"], "options.samples", whole=True, minimum=2)
        if out["axes"] not in ("structural", "principal"):
            raise input_error("options.axes", f"must be structural or principal (got {json.dumps(out['axes'])})")
        for key in ("max_growth", "max_panel_ratio"):
            out[key] = _number(out[key], f"options.{key}", minimum=0)
            if 0 < out[key] < 1:
                raise input_error(f"options.{key}", f"must be 0 (no bound) or a number, 1 or more (got {out[key]:g})")
        out["time_limit"] = _number(out["time_limit"], "options.time_limit", positive=True)
        if "thickest_at_t_star" in self.figures:
            if out["thickness"] is None:
                out["thickness"] = 0.01 * self.model_size
            out["thickness"] = _number(out["thickness"], "options.thickness", positive=True)
        elif out["thickness"] is not None:
            out["thickness"] = _number(out["thickness"], "options.thickness", positive=True)
        return out

    # -- using -----------------------------------------------------------------

    @property
    def paths(self):
        return [p["path"] for p in self.parameters]

    def to_json(self):
        """The space as stored in the atlas (the base inlined, defaults filled in)."""
        return {"base": self.base, "parameters": self.parameters, "sampling": self.sampling,
                "designs": self.designs, "seed": self.seed, "figures": self.figures, "options": self.options,
                "description": self.description}

    def values(self):
        """The parameters' values of every design, (designs, parameters) float64:
        fixed by the space and its seed (a grid: the first parameter slowest,
        its ends exact)."""
        d, n = len(self.parameters), self.designs
        if self.sampling == "grid":
            axes = [np.linspace(p["range"][0], p["range"][1], p["steps"]) for p in self.parameters]
            return np.stack([m.reshape(-1) for m in np.meshgrid(*axes, indexing="ij")], axis=1)
        from scipy.stats import qmc
        if self.sampling == "sobol":
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # balance properties want a power of 2: any count is allowed
                u = qmc.Sobol(d, scramble=True, seed=self.seed).random(n)
        else:
            u = qmc.LatinHypercube(d, seed=self.seed).random(n)
        low = np.array([p["range"][0] for p in self.parameters])
        high = np.array([p["range"][1] for p in self.parameters])
        return low + u * (high - low)

    def preset(self, row):
        """The preset of the design with these parameter values (a dict)."""
        return _core.with_fields(self.base, {path: float(v) for path, v in zip(self.paths, row)})

    def check_not_all_invalid(self, values, probe=32):
        """InputError naming the parameter whose range alone makes every design
        invalid (tried at its ends and middle, the others at the base), or the
        space when the first `probe` designs are all invalid."""
        base_values = [_core.preset_field(self.base, p, p) for p in self.paths]
        for k, p in enumerate(self.parameters):
            errors = []
            for v in (p["range"][0], 0.5 * (p["range"][0] + p["range"][1]), p["range"][1]):
                row = list(base_values)
                row[k] = v
                error = design_error(self.preset(row))
                if error is None:
                    break
                errors.append((v, error))
            else:
                v, error = errors[0]
                raise input_error(f"parameters[{k}].range", f"every design tried with {p['path']} in "
                                  f"[{p['range'][0]:g}, {p['range'][1]:g}] is invalid (at {v:g}: {error})")
        errors = []
        for i in range(min(probe, len(values))):
            error = design_error(self.preset(values[i]))
            if error is None:
                return
            errors.append(error)
        raise input_error("parameters", f"the first {len(errors)} designs of the space are all invalid "
                                        f"(design 0: {errors[0]}): narrow the ranges")


def design_error(preset):
    """None when the preset is a valid design, else the message."""
    try:
        _core.load(preset)
    except InputError as e:
        return str(e)
    return None


def read_json(path, field):
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        error = FileError(f"{path}: cannot read the {field} file ({e.strerror})")
        raise error from None
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise input_error(field, f"{path} is not JSON: {e.msg} at line {e.lineno}, column {e.colno}") from None
