"""A study as data: :class:`Study` (a base case, :class:`Variation` s, a :class:`Texture`, methods), the
analyses it holds (:meth:`Study.items`, one :class:`Item` each) and the case of each (:meth:`Study.case`).

Everything here is plain data, sent as it is to the workers, which build each analysis's model themselves.

Random values: sample ``s`` of a study of seed ``seed`` draws the variable ``name`` from NumPy's
``default_rng([seed, s, crc32(name)])`` (the texture: ``name`` "texture"), by the inverse of the distribution
function, so that a row's values depend on the seed, the sample and the variable's name only: not on the
other variables, on the order of the analyses, on the workers, or on a resumed run.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import zlib
from dataclasses import asdict, dataclass, replace
from statistics import NormalDist
from typing import Any, Dict, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from .. import _core
from ..case import Case, ModelParameters, case_from_dict
from ..units import parse_quantity

#: The load directions: "+x" the case as it is, "-x" the wall mirrored (x -> x_min + x_max - x).
DIRECTIONS = ("+x", "-x")
DISTRIBUTIONS = ("uniform", "normal", "lognormal")
#: The law keys whose variation may carry dilatancy with it (``associative = true``).
_FRICTION = "friction"


def lognormal_parameters(mean: float, std: float) -> Tuple[float, float]:
    """(mu, sigma) of ln X for a lognormal X of the given mean and standard deviation."""
    sigma2 = math.log1p((std / mean) ** 2)
    return math.log(mean) - sigma2 / 2.0, math.sqrt(sigma2)


@dataclass(frozen=True)
class Variation:
    """One varied parameter: a grid (``values``) or a distribution.

    ``distribution``: "uniform" (``low`` .. ``high``), "normal" or "lognormal" (``mean`` and ``std`` of the
    variable itself), truncated to [``low``, ``high``] when they are given. ``associative``: a friction
    carries the same value to its dilatancy. ``opening``: the opening (from 0) that opening_* move.
    """

    name: str
    values: Optional[Tuple[Any, ...]] = None
    distribution: Optional[str] = None
    low: Optional[float] = None
    high: Optional[float] = None
    mean: Optional[float] = None
    std: Optional[float] = None
    associative: bool = False
    opening: int = 0

    def _normal(self) -> NormalDist:
        """The normal distribution of the variable (normal) or of its logarithm (lognormal)."""
        assert self.mean is not None and self.std is not None
        if self.distribution == "lognormal":
            return NormalDist(*lognormal_parameters(self.mean, self.std))
        return NormalDist(self.mean, self.std)

    def window(self) -> Tuple[float, float]:
        """The probabilities (P(X < low), P(X < high)) of a normal or lognormal variable: the truncation."""
        normal, log = self._normal(), self.distribution == "lognormal"

        def cdf(x: Optional[float], default: float) -> float:
            if x is None:
                return default
            if log:
                return normal.cdf(math.log(x)) if x > 0 else 0.0
            return normal.cdf(x)

        return cdf(self.low, 0.0), cdf(self.high, 1.0)

    def draw(self, rng: np.random.Generator) -> float:
        """One value, by the inverse distribution function of one uniform number of ``rng``."""
        u = float(rng.random())
        if self.distribution == "uniform":
            assert self.low is not None and self.high is not None
            return self.low + u * (self.high - self.low)
        a, b = self.window()
        p = min(max(a + u * (b - a), 1e-300), 1.0 - 1e-16)
        x = self._normal().inv_cdf(p)
        x = math.exp(x) if self.distribution == "lognormal" else x
        lo = -math.inf if self.low is None else self.low
        hi = math.inf if self.high is None else self.high
        return min(max(x, lo), hi)  # rounding never leaves the window


@dataclass(frozen=True)
class Texture:
    """Random textures of a running-bond wall: each block's length and each course's height multiplied by
    (1 + std z), z standard normal, at least ``min_fraction`` of the nominal; ``bond`` "running" keeps the
    case's alternation of half and whole first blocks, "random" starts each course with a block of a length
    uniform between ``min_fraction`` and 1 block length."""

    length_std: float = 0.0
    height_std: float = 0.0
    bond: str = "running"
    min_fraction: float = 0.25


class Item(NamedTuple):
    """One analysis of a study: its row number, method, random sample and parameter values."""

    row: int
    method: str
    sample: int
    values: Dict[str, Any]


@dataclass(frozen=True)
class Study:
    """A base case, its variations and the methods: ``len(methods) x (grid points) x samples`` analyses.

    ``base``: the case table (plain data, as read from a case file) or a ``Model`` builder (a callable of the
    varied values). ``variations``: grid and random, in the study file's order. ``seed``: of the random
    values; ``chunk``: analyses per Dask task (0: automatic). ``inputs``: the files read (never written).
    """

    title: str
    base: Any
    methods: Tuple[str, ...]
    variations: Tuple[Variation, ...] = ()
    texture: Optional[Texture] = None
    samples: int = 1
    seed: int = 0
    chunk: int = 0
    source: str = "<study>"
    inputs: Tuple[str, ...] = ()

    @property
    def assesses(self) -> bool:
        """Whether each analysis is checked against the base case's [assessment] (a case table that has one)."""
        return not callable(self.base) and isinstance(self.base.get("assessment"), dict)

    @property
    def grid(self) -> Tuple[Variation, ...]:
        return tuple(v for v in self.variations if v.values is not None)

    @property
    def random(self) -> Tuple[Variation, ...]:
        return tuple(v for v in self.variations if v.distribution is not None)

    @property
    def parameters(self) -> Tuple[str, ...]:
        """The varied parameters' names, in the file's order (the columns of the results)."""
        return tuple(v.name for v in self.variations)

    @property
    def size(self) -> int:
        """The number of analyses."""
        return len(self.methods) * math.prod(len(v.values or ()) for v in self.grid) * self.samples

    def rng(self, sample: int, name: str) -> np.random.Generator:
        """The random numbers of ``name`` in ``sample``."""
        return np.random.default_rng([self.seed, sample, zlib.crc32(name.encode())])

    def items(self) -> Iterator[Item]:
        """The analyses in row order: samples outermost, then the grid points, then the methods."""
        grid = self.grid
        points = list(itertools.product(*(v.values or () for v in grid)))
        row = 0
        for sample in range(self.samples):
            drawn = {v.name: v.draw(self.rng(sample, v.name)) for v in self.random}
            for point in points:
                given = dict(zip((v.name for v in grid), point), **drawn)
                values = {name: given[name] for name in self.parameters}
                for method in self.methods:
                    yield Item(row, method, sample, values)
                    row += 1

    def item(self, row: int) -> Item:
        """The analysis of ``row``."""
        if not 0 <= row < self.size:
            raise IndexError(f"row {row} is not in this study of {self.size} analyses")
        return next(itertools.islice(self.items(), row, None))

    def fingerprint(self) -> str:
        """A short hash of everything that decides the rows' values (the results of another study are
        refused on resume)."""
        base = f"builder {getattr(self.base, '__qualname__', repr(self.base))}" if callable(self.base) else self.base
        data = dict(
            base=base,
            methods=self.methods,
            variations=[asdict(v) for v in self.variations],
            texture=None if self.texture is None else asdict(self.texture),
            samples=self.samples,
            seed=self.seed,
        )
        text = json.dumps(data, sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def case(self, item: Item) -> Case:
        """The checked case of an analysis (the study's base case with the item's values, texture and
        direction), with the explicit solver on one thread. Raises InputError for a bad sample."""
        named = {v.name: v for v in self.variations}
        data = apply_values(self.base, item.values, named)
        if self.texture is not None:
            geometry = data["geometry"]
            blocks = texture_blocks(geometry.pop("running_bond"), self.texture, self.rng(item.sample, "texture"))
            geometry["blocks"] = blocks
        data.setdefault("analysis", {})["threads"] = 1  # one thread per worker: no oversubscription
        case = case_from_dict(data, source=f"row {item.row}", default_title=self.title)
        if item.values.get("direction") == "-x":
            case.model = mirrored(case.model)
        return case


# --------------------------------------------------------------------------------------------------
# A case table with the values of one analysis
# --------------------------------------------------------------------------------------------------


def apply_values(
    base: Mapping[str, Any], values: Mapping[str, Any], variations: Mapping[str, Variation]
) -> Dict[str, Any]:
    """A copy of the case table ``base`` with the parameters ``values`` set (the direction is applied to the
    checked case, :func:`mirrored`). Names: a joint-law key (the [joints] default law), FAMILY.KEY, thickness,
    density, block_length, block_height, courses, length, gravity, precompression (the downward dead force on
    the top beam [N]), opening_x, opening_y (the centre of an opening [m]), opening_width, opening_height [m], ag (the
    [assessment] spectrum's a_g [m/s2])."""
    data = _tables_copied(base)
    for name, value in values.items():
        if name == "direction":
            continue
        variation = variations.get(name)
        _set(data, name, value, variation)
        if variation is not None and variation.associative:
            _set(data, name[: -len(_FRICTION)] + "dilatancy", value, None)
    return data


def _tables_copied(table: Mapping[str, Any]) -> Dict[str, Any]:
    """A copy of a case table whose tables are new (the arrays in it are shared, and replaced, never
    changed in place): a deep copy at a fraction of its cost."""
    return {key: _tables_copied(value) if isinstance(value, dict) else value for key, value in table.items()}


def _set(data: Dict[str, Any], name: str, value: Any, variation: Optional[Variation]) -> None:
    geometry = data.setdefault("geometry", {})
    if name in ("thickness", "density"):
        geometry[name] = value
    elif name in ("block_length", "block_height", "courses", "length"):
        geometry["running_bond"][name] = value
        if name == "courses":  # a number of courses replaces the base case's height
            geometry["running_bond"].pop("height", None)
    elif name == "gravity":
        data.setdefault("loads", {})["gravity"] = value
    elif name == "ag":
        data["assessment"]["ag"] = value
    elif name == "precompression":
        force = list(data["top"].get("force", [0.0, 0.0]))
        data["top"]["force"] = [force[0], -value]
    elif name.startswith("opening_"):
        k = 0 if variation is None else variation.opening
        openings = list(geometry["running_bond"]["openings"])
        openings[k] = _moved_opening(openings[k], name, float(value))
        geometry["running_bond"]["openings"] = openings
    elif "." in name:
        family, key = name.split(".", 1)
        data.setdefault("joints", {}).setdefault(family, {})[key] = value
    else:
        data.setdefault("joints", {})[name] = value


def _moved_opening(rect: Sequence[float], name: str, value: float) -> List[float]:
    """An opening [x0, y0, x1, y1] with its centre (opening_x, opening_y) or size (opening_width,
    opening_height) set, the rest kept."""
    x0, y0, x1, y1 = (float(v) for v in rect)
    cx, cy, w, h = (x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0
    cx, cy, w, h = {
        "opening_x": (value, cy, w, h),
        "opening_y": (cx, value, w, h),
        "opening_width": (cx, cy, value, h),
        "opening_height": (cx, cy, w, value),
    }[name]
    return [cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2]


def mirrored(model: ModelParameters) -> ModelParameters:
    """The wall mirrored about its vertical centre line (x -> x_min + x_max - x, a block [x0, y0, x1, y1]
    becoming [s - x1, y0, s - x0, y1] with s = x_min + x_max, a polygon's vertex [x, y] becoming [s - x, y], its
    vertices then listed backwards to go round it counter-clockwise again; the supports alike), and the top beam's
    dead force Fx -> -Fx: the live load, which pushes towards +x, then pushes the original wall towards -x."""
    force = None if model.top_force is None else [-model.top_force[0], model.top_force[1]]
    if isinstance(model.blocks, np.ndarray) and model.supports is None:  # rectangles alone: an array
        blocks = np.asarray(model.blocks, dtype=np.float64)
        s = float(blocks[:, 0].min() + blocks[:, 2].max())
        flipped = np.column_stack([s - blocks[:, 2], blocks[:, 1], s - blocks[:, 0], blocks[:, 3]])
        return replace(model, blocks=flipped, top_force=force)
    shapes = list(model.blocks) + list(model.supports or [])
    xs = [x for b in shapes for x in (np.asarray(b, dtype=np.float64).reshape(-1, 2)[:, 0] if _is_polygon(b)
                                      else (float(b[0]), float(b[2])))]
    s = min(xs) + max(xs)

    def flip(b: Any) -> List[Any]:
        if _is_polygon(b):
            return [[s - float(x), float(y)] for x, y in reversed(list(b))]
        x0, y0, x1, y1 = (float(v) for v in b)
        return [s - x1, y0, s - x0, y1]

    supports = None if model.supports is None else [flip(p) for p in model.supports]
    return replace(model, blocks=[flip(b) for b in model.blocks], supports=supports, top_force=force)


def _is_polygon(block: Any) -> bool:
    """Whether a block of a list of blocks is a polygon (vertices [x, y]), not a rectangle [x0, y0, x1, y1]."""
    return len(block) > 0 and isinstance(block[0], (list, tuple, np.ndarray))


# --------------------------------------------------------------------------------------------------
# Random textures
# --------------------------------------------------------------------------------------------------


def texture_blocks(rb: Mapping[str, Any], texture: Texture, rng: np.random.Generator) -> List[List[float]]:
    """The blocks [x0, y0, x1, y1] (m) of a running-bond wall (the keys of [geometry.running_bond]) with a
    random texture: course by course from the bottom, the course's height, then its first block and the
    others, each drawn from ``rng`` in that order. A course ends at ``length``; a last piece shorter than
    ``min_fraction`` block lengths is joined to the block before it. The openings are cut out of the blocks
    as the case file's running bond cuts them (the core's cut_openings)."""
    # lengths may be written with their unit ("400 mm"): the case was checked, so they read
    length_unit, height_unit = parse_quantity(rb["block_length"], "length"), parse_quantity(rb["block_height"], "length")
    length, half_first = parse_quantity(rb["length"], "length"), rb.get("first_course", "half") == "half"
    shortest = texture.min_fraction * length_unit
    blocks: List[List[float]] = []
    y = 0.0
    for course in range(int(rb["courses"])):
        height = height_unit * max(1.0 + texture.height_std * rng.standard_normal(), texture.min_fraction)
        if texture.bond == "random":
            first = length_unit * rng.uniform(texture.min_fraction, 1.0)
        else:
            first = length_unit * (0.5 if (course % 2 == 0) == half_first else 1.0)
        edges = _course_edges(first, length_unit, length, shortest, texture.length_std, rng)
        blocks += [[x0, y, x1, y + height] for x0, x1 in zip(edges[:-1], edges[1:])]
        y += height
    openings = [[parse_quantity(v, "length") for v in o] for o in rb.get("openings") or []]
    if not openings:
        return blocks
    return [[float(v) for v in b] for b in _core.cut_openings(blocks, openings, length_unit, height_unit)]


def _course_edges(
    first: float, unit: float, length: float, shortest: float, std: float, rng: np.random.Generator
) -> List[float]:
    """The joints' x of one course [m], from 0 to ``length``: the first block's nominal length ``first``, the
    others ``unit``, each perturbed by (1 + std z) and at least ``shortest``."""
    edges = [0.0]
    nominal = first
    while edges[-1] < length:
        piece = max(nominal * (1.0 + std * rng.standard_normal()), shortest)
        edges.append(min(edges[-1] + piece, length))
        nominal = unit
    if len(edges) > 2 and edges[-1] - edges[-2] < shortest:
        del edges[-2]  # the short last piece joins the block before it
    return edges

