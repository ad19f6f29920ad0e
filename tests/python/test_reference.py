"""The example case files against their references (docs/references.md), through the
case-file loader and the compiled core: the same numbers a user gets from `masonry-dem run`."""

from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# file, reference collapse multiplier (docs/references.md, sections 1 and 2), relative tolerance
CASES = [
    ("single-block-sliding.toml", 0.65, 0.005),
    ("single-block-rocking.toml", 1.0 / 3.0, 0.005),
    ("stack-3-blocks.toml", 0.2, 0.005),
    ("ferris-tinloi-wall1.toml", 0.6429, 0.01),
    ("ferris-tinloi-wall2.toml", 0.5800, 0.01),
]


@pytest.mark.parametrize("name,reference,tolerance", CASES)
def test_example_collapse_multiplier(name, reference, tolerance):
    res = md.load_case(EXAMPLES / name).run()
    assert res.status == "collapse", res.error
    assert abs(res.collapse_multiplier - reference) <= tolerance * reference


def test_python_and_case_file_agree_on_wall1():
    blocks = md.running_bond(0.4, 0.175, 6, 2.0, first_course="half")
    model = md.Model(blocks, gravity=10.0, joints={"default": {"friction": 0.65, "dilatancy": 0.65}})
    direct = model.solve_static()
    via_case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml").run()
    assert direct.collapse_multiplier == via_case.collapse_multiplier


def test_wall1_mechanism_is_the_leeward_wedge():
    """The collapse mechanism of wall 1: blocks on the leeward (+x) side move, the loaded side stays."""
    blocks = md.running_bond(0.4, 0.175, 6, 2.0)
    model = md.Model(blocks, gravity=10.0, joints={"default": {"friction": 0.65, "dilatancy": 0.65}})
    res = model.solve_static()
    mech = res.mechanism[: model.n_blocks]
    moving = np.hypot(mech[:, 0], mech[:, 1]) > 0.05
    cx = 0.5 * (blocks[:, 0] + blocks[:, 2])
    assert moving.any() and not moving.all()
    assert cx[moving].mean() > cx[~moving].mean(), "the moving part should lie on the leeward side"
    # the block at the bottom-left corner (loaded side) does not move
    assert not moving[np.argmin(cx + blocks[:, 1])]
