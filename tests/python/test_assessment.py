"""Seismic assessment (masonry_dem.assessment, docs/assessment.md): the code spectra against hand values at every
corner period, a tabulated spectrum, and the refusals of parameters out of the codes' ranges."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Callable, Dict

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import assessment as sa

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
G = 9.80665  # the standard gravity, the unit "g"
TIGHT = 1e-12


def close(value: float, expected: float, tol: float = TIGHT) -> bool:
    return abs(value - expected) <= tol * max(1.0, abs(expected))


# -- spectra ------------------------------------------------------------------------------------------------------
# Each site: the spectrum's parameters, its corner periods and hand values at T = 0, T_B, T_C, T_D and 4 s, written
# from the code's branches (EN 1998-1 eqs. 3.2-3.5, NTC 2018 eq. 3.2.2) with the table values typed in.

def _ec8_b() -> Dict[str, Any]:
    # type 1, ground B (Table 3.2: S 1.2, T_B 0.15, T_C 0.5, T_D 2.0), a_gR = 0.25 g, gamma_I = 1, 5%: eta = 1
    ag, S, eta = 0.25 * G, 1.2, 1.0
    plateau = ag * S * eta * 2.5
    return dict(build=dict(code="ec8", ag=0.25 * G, ground_type="B", spectrum_type=1), corners=(0.15, 0.5, 2.0),
                values={0.0: ag * S, 0.15: plateau, 0.5: plateau, 2.0: plateau * 0.5 / 2.0,
                        4.0: plateau * 0.5 * 2.0 / 16.0, 0.075: ag * S * (1 + 0.5 * (2.5 * eta - 1)),
                        1.0: plateau * 0.5 / 1.0})


def _ec8_d() -> Dict[str, Any]:
    # type 2, ground D (Table 3.3: S 1.8, T_B 0.10, T_C 0.30, T_D 1.2), a_gR = 3 m/s2, gamma_I = 1.2, 10%
    ag, S, eta = 3.0 * 1.2, 1.8, math.sqrt(10.0 / 15.0)
    plateau = ag * S * eta * 2.5
    return dict(build=dict(code="ec8", ag=3.0, ground_type="D", spectrum_type=2, importance=1.2, damping=0.10),
                corners=(0.10, 0.30, 1.2),
                values={0.0: ag * S, 0.10: plateau, 0.30: plateau, 1.2: plateau * 0.3 / 1.2,
                        4.0: plateau * 0.3 * 1.2 / 16.0, 0.05: ag * S * (1 + 0.5 * (2.5 * eta - 1))})


def _ntc_c() -> Dict[str, Any]:
    # a_g = 0.25 g, F0 = 2.5, T*_C = 0.3 s, soil C (S_S = 1.70 - 0.60 F0 a_g/g = 1.325 in [1, 1.5];
    # C_C = 1.05 T*_C^-0.33), topography T2 (S_T = 1.2), 5%
    ag, F0, S = 0.25 * G, 2.5, 1.325 * 1.2
    TC = 1.05 * 0.3 ** -0.33 * 0.3
    TB, TD = TC / 3, 4 * 0.25 + 1.6
    plateau = ag * S * 1.0 * F0
    return dict(build=dict(code="ntc2018", ag=0.25 * G, F0=2.5, Tc_star=0.3, soil="C", topography="T2"),
                corners=(TB, TC, TD),
                values={0.0: ag * S, TB: plateau, TC: plateau, TD: plateau * TC / TD, 4.0: plateau * TC * TD / 16,
                        TB / 4: plateau * (0.25 + 0.75 / F0)})


def _ntc_d() -> Dict[str, Any]:
    # a_g = 0.15 g, F0 = 2.4, T*_C = 0.35 s, soil D (S_S = 2.40 - 1.50 x 2.4 x 0.15 = 1.86, clamped to 1.8;
    # C_C = 1.25 T*_C^-0.5), topography T1, 10%: eta = sqrt(10/15)
    ag, F0, S, eta = 0.15 * G, 2.4, 1.8, math.sqrt(10.0 / 15.0)
    TC = 1.25 * 0.35 ** -0.5 * 0.35
    TB, TD = TC / 3, 4 * 0.15 + 1.6
    plateau = ag * S * eta * F0
    return dict(build=dict(code="ntc2018", ag=0.15 * G, F0=2.4, Tc_star=0.35, soil="D", damping=0.10),
                corners=(TB, TC, TD),
                values={0.0: ag * S, TB: plateau, TC: plateau, TD: plateau * TC / TD, 4.0: plateau * TC * TD / 16,
                        TB / 2: plateau * (0.5 + 0.5 / (eta * F0))})


SITES: Dict[str, Callable[[], Dict[str, Any]]] = {"ec8 type 1 B": _ec8_b, "ec8 type 2 D": _ec8_d,
                                                  "ntc C T2": _ntc_c, "ntc D T1": _ntc_d}


@pytest.mark.parametrize("site", list(SITES))
def test_spectrum_at_corner_periods(site: str) -> None:
    data = SITES[site]()
    spectrum = sa.spectrum(**data["build"])
    for got, expected in zip((spectrum.TB, spectrum.TC, spectrum.TD), data["corners"]):
        assert close(got, expected), (got, expected)
    for T, expected in data["values"].items():
        assert close(sa.elastic_spectrum(T, **data["build"]), expected), (site, T)
        # the displacement spectrum up to T_E (>= 4.5 s): S_e (T / 2 pi)^2 (EN 1998-1 eq. 3.7, NTC 2018 eq. 3.2.12)
        assert close(sa.displacement_spectrum(T, **data["build"]), expected * (T / (2 * math.pi)) ** 2), (site, T)
    # the same at an array of periods
    periods = np.array(list(data["values"]))
    assert np.allclose(spectrum.acceleration(periods), list(data["values"].values()), rtol=TIGHT, atol=0)


def test_ntc_soil_factor_clamped_and_corners() -> None:
    # soil B: S_S = 1.40 - 0.40 F0 a_g / g = 1.40 - 0.40 x 2.6 x 0.35 = 1.036; C_C = 1.10 T*_C^-0.2
    s = sa.ntc2018_spectrum(0.35 * G, 2.6, 0.4, soil="B", topography="T4")
    assert close(s.S, 1.036 * 1.4) and close(s.parameters["S_S"], 1.036)
    assert close(s.TC, 1.10 * 0.4 ** -0.2 * 0.4) and close(s.TD, 4 * 0.35 + 1.6)
    # soil B at low a_g: 1.40 - 0.40 x 2.5 x 0.05 = 1.35, clamped to 1.20
    assert close(sa.ntc2018_spectrum(0.05 * G, 2.5, 0.3, soil="B").S, 1.20)
    # soil A: S = S_T, C_C = 1
    s = sa.ntc2018_spectrum(0.2 * G, 2.4, 0.3, topography="T3")
    assert close(s.S, 1.2) and close(s.TC, 0.3) and close(s.TB, 0.1)


def test_displacement_spectrum_long_periods() -> None:
    # EN 1998-1 Annex A, ground B (T_E 5 s, T_F 10 s): linear from 2.5 eta d_g at T_E to d_g at T_F, then d_g
    ag, S = 0.25 * G, 1.2
    d_g = 0.025 * ag * S * 0.5 * 2.0
    build = dict(code="ec8", ag=ag, ground_type="B")
    assert close(sa.displacement_spectrum(7.0, **build), d_g * (2.5 + (7.0 - 5.0) / 5.0 * (1 - 2.5)))
    assert close(sa.displacement_spectrum(10.0, **build), d_g)
    assert close(sa.displacement_spectrum(15.0, **build), d_g)
    # up to T_E: S_e (T / 2 pi)^2
    plateau = ag * S * 2.5
    assert close(sa.displacement_spectrum(5.0, **build), plateau * 0.5 * 2.0 / 25.0 * (5.0 / (2 * math.pi)) ** 2)
    # NTC 2018, soil C (T_E 6 s, T_F 10 s), F0 in place of 2.5
    s = sa.ntc2018_spectrum(0.25 * G, 2.5, 0.3, soil="C")
    d_g = 0.025 * s.ag * s.S * s.TC * s.TD
    assert close(s.displacement(8.0), d_g * (2.5 + (8.0 - 6.0) / 4.0 * (1 - 2.5)))


def test_spectrum_from_a_file(tmp_path: Path) -> None:
    path = tmp_path / "site.csv"
    path.write_text("period [s], Sa [g]\n0.0, 0.30\n0.2, 0.75\n0.6, 0.75\n2.0, 0.225\n4.0, 0.06\n")
    s = sa.read_spectrum(path, units="g", TC=0.6)
    assert s.code == "file" and close(s.peak_ground_acceleration, 0.30 * G) and s.TC == 0.6
    # linear between the samples
    assert close(s.acceleration(0.1), (0.30 + 0.75) / 2 * G)
    assert close(s.acceleration(1.3), (0.75 + 0.225) / 2 * G)
    assert close(s.acceleration(3.5), (0.225 + 0.75 * (0.06 - 0.225)) * G)
    assert close(s.displacement(1.3), (0.75 + 0.225) / 2 * G * (1.3 / (2 * math.pi)) ** 2)
    # m/s2 as they are
    path.write_text("0 3\n1 6\n")
    assert close(sa.read_spectrum(path, units="m/s2").acceleration(0.25), 3.75)
    # beyond the file's last period, or a file that does not start at T = 0: refused
    with pytest.raises(md.InputError, match="ends at T = 1 s"):
        sa.read_spectrum(path, units="m/s2").acceleration(1.5)
    path.write_text("0.1 3\n1 6\n")
    with pytest.raises(md.InputError, match="must start at T = 0"):
        sa.read_spectrum(path, units="m/s2")


@pytest.mark.parametrize("build, key", [
    (dict(code="ec8", ag=0.0), "ag"),
    (dict(code="ec8", ag=-1.0), "ag"),
    (dict(code="ec8", ag=2.0, ground_type="S1"), "ground_type"),
    (dict(code="ec8", ag=2.0, ground_type="F"), "ground_type"),
    (dict(code="ec8", ag=2.0, spectrum_type=3), "spectrum_type"),
    (dict(code="ec8", ag=2.0, importance=0.0), "importance"),
    (dict(code="ec8", ag=2.0, damping=5.0), "damping"),  # a percentage where the ratio is asked
    (dict(code="ec8", ag=2.0, damping=-0.01), "damping"),
    (dict(code="ec8", ag=math.nan), "ag"),
    (dict(code="ntc2018", ag=2.0, F0=2.1, Tc_star=0.3), "F0"),
    (dict(code="ntc2018", ag=2.0, F0=2.5, Tc_star=0.0), "Tc_star"),
    (dict(code="ntc2018", ag=2.0, F0=2.5, Tc_star=0.3, soil="S2"), "soil"),
    (dict(code="ntc2018", ag=2.0, F0=2.5, Tc_star=0.3, topography="T5"), "topography"),
    (dict(code="ntc2018", ag=2.0, F0=2.5, Tc_star=0.3, ground_type="B"), "ground_type"),
    (dict(code="eurocode", ag=2.0), "code"),
])
def test_spectrum_parameters_out_of_range_refused_by_name(build: Dict[str, Any], key: str) -> None:
    with pytest.raises(md.InputError, match=rf"^{key}: ") as info:
        sa.spectrum(**build)
    assert info.value.key == key
    with pytest.raises(md.InputError, match="periods must be finite and >= 0"):
        sa.ec8_spectrum(2.0).acceleration(-0.1)
