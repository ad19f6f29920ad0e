"""Blocks from a drawing: :func:`read_dxf` reads the rectangles of a DXF file into blocks [x0, y0, x1, y1] (m).

A wall drawn in CAD, one closed outline per block, becomes the blocks of a :class:`masonry_dem.Model`:

>>> import masonry_dem as md
>>> from masonry_dem.dxf import read_dxf
>>> blocks = read_dxf("wall.dxf", layer="bricks")          # doctest: +SKIP
>>> md.Model(blocks, thickness=0.1).solve_limit()           # doctest: +SKIP

What is read, from the model space:

* closed LWPOLYLINEs and POLYLINEs of 4 vertices (or 5, the first repeated at the end) that are rectangles
  with sides along x and y, drawn in either direction;
* SOLIDs and TRACEs (filled quadrilaterals, the "2D solid" of AutoCAD) that are such rectangles.

Anything else is refused by name when it is an outline (a polyline that is not closed, has arcs, more corners,
or is rotated or skewed: the message gives its type, handle and layer, to find it in the drawing), and skipped
when it is not (lines, text, dimensions, hatches, circles). Block references (INSERT) are not exploded: explode
them in CAD first. The drawing's x is the wall's horizontal, its y the vertical (upwards); the lowest blocks
stand on the model's base, wherever the drawing puts them.

Units: the drawing's ``$INSUNITS`` header (mm, cm, dm, m, km, in, ft) converts its coordinates into metres, or
``units=`` overrides it; a unitless drawing needs ``units=``. The blocks are listed bottom to top, and left to
right within a height (the order of the model's block numbers).

ezdxf reads the file; it is an optional dependency (``pip install masonry-dem[dxf]`` or ``pip install ezdxf``),
imported when a drawing is read.
"""

from __future__ import annotations

import os
from fractions import Fraction
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._core import InputError

__all__ = ["read_dxf", "UNITS", "DEFAULT_TOLERANCE"]

PathLike = Union[str, "os.PathLike[str]"]

#: The units of a drawing read, and their length in metres (exact).
UNITS: Dict[str, Fraction] = {
    "mm": Fraction(1, 1000), "cm": Fraction(1, 100), "dm": Fraction(1, 10), "m": Fraction(1), "km": Fraction(1000),
    "in": Fraction(254, 10000), "ft": Fraction(3048, 10000),
}
# the codes of $INSUNITS for these units (0 is unitless)
_INSUNITS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m", 7: "km", 14: "dm"}

#: The default tolerance [m]: how far the corners of an outline may lie from those of a rectangle along x and y.
DEFAULT_TOLERANCE = 1e-6

# the outlines read, the filled quadrilaterals among them
_OUTLINES = ("LWPOLYLINE", "POLYLINE", "SOLID", "TRACE")
_FILLED = ("SOLID", "TRACE")

Point = Tuple[float, float]


def _ezdxf() -> Any:
    try:
        import ezdxf  # noqa: F401  (optional: only a drawing needs it)
    except ImportError:
        raise ImportError(
            "reading a DXF drawing needs ezdxf: pip install masonry-dem[dxf] (or pip install ezdxf)"
        ) from None
    return ezdxf


def read_dxf(
    path: PathLike,
    layer: Optional[Union[str, Sequence[str]]] = None,
    units: Optional[str] = None,
    tolerance: float = DEFAULT_TOLERANCE,
) -> np.ndarray:
    """The rectangles of a DXF drawing as blocks, an (n, 4) array of [x0, y0, x1, y1] in metres.

    Args:
        path: the DXF file.
        layer: a layer name, or several: only the outlines on them are read (layer names are compared
            ignoring case, as CAD does); None (the default) reads every layer.
        units: the drawing's unit ("mm", "cm", "dm", "m", "km", "in", "ft"); None (the default) takes it from
            the drawing's ``$INSUNITS``.
        tolerance: [m] how far a corner may lie off a rectangle with sides along x and y (default 1e-6 m);
            the block is the rectangle through the outermost corners.

    Returns:
        The blocks, bottom to top and left to right (``np.lexsort`` on y0, then x0); coordinates are the
        drawing's, converted to metres (a coordinate in mm is divided by 1000, so 175 mm is 0.175 exactly).

    Raises:
        OSError: the file cannot be read.
        ImportError: ezdxf is not installed.
        InputError: the file is not DXF; its units are unknown; an outline is not a rectangle along x and y
            (the message names its type, handle and layer); two outlines are the same rectangle; no
            rectangle is found (on ``layer``).
    """
    ezdxf = _ezdxf()
    source = os.fspath(path)
    if not (isinstance(tolerance, (int, float)) and tolerance > 0):
        raise ValueError(f"read_dxf: tolerance must be > 0 [m], got {tolerance!r}")
    if not os.path.exists(source):  # ezdxf reports a missing file as one that is not DXF
        raise FileNotFoundError(2, "No such file or directory", source)
    if not os.path.isfile(source):  # a folder, /dev/zero, a pipe: nothing to read to its end
        raise InputError(f"{source}: not a file")
    try:
        doc = ezdxf.readfile(source)
    except (ezdxf.DXFError, ValueError, KeyError, IndexError, TypeError) as exc:  # a damaged drawing
        raise InputError(f"{source}: not a DXF file that can be read ({type(exc).__name__}: {exc})") from None
    except OSError as exc:  # ezdxf's refusal of a file that is not DXF at all
        if "not a DXF file" not in str(exc):
            raise
        raise InputError(f"{source}: not a DXF file") from None
    unit = _units(doc, units, source)
    scale = UNITS[unit]
    layers = _layers(layer)
    found, seen, skipped = [], {}, {}  # type: List[List[float]], Dict[Tuple[float, ...], str], Dict[str, int]
    for entity in doc.modelspace():
        kind = entity.dxftype()
        if layers is not None and entity.dxf.layer.casefold() not in layers:
            continue
        if kind not in _OUTLINES:
            skipped[kind] = skipped.get(kind, 0) + 1
            continue
        name = f"{kind} (handle {entity.dxf.handle}) on layer '{entity.dxf.layer}'"
        rect = _rectangle(entity, kind, float(tolerance / scale))
        if isinstance(rect, str):
            raise InputError(f"{source}: {name} {rect} [{unit}]")
        block = [float(Fraction(v) * scale) for v in rect]
        key = tuple(round(v / tolerance) for v in block)
        if key in seen:
            raise InputError(f"{source}: {name} is the same rectangle as {seen[key]}: a block drawn twice")
        seen[key] = name
        found.append(block)
    if not found:
        raise InputError(f"{source}: {_nothing(layer, skipped, doc)}")
    blocks = np.array(found, dtype=np.float64)
    return blocks[np.lexsort((blocks[:, 0], blocks[:, 1]))]


def _units(doc: Any, units: Optional[str], source: str) -> str:
    """The drawing's unit: ``units`` when given, else its $INSUNITS."""
    if units is not None:
        if units not in UNITS:
            raise InputError(f"{source}: unknown units {units!r} (expected one of {', '.join(UNITS)})")
        return units
    code = doc.header.get("$INSUNITS", 0)
    if code in _INSUNITS:
        return _INSUNITS[code]
    what = "unitless" if code == 0 else f"a unit masonry-dem does not read, code {code}"
    raise InputError(
        f"{source}: the drawing does not say its units ($INSUNITS = {code}, {what}): give them, "
        f"units=\"mm\" from Python or dxf_units = \"mm\" in a case file (one of {', '.join(UNITS)})"
    )


def _layers(layer: Optional[Union[str, Sequence[str]]]) -> Optional[set]:
    if layer is None:
        return None
    names: Iterable[str] = [layer] if isinstance(layer, str) else layer
    return {str(n).casefold() for n in names}


def _nothing(layer: Optional[Union[str, Sequence[str]]], skipped: Dict[str, int], doc: Any) -> str:
    """The message for a drawing without a rectangle: what it has instead, and its layers with outlines."""
    where = "" if layer is None else f" on layer {layer!r}" if isinstance(layer, str) else f" on layers {list(layer)}"
    text = f"no block found{where}: blocks are closed polylines (LWPOLYLINE, POLYLINE) or SOLIDs, rectangles along x and y"
    if skipped:
        text += "; skipped: " + ", ".join(f"{n} {k}" for k, n in sorted(skipped.items()))
        if "INSERT" in skipped:
            text += " (block references: explode them in CAD)"
    if layer is not None:
        with_outlines = sorted({e.dxf.layer for e in doc.modelspace() if e.dxftype() in _OUTLINES})
        text += f"; layers with outlines: {', '.join(with_outlines) or 'none'}"
    return text


def _corners(entity: Any, kind: str) -> Union[str, Tuple[List[Point], bool]]:
    """The corners of an outline in the world's x and y, and whether it was closed; a string: why it is
    not an outline that can be a rectangle."""
    if kind == "LWPOLYLINE":
        if any(b for _, _, b in entity.get_points("xyb")):
            return "has arcs (bulges): a block is a rectangle of straight sides"
        points, closed = list(entity.vertices_in_wcs()), bool(entity.closed)
    elif kind == "POLYLINE":
        if not (entity.is_2d_polyline or entity.is_3d_polyline):
            return "is a mesh, not an outline"
        if any(v.dxf.get("bulge", 0) for v in entity.vertices):
            return "has arcs (bulges): a block is a rectangle of straight sides"
        points, closed = list(entity.points_in_wcs()), bool(entity.is_closed)
    else:  # SOLID, TRACE: four corners, always closed (the third and fourth equal for a triangle)
        points, closed = list(entity.wcs_vertices()), True
    return [(float(p[0]), float(p[1])) for p in points], closed


def _rectangle(entity: Any, kind: str, tol: float) -> Union[str, Tuple[float, float, float, float]]:
    """The rectangle (x0, y0, x1, y1) of an outline, in drawing units; a string: why it is not one.
    ``tol``: the tolerance in drawing units."""
    corners = _corners(entity, kind)
    if isinstance(corners, str):
        return corners
    points, closed = corners
    if len(points) == 5 or (len(points) > 1 and not closed):
        first, last = points[0], points[-1]
        if abs(first[0] - last[0]) <= tol and abs(first[1] - last[1]) <= tol:
            points, closed = points[:-1], True
    if not closed:
        return "is not closed: a block is a closed outline"
    if len(points) != 4:
        return f"has {len(points)} corners: a block has 4 (or 5, the first repeated at the end)"
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    x0, x1, y0, y1 = min(xs), max(xs), min(ys), max(ys)
    shown = ", ".join(f"({x:g}, {y:g})" for x, y in points)
    if x1 - x0 <= tol or y1 - y0 <= tol:
        return f"has no area: its corners are {shown}"
    sides = []
    for x, y in points:
        ix = 0 if abs(x - x0) <= tol else 1 if abs(x - x1) <= tol else None
        iy = 0 if abs(y - y0) <= tol else 1 if abs(y - y1) <= tol else None
        sides.append((ix, iy))
    square = None not in (s for side in sides for s in side) and len(set(sides)) == 4
    # a polyline goes round its corners; a SOLID lists them crosswise (1, 2, 4, 3)
    if square and kind not in _FILLED:
        square = all(sum(a != b for a, b in zip(sides[i], sides[i - 1])) == 1 for i in range(4))
    if not square:
        return f"is not a rectangle with sides along x and y (rotated, skewed or crossed): its corners are {shown}"
    return x0, y0, x1, y1
