"""Vaults and domes from Python and from case files: the generators' refusals by key, the example case of a barrel
vault against the plane's arch, and a bad key of a case exiting with status 2 on one line."""

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
