"""The core's binding of polygon blocks: Model takes rectangles, vertex lists and supports and gives the polygons,
centroids, kinds and bounding boxes; gravity_direction; the arch generator; refusals name their block or key."""

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import _core


def test_a_model_of_rectangles_and_polygons_gives_its_blocks_in_order() -> None:
    # a rectangle row, a triangle as a list, a square as a (4, 2) array given clockwise, on the rectangle
    square = np.array([[0.5, 0.5], [0.5, 1.0], [1.0, 1.0], [1.0, 0.5]])
    model = _core.Model([[0.0, 0.0, 1.0, 0.5], [[0.0, 0.5], [0.5, 0.5], [0.0, 1.0]], square], gravity=10.0)
    assert model.block_kinds == ["wall", "wall", "wall", "base"]
    assert model.support_indices == []
    polygons = model.polygons
    assert [p.shape for p in polygons] == [(4, 2), (3, 2), (4, 2), (4, 2)]
    # counter-clockwise from the lowest vertex (the leftmost of the lowest)
    np.testing.assert_array_equal(polygons[2], [[0.5, 0.5], [1.0, 0.5], [1.0, 1.0], [0.5, 1.0]])
    np.testing.assert_allclose(model.centroids[1], [1.0 / 6.0, 2.0 / 3.0], rtol=1e-15)
    # rects: the bounding boxes, a rectangle's itself
    np.testing.assert_array_equal(model.rects[:3], [[0.0, 0.0, 1.0, 0.5], [0.0, 0.5, 0.5, 1.0], [0.5, 0.5, 1.0, 1.0]])
    assert model.gravity_direction == [0.0, -1.0]
    # the triangle touches the square at a corner only (no joint between them); both stand on the rectangle
    assert sorted(map(tuple, model.interface_blocks.tolist())) == [(0, 1), (0, 2), (3, 0)]
    trapezoid = [[0.2, 1.0], [0.8, 1.0], [1.0, 1.3], [0.0, 1.3]]
    with pytest.raises(md.InputError, match=r"block 1 \(polygon of 4 vertices: \(0.2, 1\), \(0.8, 1\), \(1, 1.3\), ...\) touches no other block"):
        _core.Model([[0.0, 0.0, 1.0, 0.5], trapezoid])


def test_supports_replace_the_base_unless_it_is_asked_for() -> None:
    block = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    slab = [[-1.0, -0.5], [2.0, -0.5], [2.0, 0.0], [-1.0, 0.0]]
    on_support = _core.Model([block], supports=[slab])
    assert on_support.base_index is None and on_support.support_indices == [1]
    assert on_support.block_kinds == ["wall", "support"] and on_support.interface_family == ["base"]
    both = _core.Model([[0.0, 0.0, 1.0, 1.0]], supports=[[[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]]], base=True)
    assert both.block_kinds == ["wall", "support", "base"]
    assert list(both.weights[1:]) == [0.0, 0.0]
    with pytest.raises(md.InputError, match=r"support 0 \[2, 0, 1, 1\] has zero or negative size"):
        _core.Model([[0.0, 0.0, 1.0, 1.0]], supports=[[2.0, 0.0, 1.0, 1.0]])


def test_gravity_direction_turns_the_loads() -> None:
    block = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    wall = [[1.0, -1.0], [2.0, -1.0], [2.0, 2.0], [1.0, 2.0]]
    model = _core.Model([block], supports=[wall], gravity_direction=[3.0, 0.0], gravity=10.0)
    assert model.gravity_direction == [1.0, 0.0]
    for bad in ([0.0, 0.0], [float("nan"), 1.0]):
        with pytest.raises(md.InputError, match="gravity_direction"):
            _core.Model([block], supports=[wall], gravity_direction=bad)
    with pytest.raises(md.InputError, match=r"gravity_direction: expected 2 numbers"):
        _core.Model([block], gravity_direction=[0.0, -1.0, 0.0])


@pytest.mark.parametrize(
    "blocks, words",
    [
        ([[[0.0, 0.0], [1.0, 0.0, 2.0], [0.0, 1.0]]], r"blocks\[0\]\[1\]: expected a vertex of 2 numbers"),
        ([[0.0, 0.0, 1.0]], r"blocks\[0\]: expected 4 numbers"),
        ([[0.0, 0.0, 0.0, 1.0]], r"block 0 \[0, 0, 0, 1\] has zero or negative size"),
        ([[[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]], r"block 0 \(polygon of 6 vertices.*vertex 3 \(1, 1\) is a re-entrant corner"),
        ([[[0.0, 0.0], [1.0, 0.0]]], r"block 0 .*2 vertices: a block needs at least 3"),
        (np.zeros((3, 2)), r"an array of blocks has 4 columns"),
    ],
)
def test_bad_blocks_are_refused_naming_them(blocks: object, words: str) -> None:
    with pytest.raises(md.InputError, match=words):
        _core.Model(blocks)


def test_an_arch_on_abutments_makes_a_model_that_stands() -> None:
    a = md.arch("semicircular", thickness=0.15, voussoirs=20, radius=1.0)
    assert set(a) == {"blocks", "supports", "intrados", "extrados", "carried"} and a["carried"] == []  # no backfill
    assert len(a["blocks"]) == 20 and len(a["supports"]) == 2 and len(a["intrados"]) == len(a["extrados"]) == 21
    model = md._core.Model(a["blocks"], supports=a["supports"], joints={"default": {"friction": 10.0, "dilatancy": 10.0}})
    assert model.n_interfaces == 21 and model.base_index is None
    results = model.solve_limit()
    assert results.status == "collapse" and results.collapse_multiplier > 0.0
    # on piers of two courses: no supports, the base under the piers
    piers = md.arch("segmental", thickness=0.3, voussoirs=9, span=4.0, rise=1.0, pier_width=0.6, pier_height=2.0, pier_courses=2)
    assert piers["supports"] == [] and len(piers["blocks"]) == 9 + 4
    model = _core.Model(piers["blocks"])
    assert model.block_kinds.count("base") == 1


@pytest.mark.parametrize(
    "kwargs, key",
    [
        (dict(kind="gothic", thickness=0.1, voussoirs=10, span=2.0), "geometry.arch.kind"),
        (dict(kind="semicircular", thickness=0.1, voussoirs=0, span=2.0), "geometry.arch.voussoirs"),
        (dict(kind="pointed", thickness=0.1, voussoirs=9, span=2.0, rise=1.5), "geometry.arch.voussoirs"),
        (dict(kind="segmental", thickness=0.1, voussoirs=9, span=2.0), "geometry.arch.rise"),
        (dict(kind="semicircular", thickness=0.1, voussoirs=9, span=2.0, pier_width=1.0), "geometry.arch.pier_height"),
    ],
)
def test_bad_arches_are_refused_naming_their_key(kwargs: dict, key: str) -> None:
    with pytest.raises(md.InputError, match=key.replace(".", r"\.")):
        md.arch(**kwargs)
