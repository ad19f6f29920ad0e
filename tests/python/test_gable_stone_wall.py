"""The gable and stone-wall generators from Python (``masonry_dem.gable``, ``masonry_dem.stone_wall``) and from a case
file ([geometry.gable], [geometry.stone_wall]): the same blocks both ways, the wall's area, a seed's wall the same
every time, each bad key refused by name in one line; and a study (Dask) over a stone wall's seed that runs to
results, each row the analysis of that seed's wall run alone."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.case import parse_case
from masonry_dem.study import run_study, study_from_dict

GABLE = dict(block_length=0.4, block_height=0.2, length=2.0, eaves_height=1.0, ridge_height=1.6)
STONES = dict(length=2.0, height=1.0, stone_length=0.4, stone_height=0.25, irregularity=0.3, head_angle=20.0,
              bed_angle=4.0)


def toml(table: str, keys: dict[str, Any]) -> str:
    lines = "\n".join(f"{k} = {v!r}" if not isinstance(v, str) else f'{k} = "{v}"' for k, v in keys.items())
    return f"format = 1\n[geometry.{table}]\n{lines}\n[joints]\nfriction = 0.65\ndilatancy = 0.65\n"


def area(blocks: Any) -> float:
    """The blocks' areas together (the shoelace formula) [m2]."""
    total = 0.0
    for b in blocks:
        x, y = np.asarray(b, dtype=np.float64).T
        total += 0.5 * float((x * np.roll(y, -1) - np.roll(x, -1) * y).sum())
    return total


def test_a_gable_from_python_and_from_a_case_file() -> None:
    blocks = md.gable(**GABLE)
    assert area(blocks) == pytest.approx(2.0 * 1.0 + 0.5 * 2.0 * 0.6, rel=1e-12)
    case = parse_case(toml("gable", GABLE))
    assert [np.asarray(b).tolist() for b in case.model.blocks] == blocks
    # a single slope, its ridge at the right end
    single = md.gable(**{**GABLE, "ridge_x": 2.0, "first_course": "full"})
    assert area(single) == pytest.approx(2.0 * 1.3, rel=1e-12)
    assert md.Model(single).n_blocks == len(single)


def test_a_stone_wall_is_its_seeds() -> None:
    walls = [md.stone_wall(**STONES, seed=s) for s in (7, 7, 8)]
    assert walls[0] == walls[1] and walls[0] != walls[2]
    assert area(walls[0]) == pytest.approx(2.0, rel=1e-12)
    case = parse_case(toml("stone_wall", {**STONES, "seed": 7}))
    assert [np.asarray(b).tolist() for b in case.model.blocks] == walls[0]
    result = case.run("limit")
    assert result.status == "collapse" and 0.0 < result.collapse_multiplier < 0.65


@pytest.mark.parametrize(
    "table, change, key",
    [
        ("gable", {"ridge_height": 0.8}, "geometry.gable.ridge_height"),
        ("gable", {"ridge_x": 2.5}, "geometry.gable.ridge_x"),
        ("gable", {"eaves_height": -0.1}, "geometry.gable.eaves_height"),
        ("gable", {"first_course": "third"}, "geometry.gable.first_course"),
        ("gable", {"block_length": 0}, "geometry.gable.block_length"),
        ("stone_wall", {"head_angle": 45.0}, "geometry.stone_wall.head_angle"),
        ("stone_wall", {"bed_angle": 12.0}, "geometry.stone_wall.bed_angle"),
        ("stone_wall", {"irregularity": 0.6}, "geometry.stone_wall.irregularity"),
        ("stone_wall", {"seed": -1}, "geometry.stone_wall.seed"),
        ("stone_wall", {"length": 0.3}, "geometry.stone_wall.length"),
        ("stone_wall", {"stone_height": -1.0}, "geometry.stone_wall.stone_height"),
    ],
)
def test_bad_keys_are_refused_by_name(table: str, change: dict[str, Any], key: str) -> None:
    base = GABLE if table == "gable" else STONES
    with pytest.raises(md.InputError) as caught:
        parse_case(toml(table, {**base, **change}), source="wall.toml")
    message = str(caught.value)
    assert caught.value.key == key and key.split(".")[-1] in message and "\n" not in message, message
    assert message.startswith("wall.toml: ")
    # the same refusal from Python, where the generator checks the key itself
    if table == "stone_wall" or key != "geometry.gable.eaves_height":
        with pytest.raises(md.InputError, match=key.split(".")[-1]):
            (md.gable if table == "gable" else md.stone_wall)(**{**base, **change})


def stone_wall_model(stones: int) -> Any:
    """The stone wall of seed ``stones``, dry associative joints (a study's builder: a module-level function, pickled
    to the workers; its parameter is not named seed, a column of every study's rows)."""
    return md.Model(md.stone_wall(**STONES, seed=int(stones)), joints={"default": md.dry_joint(0.65, dilatancy=0.65)})


def test_a_study_over_a_stone_walls_seed() -> None:
    seeds = [1, 2, 3]
    study = study_from_dict({"format": 1, "case": stone_wall_model, "study": {"methods": ["limit"]},
                             "vary": {"stones": {"values": seeds}}})
    table = run_study(study, workers=1)
    assert sorted(table["stones"].tolist()) == seeds
    assert (table["status"] == "collapse").all(), table[["stones", "status", "error"]]
    for seed, lam in zip(table["stones"], table["collapse_multiplier"]):
        alone = stone_wall_model(seed).solve_limit()
        assert lam == alone.collapse_multiplier, seed  # the same wall in a worker, the same program
