"""masonry_dem.dxf.read_dxf and the case form [geometry] dxf: drawings written with ezdxf, read back."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import ezdxf
import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.dxf import read_dxf

# a running bond of 3 courses, 2 blocks long, in mm: 400 x 175 mm blocks, the first course starting with a half
BLOCK_MM, HEIGHT_MM = 400.0, 175.0
WALL = md.running_bond(0.4, 0.175, courses=3, length=0.8)


def _sorted(blocks: np.ndarray) -> np.ndarray:
    return blocks[np.lexsort((blocks[:, 0], blocks[:, 1]))]


def _drawing(path: Path, units: Optional[int] = 4, offset=(0.0, 0.0), layer: str = "bricks") -> Path:
    """The wall WALL drawn in mm (as closed LWPOLYLINEs, corners anticlockwise or clockwise), with a dimension
    line, a text, a rotated rectangle and then an outline with an arc on the layer "notes"."""
    doc = ezdxf.new(units=units if units is not None else 0)
    if units is None:
        doc.header["$INSUNITS"] = 0
    msp = doc.modelspace()
    dx, dy = offset
    for i, (x0, y0, x1, y1) in enumerate(WALL * 1000.0):
        corners = [(x0 + dx, y0 + dy), (x1 + dx, y0 + dy), (x1 + dx, y1 + dy), (x0 + dx, y1 + dy)]
        if i % 2:
            corners.reverse()
        msp.add_lwpolyline(corners, close=True, dxfattribs={"layer": layer})
    msp.add_line((0, -50), (800, -50), dxfattribs={"layer": "notes"})
    msp.add_text("wall 1", dxfattribs={"layer": "notes"})
    c, s = np.cos(np.radians(10)), np.sin(np.radians(10))
    rotated = [(1000 + 400 * c * u - 175 * s * v, 400 * s * u + 175 * c * v) for u, v in ((0, 0), (1, 0), (1, 1), (0, 1))]
    msp.add_lwpolyline(rotated, close=True, dxfattribs={"layer": "notes"})
    msp.add_lwpolyline([(0, 500, 0.5), (400, 500, 0), (400, 675, 0), (0, 675, 0)], format="xyb", close=True,
                       dxfattribs={"layer": "notes"})
    doc.saveas(path)
    return path


def _one(tmp_path: Path, add, units: int = 4) -> Path:
    """A drawing of one entity added by ``add(msp)``."""
    doc = ezdxf.new(units=units)
    add(doc.modelspace())
    path = tmp_path / "one.dxf"
    doc.saveas(path)
    return path


def test_running_bond_in_mm_reads_back_exactly(tmp_path: Path) -> None:
    path = _drawing(tmp_path / "wall.dxf")
    blocks = read_dxf(path, layer="bricks")
    assert blocks.shape == (len(WALL), 4) and blocks.dtype == np.float64
    assert np.array_equal(blocks, _sorted(WALL))  # 175 mm is 0.175 exactly, as running_bond's
    assert np.array_equal(read_dxf(path, layer="BRICKS"), blocks)  # layer names ignore case
    assert np.array_equal(read_dxf(path, layer=["bricks", "other"]), blocks)


def test_rotated_rectangle_is_refused_by_handle_and_layer(tmp_path: Path) -> None:
    path = _drawing(tmp_path / "wall.dxf")
    with pytest.raises(md.InputError) as info:
        read_dxf(path)  # every layer: the rotated rectangle on "notes" too
    message = str(info.value)
    assert message.startswith(f"{path}: LWPOLYLINE (handle ")
    assert "on layer 'notes' is not a rectangle with sides along x and y" in message
    handle = message.split("(handle ")[1].split(")")[0]
    doc = ezdxf.readfile(path)
    assert doc.entitydb[handle].dxf.layer == "notes"


def test_units_from_header_and_override(tmp_path: Path) -> None:
    metres = read_dxf(_drawing(tmp_path / "m.dxf"), layer="bricks")
    assert np.array_equal(read_dxf(_drawing(tmp_path / "cm.dxf", units=5), layer="bricks", units="mm"), metres)
    in_cm = read_dxf(_drawing(tmp_path / "cm.dxf", units=5), layer="bricks")
    assert np.allclose(in_cm, metres * 10.0, rtol=1e-15, atol=0)
    unitless = _drawing(tmp_path / "none.dxf", units=None)
    with pytest.raises(md.InputError, match=r"does not say its units \(\$INSUNITS = 0, unitless\)"):
        read_dxf(unitless, layer="bricks")
    assert np.array_equal(read_dxf(unitless, layer="bricks", units="mm"), metres)


def test_offset_drawing_keeps_its_coordinates_and_stands_on_the_base(tmp_path: Path) -> None:
    blocks = read_dxf(_drawing(tmp_path / "wall.dxf", offset=(5000.0, 2000.0)), layer="bricks")
    assert np.allclose(blocks, _sorted(WALL) + [5.0, 2.0, 5.0, 2.0], rtol=0, atol=1e-12)
    results = md.Model(blocks, joints={"default": md.dry_joint(0.65, dilatancy=0.65)}).solve_limit()
    reference = md.Model(WALL, joints={"default": md.dry_joint(0.65, dilatancy=0.65)}).solve_limit()
    assert results.collapse_multiplier == pytest.approx(reference.collapse_multiplier, rel=1e-6)


def test_model_from_drawing_runs_limit_analysis(tmp_path: Path) -> None:
    blocks = read_dxf(_drawing(tmp_path / "wall.dxf"), layer="bricks")
    model = md.Model(blocks, thickness=0.1, joints={"default": md.dry_joint(0.65, dilatancy=0.65)})
    results = model.solve_limit()
    expected = md.Model(_sorted(WALL), thickness=0.1, joints={"default": md.dry_joint(0.65, dilatancy=0.65)}).solve_limit()
    assert results.collapse_multiplier == expected.collapse_multiplier
    assert 0 < results.collapse_multiplier < 1


def test_closed_by_repeated_point_polyline_and_solid(tmp_path: Path) -> None:
    def add(msp) -> None:
        msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (0, 175), (0, 0)])  # not flagged closed: 5 points
        msp.add_polyline2d([(400, 0), (800, 0), (800, 175), (400, 175)], close=True)
        msp.add_solid([(0, 175), (400, 175), (0, 350), (400, 350)])  # a SOLID lists its corners crosswise

    blocks = read_dxf(_one(tmp_path, add))
    assert blocks.tolist() == [[0.0, 0.0, 0.4, 0.175], [0.4, 0.0, 0.8, 0.175], [0.0, 0.175, 0.4, 0.35]]


@pytest.mark.parametrize(
    "add, problem",
    [
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (0, 175)]), "is not closed"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (200, 250), (0, 175)], close=True),
         "has 5 corners"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (410, 175), (0, 175)], close=True),
         "is not a rectangle with sides along x and y"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 175), (400, 0), (0, 175)], close=True),
         "is not a rectangle with sides along x and y"),  # crossed: a bow tie through the corners
        (lambda msp: msp.add_lwpolyline([(0, 0, 0.5), (400, 0, 0), (400, 175, 0), (0, 175, 0)],
                                        format="xyb", close=True), "has arcs"),
        (lambda msp: msp.add_lwpolyline([(0, 0), (400, 0), (400, 0), (0, 0)], close=True), "has no area"),
    ],
)
def test_outlines_refused(tmp_path: Path, add, problem: str) -> None:
    with pytest.raises(md.InputError, match=r"one\.dxf: (LWPOLYLINE|POLYLINE) \(handle \w+\) on layer '0' " + problem):
        read_dxf(_one(tmp_path, add))


def test_block_drawn_twice_is_refused(tmp_path: Path) -> None:
    def add(msp) -> None:
        msp.add_lwpolyline([(0, 0), (400, 0), (400, 175), (0, 175)], close=True)
        msp.add_lwpolyline([(400, 175), (0, 175), (0, 0), (400, 0)], close=True)

    with pytest.raises(md.InputError, match="is the same rectangle as LWPOLYLINE .*: a block drawn twice"):
        read_dxf(_one(tmp_path, add))


def test_nothing_to_read(tmp_path: Path) -> None:
    path = _drawing(tmp_path / "wall.dxf")
    with pytest.raises(md.InputError) as info:
        read_dxf(path, layer="walls")
    assert str(info.value) == (
        f"{path}: no block found on layer 'walls': blocks are closed polylines (LWPOLYLINE, POLYLINE) or SOLIDs, "
        "rectangles along x and y; layers with outlines: bricks, notes"
    )

    def add(msp) -> None:
        msp.add_line((0, 0), (1, 1))
        msp.add_blockref("brick", (0, 0))

    with pytest.raises(md.InputError, match=r"skipped: 1 INSERT, 1 LINE \(block references: explode them"):
        read_dxf(_one(tmp_path, add))


def test_bad_files(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError):
        read_dxf(tmp_path / "missing.dxf")
    with pytest.raises(md.InputError, match="not a file"):
        read_dxf(tmp_path)
    text = tmp_path / "notes.dxf"
    text.write_text("not a drawing\n")
    with pytest.raises(md.InputError, match="notes.dxf: not a DXF file"):
        read_dxf(text)
    with pytest.raises(md.InputError, match="unknown units 'yd'"):
        read_dxf(_drawing(tmp_path / "wall.dxf"), units="yd")


# --------------------------------------------------------------------------------------------------
# The case form [geometry] dxf
# --------------------------------------------------------------------------------------------------

CASE = """format = 1
[geometry]
thickness = "100 mm"
{geometry}
[base]
kind = "fixed"
[joints]
friction = 0.65
dilatancy = 0.65
[analysis]
method = "limit"
"""


def _case(tmp_path: Path, geometry: str) -> Path:
    path = tmp_path / "case.toml"
    path.write_text(CASE.format(geometry=geometry))
    return path


def test_case_with_drawing(tmp_path: Path) -> None:
    (tmp_path / "drawings").mkdir()
    _drawing(tmp_path / "drawings" / "wall.dxf", units=None)
    case = md.load_case(_case(tmp_path, 'dxf = "drawings/wall.dxf"\ndxf_layer = "bricks"\ndxf_units = "mm"'))
    assert np.array_equal(case.model.blocks, _sorted(WALL))
    assert case.model.thickness == 0.1
    blocks_case = md.load_case(_case(tmp_path, "blocks = " + str(_sorted(WALL).tolist())))
    assert case.run().collapse_multiplier == blocks_case.run().collapse_multiplier


@pytest.mark.parametrize(
    "geometry, key, fragment",
    [
        # the one with an arc on "notes" (the rotated rectangle before it is a polygon block)
        ('dxf = "drawings/wall.dxf"', "geometry.dxf", "LWPOLYLINE (handle"),
        ('dxf = "drawings/wall.dxf"\ndxf_layer = "bricks"\ndxf_units = "yd"', "geometry.dxf_units",
         'expected one of "mm"'),
        ('dxf = "missing.dxf"', "geometry.dxf", "cannot read"),
        ('blocks = [[0, 0, 1, 1]]\ndxf_layer = "bricks"', "geometry.dxf_layer", "applies to a drawing (dxf)"),
        ('dxf = "drawings/wall.dxf"\nblocks = [[0, 0, 1, 1]]', None, "blocks and dxf are both given"),
    ],
)
def test_case_drawing_errors_name_the_key(tmp_path: Path, geometry: str, key: Optional[str], fragment: str) -> None:
    (tmp_path / "drawings").mkdir()
    _drawing(tmp_path / "drawings" / "wall.dxf")
    path = _case(tmp_path, geometry)
    with pytest.raises(md.InputError) as info:
        md.load_case(path)
    assert str(info.value).startswith(f"{path}: ")
    assert fragment in str(info.value)
    assert info.value.key == key
