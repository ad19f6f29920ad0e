"""Blocks from a drawing: :func:`read_dxf_polygons` reads every closed convex outline of a DXF file into a block
(its vertices [x, y], m); :func:`read_dxf` reads a drawing of rectangles along x and y into blocks [x0, y0, x1, y1]
(m), as a wall of rectangles takes them.

A wall drawn in CAD, one closed outline per block, becomes the blocks of a :class:`masonry_dem.Model`:

>>> import masonry_dem as md
>>> from masonry_dem.dxf import read_dxf, read_dxf_polygons
>>> blocks = read_dxf("wall.dxf", layer="bricks")          # doctest: +SKIP
>>> md.Model(blocks, thickness=0.1).solve_limit()           # doctest: +SKIP
>>> arch = read_dxf_polygons("arch.dxf", layer="voussoirs")  # doctest: +SKIP

What is read, from the model space:

* closed LWPOLYLINEs and POLYLINEs of straight segments (the first vertex may be repeated at the end, in place of
  the closed flag), drawn in either direction: by :func:`read_dxf_polygons` every convex one, by :func:`read_dxf`
  those of 4 vertices that are rectangles with sides along x and y;
* SOLIDs and TRACEs (filled triangles and quadrilaterals, the "2D solid" of AutoCAD): the convex ones, or the
  rectangles.

Anything else is refused by name when it is an outline (a polyline that is not closed, has arcs, is concave or
crosses itself, or for :func:`read_dxf` is no rectangle along x and y: the message gives its type, handle and
layer, to find it in the drawing, and the vertex at fault), and skipped when it is not (lines, text, dimensions,
hatches, circles). A polyline with arcs (bulges) is refused: explode its arcs to straight segments in CAD first.
Block references (INSERT) are not exploded: explode them in CAD first. The drawing's x is the wall's horizontal, its
y the vertical (upwards); the lowest blocks stand on the model's base, wherever the drawing puts them.

Units: the drawing's ``$INSUNITS`` header (mm, cm, dm, m, km, in, ft) converts its coordinates into metres, or
``units=`` overrides it; a unitless drawing needs ``units=``. The blocks are listed bottom to top, and left to
right within a height (the order of the model's block numbers).

ezdxf reads the file; it is an optional dependency (``pip install masonry-dem[dxf]`` or ``pip install ezdxf``),
imported when a drawing is read.
"""

from __future__ import annotations

import os
from fractions import Fraction
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._core import InputError
from ._shapes import polygon_problem

__all__ = ["read_dxf", "read_dxf_polygons", "read_dxf_blocks", "UNITS", "DEFAULT_TOLERANCE"]

PathLike = Union[str, "os.PathLike[str]"]

#: The units of a drawing read, and their length in metres (exact).
UNITS: Dict[str, Fraction] = {
    "mm": Fraction(1, 1000), "cm": Fraction(1, 100), "dm": Fraction(1, 10), "m": Fraction(1), "km": Fraction(1000),
    "in": Fraction(254, 10000), "ft": Fraction(3048, 10000),
}
# the codes of $INSUNITS for these units (0 is unitless)
_INSUNITS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m", 7: "km", 14: "dm"}

#: The default tolerance [m]: how far the corners of an outline may lie from those of a rectangle along x and y, and
#: a vertex from the line through its neighbours and still be on it (not a corner).
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
    found = _read(path, layer, units, tolerance, _rectangle)
    blocks = np.array([[x0, y0, x1, y1] for (x0, y0), (x1, y1) in found], dtype=np.float64).reshape(-1, 4)
    return blocks[np.lexsort((blocks[:, 0], blocks[:, 1]))]


def read_dxf_polygons(
    path: PathLike,
    layer: Optional[Union[str, Sequence[str]]] = None,
    units: Optional[str] = None,
    tolerance: float = DEFAULT_TOLERANCE,
) -> List[np.ndarray]:
    """The convex outlines of a DXF drawing as blocks: a list of (k, 2) arrays of vertices [x, y] in metres.

    Every closed polyline of straight segments (LWPOLYLINE, POLYLINE) and every SOLID or TRACE that is a convex
    polygon is a block, its vertices as drawn, in either direction (the model drops a vertex on a straight side).
    Arguments as :func:`read_dxf`'s; ``tolerance`` [m]: how far a vertex may lie from the line through its
    neighbours and still be on it.

    Returns:
        The blocks, bottom to top and left to right (by the lowest y of each, then its lowest x); coordinates are
        the drawing's, converted to metres exactly as :func:`read_dxf` converts them.

    Raises:
        OSError: the file cannot be read.
        ImportError: ezdxf is not installed.
        InputError: the file is not DXF; its units are unknown; an outline is not closed, has arcs (bulges:
            explode them to straight segments in CAD), is concave (the message names the vertex), crosses itself
            or has no area (each message names its type, handle and layer); two outlines are the same polygon; no
            outline is found (on ``layer``).
    """
    found = _read(path, layer, units, tolerance, _polygon)
    polygons = [np.array(p, dtype=np.float64) for p in found]
    order = np.lexsort(([p[:, 0].min() for p in polygons], [p[:, 1].min() for p in polygons]))
    return [polygons[i] for i in order]


def read_dxf_blocks(
    path: PathLike,
    layer: Optional[Union[str, Sequence[str]]] = None,
    units: Optional[str] = None,
    tolerance: float = DEFAULT_TOLERANCE,
) -> Union[np.ndarray, List[List[Any]]]:
    """The blocks of a drawing as :class:`masonry_dem.Model` takes them (what a case file's ``dxf`` reads): the
    outlines of :func:`read_dxf_polygons`, in its order, each rectangle along x and y (within ``tolerance``) as a row
    [x0, y0, x1, y1] (the numbers :func:`read_dxf` gives), any other as its vertices [[x, y], ...] (m). An (n, 4)
    array when every block is such a rectangle, else a list. Arguments and errors as :func:`read_dxf_polygons`'s."""
    blocks: List[Any] = []
    for vertices in read_dxf_polygons(path, layer, units, tolerance):
        rect = _rectangle([(float(x), float(y)) for x, y in vertices], "LWPOLYLINE", float(tolerance))
        blocks.append(vertices.tolist() if isinstance(rect, str) else [rect[0][0], rect[0][1], rect[1][0], rect[1][1]])
    if all(len(b) == 4 and not isinstance(b[0], list) for b in blocks):
        return np.array(blocks, dtype=np.float64).reshape(-1, 4)
    return blocks


#: What an outline is read into, in drawing units: its vertices, or a string that says why it is no block.
Shape = Callable[[List[Point], str, float], Union[str, List[Point]]]


def _read(
    path: PathLike, layer: Optional[Union[str, Sequence[str]]], units: Optional[str], tolerance: float, shape: Shape,
) -> List[List[Tuple[float, float]]]:
    """The outlines of a drawing read by ``shape`` (:func:`_rectangle`, :func:`_polygon`) into vertices [m], in the
    drawing's order; every refusal of :func:`read_dxf` and :func:`read_dxf_polygons`."""
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
    noun = "rectangle" if shape is _rectangle else "polygon"
    found: List[List[Tuple[float, float]]] = []
    seen: Dict[Tuple[Any, ...], str] = {}
    skipped: Dict[str, int] = {}
    for entity in doc.modelspace():
        kind = entity.dxftype()
        if layers is not None and entity.dxf.layer.casefold() not in layers:
            continue
        if kind not in _OUTLINES:
            skipped[kind] = skipped.get(kind, 0) + 1
            continue
        name = f"{kind} (handle {entity.dxf.handle}) on layer '{entity.dxf.layer}'"
        tol = float(tolerance / scale)
        outline = _outline(entity, kind, tol)
        vertices = outline if isinstance(outline, str) else shape(outline, kind, tol)
        if isinstance(vertices, str):
            raise InputError(f"{source}: {name} {vertices} [{unit}]")
        block = [(float(Fraction(x) * scale), float(Fraction(y) * scale)) for x, y in vertices]
        key = tuple(sorted((round(x / tolerance), round(y / tolerance)) for x, y in block))
        if key in seen:
            raise InputError(f"{source}: {name} is the same {noun} as {seen[key]}: a block drawn twice")
        seen[key] = name
        found.append(block)
    if not found:
        raise InputError(f"{source}: {_nothing(layer, skipped, doc, noun)}")
    return found


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


def _nothing(layer: Optional[Union[str, Sequence[str]]], skipped: Dict[str, int], doc: Any, noun: str) -> str:
    """The message for a drawing without a block (``noun``: "rectangle" or "polygon"): what it has instead, and its
    layers with outlines."""
    where = "" if layer is None else f" on layer {layer!r}" if isinstance(layer, str) else f" on layers {list(layer)}"
    shapes = "rectangles along x and y" if noun == "rectangle" else "convex polygons of straight sides"
    text = f"no block found{where}: blocks are closed polylines (LWPOLYLINE, POLYLINE) or SOLIDs, {shapes}"
    if skipped:
        text += "; skipped: " + ", ".join(f"{n} {k}" for k, n in sorted(skipped.items()))
        if "INSERT" in skipped:
            text += " (block references: explode them in CAD)"
    if layer is not None:
        with_outlines = sorted({e.dxf.layer for e in doc.modelspace() if e.dxftype() in _OUTLINES})
        text += f"; layers with outlines: {', '.join(with_outlines) or 'none'}"
    return text


def _outline(entity: Any, kind: str, tol: float) -> Union[str, List[Point]]:
    """The vertices of a closed outline in the world's x and y (a last vertex repeating the first dropped; a SOLID's
    as ezdxf gives them); a string: why it is not a closed outline of straight sides. ``tol``: the tolerance in
    drawing units."""
    arcs = "has arcs (bulges): a block has straight sides; explode its arcs to straight segments in CAD"
    if kind == "LWPOLYLINE":
        if any(b for _, _, b in entity.get_points("xyb")):
            return arcs
        points, closed = list(entity.vertices_in_wcs()), bool(entity.closed)
    elif kind == "POLYLINE":
        if not (entity.is_2d_polyline or entity.is_3d_polyline):
            return "is a mesh, not an outline"
        if any(v.dxf.get("bulge", 0) for v in entity.vertices):
            return arcs
        points, closed = list(entity.points_in_wcs()), bool(entity.is_closed)
    else:  # SOLID, TRACE: three or four corners, always closed
        points, closed = list(entity.wcs_vertices()), True
    vertices = [(float(p[0]), float(p[1])) for p in points]
    if len(vertices) > 1 and (len(vertices) == 5 or not closed):
        first, last = vertices[0], vertices[-1]
        if abs(first[0] - last[0]) <= tol and abs(first[1] - last[1]) <= tol:
            vertices, closed = vertices[:-1], True
    if not closed:
        return "is not closed: a block is a closed outline"
    return vertices


def _rectangle(points: List[Point], kind: str, tol: float) -> Union[str, List[Point]]:
    """The rectangle of an outline's vertices, its corners (x0, y0) and (x1, y1) in drawing units; a string: why it
    is not one. ``tol``: the tolerance in drawing units."""
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
        return (f"is not a rectangle with sides along x and y (rotated, skewed or crossed): its corners are {shown} "
                "(read_dxf_polygons reads convex polygons)")
    return [(x0, y0), (x1, y1)]


def _polygon(points: List[Point], kind: str, tol: float) -> Union[str, List[Point]]:
    """The vertices of a convex outline, in drawing units; a string: why it is no block
    (:func:`masonry_dem._shapes.polygon_problem`, naming the vertex at fault). ``tol``: the tolerance in drawing
    units. A SOLID's corners come in order round it (ezdxf's ``wcs_vertices``), a triangle's repeated corner dropped."""
    if kind in _FILLED and len(points) == 4:
        if abs(points[2][0] - points[3][0]) <= tol and abs(points[2][1] - points[3][1]) <= tol:
            points = points[:3]
    problem = polygon_problem(points, tol)
    return problem if problem else points
