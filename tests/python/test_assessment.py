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
G_NTC = 9.81  # the g of a_g / g in NTC 2018 Table 3.2.IV and eq. 3.2.7 (3.2.3.2.1: "g = 9,81 m/s2")
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
    ag, F0, S = 0.25 * G_NTC, 2.5, 1.325 * 1.2
    TC = 1.05 * 0.3 ** -0.33 * 0.3
    TB, TD = TC / 3, 4 * 0.25 + 1.6
    plateau = ag * S * 1.0 * F0
    return dict(build=dict(code="ntc2018", ag=0.25 * G_NTC, F0=2.5, Tc_star=0.3, soil="C", topography="T2"),
                corners=(TB, TC, TD),
                values={0.0: ag * S, TB: plateau, TC: plateau, TD: plateau * TC / TD, 4.0: plateau * TC * TD / 16,
                        TB / 4: plateau * (0.25 + 0.75 / F0)})


def _ntc_d() -> Dict[str, Any]:
    # a_g = 0.15 g, F0 = 2.4, T*_C = 0.35 s, soil D (S_S = 2.40 - 1.50 x 2.4 x 0.15 = 1.86, clamped to 1.8;
    # C_C = 1.25 T*_C^-0.5), topography T1, 10%: eta = sqrt(10/15)
    ag, F0, S, eta = 0.15 * G_NTC, 2.4, 1.8, math.sqrt(10.0 / 15.0)
    TC = 1.25 * 0.35 ** -0.5 * 0.35
    TB, TD = TC / 3, 4 * 0.15 + 1.6
    plateau = ag * S * eta * F0
    return dict(build=dict(code="ntc2018", ag=0.15 * G_NTC, F0=2.4, Tc_star=0.35, soil="D", damping=0.10),
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
    s = sa.ntc2018_spectrum(0.35 * G_NTC, 2.6, 0.4, soil="B", topography="T4")
    assert close(s.S, 1.036 * 1.4) and close(s.parameters["S_S"], 1.036)
    assert close(s.TC, 1.10 * 0.4 ** -0.2 * 0.4) and close(s.TD, 4 * 0.35 + 1.6)
    # soil B at low a_g: 1.40 - 0.40 x 2.5 x 0.05 = 1.35, clamped to 1.20
    assert close(sa.ntc2018_spectrum(0.05 * G_NTC, 2.5, 0.3, soil="B").S, 1.20)
    # soil A: S = S_T, C_C = 1
    s = sa.ntc2018_spectrum(0.2 * G_NTC, 2.4, 0.3, topography="T3")
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


# -- the linear kinematic check --------------------------------------------------------------------------------------

def _dry(friction: float = 1.0) -> Dict[str, Any]:
    return {"default": md.dry_joint(friction, dilatancy=friction)}


def _site(**parameters: Any) -> sa.AssessmentParameters:
    return sa.AssessmentParameters(spectrum=sa.ec8_spectrum(0.25 * G, "B"), **parameters)


@pytest.mark.parametrize("b, h", [(0.4, 1.2), (0.5, 0.8)])
def test_single_block_at_ground_level(b: float, h: float) -> None:
    thickness, density, g = 0.5, 1800.0, 9.81
    model = md.Model([[0.0, 0.0, b, h]], thickness=thickness, density=density, joints=_dry(), gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    check = sa.linear_check(model, results, _site(), gravity=g)
    mass = b * h * thickness * density
    assert close(check.alpha0, b / h, 1e-9)
    assert close(check.mass_fraction, 1.0, 1e-9) and close(check.participating_mass, mass, 1e-9)
    assert close(check.a0_star, (b / h) * g / 1.35, 1e-9)
    # demand at ground level: a_g S / q, type 1 ground B
    assert close(check.demand_ground, 0.25 * G * 1.2 / 2.0) and check.demand == check.demand_ground
    assert close(check.ratio, check.a0_star / check.demand)
    assert check.verdict == ("pass" if check.ratio >= 1 else "fail")
    assert math.isnan(check.demand_height) and check.moving_blocks == 1


@pytest.mark.parametrize("n", [2, 5])
def test_stack_turning_as_one_about_the_toe(n: int) -> None:
    # n equal blocks in a column: the base joint is the weakest (lambda = b / (height above a joint)), so the
    # column turns as one about the toe of its base; weights lumped at the blocks' centroids y_i
    b, hb, g = 0.3, 0.25, 9.81
    blocks = [[0.0, i * hb, b, (i + 1) * hb] for i in range(n)]
    model = md.Model(blocks, thickness=1.0, density=2000.0, joints=_dry(), gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    check = sa.linear_check(model, results, _site(q=1.5, confidence_factor=1.2), gravity=g)
    y = (np.arange(n) + 0.5) * hb
    e_star = y.sum() ** 2 / (n * (y**2).sum())
    m = b * hb * 2000.0
    assert close(check.alpha0, b / (n * hb), 1e-9)
    assert close(check.mass_fraction, e_star, 1e-9)
    assert close(check.participating_mass, e_star * n * m, 1e-9)
    assert close(check.a0_star, b / (n * hb) * g / (e_star * 1.2), 1e-9)
    assert close(check.demand, 0.25 * G * 1.2 / 1.5) and check.moving_blocks == n


def test_facade_hand_check_of_the_formulas() -> None:
    # the facade of the shared benchmark (section 4): t = 0.5 m, h = 6 m, the wall's 100 kN at (t/2, h/2) from the
    # hinge, a floor's 20 kN at height h, 0.25 m from it; a rotation about the hinge moves them by h/2 and h
    # (its a0* is written with g = 9.81 m/s2)
    weights, dx, g = [100e3, 20e3], [3.0, 6.0], 9.81
    alpha0 = (100 * 0.25 + 20 * 0.25) / (100 * 3.0 + 20 * 6.0)  # 30 / 420
    check = sa.linear_check_of(alpha0, weights, dx, g, _site())
    assert close(alpha0, 0.071429, 1e-5)
    assert close(check.participating_mass * g, 420e3**2 / 1620e3, 1e-12)  # 108.89 kN
    assert close(check.mass_fraction, 420.0**2 / 1620.0 / 120.0, 1e-12)
    assert round(check.mass_fraction, 4) == 0.9074
    assert close(check.a0_star, alpha0 * g / (check.mass_fraction * 1.35), 1e-12)
    assert round(check.a0_star, 4) == 0.5720 and round(check.a0_star / g, 4) == 0.0583


def test_mechanism_at_height_circolare_2009() -> None:
    # Z = 6 m in a building of H = 9 m and N = 3 storeys: T1 = 0.05 H^(3/4), psi = Z / H, gamma = 3N / (2N + 1); the
    # demand is the larger of a_g S / q and S_e(T1) psi gamma / q
    b, h, g = 0.4, 1.2, 9.81
    model = md.Model([[0.0, 0.0, b, h]], thickness=0.5, density=1800.0, joints=_dry(), gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    spectrum = sa.ec8_spectrum(0.25 * G, "B")
    check = sa.linear_check(model, results, spectrum, mechanism_height=6.0, building_height=9.0, storeys=3, gravity=g)
    T1 = 0.05 * 9.0**0.75
    assert close(check.T1, T1) and close(check.psi, 6 / 9) and close(check.gamma, 9 / 7)
    assert 0.15 < T1 < 0.5  # on the plateau: S_e(T1) = a_g S 2.5
    assert close(check.demand_height, 0.25 * G * 1.2 * 2.5 * (6 / 9) * (9 / 7) / 2.0)
    assert check.demand == max(check.demand_ground, check.demand_height) == check.demand_height


@pytest.mark.parametrize("kwargs, key", [
    (dict(confidence_factor=0.9), "confidence_factor"),
    (dict(q=0.5), "q"),
    (dict(mechanism_height=10.0, building_height=9.0, storeys=3), "mechanism_height"),
    (dict(mechanism_height=-1.0), "mechanism_height"),
    (dict(mechanism_height=3.0, storeys=3), "building_height"),
    (dict(mechanism_height=3.0, building_height=9.0), "storeys"),
    (dict(mechanism_height=3.0, building_height=9.0, storeys=0), "storeys"),
])
def test_check_parameters_refused_by_name(kwargs: Dict[str, Any], key: str) -> None:
    with pytest.raises(md.InputError, match=rf"^{key}: ") as info:
        _site(**kwargs)
    assert info.value.key == key


def test_mechanism_refusals() -> None:
    model = md.Model([[0.0, 0.0, 0.4, 1.2]], thickness=0.5, density=1800.0, joints=_dry(), gravity=9.81)
    results = model.solve_limit()
    with pytest.raises(md.InputError, match="^gravity: "):
        sa.linear_check(model, results, sa.ec8_spectrum(2.0))

    class Still:  # a collapse whose mechanism moves no block
        status, collapse_multiplier = "collapse", 0.3
        mechanism = np.zeros((2, 3))

    with pytest.raises(md.InputError, match="^mechanism: no block moves"):
        sa.linear_check(model, Still(), sa.ec8_spectrum(2.0), gravity=9.81)
    # no collapse: a displacement-controlled path that ends before the peak ("completed")
    short = model.solve_static(control="displacement", steps=2, max_displacement=1e-9)
    assert short.status == "completed"
    with pytest.raises(md.InputError, match="^mechanism: no collapse mechanism"):
        sa.linear_check(model, short, sa.ec8_spectrum(2.0), gravity=9.81)
    # a multiplier that is a force, not a fraction of the weights
    beam = md.Model([[0.0, 0.0, 0.4, 1.2]], top_rotation="free", live="top_horizontal", joints=_dry())
    with pytest.raises(md.InputError, match="^loads.live: "):
        sa.linear_check(beam, beam.solve_limit(), sa.ec8_spectrum(2.0), gravity=9.81)


def test_wall1_static_explicit_and_limit_mechanisms_agree() -> None:
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    model = case.build_model()
    checks = {m: sa.linear_check(model, case.solve(model, m), _site(), gravity=10.0)
              for m in ("limit", "static", "dynamic")}
    ref = checks["limit"]
    # the wedge of 12 blocks turning about its toe: e* well below 1 (the blocks are weights at their centroids)
    assert ref.moving_blocks == 12 and 0.5 < ref.mass_fraction < 0.9
    for method, check in checks.items():
        for name in ("alpha0", "participating_mass", "mass_fraction", "a0_star"):
            assert abs(getattr(check, name) / getattr(ref, name) - 1) < 0.02, (method, name)
        assert check.verdict == ref.verdict


# -- N2 (EN 1998-1 Annex B) ------------------------------------------------------------------------------------------

def _epp(F_y: float, d_y: float, d_u: float) -> Any:
    """An elastic-perfectly plastic curve: (0, 0), (d_y, F_y), (d_u, F_y)."""
    return np.array([0.0, d_y, d_u]), np.array([0.0, F_y, F_y])


def _n2_by_hand(m_star: float, F_y: float, d_y: float, gamma: float, ag: float, S: float, TB: float, TC: float,
                TD: float) -> Dict[str, float]:
    """Annex B's formulas on an elastic-perfectly plastic system (its F*_y, d*_y), a type 1 spectrum at 5%."""
    T = 2 * math.pi * math.sqrt(m_star * d_y / F_y)
    plateau = ag * S * 2.5
    Se = (ag * S * (1 + T / TB * 1.5) if T < TB else plateau if T < TC else plateau * TC / T if T < TD
          else plateau * TC * TD / T**2)
    d_et = Se * (T / (2 * math.pi)) ** 2
    q_u = Se * m_star / F_y
    if T >= TC or F_y / m_star >= Se:
        d_t = d_et
    else:
        d_t = max(d_et / q_u * (1 + (q_u - 1) * TC / T), d_et)
    d_t = min(d_t, 3 * d_et)
    return dict(T_star=T, Se=Se, d_et=d_et, q_u=q_u, d_t_star=d_t, d_t=gamma * d_t)


def test_n2_hand_check_short_period() -> None:
    # the shared benchmark (section 5): m* = 100 t, F*_y = 200 kN, d*_y = 0.010 m, type 1 ground B, a_g = 0.25 g
    # (written with g = 9.81 m/s2): T* = 0.4443 s, S_e = 7.3575 m/s2, d*_et = 0.03679 m, q_u = 3.679, d*_t = 0.04015 m
    spectrum = sa.ec8_spectrum(0.25 * 9.81, "B")
    d, F = _epp(200e3, 0.010, 0.08)
    check = sa.n2(d, F, [100e3], [1.0], spectrum)
    hand = _n2_by_hand(100e3, 200e3, 0.010, 1.0, 0.25 * 9.81, 1.2, 0.15, 0.5, 2.0)
    for name, value in hand.items():
        assert close(getattr(check, name), value), name
    assert close(check.gamma, 1.0) and close(check.m_star, 100e3) and close(check.d_y, 0.010)
    assert close(check.F_y, 200e3) and close(check.d_m, 0.010) and close(check.E_m, 0.5 * 200e3 * 0.010)
    assert check.branch == "short period, inelastic" and not check.capped
    assert (round(check.T_star, 4), round(check.Se, 4), round(check.d_et, 5), round(check.q_u, 3),
            round(check.d_t_star, 5)) == (0.4443, 7.3575, 0.03679, 3.679, 0.04015)
    assert close(check.d_u, 0.08) and close(check.ratio, 0.08 / check.d_t) and check.verdict == "pass"


def test_n2_gamma_and_the_other_branches() -> None:
    ag, spectrum = 0.25 * 9.81, sa.ec8_spectrum(0.25 * 9.81, "B")
    # two masses of 50 t with Phi = (0.5, 1): m* = 75 t, Gamma = 75 / (12.5 + 50) = 1.2; the curve in d_n, F_b is
    # Gamma times the system's: F*_y = 150 kN, d*_y = 0.2 m: T* = 2 pi sqrt(0.1) > T_C, the long-period branch
    d, F = _epp(1.2 * 150e3, 1.2 * 0.2, 1.2 * 0.6)
    check = sa.n2(d, F, [50e3, 50e3], [0.5, 1.0], spectrum)
    assert close(check.gamma, 1.2) and close(check.m_star, 75e3)
    hand = _n2_by_hand(75e3, 150e3, 0.2, 1.2, ag, 1.2, 0.15, 0.5, 2.0)
    for name, value in hand.items():
        assert close(getattr(check, name), value), name
    assert check.branch == "long period" and close(check.d_t_star, check.d_et)
    # short period, strong: F*_y / m* = 10 m/s2 >= S_e(T*): the elastic displacement
    check = sa.n2(*_epp(1000e3, 0.01, 0.05), [100e3], [1.0], spectrum)
    assert check.branch == "short period, elastic" and close(check.d_t_star, check.d_et)
    for name, value in _n2_by_hand(100e3, 1000e3, 0.01, 1.0, ag, 1.2, 0.15, 0.5, 2.0).items():
        assert close(getattr(check, name), value), name
    # very short period, weak: the cap d*_t <= 3 d*_et
    d_y = 200e3 * 0.05**2 / (4 * math.pi**2 * 100e3)  # T* = 0.05 s
    check = sa.n2(*_epp(200e3, d_y, 0.05), [100e3], [1.0], spectrum)
    assert check.capped and close(check.d_t_star, 3 * check.d_et) and close(check.T_star, 0.05)
    for name, value in _n2_by_hand(100e3, 200e3, d_y, 1.0, ag, 1.2, 0.15, 0.5, 2.0).items():
        assert close(getattr(check, name), value), name
    # the ultimate displacement where the force has fallen to 80% of its peak after it
    d = np.array([0.0, 0.01, 0.02, 0.03, 0.04])
    F = np.array([0.0, 100.0, 100.0, 90.0, 70.0])
    assert close(sa.n2(d, F, [1.0], [1.0], spectrum).d_u, 0.03 + 0.01 * (90 - 80) / (90 - 70))


def test_n2_of_wall1_static_pushover() -> None:
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    model = case.build_model()
    results = model.solve_static(control="displacement", max_displacement=0.02, steps=100)
    spectrum = sa.ntc2018_spectrum(0.2 * G, 2.5, 0.3, soil="C")
    g = 10.0
    check = sa.pushover_n2(model, results, spectrum, gravity=g)
    # every number again, from the results
    W = np.asarray(model.weights)
    u = np.asarray(results.displacements)[:, 0]
    c = results.control_block
    blocks = range(model.n_blocks)
    m = [W[i] / g for i in blocks]
    phi = [u[i] / u[c] for i in blocks]
    m_star = sum(mi * p for mi, p in zip(m, phi))
    gamma = m_star / sum(mi * p * p for mi, p in zip(m, phi))
    d_n = list(results.curve_displacement)
    F_b = [lam * sum(W[i] for i in blocks) for lam in results.curve_multiplier]
    k = max(range(len(F_b)), key=lambda j: (F_b[j], -j))  # the first peak
    F_y, d_m = F_b[k] / gamma, d_n[k] / gamma
    E_m = sum((F_b[j] + F_b[j - 1]) / 2 / gamma * (d_n[j] - d_n[j - 1]) / gamma for j in range(1, k + 1))
    d_y = 2 * (d_m - E_m / F_y)
    assert close(check.gamma, gamma, 1e-12) and close(check.m_star, m_star, 1e-12)
    assert close(check.F_y, F_y, 1e-12) and close(check.d_m, d_m, 1e-12) and close(check.E_m, E_m, 1e-9)
    assert close(check.d_y, d_y, 1e-9)
    T = 2 * math.pi * math.sqrt(m_star * d_y / F_y)
    Se = spectrum.acceleration(T)
    assert T < spectrum.TB  # a stiff wall of rigid blocks: on the rising branch
    assert close(Se, spectrum.ag * spectrum.S * (2.5 * T / spectrum.TB + (1 - T / spectrum.TB)), 1e-12)
    d_et = Se * (T / (2 * math.pi)) ** 2
    q_u = Se * m_star / F_y
    assert close(check.T_star, T, 1e-9) and close(check.d_et, d_et, 1e-9) and close(check.q_u, q_u, 1e-9)
    if F_y / m_star >= Se:
        d_t = d_et
    else:
        d_t = min(max(d_et / q_u * (1 + (q_u - 1) * spectrum.TC / T), d_et), 3 * d_et)
    assert close(check.d_t_star, d_t, 1e-9) and close(check.d_t, gamma * d_t, 1e-9)
    # the curve does not fall to 80% of its peak by 2 cm: its last point is the ultimate displacement
    assert min(F_b[k:]) > 0.8 * F_b[k] and close(check.d_u, d_n[-1])
    assert check.verdict == ("pass" if check.d_t <= d_n[-1] else "fail")
    # limit analysis has no curve
    with pytest.raises(md.InputError, match="^method: "):
        sa.pushover_n2(model, model.solve_limit(), spectrum, gravity=g)


# -- the case file's [assessment], the command line, the result file, the table and the figure ----------------------

WALL1 = (EXAMPLES / "ferris-tinloi-wall1.toml").read_text().split("[assessment]")[0]


def _case(tmp_path: Path, table: str, name: str = "case.toml") -> Path:
    path = tmp_path / name
    path.write_text(WALL1 + "\n[assessment]\n" + table)
    return path


def test_case_table_read_with_units_and_defaults(tmp_path: Path) -> None:
    case = md.load_case(_case(tmp_path, 'spectrum = "ec8"\nag = "0.3 g"\nground_type = "C"\nspectrum_type = 2\n'
                                        'importance = 1.2\ndamping = 0.1\n'))
    p = case.assessment
    assert p.spectrum.code == "ec8" and close(p.spectrum.ag, 0.3 * G * 1.2) and p.spectrum.S == 1.5
    assert close(p.spectrum.eta, math.sqrt(10 / 15))
    assert (p.q, p.confidence_factor, p.mechanism_height, p.building_height, p.storeys) == (2.0, 1.35, 0.0, None, None)
    case = md.load_case(_case(tmp_path, 'spectrum = "ntc2018"\nag = "2.0 m/s2"\nF0 = 2.4\nTc_star = "300 ms"\n'
                                        'q = 1.5\nconfidence_factor = 1.2\nmechanism_height = "6 m"\n'
                                        'building_height = 9.0\nstoreys = 3\n'))
    p = case.assessment
    assert p.spectrum.ag == 2.0 and close(p.spectrum.parameters["Tc_star"], 0.3) and p.storeys == 3
    assert (p.q, p.confidence_factor, p.mechanism_height, p.building_height) == (1.5, 1.2, 6.0, 9.0)
    # a spectrum file, relative to the case file
    (tmp_path / "site.csv").write_text("0 0.3\n0.5 0.75\n4 0.1\n")
    case = md.load_case(_case(tmp_path, 'spectrum = "site.csv"\nspectrum_units = "g"\nTc = 0.5\n'))
    assert case.assessment.spectrum.code == "file" and close(case.assessment.spectrum.acceleration(0.25), 0.525 * G)
    # the rule at height, the building's damping and period
    case = md.load_case(_case(tmp_path, 'spectrum = "ec8"\nag = 2.0\nheight_rule = "circ2019"\n'
                                        'building_damping = 0.1\nT1 = "500 ms"\n'))
    p = case.assessment
    assert (p.height_rule, p.building_damping, p.T1) == ("circ2019", 0.1, 0.5)
    # no table: no assessment
    assert md.load_case(EXAMPLES / "ferris-tinloi-wall2.toml").assessment is None


@pytest.mark.parametrize("table, key, words", [
    ('spectrum = "ntc2018"\nag = "0.25 g"\nF0 = 2.1\nTc_star = 0.3\n', "F0", "must be >= 2.2"),
    ('spectrum = "ec8"\nag = 0\n', "ag", "must be > 0"),
    ('spectrum = "ec8"\nag = 2.0\nground_type = "S1"\n', "ground_type", "study of their own"),
    ('spectrum = "ec8"\nag = 2.0\ndamping = 5\n', "damping", "0.05 for 5%"),
    ('spectrum = "ec8"\nag = 2.0\nconfidence_factor = 0.9\n', "confidence_factor", "must be >= 1"),
    ('spectrum = "ec8"\nag = 2.0\nmechanism_height = 12.0\nbuilding_height = 9.0\nstoreys = 3\n', "mechanism_height",
     "above the building"),
    ('spectrum = "ec8"\nag = 2.0\nmechanism_height = 3.0\nstoreys = 3\n', "building_height", "needs the building"),
    ('spectrum = "ec8"\nag = 2.0\nF0 = 2.5\n', "F0", 'does not apply to spectrum = "ec8"'),
    ('spectrum = "ec8"\nag = "0.25 MPa"\n', "ag", "is a stress"),
    ('spectrum = "site.csv"\n', "spectrum_units", "missing key"),
    ('spectrum = "missing.csv"\nspectrum_units = "g"\n', "spectrum", "cannot read"),
    ('spectrum = "ec8"\nag = 2.0\nqq = 2\n', "qq", "unknown key"),
    ('spectrum = "ec8"\nag = 2.0\nheight_rule = "circ2008"\n', "height_rule", 'expected one of "circ2009"'),
    ('spectrum = "ec8"\nag = 2.0\nbuilding_damping = 5\n', "building_damping", "0.05 for 5%"),
    ('spectrum = "ec8"\nag = 2.0\nT1 = "0 s"\n', "T1", "must be > 0"),
])
def test_case_table_refusals_name_the_key(tmp_path: Path, table: str, key: str, words: str) -> None:
    (tmp_path / "site.csv").write_text("0 0.3\n1 0.5\n")
    with pytest.raises(md.InputError) as info:
        md.load_case(_case(tmp_path, table))
    message = str(info.value)
    assert message.startswith(f"{tmp_path / 'case.toml'}: ") and words in message and "\n" not in message, message
    assert info.value.key == f"assessment.{key}" and (f"assessment.{key}" in message or f"'{key}'" in message)


def test_assess_command_line(tmp_path: Path, capsys: Any) -> None:
    from masonry_dem.cli import main

    out_json, out_png = tmp_path / "a.json", tmp_path / "a.png"
    assert main(["assess", str(EXAMPLES / "ferris-tinloi-wall1.toml"), "-q", "--json", str(out_json), "--plot",
                 str(out_png)]) == 0
    text = capsys.readouterr().out
    for quantity, unit, clause in (("participating mass M*", "kg", "C8A.4.1"), ("a0* = alpha0 g / (e* FC)", "m/s2",
                                                                               "C8A.4.1"),
                                   ("demand at ground level a_g S / q", "m/s2", "C8A.4.2.3"),
                                   ("a_g", "m/s2", "NTC 2018 3.2.3.2.1")):
        line = next(line for line in text.splitlines() if line.strip().startswith(quantity))
        assert unit in line.split() and clause in line, line
    data = __import__("json").loads(out_json.read_text())
    a = data["assessment"]
    assert data["method"] == "limit" and a["n2"] is None
    # the result file's numbers are the check's, from Python
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    model = case.build_model()
    check = sa.linear_check(model, model.solve_limit(), case.assessment, gravity=10.0)
    for key in ("alpha0", "participating_mass", "mass_fraction", "a0_star", "demand", "ratio"):
        assert close(a[key], getattr(check, key), 1e-9), key
    assert a["verdict"] == check.verdict == "pass" and a["spectrum"]["code"] == "ntc2018"
    assert out_png.stat().st_size > 10_000
    # a static pushover: the N2 method too
    assert main(["assess", str(EXAMPLES / "ferris-tinloi-wall1.toml"), "-q", "--method", "static", "--json",
                 str(out_json)]) == 0
    assert __import__("json").loads(out_json.read_text())["assessment"]["n2"]["branch"].startswith("short period")


def test_assess_command_line_refusals(tmp_path: Path, capsys: Any) -> None:
    from masonry_dem.cli import main

    # no [assessment]
    assert main(["assess", str(EXAMPLES / "ferris-tinloi-wall2.toml"), "-q"]) == 2
    err = capsys.readouterr().err
    assert "no [assessment] table" in err and len(err.strip().splitlines()) == 1
    # a height above the building, FC below 1: refused by name, before any analysis
    path = _case(tmp_path, 'spectrum = "ec8"\nag = 2.0\nmechanism_height = 10\nbuilding_height = 6\nstoreys = 2\n')
    assert main(["assess", str(path), "-q"]) == 2
    assert "assessment.mechanism_height" in capsys.readouterr().err
    path = _case(tmp_path, 'spectrum = "ec8"\nag = 2.0\nconfidence_factor = 0.5\n')
    assert main(["assess", str(path), "-q"]) == 2
    assert "assessment.confidence_factor" in capsys.readouterr().err
    # a spectrum parameter out of the code's range, one line naming it
    path = _case(tmp_path, 'spectrum = "ntc2018"\nag = "0.25 g"\nF0 = 2.1\nTc_star = 0.3\n')
    assert main(["assess", str(path), "-q"]) == 2
    err = capsys.readouterr().err
    assert "assessment.F0" in err and "must be >= 2.2" in err and len(err.strip().splitlines()) == 1


# -- the nonlinear kinematic check of one rigid body ----------------------------------------------------------------

@pytest.mark.parametrize("b, h, n", [(0.4, 1.2, 1), (0.5, 0.8, 1), (0.3, 0.25, 4)])
def test_nonlinear_check_of_a_body_turning_about_its_toe(b: float, h: float, n: int) -> None:
    # n equal blocks of b x h in a column turn as one about the toe (b, 0): alpha(theta) = tan(atan(b / H) - theta)
    # with H = n h; the weights' centroid G = (b/2, H/2) stands over the toe at theta_0 = atan(b / H), having moved
    # by b / 2; d* = d_G sum P dx^2 / (dx_G sum P dx) with dx_i = y_i per unit rotation
    g, H = 9.81, n * h
    model = md.Model([[0.0, i * h, b, (i + 1) * h] for i in range(n)], thickness=0.5, density=1800.0, joints=_dry(),
                     gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    params = _site()
    check = sa.nonlinear_check(model, results, params, gravity=g)
    assert check.sense == -1 and close(check.hinge[0], b, 1e-9) and abs(check.hinge[1]) < 1e-9
    lam = np.tan(math.atan(b / H) - check.theta)
    y = (np.arange(n) + 0.5) * h
    e_star = y.sum() ** 2 / (n * (y**2).sum())
    assert np.allclose(check.a_star * e_star * 1.35 / g, lam, rtol=0, atol=1e-9)
    # the same from the weights directly, at any rotation
    theta = np.array([0.0, 0.05, 0.2])
    points = np.column_stack((np.full(n, b / 2), y))
    assert np.allclose(sa.alpha_of_rotation(np.ones(n), points, (b, 0.0), -1, theta),
                       np.tan(math.atan(b / H) - theta), rtol=0, atol=1e-12)
    to_star = (y**2).sum() / ((H / 2) * y.sum())
    assert close(check.theta0, math.atan(b / H), 1e-9)
    assert close(check.d0_star, b / 2 * to_star, 1e-9)
    assert close(check.du_star, 0.4 * b / 2 * to_star, 1e-9) and close(check.ds_star, 0.16 * b / 2 * to_star, 1e-9)
    # d*_s: the centroid at R (cos(beta - theta), ...) from the toe, beta = pi - atan(H / b), has moved by d*_s
    R, beta = math.hypot(b, H) / 2, math.pi - math.atan(H / b)
    theta_s = beta - math.acos(math.cos(beta) + 0.16 * b / 2 / R)
    a_s = math.tan(math.atan(b / H) - theta_s) * g / (e_star * 1.35)
    assert close(check.as_star, a_s, 1e-9)
    Ts = 2 * math.pi * math.sqrt(check.ds_star / a_s)
    assert close(check.Ts, Ts, 1e-9)
    assert close(check.demand, params.spectrum.displacement(Ts), 1e-9)
    assert close(check.ratio, check.du_star / check.demand)
    assert check.verdict == ("pass" if check.ratio >= 1 else "fail")


def test_nonlinear_check_at_height_and_refusals() -> None:
    b, h, g = 0.4, 1.2, 9.81
    model = md.Model([[0.0, 0.0, b, h]], thickness=0.5, density=1800.0, joints=_dry(), gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    params = _site(mechanism_height=6.0, building_height=9.0, storeys=3)
    check = sa.nonlinear_check(model, results, params, gravity=g)
    T1 = 0.05 * 9.0**0.75
    top = params.spectrum.displacement(T1) * (6 / 9) * (9 / 7)
    r = check.Ts / T1
    expected = top if check.Ts >= 1.5 * T1 else top * r**2 / math.sqrt((1 - r) ** 2 + 0.02 * r)
    assert close(check.demand_height, expected, 1e-12) and check.demand == max(check.demand_ground, expected)
    # wall 1's mechanism is bodies that turn and a wedge that slides on them: no hinge for some
    case = md.load_case(EXAMPLES / "ferris-tinloi-wall1.toml")
    wall = case.build_model()
    with pytest.raises(md.InputError, match="^mechanism: .*turns about no hinge.*slides"):
        sa.nonlinear_check(wall, wall.solve_limit(), params, gravity=10.0)
    # and the assessment says why it is not made
    assessed = sa.assess(wall, wall.solve_limit(), case.assessment, gravity=10.0)
    assert assessed.nonlinear is None and "slides" in assessed.nonlinear_note
    assert "nonlinear kinematic check of the mechanism: not made" in sa.assessment_table(assessed)
    # a sliding block: refused
    squat = md.Model([[0.0, 0.0, 1.0, 0.3]], joints=_dry(0.2), gravity=g)
    with pytest.raises(md.InputError, match="^mechanism: it slides"):
        sa.nonlinear_check(squat, squat.solve_limit(), params, gravity=g)


def test_linear_check_of_a_3d_leaf_overturning_out_of_plane() -> None:
    # a leaf 2.0 m x 1.05 m x 0.1 m pushed along +y (direction 90) overturns as one about its base edge:
    # alpha0 = t / H; every box moves by dx_i = z_i (its centroid's height) per unit rotation
    boxes = md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175)
    model = md.Model3D(boxes, joints={"default": md.dry_joint(0.7, dilatancy=0.7)}, direction=90)
    results = model.solve_limit(tolerance=1e-11)
    check = sa.linear_check(model, results, _site())
    P = np.asarray(model.weights)[: model.n_blocks]
    z = 0.5 * (np.asarray(boxes)[:, 2] + np.asarray(boxes)[:, 5])
    e_star = (P @ z) ** 2 / (P.sum() * (P @ z**2))
    assert check.moving_blocks == model.n_blocks
    assert close(check.alpha0, 0.1 / 1.05, 1e-9)
    assert close(check.mass_fraction, e_star, 1e-9)
    assert close(check.a0_star, 0.1 / 1.05 * model.gravity / (e_star * 1.35), 1e-9)


def _facade_with_return(t: float, h: float, courses: int, facade: float, dragged: float, far: float,
                         gap: float) -> np.ndarray:
    """An L of boxes t thick and h high per course: a facade along x (y in [0, t], x in [0, facade]) and a return
    wall along +y at x in [0, t], bonded at the corner: in the odd courses the facade's box runs over the corner and
    the return's starts behind it (y from t), in the even ones (the lowest among them) the return's box runs over the
    corner (y from 0) and the facade's starts beside it (x from t). The return reaches y = dragged, then an open
    vertical crack ``gap`` wide, then its far part to y = far. Per course: the facade's box, the return's near box,
    its far box."""
    boxes = []
    for k in range(courses):
        z0, z1 = k * h, (k + 1) * h
        if k % 2:
            boxes += [[0.0, 0.0, z0, facade, t, z1], [0.0, t, z0, t, dragged, z1]]
        else:
            boxes += [[t, 0.0, z0, facade, t, z1], [0.0, 0.0, z0, t, dragged, z1]]
        boxes.append([0.0, dragged + gap, z0, t, far, z1])
    return np.array(boxes)


def test_linear_check_of_a_3d_facade_overturning_with_part_of_its_return_wall() -> None:
    # the facade, pushed outwards (towards -y, direction 270), turns about its outer base edge (the x axis) and drags
    # the near part of the return wall bonded to it, up to the vertical crack: the corner's boxes of the even courses
    # sit across the facade's bed joints, and the return's near boxes of the odd courses sit on them. It is the least
    # mechanism: the facade cannot leave the corner's boxes (their bed joints with the facade's boxes would slip
    # by omega z at y = 0, where a rotation about the x axis opens nothing), nor these leave the return's boxes under
    # them (a bed joint at z = h that opens by omega y >= omega t and slips by omega z = omega h needs t >= mu h, and
    # t = 0.3 < 0.8 x 0.5); the far part, past the crack, stays (with it alpha0 would rise: its centroids are far
    # from the hinge). Turning about the hinge moves the centroid (y_i, z_i) of each moving block by omega z_i
    # horizontally and omega y_i upwards, so by virtual work (dry joints dissipate nothing) alpha0 = sum P_i y_i /
    # sum P_i z_i, and the check's dx_i = z_i (any scale).
    t, h, courses, facade, dragged, far, gap = 0.3, 0.5, 6, 2.0, 1.0, 2.0, 0.01
    density, g, mu = 1800.0, 9.81, 0.8
    boxes = _facade_with_return(t, h, courses, facade, dragged, far, gap)
    model = md.Model3D(boxes, density=density, gravity=g, direction=270,
                       joints={"default": md.dry_joint(mu, dilatancy=mu)})
    results = model.solve_limit(tolerance=1e-12)
    assert results.status == "collapse"
    # the hand calculation: the facade's box and the return's near box of each course move
    moving = [i for i in range(len(boxes)) if i % 3 != 2]
    lo, hi = boxes[moving, :3], boxes[moving, 3:]
    P = density * g * np.prod(hi - lo, axis=1)
    y, z = 0.5 * (lo[:, 1] + hi[:, 1]), 0.5 * (lo[:, 2] + hi[:, 2])
    # per course the two boxes weigh rho g t h (facade + dragged - t) together
    assert np.allclose(P[0::2] + P[1::2], density * g * t * h * (facade + dragged - t), rtol=1e-14)
    alpha0 = (P @ y) / (P @ z)
    M_star = (P @ z) ** 2 / (g * (P @ z**2))
    e_star = g * M_star / P.sum()
    site = _site(q=2.0, confidence_factor=1.35)
    a0_star = alpha0 * g / (e_star * 1.35)
    demand = 0.25 * G * 1.2 / 2.0  # a_g S / q, EC8 type 1 ground B
    # limit analysis returns this mechanism: the moving blocks, each turning with the rotation vector (w, 0, 0), w > 0
    # (the top goes to -y), about the hinge (y, z) = (0, 0): v = w (0, -z, y) at its centroid
    mech = np.asarray(results.mechanism)[: len(boxes)]
    w = mech[moving[0], 3]
    assert w > 0
    at_rest = [i for i in range(len(boxes)) if i not in moving]
    assert np.abs(mech[at_rest]).max() < 1e-6 * w
    rigid = w * np.stack([0 * y, -z, y, np.ones_like(y), 0 * y, 0 * y], axis=1)
    assert np.abs(mech[moving] - rigid).max() < 1e-6 * w
    check = sa.linear_check(model, results, site)
    assert check.moving_blocks == len(moving) == 12
    assert close(check.alpha0, alpha0, 1e-9)
    assert close(check.participating_mass, M_star, 1e-9)
    assert close(check.mass_fraction, e_star, 1e-9)
    assert close(check.a0_star, a0_star, 1e-9)
    assert close(check.demand, demand) and close(check.ratio, a0_star / demand, 1e-9)
    assert check.verdict == "pass" and a0_star / demand > 1.05
    # a stronger site fails it: a_g = 0.35 g
    stronger = sa.linear_check(model, results, sa.AssessmentParameters(spectrum=sa.ec8_spectrum(0.35 * G, "B")))
    assert close(stronger.ratio, a0_star / (0.35 * G * 1.2 / 2.0), 1e-9)
    assert stronger.verdict == "fail" and a0_star / (0.35 * G * 1.2 / 2.0) < 0.95


# -- the nonlinear check of several bodies, the 2019 rule at height, N2 in 3D -------------------------------------------

def _turned(r: np.ndarray, phi: float) -> np.ndarray:
    """r turned clockwise by phi, and its derivative in phi: R(-phi) r, d/dphi R(-phi) r."""
    c, s = math.cos(phi), math.sin(phi)
    return (np.array([r[0] * c + r[1] * s, -r[0] * s + r[1] * c]),
            np.array([-r[0] * s + r[1] * c, -r[0] * c - r[1] * s]))


def _bisect(f: Callable[[float], float], lo: float, hi: float) -> float:
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if f(mid) > 0 else (lo, mid)
    return 0.5 * (lo + hi)


def test_nonlinear_check_of_a_two_body_chain() -> None:
    # two blocks b x h1 and b x h2 stacked; the lower turns clockwise about its toe p0 = (b, 0), the upper about the
    # joint's right corner p1 = (b, h1) on it, rho = 1.5 times as fast (the joint opens at its left). At a rotation phi
    # of the lower block: c1 = p0 + R(-phi) (c1 - p0), p1 moves to p0 + R(-phi) (p1 - p0), c2 = p1(phi) +
    # R(-rho phi) (c2 - p1); virtual work with the forces alpha P_i: alpha = sum P_i y_i' / sum P_i x_i'.
    b, h1, h2, g, rho = 0.4, 0.8, 0.6, 9.81, 1.5
    model = md.Model([[0.0, 0.0, b, h1], [0.0, h1, b, h1 + h2]], thickness=0.5, density=1800.0, joints=_dry(),
                     gravity=g)
    p0, p1 = np.array([b, 0.0]), np.array([b, h1])
    c1, c2 = np.array([b / 2, h1 / 2]), np.array([b / 2, h1 + h2 / 2])
    P = np.array([b * h1, b * h2]) * 0.5 * 1800.0 * g

    def velocity(w: float, about: np.ndarray, x: np.ndarray) -> np.ndarray:  # w k x (x - about)
        return w * np.array([-(x[1] - about[1]), x[0] - about[0]])

    mech = np.zeros((len(model.weights), 3))
    mech[0] = [*velocity(-1.0, p0, c1), -1.0]
    mech[1] = [*(velocity(-1.0, p0, p1) + velocity(-rho, p1, c2)), -rho]

    class TwoBodies:  # the mechanism as limit analysis would give it (a collapse multiplier: alpha at rest)
        status, collapse_multiplier, mechanism = "collapse", 0.2, mech

    def state(phi: float) -> Any:
        """(x, y, x', y') of the two centroids at phi."""
        q1, dq1 = _turned(c1 - p0, phi)
        j, dj = _turned(p1 - p0, phi)
        q2, dq2 = _turned(c2 - p1, rho * phi)
        x = np.array([p0 + q1, p0 + j + q2])
        v = np.array([dq1, dj + rho * dq2])
        return x, v

    def alpha(phi: float) -> float:
        _, v = state(phi)
        return float(P @ v[:, 1] / (P @ v[:, 0]))

    params = _site()
    check = sa.nonlinear_check(model, TwoBodies(), params, gravity=g)
    assert check.bodies == 2 and check.sense == -1
    assert np.allclose(check.hinges, [p0, p1], rtol=0, atol=1e-12)
    # the curve: the parameter is the fastest body's rotation, rho phi
    phi = check.theta / rho
    _, v0 = state(0.0)
    dx = v0[:, 0]
    e_star = (P @ dx) ** 2 / (P.sum() * (P @ dx**2))
    assert np.allclose(check.a_star, [alpha(f) * g / (e_star * 1.35) for f in phi], rtol=0, atol=1e-9)
    phi0 = _bisect(alpha, 0.0, 0.5)
    assert alpha(0.5) < 0 < alpha(0.0) and close(check.theta0, rho * phi0, 1e-9)
    x_rest = P @ state(0.0)[0][:, 0] / P.sum()
    to_star = (P @ dx**2) / ((P @ dx / P.sum()) * (P @ dx))

    def d_star(f: float) -> float:  # d* = d_G sum P dx^2 / (dx_G sum P dx), G the weights' centroid
        return float((P @ state(f)[0][:, 0] / P.sum() - x_rest) * to_star)

    d0 = d_star(phi0)
    assert close(check.d0_star, d0, 1e-9) and close(check.du_star, 0.4 * d0, 1e-9)
    ds = 0.16 * d0
    phi_s = _bisect(lambda f: ds - d_star(f), 0.0, phi0)
    a_s = alpha(phi_s) * g / (e_star * 1.35)
    Ts = 2 * math.pi * math.sqrt(ds / a_s)
    assert close(check.ds_star, ds, 1e-9) and close(check.as_star, a_s, 1e-9) and close(check.Ts, Ts, 1e-9)
    assert close(check.demand, params.spectrum.displacement(Ts), 1e-9)
    assert check.verdict == ("pass" if 0.4 * d0 >= check.demand else "fail")
    # the same mechanism turned as one body is the column about its toe: the one-body closed form
    mech[1] = [*velocity(-1.0, p0, c2), -1.0]
    one = sa.nonlinear_check(model, TwoBodies(), params, gravity=g)
    assert one.bodies == 1
    H_G = (P @ np.array([c1[1], c2[1]])) / P.sum()
    assert close(one.theta0, math.atan((b / 2) / H_G), 1e-9)


def test_nonlinear_check_refuses_a_closed_chain() -> None:
    # two piers rocking about their toes and a lintel on them that translates, hinged to both: four hinges for three
    # bodies (a portal's sway), a loop that the check does not follow
    b, h = 0.3, 1.0
    model = md.Model([[0.0, 0.0, b, h], [b, 0.0, 2 * b, h], [0.0, h, 2 * b, h + 0.2]], joints=_dry(), gravity=9.81)
    mech = np.zeros((len(model.weights), 3))
    mech[0] = [h / 2, b / 2, -1.0]  # about (b, 0): -J (c - p) with c - p = (-b / 2, h / 2)
    mech[1] = [h / 2, b / 2, -1.0]  # about (2b, 0)
    mech[2] = [h, 0.0, 0.0]  # the lintel moves as the piers' tops do

    class Portal:
        status, collapse_multiplier, mechanism = "collapse", 0.2, mech

    with pytest.raises(md.InputError, match="^mechanism: its 3 bodies are held by 4 hinges"):
        sa.nonlinear_check(model, Portal(), _site(), gravity=9.81)


def test_mechanism_at_height_circolare_2019() -> None:
    # the 2019 Circolare (C8.7.1.2.1.7 with C7.2.7, C7.2.8, C7.2.10, C7.3.2): the demand is a_Z / q with
    # a_Z = S_e(T1, xi_1) gamma psi sqrt(1 + 0.0004 xi_1^2), xi_1 in percent, the ground's spectrum at xi_1
    b, h, g = 0.4, 1.2, 9.81
    model = md.Model([[0.0, 0.0, b, h]], thickness=0.5, density=1800.0, joints=_dry(), gravity=g)
    results = model.solve_limit(tolerance=1e-11)
    spectrum = sa.ec8_spectrum(0.25 * G, "B")
    T1 = 0.05 * 9.0**0.75
    assert 0.15 < T1 < 0.5  # on the plateau of type 1 ground B: S_e = a_g S eta 2.5
    for xi in (0.05, 0.10):
        check = sa.linear_check(model, results, spectrum, mechanism_height=6.0, building_height=9.0, storeys=3,
                                gravity=g, height_rule="circ2019", building_damping=xi)
        eta = max(math.sqrt(10 / (5 + 100 * xi)), 0.55)
        a_Z = 0.25 * G * 1.2 * eta * 2.5 * (9 / 7) * (6 / 9) * math.sqrt(1 + 0.0004 * (100 * xi) ** 2)
        assert close(check.floor_acceleration, a_Z) and close(check.demand_height, a_Z / 2.0)
        assert check.height_rule == "circ2019" and check.demand == max(check.demand_ground, check.demand_height)
    # at 5% the two rules differ by sqrt(1.01) alone
    old = sa.linear_check(model, results, spectrum, mechanism_height=6.0, building_height=9.0, storeys=3, gravity=g)
    new = sa.linear_check(model, results, spectrum, mechanism_height=6.0, building_height=9.0, storeys=3, gravity=g,
                          height_rule="circ2019")
    assert close(new.demand_height, old.demand_height * math.sqrt(1.01)) and math.isnan(old.floor_acceleration)
    # a period given (from a model of the building) in place of 0.05 H^(3/4): T1 = 0.8 s, on the 1 / T branch
    given = sa.linear_check(model, results, spectrum, mechanism_height=6.0, building_height=9.0, storeys=3, gravity=g,
                            height_rule="circ2019", T1=0.8)
    a_Z = 0.25 * G * 1.2 * 2.5 * 0.5 / 0.8 * (9 / 7) * (6 / 9) * math.sqrt(1.01)
    assert close(given.T1, 0.8) and close(given.demand_height, a_Z / 2.0)
    # the table names the 2019 clauses; the nonlinear check at height under the 2019 rule is not made, and says so
    params = sa.AssessmentParameters(spectrum=spectrum, mechanism_height=6.0, building_height=9.0, storeys=3,
                                     height_rule="circ2019")
    assessed = sa.assess(model, results, params, gravity=g)
    table = sa.assessment_table(assessed)
    assert "C7.2.7, C7.2.8" in table and "C8.7.1.2.1.7" in table and "eq. C7.3.2" in table
    assert assessed.nonlinear is None and "2019" in assessed.nonlinear_note
    # a spectrum from a file is at its own damping
    file_spectrum = sa.tabulated_spectrum([0.0, 0.5, 4.0], [3.0, 7.5, 1.0])
    with pytest.raises(md.InputError, match="^building_damping: "):
        sa.AssessmentParameters(spectrum=file_spectrum, mechanism_height=6.0, building_height=9.0, storeys=3,
                                height_rule="circ2019", building_damping=0.1)
    with pytest.raises(md.InputError, match="^height_rule: "):
        sa.AssessmentParameters(spectrum=spectrum, height_rule="circ2008")


def test_n2_of_a_3d_pushover() -> None:
    # two boxes stacked, pushed along y by the explicit solver: every number of N2 again from the results
    boxes = [[0.0, 0.0, 0.0, 0.4, 0.1, 0.25], [0.0, 0.0, 0.25, 0.4, 0.1, 0.5]]
    model = md.Model3D(boxes, joints={"default": md.dry_joint(0.7, dilatancy=0.7)}, direction=90)
    results = model.solve_dynamic(threads=1)
    spectrum = sa.ec8_spectrum(0.25 * G, "B")
    check = sa.pushover_n2(model, results, spectrum)
    g = model.gravity
    W = np.asarray(model.weights)
    u = np.asarray(results.displacements)[:, 1]  # along y, the live load's direction
    c = results.control_block
    blocks = [i for i in range(len(W)) if W[i] > 0]
    assert len(blocks) == 2 and u[c] > 0
    m = [W[i] / g for i in blocks]
    phi = [u[i] / u[c] for i in blocks]
    m_star = sum(mi * p for mi, p in zip(m, phi))
    gamma = m_star / sum(mi * p * p for mi, p in zip(m, phi))
    d_n = list(results.curve_displacement)
    F_b = [lam * sum(W) for lam in results.curve_multiplier]
    k = max(range(len(F_b)), key=lambda j: (F_b[j], -j))
    F_y, d_m = F_b[k] / gamma, d_n[k] / gamma
    E_m = sum((F_b[j] + F_b[j - 1]) / 2 / gamma * (d_n[j] - d_n[j - 1]) / gamma for j in range(1, k + 1))
    d_y = 2 * (d_m - E_m / F_y)
    T = 2 * math.pi * math.sqrt(m_star * d_y / F_y)
    Se = spectrum.acceleration(T)
    d_et = Se * (T / (2 * math.pi)) ** 2
    q_u = Se * m_star / F_y
    if T >= spectrum.TC or F_y / m_star >= Se:
        d_t = d_et
    else:
        d_t = min(max(d_et / q_u * (1 + (q_u - 1) * spectrum.TC / T), d_et), 3 * d_et)
    for name, value in dict(gamma=gamma, m_star=m_star, F_y=F_y, d_m=d_m, d_y=d_y, T_star=T, Se=Se, d_et=d_et,
                            q_u=q_u, d_t_star=d_t, d_t=gamma * d_t).items():
        assert close(getattr(check, name), value, 1e-9), name
    assert close(check.E_m, E_m, 1e-9)
    d_u = d_n[-1] if min(F_b[k:]) > 0.8 * F_b[k] else check.d_u
    assert close(check.d_u, d_u) and check.verdict == ("pass" if gamma * d_t <= d_u else "fail")
    # assess makes it on a 3D pushover; a load along neither axis is refused by name
    assert sa.assess(model, results, sa.AssessmentParameters(spectrum=spectrum)).n2 is not None
    oblique = md.Model3D(boxes, joints={"default": md.dry_joint(0.7, dilatancy=0.7)}, direction=45)
    with pytest.raises(md.InputError, match="^direction: "):
        sa.pushover_n2(oblique, results, spectrum)
