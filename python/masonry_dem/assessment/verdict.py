"""An analysis's seismic assessment: the checks that apply to its results (:func:`assess`), the result file's
``assessment`` object (:func:`assessment_dict`) and the plain-text table of a calculation report
(:func:`assessment_table`: each quantity with its value, its unit and the clause it comes from).

The linear kinematic check applies to a collapse with a mechanism (limit analysis, or a static or explicit
collapse); the nonlinear kinematic check to a mechanism of rigid bodies turning about hinges (on the ground or on
one another, without a closed loop) in a wall in the plane; the N2 method to a pushover's capacity curve (a static or
explicit analysis of a wall in the plane, or the explicit solver's of a 3D wall pushed along x or y).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, Dict, List, Optional, Tuple

from .._core import InputError
from ..case.result_file import json_float
from ..units import STANDARD_GRAVITY
from .kinematic import LinearCheck, MechanismWeights, linear_check_of, mechanism_weights
from .nonlinear import NonlinearCheck, nonlinear_check
from .pushover import N2Check, pushover_n2
from .parameters import AssessmentParameters

#: The texts the checks follow, as the table names them.
CIRCOLARE_2009 = "Circ. 617/2009"
CIRCOLARE_2019 = "Circ. 2019"
EC8 = "EN 1998-1"


@dataclass(frozen=True, eq=False)
class Assessment:
    """The checks of one analysis against one site.

    Attributes:
        parameters: the spectrum and the check's parameters.
        method: the analysis ("limit", "static" or "dynamic").
        mechanism: the mechanism's moving blocks, weights and virtual displacements (None without a collapse).
        linear: the linear kinematic check (None without a collapse).
        n2: the N2 method on the pushover's curve (None without one: limit analysis).
        nonlinear: the nonlinear kinematic check (None unless the mechanism is rigid bodies turning about hinges, on
            the ground or on one another, in a wall in the plane); nonlinear_note: why it is None ("" when it is
            made).
    """

    parameters: AssessmentParameters
    method: str
    mechanism: Optional[MechanismWeights]
    linear: Optional[LinearCheck]
    n2: Optional[N2Check]
    nonlinear: Optional[NonlinearCheck] = None
    nonlinear_note: str = ""

    @property
    def verdict(self) -> str:
        """"fail" if a check fails, else "pass"."""
        checks = [c for c in (self.linear, self.nonlinear, self.n2) if c is not None]
        return "fail" if any(c.verdict == "fail" for c in checks) else "pass"


def assess(model: Any, results: Any, parameters: AssessmentParameters, gravity: Optional[float] = None) -> Assessment:
    """The checks that apply to ``results`` of ``model`` (``gravity``: the model's, needed for a wall in the plane):
    the linear kinematic check of the collapse mechanism, the nonlinear one when the mechanism is rigid bodies
    turning about hinges, and the N2 method on a pushover's curve.

    Raises InputError when neither applies (no collapse and no curve), or what the checks refuse (a mechanism with
    no moving block, a spectrum without T_C for N2, ...), naming it."""
    method = str(results.method)
    mechanism = linear = None
    if str(results.status) == "collapse":
        mechanism = mechanism_weights(model, results, gravity)
        linear = linear_check_of(float(results.collapse_multiplier), mechanism.weights, mechanism.dx,
                                 mechanism.gravity, parameters)
    nonlinear, note = None, "no collapse mechanism"
    if mechanism is not None:
        try:
            nonlinear, note = nonlinear_check(model, results, parameters, gravity), ""
        except InputError as exc:  # several bodies, sliding, 3D: said in the table
            if getattr(exc, "key", None) != "mechanism":
                raise
            note = str(exc)[len("mechanism: "):]
    n2 = None
    if method != "limit" and len(results.curve_displacement) > 1:
        n2 = pushover_n2(model, results, parameters.spectrum, gravity)
    if linear is None and n2 is None:
        mechanism_weights(model, results, gravity)  # refuses, saying why there is no mechanism
    return Assessment(parameters=parameters, method=method, mechanism=mechanism, linear=linear, n2=n2,
                      nonlinear=nonlinear, nonlinear_note=note)


def _floats(data: Dict[str, Any]) -> Dict[str, Any]:
    return {k: json_float(v) if isinstance(v, float) else v for k, v in data.items()}


def assessment_dict(assessment: Assessment) -> Dict[str, Any]:
    """The result file's ``assessment`` object (docs/case-format.md, "Result file"): the linear check's quantities
    at its top (``alpha0``, ``participating_mass`` [kg], ``mass_fraction``, ``a0_star`` [m/s2], ``demand`` [m/s2],
    ``ratio``, ``verdict``, and the rest), the spectrum, and ``n2`` (or null). NaN is written as null."""
    p = assessment.parameters
    s = p.spectrum
    out: Dict[str, Any] = {"verdict": assessment.verdict, "method": assessment.method}
    if assessment.linear is not None:
        out.update(_floats(asdict(assessment.linear)))
        out["verdict"] = assessment.linear.verdict
    out.update(_floats({"mechanism_height": p.mechanism_height, "building_height": p.building_height,
                        "storeys": p.storeys, "building_damping": p.building_damping}))
    out["spectrum"] = _floats({"code": s.code, **{k: v for k, v in s.parameters.items()},
                               "peak_ground_acceleration": s.peak_ground_acceleration, "S": s.S, "eta": s.eta,
                               "F0": s.F0, "TB": s.TB, "TC": s.TC, "TD": s.TD})
    if assessment.n2 is not None:
        n2 = {k: v for k, v in asdict(assessment.n2).items() if not k.startswith("curve_")}
        out["n2"] = _floats(n2)
    else:
        out["n2"] = None
    if assessment.nonlinear is not None:
        kept = {k: v for k, v in asdict(assessment.nonlinear).items() if k not in ("theta", "d_star", "a_star")}
        kept["hinge"] = list(assessment.nonlinear.hinge)
        kept["hinges"] = [list(h) for h in assessment.nonlinear.hinges]
        out["nonlinear"] = _floats(kept)
    else:
        out["nonlinear"] = None
    return out


# -- the plain-text table ------------------------------------------------------------------------------------------

Row = Tuple[str, str, str, str]  # quantity, value, unit, clause


def _value(x: Optional[float], digits: int = 4) -> str:
    if x is None or not math.isfinite(float(x)):
        return "-"
    x = float(x)
    return f"{x:.{digits}g}" if abs(x) < 1e5 else f"{x:.{digits}e}"


def spectrum_rows(assessment: Assessment) -> List[Row]:
    """The demand spectrum's rows of the table."""
    s = assessment.parameters.spectrum
    if s.code == "file":
        return [("spectrum (a file)", str(s.parameters.get("file", "")), "", "site study"),
                ("S_e(0) = a_g S", _value(s.peak_ground_acceleration), "m/s2", "")]
    clause = f"{EC8} 3.2.2.2" if s.code == "ec8" else "NTC 2018 3.2.3.2.1"
    p = s.parameters
    rows: List[Row] = []
    if s.code == "ec8":
        rows += [("spectrum", f"type {p['spectrum_type']}, ground {p['ground_type']}", "", f"{EC8} Tables 3.2, 3.3"),
                 ("a_gR", _value(p["ag"]), "m/s2", f"{EC8} 3.2.1"),
                 ("importance factor gamma_I", _value(p["importance"]), "-", f"{EC8} 4.2.5")]
    else:
        rows += [("spectrum", f"soil {p['soil']}, topography {p['topography']}", "", "NTC 2018 Tables 3.2.IV, 3.2.V"),
                 ("F0", _value(s.F0), "-", "NTC 2018 3.2.3.2.1"), ("T*_C", _value(p["Tc_star"]), "s", "NTC 2018 3.2")]
    rows += [("a_g", f"{_value(s.ag)} ({s.ag / STANDARD_GRAVITY:.3f} g)", "m/s2", clause),
             ("S", _value(s.S), "-", clause), ("eta (damping correction)", _value(s.eta), "-", clause),
             ("T_B, T_C, T_D", f"{s.TB:.4g}, {s.TC:.4g}, {s.TD:.4g}", "s", clause)]
    return rows


def _period_row(assessment: Assessment, clause: str) -> Row:
    """The row of the building's period: given (T1), or C1 H^(3/4) by ``clause``."""
    c = assessment.linear
    assert c is not None
    if assessment.parameters.T1 is not None:
        return ("T1 (given)", _value(c.T1), "s", "the building's model")
    return ("T1 = 0.05 H^(3/4)", _value(c.T1), "s", clause)


def linear_rows(assessment: Assessment) -> List[Row]:
    """The linear kinematic check's rows of the table."""
    c = assessment.linear
    if c is None:
        return []
    q1, q2 = f"{CIRCOLARE_2009} C8A.4.1", f"{CIRCOLARE_2009} C8A.4.2.3"
    multiplier = "limit analysis" if assessment.method == "limit" else f"{assessment.method} collapse"
    rows: List[Row] = [
        ("multiplier alpha0", _value(c.alpha0), "-", f"{q1} ({multiplier})"),
        ("moving blocks", str(c.moving_blocks), "", "weights at the blocks' centroids"),
        ("weight of the moving blocks sum P_i", _value(c.weight / 1e3), "kN", q1),
        ("participating mass M*", _value(c.participating_mass), "kg", q1),
        ("mass fraction e*", _value(c.mass_fraction), "-", q1),
        ("confidence factor FC", _value(c.confidence_factor), "-", "knowledge level"),
        ("a0* = alpha0 g / (e* FC)", f"{_value(c.a0_star)} ({c.a0_star / STANDARD_GRAVITY:.4f} g)", "m/s2", q1),
        ("behaviour factor q", _value(c.q), "-", q2),
        ("demand at ground level a_g S / q", _value(c.demand_ground), "m/s2", q2),
    ]
    if math.isfinite(c.demand_height) and c.height_rule == "circ2019":
        p = assessment.parameters
        r = f"{CIRCOLARE_2019} C8.7.1.2.1.7"
        rows += [("mechanism height Z, building H, storeys N", f"{p.mechanism_height:g}, {p.building_height:g}, "
                  f"{p.storeys}", "m, m, -", r),
                 _period_row(assessment, f"{CIRCOLARE_2019} eq. C7.3.2"),
                 ("psi(Z) = Z / H, gamma = 3N / (2N + 1)", f"{c.psi:.4g}, {c.gamma:.4g}", "-",
                  f"{CIRCOLARE_2019} C7.2.3, eq. C7.2.10"),
                 ("building's damping xi_1", _value(100.0 * p.building_damping), "%", f"{CIRCOLARE_2019} C7.2.3"),
                 ("floor acceleration a_Z = S_e(T1, xi_1) gamma psi sqrt(1 + 0.0004 xi_1^2)",
                  _value(c.floor_acceleration), "m/s2", f"{CIRCOLARE_2019} eqs. C7.2.7, C7.2.8"),
                 ("demand at height a_Z / q", _value(c.demand_height), "m/s2", r)]
    elif math.isfinite(c.demand_height):
        p = assessment.parameters
        rows += [("mechanism height Z, building H, storeys N", f"{p.mechanism_height:g}, {p.building_height:g}, "
                  f"{p.storeys}", "m, m, -", q2),
                 _period_row(assessment, "NTC 2008 7.3.3.2"),
                 ("psi(Z) = Z / H, gamma = 3N / (2N + 1)", f"{c.psi:.4g}, {c.gamma:.4g}", "-", q2),
                 ("demand at height S_e(T1) psi gamma / q", _value(c.demand_height), "m/s2", q2)]
    rows += [("demand", _value(c.demand), "m/s2", q2),
             ("ratio a0* / demand", _value(c.ratio), "-", q2),
             ("verdict", c.verdict, "", q2)]
    return rows


def nonlinear_rows(assessment: Assessment) -> List[Row]:
    """The nonlinear kinematic check's rows of the table (none when it is not made: the table says why)."""
    c = assessment.nonlinear
    if c is None:
        return []
    q = f"{CIRCOLARE_2009} C8A.4.2"
    rows: List[Row] = [
        ("hinge (x, y)", f"{c.hinge[0]:.4g}, {c.hinge[1]:.4g}", "m",
         "one rigid body" if c.bodies == 1 else f"the first of {c.bodies} bodies"),
        ("rotation to alpha = 0, theta_0", _value(c.theta0), "rad", f"{q}.1 (finite rotation)"),
        ("d*_0", _value(c.d0_star), "m", f"{q}.1"),
        ("d*_u = 0.4 d*_0", _value(c.du_star), "m", f"{q}.2"),
        ("d*_s = 0.4 d*_u, a*_s", f"{_value(c.ds_star)} m, {_value(c.as_star)} m/s2", "", f"{q}.3"),
        ("secant period T_s", _value(c.Ts), "s", f"{q}.3"),
        ("demand at ground level S_De(T_s)", _value(c.demand_ground), "m", f"{q}.3"),
    ]
    if math.isfinite(c.demand_height):
        rows.append(("demand at height", _value(c.demand_height), "m", f"{q}.3"))
    rows += [("ratio d*_u / demand", _value(c.ratio), "-", f"{q}.3"), ("verdict", c.verdict, "", f"{q}.3")]
    return rows


def n2_rows(assessment: Assessment) -> List[Row]:
    """The N2 method's rows of the table."""
    c = assessment.n2
    if c is None:
        return []
    b = f"{EC8} Annex B"
    return [
        ("transformation factor Gamma", _value(c.gamma), "-", f"{b}, B.2"),
        ("m* = sum m_i Phi_i", _value(c.m_star), "kg", f"{b}, B.2"),
        ("F*_y (peak of F* = F_b / Gamma)", _value(c.F_y / 1e3), "kN", f"{b}, B.3"),
        ("d*_m, E*_m", f"{_value(c.d_m)} m, {_value(c.E_m)} J", "", f"{b}, B.3"),
        ("d*_y = 2 (d*_m - E*_m / F*_y)", _value(c.d_y), "m", f"{b}, B.3"),
        ("T* = 2 pi sqrt(m* d*_y / F*_y)", _value(c.T_star), "s", f"{b}, B.4"),
        ("S_e(T*)", _value(c.Se), "m/s2", f"{EC8} 3.2.2.2"),
        ("d*_et = S_e(T*) (T* / 2 pi)^2", _value(c.d_et), "m", f"{b}, B.5"),
        ("q_u = S_e(T*) m* / F*_y", _value(c.q_u), "-", f"{b}, B.5"),
        ("branch", c.branch + (", capped at 3 d*_et" if c.capped else ""), "", f"{b}, B.5"),
        ("d*_t", _value(c.d_t_star), "m", f"{b}, B.5"),
        ("target displacement d_t = Gamma d*_t", _value(c.d_t), "m", f"{b}, B.6"),
        ("ultimate displacement d_u (the curve's)", _value(c.d_u), "m", "80% of the peak, or the curve's end"),
        ("ratio d_u / d_t", _value(c.ratio), "-", ""),
        ("verdict", c.verdict, "", ""),
    ]


def assessment_table(assessment: Assessment, title: str = "") -> str:
    """The plain-text table of the assessment (quantity, value, unit, clause), to paste in a calculation report."""
    sections = [("demand spectrum", spectrum_rows(assessment)),
                ("linear kinematic check of the mechanism", linear_rows(assessment)),
                ("nonlinear kinematic check of the mechanism", nonlinear_rows(assessment)),
                ("N2 method on the capacity curve", n2_rows(assessment))]
    rows = [r for _, rs in sections for r in rs] + [("quantity", "value", "unit", "clause")]
    widths = [max(len(r[k]) for r in rows) for k in range(3)]
    lines = [f"Seismic assessment{': ' + title if title else ''} (verdict: {assessment.verdict})"]
    for name, section in sections:
        if not section:
            if section is sections[2][1] and assessment.mechanism is not None:
                lines.append(f"  {name}: not made ({assessment.nonlinear_note})")
            continue
        lines.append(f"  {name}")
        lines.append("    " + "  ".join(h.ljust(w) for h, w in zip(("quantity", "value", "unit"), widths)) + "  clause")
        for r in section:
            lines.append(("    " + "  ".join(v.ljust(w) for v, w in zip(r[:3], widths)) + "  " + r[3]).rstrip())
    return "\n".join(lines)
