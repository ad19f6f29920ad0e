"""Arches and other chains of blocks against the four-hinge mechanisms: the limit analysis of a chain of rigid
blocks between fixed ends (an arch on its abutments, a portal on its base) with friction high enough to exclude
sliding is the least multiplier of the mechanisms with four hinges, each hinge at an end of a joint of the chain.
The enumeration below computes that least multiplier by virtual work alone, independently of the linear program."""

from __future__ import annotations

import itertools
import math
from typing import Any, List, Optional, Tuple

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem._shapes import centroids
from masonry_dem.thrust import thrust_chains

#: Friction high enough that no mechanism slides (associative: dilatancy = friction).
STICKY = {"default": md.dry_joint(2.0, dilatancy=2.0)}


def _cross(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def four_hinge_multiplier(model: Any) -> Tuple[float, Optional[List[Tuple[int, np.ndarray]]]]:
    """(the least multiplier of the four-hinge mechanisms of the model's one chain of blocks, its hinges as
    (interface, point)), by virtual work: with hinges at the ends A, B, C, D of joints j1 < j2 < j3 < j4 of the chain,
    the blocks between A and B turn about A (omega_1 = 1), those between C and D about D (omega_3), those between B
    and C move rigidly (omega_2, u_2), the rest stay; the velocities agree at B and C. The multiplier is the power of
    the weights over that of the live load, lambda = sum W v_y / sum W v_x (with sum W v_x > 0); a mechanism counts
    when every hinge opens its joint (the joint's other end separates)."""
    chains = thrust_chains(model)
    assert len(chains) == 1, "one chain of blocks"
    chain = chains[0]
    pairs = np.asarray(model.interface_blocks).reshape(-1, 2)
    geom = np.asarray(model.interface_geometry, dtype=np.float64).reshape(-1, 5)
    cents = centroids(model)
    weights = np.asarray(model.weights, dtype=np.float64)
    # the blocks in the order of the chain: the block after joint j is shared by joints j and j + 1
    first = set(pairs[chain[0]]) - set(pairs[chain[1]])
    order = [int(first.pop())]
    for k in chain:
        a, b = (int(i) for i in pairs[k])
        order.append(b if a == order[-1] else a)
    # each joint's two ends, and its normal from the block before it (in the chain) to the block after it
    ends, normals = [], []
    for j, k in enumerate(chain):
        cx, cy, nx, ny, length = geom[k]
        c, t = np.array([cx, cy]), np.array([ny, -nx])
        ends.append((c - length / 2 * t, c + length / 2 * t))
        n = np.array([nx, ny])
        normals.append(n if int(pairs[k][0]) == order[j] else -n)
    best, hinges = math.inf, None
    m = len(chain)
    for joints in itertools.combinations(range(m), 4):
        for sides in itertools.product((0, 1), repeat=4):
            A, B, C, D = (ends[j][s] for j, s in zip(joints, sides))
            # omega_2 (B - C) + omega_3 (C - D) = omega_1 (B - A), omega_1 = 1
            matrix = np.array([B - C, C - D]).T
            if abs(np.linalg.det(matrix)) < 1e-12 * np.abs(matrix).max() ** 2:
                continue
            w2, w3 = np.linalg.solve(matrix, B - A)
            u2 = np.array([-(B - A)[1], (B - A)[0]]) - w2 * np.array([-B[1], B[0]])  # v1(B) - w2 k x B

            def velocity(body: int, p: np.ndarray) -> np.ndarray:
                if body == 1:
                    return np.array([-(p - A)[1], (p - A)[0]])
                if body == 2:
                    return u2 + w2 * np.array([-p[1], p[0]])
                return w3 * np.array([-(p - D)[1], (p - D)[0]])

            j1, j2, j3, j4 = joints
            power_x = power_y = 0.0
            for position in range(j1 + 1, j4 + 1):  # the blocks after joint j1 up to joint j4
                body = 1 if position <= j2 else 2 if position <= j3 else 3
                v = velocity(body, cents[order[position]])
                power_x += weights[order[position]] * v[0]
                power_y += weights[order[position]] * v[1]
            if abs(power_x) < 1e-12 * max(abs(power_y), 1.0):
                continue
            sign = 1.0 if power_x > 0 else -1.0
            omegas = sign * np.array([0.0, 1.0, w2, w3, 0.0])  # the fixed part, bodies 1, 2, 3, the fixed part
            opens = True
            for h, (j, s) in enumerate(zip(joints, sides)):
                turn = omegas[h + 1] - omegas[h]  # of the block after the joint over the block before it
                other = ends[j][1 - s] - ends[j][s]
                if not turn * float(normals[j] @ np.array([-other[1], other[0]])) > 1e-12 * np.abs(other).max():
                    opens = False
                    break
            if not opens:
                continue
            multiplier = power_y / power_x
            if 0 < multiplier < best:
                best = multiplier
                hinges = [(chain[j], ends[j][s]) for j, s in zip(joints, sides)]
    return best, hinges


def test_a_portal_sways_at_b_over_h() -> None:
    b, h = 0.3, 1.2
    # two piers b x h on the base, a lintel resting on them: the sway mechanism, four hinges, lambda = b / h
    model = md.Model([[0.0, 0.0, b, h], [1.0, 0.0, 1.0 + b, h], [0.0, h, 1.0 + b, h + 0.25]], joints=STICKY)
    assert len(thrust_chains(model)[0]) == 4
    multiplier, hinges = four_hinge_multiplier(model)
    assert multiplier == pytest.approx(b / h, rel=1e-12)
    results = model.solve_limit()
    assert results.status == "collapse" and results.collapse_multiplier == pytest.approx(b / h, rel=1e-7)
    # the piers turn about their right toes, the lintel about the piers' top left corners
    assert sorted(tuple(p.round(12)) for _, p in hinges) == [(0.0, h), (b, 0.0), (1.0, h), (1.0 + b, 0.0)]
    found = md.report.hinges(model, results.mechanism)
    assert sorted(tuple(h.point.round(9)) for h in found) == sorted(tuple(p.round(9)) for _, p in hinges)


#: The arches of the four kinds, each on abutments: the generator's arguments (m).
ARCHES = {
    "semicircular": dict(kind="semicircular", span=2.0, thickness=0.15, voussoirs=12),
    "segmental": dict(kind="segmental", span=2.0, rise=0.6, thickness=0.2, voussoirs=10),
    "pointed": dict(kind="pointed", span=2.0, rise=1.4, thickness=0.15, voussoirs=12),
    "elliptical": dict(kind="elliptical", span=2.4, rise=0.8, thickness=0.2, voussoirs=12),
}


def arch_model(arguments: dict, **model) -> Tuple[Any, dict]:
    made = md.arch(**arguments)
    return md.Model(made["blocks"], supports=made["supports"] or None, joints=STICKY, thickness=1.0, density=2000.0,
                    **model), made


@pytest.mark.parametrize("name", sorted(ARCHES))
def test_an_arch_collapses_at_its_least_four_hinge_mechanism(name: str) -> None:
    from masonry_dem.report import hinges
    from masonry_dem.thrust import resultant_points

    model, made = arch_model(ARCHES[name])
    expected, expected_hinges = four_hinge_multiplier(model)
    assert 0 < expected < 1
    results = model.solve_limit()
    assert results.status == "collapse"
    assert results.collapse_multiplier == pytest.approx(expected, rel=1e-6)
    # the report's hinges are the mechanism's four, each named by the arch's curves: the generator's joint ends
    found = hinges(model, results.mechanism, made)
    assert [(h.interface, tuple(np.round(h.point, 9))) for h in found] == sorted(
        [(k, tuple(np.round(p, 9))) for k, p in expected_hinges], key=lambda x: (x[1][0], x[1][1]))
    for h in found:
        ends = {side: min(np.hypot(*(np.asarray(made[side]) - h.point).T)) for side in ("intrados", "extrados")}
        assert ends[h.end] < 1e-12  # at that curve's joint end
    assert sorted(h.end for h in found) == ["extrados", "extrados", "intrados", "intrados"]
    # at collapse the line of thrust passes through the hinges: each hinged joint's centre of pressure is its hinge
    points = resultant_points(model, results)
    for h in found:
        assert points[h.interface] == pytest.approx(h.point, abs=1e-6)


def test_an_arch_on_piers_collapses_at_its_least_four_hinge_mechanism() -> None:
    arguments = dict(kind="semicircular", span=2.0, thickness=0.2, voussoirs=8, pier_width=0.3, pier_height=0.8)
    model, made = arch_model(arguments)
    assert made["supports"] == [] and model.base_index is not None and model.n_blocks == 10  # the piers: wall blocks
    expected, expected_hinges = four_hinge_multiplier(model)  # the chain runs from the base through both piers
    results = model.solve_limit()
    assert results.status == "collapse" and results.collapse_multiplier == pytest.approx(expected, rel=1e-6)


def test_the_line_of_thrust_of_an_arch_stays_within_its_ring_along_a_static_path() -> None:
    from masonry_dem.thrust import resultant_points, thrust_lines

    model, _ = arch_model(ARCHES["semicircular"])
    results = model.solve_static()
    assert results.status == "collapse"
    geom = model.interface_geometry
    points = resultant_points(model, results)
    # no tension: every joint's centre of pressure within the joint (|e| <= l / 2, to the solver's precision)
    e = np.hypot(*(points - geom[:, :2]).T)
    assert np.all(e <= geom[:, 4] / 2 * (1 + 1e-9))
    (line,) = thrust_lines(model, results)
    assert len(line) == model.n_interfaces  # from abutment to abutment through every joint


# --------------------------------------------------------------------------------------------------
# [geometry.arch] in a case file
# --------------------------------------------------------------------------------------------------

ARCH_CASE = """format = 1
title = "arch"
[geometry]
thickness = 1.0
density = 2000.0
{extra}
[geometry.arch]
{arch}
[joints]
friction = 2.0
dilatancy = 2.0
[analysis]
method = "limit"
"""
SEMICIRCULAR = 'kind = "semicircular"\nspan = "2 m"\nthickness = "150 mm"\nvoussoirs = 12'


def test_an_arch_case_is_the_generator_s_arch(tmp_path, capsys) -> None:
    from masonry_dem import cli

    path = tmp_path / "arch.toml"
    path.write_text(ARCH_CASE.format(extra="", arch=SEMICIRCULAR))
    case = md.load_case(path)
    made = md.arch(**ARCHES["semicircular"])
    assert case.model.blocks == made["blocks"] and case.model.supports == made["supports"]
    assert case.model.base is False  # on its abutments alone
    assert case.arch["intrados"] == made["intrados"] and case.arch["extrados"] == made["extrados"]
    model, _ = arch_model(ARCHES["semicircular"])
    assert case.run().collapse_multiplier == pytest.approx(model.solve_limit().collapse_multiplier, rel=1e-12)
    assert cli.main(["run", str(path)]) == 0
    out = capsys.readouterr().out
    assert "  hinges:              4: the intrados of a bed joint at (-0.87, 0.50) m, the extrados of a head joint at " \
           "(0.00, 1.15) m, the intrados of a bed joint at (0.71, 0.71) m, the extrados of a base joint at (1.15, " \
           "0.00) m\n" in out
    # supports beside the arch come after its abutments; a [base] table puts the foundation back
    path.write_text(ARCH_CASE.format(extra='supports = [[[2, -0.15], [3, -0.15], [3, 0]]]', arch=SEMICIRCULAR)
                    + '[base]\nkind = "fixed"\n')
    case = md.load_case(path)
    assert case.model.supports == made["supports"] + [[[2.0, -0.15], [3.0, -0.15], [3.0, 0.0]]]
    assert case.model.base is True
    # on piers: no abutments, the piers on the base
    path.write_text(ARCH_CASE.format(extra="", arch=SEMICIRCULAR + "\npier_width = 0.3\npier_height = 0.8\n"
                                                                   "pier_courses = 2"))
    case = md.load_case(path)
    assert case.model.supports is None and case.model.base is None and len(case.model.blocks) == 16
    assert case.build_model().base_index is not None


def test_an_arch_s_backfill_is_carried_by_its_voussoirs(tmp_path) -> None:
    # the fill's weights: the generator's with the case's thickness and gravity, after the case's own loads
    path = tmp_path / "arch.toml"
    fill = '\n[geometry.arch.backfill]\nlevel = "1.4 m"\ndensity = "1.8 t/m3"\n'
    loads = '[loads]\ngravity = 10.0\n[[loads.carried]]\nblock = 5\npoint = [0.0, 1.0]\nweight = "1 kN"\n'
    path.write_text(ARCH_CASE.format(extra="", arch=SEMICIRCULAR + fill).replace("[geometry]\nthickness = 1.0",
                                                                                 "[geometry]\nthickness = 0.5") + loads)
    case = md.load_case(path)
    made = md.arch(**ARCHES["semicircular"], backfill_level=1.4, backfill_density=1800.0, wall_thickness=0.5,
                   gravity=10.0)
    assert case.model.carried == [(5, [0.0, 1.0], 1000.0)] + made["carried"]
    assert len(made["carried"]) == 12 and all(w > 0 for _, _, w in made["carried"])
    # the weight of the fill: density x thickness x g x (the rectangle 2 re x level less the 12 extrados triangles)
    re = 1.15
    area = 2 * re * 1.4 - 6 * re * re * math.sin(math.pi / 12)
    assert sum(w for _, _, w in made["carried"]) == pytest.approx(1800.0 * 0.5 * 10.0 * area, rel=1e-12)
    # each voussoir weighs its own weight and its loads'
    bare = md.Model(made["blocks"], supports=made["supports"], thickness=0.5, density=2000.0, gravity=10.0)
    assert sum(case.build_model().weights) == pytest.approx(sum(bare.weights) + 1000.0 + 1800.0 * 0.5 * 10.0 * area,
                                                            rel=1e-12)
    assert case.run().status == "collapse"


@pytest.mark.parametrize(
    "arch, extra, key, message",
    [
        ('kind = "gothic"\nspan = 2\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.kind",
         'geometry.arch.kind: expected one of "semicircular", "segmental", "pointed", "elliptical", got "gothic"'),
        ('kind = "semicircular"\nspan = 2\nvoussoirs = 8', "", "geometry.arch.thickness",
         "missing key 'thickness' in [geometry.arch]"),
        ('kind = "semicircular"\nspan = 2\nthickness = 0.1', "", "geometry.arch.voussoirs",
         "missing key 'voussoirs' in [geometry.arch]"),
        ('kind = "semicircular"\nspan = 2\nthickness = 0.1\nvoussoirs = 0', "", "geometry.arch.voussoirs",
         "geometry.arch.voussoirs: must be >= 1, got 0"),
        ('kind = "semicircular"\nspan = -2\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.span",
         "geometry.arch.span: must be > 0, got -2"),
        ('kind = "semicircular"\nspan = "2 kN"\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.span",
         "'2 kN' is a force; geometry.arch.span is a length"),
        ('kind = "semicircular"\nspna = 2\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.spna",
         "unknown key 'spna' in [geometry.arch] (did you mean 'span'?)"),
        ('kind = "semicircular"\nspan = 2\nradius = 1\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.radius",
         "geometry.arch.radius and geometry.arch.span are both given: give one"),
        ('kind = "segmental"\nspan = 2\nthickness = 0.1\nvoussoirs = 8', "", "geometry.arch.rise",
         "geometry.arch.rise is required for a segmental arch"),
        ('kind = "pointed"\nspan = 2\nrise = 1.5\nthickness = 0.1\nvoussoirs = 7', "", "geometry.arch.voussoirs",
         "geometry.arch.voussoirs = 7 for a pointed arch must be even"),
        ('kind = "semicircular"\nspan = 2\nthickness = 0.1\nvoussoirs = 8\nabutment_width = 0.3\npier_width = 0.3\n'
         'pier_height = 1', "", "geometry.arch", "geometry.arch: give abutment_width and abutment_height, or "
                                                "pier_width, pier_height and pier_courses, not both"),
        ('kind = "semicircular"\nspan = 2\nthickness = 0.1\nvoussoirs = 8', "blocks = [[0, 0, 1, 1]]", None,
         "[geometry] needs exactly one of running_bond, pattern, blocks, dxf, polygons, arch, gable, stone_wall; blocks "
         "and arch are both given"),
        ('kind = "semicircular"\nspan = 2\nthickness = 0.1\nvoussoirs = 8', "supports = [[[0, 0], [1, 0]]]",
         "geometry.supports[0]", "geometry.supports[0]: 2 vertices: a block needs at least 3"),
        (SEMICIRCULAR + "\nbackfill = { level = -1, density = 1800 }", "", "geometry.arch.backfill.level",
         "geometry.arch.backfill.level: must be > 0, got -1"),
        (SEMICIRCULAR + "\nbackfill = { level = nan, density = 1800 }", "", "geometry.arch.backfill.level",
         "geometry.arch.backfill.level: expected a finite number"),
        (SEMICIRCULAR + "\nbackfill = { level = 1.5 }", "", "geometry.arch.backfill.density",
         "missing key 'density' in [geometry.arch.backfill]"),
        (SEMICIRCULAR + '\nbackfill = { level = 1.5, density = "2 kN" }', "", "geometry.arch.backfill.density",
         "'2 kN' is a force; geometry.arch.backfill.density is a mass density"),
        ('kind = "segmental"\nspan = 4\nrise = 1\nthickness = 0.3\nvoussoirs = 8\nbackfill = { level = 0.1, density = '
         '1800 }', "", "geometry.arch.backfill.level", "geometry.arch.backfill.level = 0.1 m does not reach the "
                                                     "extrados, whose lowest point is 0.180000 m above the springing line"),
    ],
)
def test_arch_refusals(tmp_path, capsys, arch: str, extra: str, key, message: str) -> None:
    from masonry_dem import cli

    path = tmp_path / "arch.toml"
    path.write_text(ARCH_CASE.format(extra=extra, arch=arch))
    with pytest.raises(md.InputError) as info:
        md.load_case(path)
    assert str(info.value).startswith(f"{path}: ") and message in str(info.value) and info.value.key == key
    assert cli.main(["run", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"masonry-dem: error: {info.value}"]


def test_the_arch_example_s_reference_is_its_least_four_hinge_mechanism() -> None:
    from pathlib import Path

    case = md.load_case(Path(__file__).resolve().parents[2] / "examples" / "semicircular-arch.toml")
    expected, hinges = four_hinge_multiplier(case.build_model())
    assert case.reference["collapse_multiplier"] == pytest.approx(expected, abs=5e-5)  # its 4 digits
    assert [tuple(np.round(p, 2)) for _, p in hinges] == [(-0.87, 0.5), (0.0, 1.15), (0.71, 0.71), (1.15, 0.0)]
