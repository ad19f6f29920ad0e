"""The N2 method of EN 1998-1 Annex B: a pushover's capacity curve turned into a target displacement and checked
against the curve's ultimate displacement (:func:`n2`, the curve given directly; :func:`pushover_n2`, from a static or
explicit pushover's :class:`masonry_dem.Results` of a wall in the plane, or an explicit pushover of a 3D wall).

Steps (Annex B): the transformation factor Gamma = m* / sum m_i Phi_i^2 with m* = sum m_i Phi_i, the displaced shape
Phi normalised to 1 at the control point (B.2); the equivalent single degree of freedom F* = F_b / Gamma,
d* = d_n / Gamma (B.2); its elastic-perfectly plastic idealisation by equal energy, F*_y the peak of F*, d*_m the
displacement at the peak, E*_m the energy up to it, d*_y = 2 (d*_m - E*_m / F*_y) (B.3); the period
T* = 2 pi sqrt(m* d*_y / F*_y) (B.4); the target displacement (B.5): d*_et = S_e(T*) (T* / 2 pi)^2, and d*_t = d*_et
for T* >= T_C, or for T* < T_C with F*_y / m* >= S_e(T*); otherwise d*_t = d*_et / q_u (1 + (q_u - 1) T_C / T*)
>= d*_et with q_u = S_e(T*) m* / F*_y; never more than 3 d*_et (B.5's note); d_t = Gamma d*_t (B.6).

The ultimate displacement d_u is the curve's: where, after the peak, the base shear falls to 80% of it (the
convention of the Italian code for masonry buildings), else the curve's last point. The check is d_t <= d_u.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from .spectra import Spectrum, _refuse

#: The fraction of the peak base shear at which the curve's ultimate displacement is read, after the peak.
ULTIMATE_DROP = 0.8
#: EN 1998-1 B.5: the target displacement need not exceed this many times the elastic one.
TARGET_CAP = 3.0
#: A 3D live load is along an axis when the sine of its angle to it is below this.
AXIS_TOLERANCE = 1e-9


@dataclass(frozen=True)
class N2Check:
    """The N2 method's quantities (EN 1998-1 Annex B); starred ones are of the equivalent single degree of freedom.

    Attributes:
        gamma: Gamma, the transformation factor (B.2).
        m_star: m* [kg] (B.2).
        F_y: F*_y [N], the idealised system's yield force (the peak of F*) (B.3).
        d_m: d*_m [m], the displacement at the peak; E_m: E*_m [J], the energy up to it (B.3).
        d_y: d*_y [m], the yield displacement (B.3).
        T_star: T* [s] (B.4).
        Se: S_e(T*) [m/s2]; TC: the spectrum's T_C [s].
        d_et: d*_et [m], the elastic target displacement (B.5).
        q_u: S_e(T*) m* / F*_y (B.5; it decides the short-period branch).
        branch: "long period" (T* >= T_C), "short period, elastic" (F*_y / m* >= S_e(T*)) or
            "short period, inelastic".
        d_t_star: d*_t [m], after the bound d*_t >= d*_et (inelastic branch) and the cap 3 d*_et; capped: whether
            the cap applied.
        d_t: d_t = Gamma d*_t [m], the target displacement of the control point (B.6).
        d_u: the curve's ultimate displacement of the control point [m].
        ratio: d_u / d_t (capacity over demand); verdict: "pass" when d_t <= d_u, else "fail".
        curve_displacement, curve_force: the capacity curve as given, d_n [m] and F_b [N] (for the plots).
    """

    gamma: float
    m_star: float
    F_y: float
    d_m: float
    E_m: float
    d_y: float
    T_star: float
    Se: float
    TC: float
    d_et: float
    q_u: float
    branch: str
    d_t_star: float
    capped: bool
    d_t: float
    d_u: float
    ratio: float
    verdict: str
    curve_displacement: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    curve_force: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)


def ultimate_displacement(displacement: Any, force: Any) -> float:
    """The curve's ultimate displacement [m]: where the force first falls to :data:`ULTIMATE_DROP` of its peak after
    the peak (linear between points), else the last point's displacement."""
    d = np.asarray(displacement, dtype=np.float64)
    f = np.asarray(force, dtype=np.float64)
    peak = int(np.argmax(f))
    limit = ULTIMATE_DROP * f[peak]
    below = np.nonzero(f[peak:] <= limit)[0]
    if not len(below):
        return float(d[-1])
    k = peak + int(below[0])
    t = (f[k - 1] - limit) / (f[k - 1] - f[k])
    return float(d[k - 1] + t * (d[k] - d[k - 1]))


def n2(displacement: Any, force: Any, masses: Any, shape: Any, spectrum: Spectrum) -> N2Check:
    """The N2 method on a capacity curve given directly.

    Args:
        displacement: (k,) the control point's displacement d_n [m], from 0, along the curve.
        force: (k,) the base shear F_b [N] at those points.
        masses: (n,) the masses m_i [kg] that take the lateral forces.
        shape: (n,) their displaced shape Phi_i, normalised to 1 at the control point.
        spectrum: the elastic spectrum (its T_C: a tabulated spectrum needs one given).
    Raises:
        masonry_dem.InputError: a curve of fewer than two points or without a positive peak, masses and shape of
            different lengths, a shape with sum m_i Phi_i <= 0, a spectrum without T_C.
    """
    d = np.asarray(displacement, dtype=np.float64).reshape(-1)
    f = np.asarray(force, dtype=np.float64).reshape(-1)
    m = np.asarray(masses, dtype=np.float64).reshape(-1)
    phi = np.asarray(shape, dtype=np.float64).reshape(-1)
    if len(d) != len(f) or len(d) < 2 or not (np.all(np.isfinite(d)) and np.all(np.isfinite(f))):
        raise _refuse("curve", f"expected at least 2 finite points of displacement and force, got {len(d)} and "
                               f"{len(f)}")
    if not np.max(f) > 0:
        raise _refuse("curve", "the base shear never rises above 0")
    if len(m) != len(phi) or not len(m):
        raise _refuse("shape", f"expected one value per mass, got {len(phi)} for {len(m)} masses")
    m_star = float(m @ phi)
    if not (math.isfinite(m_star) and m_star > 0):
        raise _refuse("shape", f"sum m_i Phi_i must be > 0, got {m_star:g}")
    TC = spectrum.TC
    if not math.isfinite(TC):
        raise _refuse("Tc", "the N2 method's short-period rule needs the spectrum's corner period T_C: give it with "
                            "the tabulated spectrum")
    gamma = m_star / float(m @ (phi * phi))
    ds, fs = d / gamma, f / gamma
    peak = int(np.argmax(fs))
    F_y, d_m = float(fs[peak]), float(ds[peak])
    E_m = float(np.sum(0.5 * (fs[1:peak + 1] + fs[:peak]) * np.diff(ds[:peak + 1])))
    d_y = 2.0 * (d_m - E_m / F_y)
    if not d_y > 0:
        raise _refuse("curve", f"its equal-energy yield displacement d*_y = {d_y:g} m is not positive")
    T_star = 2.0 * math.pi * math.sqrt(m_star * d_y / F_y)
    Se = float(spectrum.acceleration(T_star))
    d_et = Se * (T_star / (2.0 * math.pi)) ** 2
    q_u = Se * m_star / F_y
    if T_star >= TC:
        branch, d_t = "long period", d_et
    elif F_y / m_star >= Se:
        branch, d_t = "short period, elastic", d_et
    else:
        branch, d_t = "short period, inelastic", max(d_et / q_u * (1.0 + (q_u - 1.0) * TC / T_star), d_et)
    capped = d_t > TARGET_CAP * d_et
    d_t = min(d_t, TARGET_CAP * d_et)
    target = gamma * d_t
    d_u = ultimate_displacement(d, f)
    ratio = d_u / target
    return N2Check(gamma=gamma, m_star=m_star, F_y=F_y, d_m=d_m, E_m=E_m, d_y=d_y, T_star=T_star, Se=Se, TC=TC,
                   d_et=d_et, q_u=q_u, branch=branch, d_t_star=d_t, capped=capped, d_t=target, d_u=d_u, ratio=ratio,
                   verdict="pass" if ratio >= 1.0 else "fail", curve_displacement=d, curve_force=f)


def pushover_n2(model: Any, results: Any, spectrum: Spectrum, gravity: Optional[float] = None) -> N2Check:
    """The N2 method on the capacity curve of a pushover under the live load "horizontal_weight": a static or explicit
    pushover of a wall in the plane, or the explicit solver's of a 3D wall pushed along x or y. The base shear
    F_b = lambda sum W_i against the control block's displacement along the curve's axis (x in the plane; in 3D the
    axis of the live load's direction), the masses m_i = W_i / g of the blocks, and the displaced shape Phi_i of the
    blocks' displacements along that axis at the end of the path (their centroids'), over the control block's.

    ``gravity`` [m/s2]: the model's gravity (a wall in the plane's Model does not tell it; a 3D one does). Refuses
    (InputError) a run without a curve (limit analysis), a live load other than "horizontal_weight", a 3D live load
    whose direction is not along x or y, and a control block that has not moved."""
    three_d = int(getattr(model, "dimension", 2)) == 3
    live = str(getattr(model, "live", "horizontal_weight"))
    if live != "horizontal_weight":
        raise _refuse("loads.live", f'the N2 method needs the live load "horizontal_weight", got "{live}"')
    d = np.asarray(results.curve_displacement, dtype=np.float64)
    lam = np.asarray(results.curve_multiplier, dtype=np.float64)
    if len(d) < 2:
        raise _refuse("method", f"the N2 method needs a pushover's capacity curve; the {results.method!r} analysis "
                                "has none")
    g = getattr(model, "gravity", None) if gravity is None else gravity
    if g is None or not float(g) > 0:
        raise _refuse("gravity", "a wall in the plane's Model does not tell its gravity: give the one it was built "
                                 "with")
    weights = np.asarray(model.weights, dtype=np.float64)
    axis, sign = 0, 1.0
    if three_d:
        angle = math.radians(float(getattr(model, "direction", 0.0) or 0.0))
        c, s = math.cos(angle), math.sin(angle)
        axis = 0 if abs(c) >= abs(s) else 1  # the axis the explicit solver's curve follows
        if abs(s if axis == 0 else c) > AXIS_TOLERANCE:
            raise _refuse("direction", f"the N2 method in 3D takes a live load along x or y (the axis of the "
                                       f"pushover's curve), got a direction of {math.degrees(angle):g} degrees")
        sign = 1.0 if (c if axis == 0 else s) > 0 else -1.0
    u = sign * np.asarray(results.displacements, dtype=np.float64)[:, axis]
    control = int(results.control_block)
    if not u[control] != 0:
        raise _refuse("curve", "the control block has not moved: no displaced shape")
    keep = weights > 0
    return n2(sign * d, lam * float(weights.sum()), weights[keep] / float(g), u[keep] / u[control], spectrum)
