"""Vaults, domes and buttressed walls from Python and from case files: the generators' refusals by key, the example
case of a barrel vault against the plane's arch, the cross vault's example pushed along x and along y, the buttressed
wall's case against the sum of moments, and a bad key of a case exiting with status 2 on one line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any, Callable

import pytest

import masonry_dem as md

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_the_barrel_vault_example_has_the_plane_arch_example_s_multiplier() -> None:
    # the vault in staggered courses pushed across its axis is a row of arches (tests/space_vaults.rs)
    vault = md.load_case(EXAMPLES / "barrel-vault.toml")
    assert vault.dimension == 3 and vault.model.base is False
    model = vault.build_model()
    assert (model.n_blocks, model.base_index) == (6 * 3 + 6 * 4, None)  # every other course starts with a half
    arch = md.load_case(EXAMPLES / "semicircular-arch.toml").build_model()
    want = arch.solve_limit(tolerance=1e-10).collapse_multiplier
    got = model.solve_limit(tolerance=1e-10).collapse_multiplier
    assert got == pytest.approx(want, rel=1e-7)
    assert vault.run().collapse_multiplier == pytest.approx(vault.reference["collapse_multiplier"], rel=1e-2)


def test_a_dome_case_runs_on_its_base() -> None:
    text = """format = 1
[geometry.dome]
kind = "pointed"
span = 4.0
rise = 2.6
thickness = "250 mm"
meridians = 10
parallels = 4
[joints]
friction = 0.8
dilatancy = 0.8
"""
    case = md.parse_case(text, source="dome.toml")
    model = case.build_model()
    assert (model.n_blocks, model.base_index) == (40, 40)
    r = case.run()
    assert r.status == "collapse" and r.collapse_multiplier > 0
    # axisymmetric: pushed along a meridian plane at 36 deg, the same multiplier
    d = md.dome("pointed", 0.25, 10, 4, span=4.0, rise=2.6)
    turned = md.Model3D(polyhedra=d["polyhedra"], joints={"default": {"friction": 0.8, "dilatancy": 0.8}},
                        direction=36.0)
    assert turned.solve_limit(tolerance=1e-10).collapse_multiplier == pytest.approx(
        model.solve_limit(tolerance=1e-10).collapse_multiplier, rel=1e-6)


def test_the_cross_vault_example_has_one_multiplier_along_x_and_along_y() -> None:
    case = md.load_case(EXAMPLES / "cross-vault.toml")
    assert case.dimension == 3 and case.model.base is False
    model = case.build_model()
    assert (model.n_blocks, model.base_index) == (4 * 12, None)
    r = case.run()
    assert r.status == "collapse" and r.collapse_multiplier > 0
    text = (EXAMPLES / "cross-vault.toml").read_text().replace("direction = 0.0 ", "direction = 90.0 ")
    along_y = md.parse_case(text, source="cross-vault.toml").run()
    assert along_y.collapse_multiplier == pytest.approx(r.collapse_multiplier, rel=1e-7)
    # the generator's blocks from Python are the case's
    v = md.cross_vault("semicircular", 0.15, 12, span=2.0, abutment_height=0.3)
    assert (len(v["polyhedra"]), len(v["supports"])) == (48, 4)
    # on four piers 0.4 m square, 0.9 m high in 3 courses, on the base, from the case file: the vault's blocks and the
    # piers'; the piers give way before the vault on its fixed supports does
    piers = "pier_height = 0.9\npier_width = 0.4\npier_courses = 3 "
    text = (EXAMPLES / "cross-vault.toml").read_text().replace("abutment_height = 0.3 ", piers)
    on_piers = md.parse_case(text, source="cross-vault.toml")
    model = on_piers.build_model()
    assert (model.n_blocks, model.base_index) == (48 + 4 * 3, 60)
    p = on_piers.run()
    assert p.status == "collapse" and 0 < p.collapse_multiplier < r.collapse_multiplier


def test_a_buttressed_wall_case_overturns_about_the_buttresses_toe() -> None:
    # a wall 2.4 m x 1.2 m x 0.2 m with two bonded buttresses 0.4 m x 0.4 m, pushed towards them (-y): the wall and
    # the buttresses turn as one body about the buttresses' toe, y = -0.4 (tests/space_buttresses.rs): by the sum of
    # moments of the volumes (one density), lambda = (V_w 0.5 + V_b 0.2) / ((V_w + V_b) 0.6)
    text = """format = 1
[geometry.buttressed_wall]
length = 2.4
height = 1.2
thickness = "200 mm"
block_length = 0.4
block_height = 0.2
spacing = 1.2
buttress_width = 0.4
buttress_depth = 0.4
[joints]
friction = 2.0
dilatancy = 2.0
[loads]
direction = 270.0
"""
    case = md.parse_case(text, source="buttresses.toml")
    boxes = md.buttressed_wall(2.4, 1.2, 0.2, 0.4, 0.2, 1.2, 0.4, 0.4)
    assert case.build_model().n_blocks == len(boxes) == 45
    vw, vb = 2.4 * 0.2 * 1.2, 2 * 0.4 * 0.4 * 1.2
    r = case.run()
    assert r.status == "collapse"
    assert r.collapse_multiplier == pytest.approx((vw * 0.5 + vb * 0.2) / ((vw + vb) * 0.6), rel=1e-7)
    loose = md.parse_case(text.replace("buttress_depth = 0.4", "buttress_depth = 0.4\nbonded = false"), source="b.toml")
    assert loose.build_model().n_blocks == len(md.buttressed_wall(2.4, 1.2, 0.2, 0.4, 0.2, 1.2, 0.4, 0.4, bonded=False))
    with pytest.raises(md.InputError) as info:
        md.parse_case(text.replace("buttress_depth = 0.4", "buttress_depth = 0.4\nbonded = 1"), source="b.toml")
    message = str(info.value)
    assert message == "b.toml: geometry.buttressed_wall.bonded: expected true or false, got integer 1", message
    with pytest.raises(md.InputError) as info:
        md.parse_case(text.replace("spacing = 1.2", "spacing = 0.41"), source="b.toml").build_model()
    assert str(info.value).startswith("b.toml: geometry.buttressed_wall.spacing = 0.41 m must exceed buttress_width")


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: md.dome("hemispherical", 0.1, 2, 4, radius=1.0), "geometry.dome.meridians must be at least 3, got 2"),
        (lambda: md.dome("hemispherical", 0.1, 8, 0, radius=1.0), "geometry.dome.parallels must be at least 1, got 0"),
        (lambda: md.dome("conical", 0.1, 8, 4, radius=1.0), 'geometry.dome.kind must be "hemispherical" or "pointed"'),
        (lambda: md.dome("pointed", 0.1, 8, 4, span=4.0, rise=1.0),
         "geometry.dome.rise = 1 m of a pointed dome must be at least half its span (2 m)"),
        (lambda: md.dome("hemispherical", -0.1, 8, 4, radius=1.0), "geometry.dome.thickness must be a finite number > 0"),
        (lambda: md.barrel_vault("semicircular", 0.1, 8, -1.0, radius=1.0),
         "geometry.barrel_vault.length must be a finite number > 0, got -1"),
        (lambda: md.barrel_vault("semicircular", 0.1, 8, 1.0, block_length=0.0, radius=1.0),
         "geometry.barrel_vault.block_length must be a finite number > 0, got 0"),
        (lambda: md.barrel_vault("gothic", 0.1, 8, 1.0, radius=1.0), "geometry.barrel_vault.kind must be"),
        (lambda: md.barrel_vault("pointed", 0.1, 7, 1.0, span=2.0, rise=1.5),
         "geometry.barrel_vault.voussoirs = 7 for a pointed arch must be even"),
        (lambda: md.barrel_vault("semicircular", 0.1, 8, 1.0, radius=1.0, abutment_width=1.0, pier_width=1.0),
         "geometry.barrel_vault: give abutment_width and abutment_height, or pier_width"),
        (lambda: md.Model3D(polyhedra=[[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]]), "polyhedra[0]: fewer than 4"),
        (lambda: md.cross_vault("segmental", 0.1, 8, span=2.0, rise=0.5),
         'geometry.cross_vault.kind must be "semicircular" or "pointed", got "segmental"'),
        (lambda: md.cross_vault("semicircular", 0.1, 1, radius=1.0),
         "geometry.cross_vault.voussoirs of a semicircular arch must lie in 2..="),
        (lambda: md.cross_vault("semicircular", 0.1, 8, radius=1.0, abutment_height=0.0),
         "geometry.cross_vault.abutment_height must be a finite number > 0, got 0"),
        (lambda: md.cross_vault("semicircular", 0.1, 8, radius=1.0, span=2.0),
         "geometry.cross_vault.radius and geometry.cross_vault.span are both given"),
        (lambda: md.cross_vault("semicircular", 0.1, 8, radius=1.0, pier_width=0.5),
         "geometry.cross_vault.pier_height is required for piers"),
        (lambda: md.cross_vault("semicircular", 0.2, 8, radius=1.0, pier_height=1.0, pier_width=0.1),
         "geometry.cross_vault.pier_width"),
        (lambda: md.cross_vault("semicircular", 0.2, 8, radius=1.0, pier_height=1.0, pier_width=0.3, pier_courses=0),
         "geometry.cross_vault.pier_courses must be at least 1, got 0"),
        (lambda: md.buttressed_wall(2.4, 1.2, 0.2, 0.4, 0.2, 1.2, 0.4, -0.4),
         "buttressed_wall.buttress_depth must be a finite number > 0, got -0.4"),
        (lambda: md.buttressed_wall(0.7, 1.2, 0.2, 0.4, 0.2, 1.2, 0.4, 0.4), "buttressed_wall.length = 0.7 m holds no"),
        (lambda: md.buttressed_wall(2.4, 1.21, 0.2, 0.4, 0.2, 1.2, 0.4, 0.4), "buttressed_wall.height = 1.21 m"),
    ],
)
def test_bad_parameters_are_refused_naming_the_key(make: Callable[[], Any], message: str) -> None:
    with pytest.raises(md.InputError) as info:
        make()
    assert message in str(info.value) and "\n" not in str(info.value), str(info.value)


def test_a_bad_key_of_a_vault_case_exits_with_status_2_on_one_line(tmp_path: Path) -> None:
    text = (EXAMPLES / "barrel-vault.toml").read_text().replace("length = 1.2 ", "length = -1.2 ")
    (tmp_path / "vault.toml").write_text(text)
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", "run", "vault.toml"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr, proc.stderr
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("masonry-dem: error: vault.toml: ") and "length" in lines[0], lines
    # a generator's refusal of keys that go together: the file and the key named
    text = (EXAMPLES / "barrel-vault.toml").read_text().replace("span = 2.0 ", "radius = 1.0\nspan = 2.0 ")
    with pytest.raises(md.InputError) as info:
        md.parse_case(text, source="vault.toml")
    assert str(info.value).startswith("vault.toml: geometry.barrel_vault.radius and geometry.barrel_vault.span are "
                                      "both given"), str(info.value)
