"""The nonlinear kinematic check (Circolare 617/2009 C8A.4.2) of a mechanism of one rigid body turning about a hinge:
a single block, or blocks that move as one (a column about the toe of its base), in a wall in the plane.

The body's weights P_i (at the blocks' centroids) are turned about the hinge H by a finite rotation theta, and the
multiplier that holds it there follows from virtual work at that position: with the horizontal forces alpha P_i,
alpha(theta) = -sum P_i (x_i(theta) - H_x) / sum P_i (y_i(theta) - H_y) (the hinge kept, no other contact made or
lost). For a block of base b and height h about its toe this is tan(atan(b / h) - theta). The curve goes to zero at
theta_0, where the weights' centroid G stands over the hinge.

The equivalent system (C8A.4.2.1), the control point k being G: d* = d_k sum P_i dx_i^2 / (dx_k sum P_i dx_i),
a* = alpha g / (e* FC); d*_0 where a* = 0; d*_u = 0.4 d*_0 (C8A.4.2.2); d*_s = 0.4 d*_u, a*_s the curve's a* there,
T_s = 2 pi sqrt(d*_s / a*_s) (C8A.4.2.3; the exact curve, where the Circolare allows a straight line). The check:
d*_u >= S_De(T_s) at ground level; at height Z, d*_u >= S_De(T1) psi(Z) gamma (T_s / T1)^2 / sqrt((1 - T_s / T1)^2 +
0.02 T_s / T1) for T_s < 1.5 T1, S_De(T1) psi(Z) gamma beyond, the demand being the larger of this and the
ground's.

Not covered: mechanisms of several bodies, or with sliding (their contacts would have to be followed as they move:
the geometry of each body and of the hinges between them), and walls in 3D.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional, Tuple

import numpy as np

from .._shapes import shapes
from .kinematic import mechanism_weights, participating_mass
from .parameters import AssessmentParameters
from .spectra import _refuse

#: Two blocks turn as one when their rotation rates and their instantaneous centres agree to this fraction (of the
#: largest rate, of the body's size).
RIGID_TOLERANCE = 1e-4
#: d*_u = 0.4 d*_0 and d*_s = 0.4 d*_u (Circolare 617/2009 C8A.4.2.2, C8A.4.2.3).
ULTIMATE_FRACTION = 0.4
#: Points of the capacity curve kept for the plots.
CURVE_POINTS = 101


@dataclass(frozen=True)
class NonlinearCheck:
    """The nonlinear kinematic check of a one-body mechanism (Circolare 617/2009 C8A.4.2).

    Attributes:
        hinge: (x, y) [m], the point the body turns about; sense: +1 counterclockwise, -1 clockwise.
        theta0: the rotation [rad] at which alpha falls to 0.
        d0_star: d*_0 [m]; du_star: d*_u = 0.4 d*_0 [m]; ds_star: d*_s = 0.4 d*_u [m].
        as_star: a*_s [m/s2], the curve's a* at d*_s; Ts: T_s = 2 pi sqrt(d*_s / a*_s) [s].
        demand_ground: S_De(T_s) [m]; demand_height: the demand at height [m] (NaN at ground level).
        demand: the demand [m] (at height the larger of the two); ratio: d*_u / demand; verdict.
        theta, d_star, a_star: the capacity curve, (CURVE_POINTS,) each: rotations [rad], d* [m], a* [m/s2].
    """

    hinge: Tuple[float, float]
    sense: int
    theta0: float
    d0_star: float
    du_star: float
    ds_star: float
    as_star: float
    Ts: float
    demand_ground: float
    demand_height: float
    demand: float
    ratio: float
    verdict: str
    theta: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    d_star: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    a_star: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)


def rigid_hinge(model: Any, results: Any, blocks: np.ndarray) -> Tuple[Tuple[float, float], int]:
    """The hinge (x, y) [m] and the sense (+1 counterclockwise, -1 clockwise, in the mechanism's direction that does
    positive work) of the moving ``blocks`` of a wall in the plane, when they turn as one rigid body; refuses
    (InputError "mechanism") a mechanism of several bodies, or one that slides."""
    if int(getattr(model, "dimension", 2)) == 3:
        raise _refuse("mechanism", "the nonlinear kinematic check is of a wall in the plane in this version")
    every = shapes(model)  # convex polygons: rectangles among them
    bounds = every.bounds[blocks]
    mech = np.asarray(results.mechanism, dtype=np.float64)[blocks]
    centroids = every.centroids[blocks]
    size = float(np.max(bounds[:, 2:].max(axis=0) - bounds[:, :2].min(axis=0)))
    phi = mech[:, 2]
    peak = float(np.max(np.abs(phi)))
    speed = float(np.max(np.hypot(mech[:, 0], mech[:, 1])))
    if not peak * size > RIGID_TOLERANCE * speed:
        raise _refuse("mechanism", "it slides: the nonlinear kinematic check here is of one body turning about a "
                                   "hinge")
    if np.max(np.abs(phi - phi[0])) > RIGID_TOLERANCE * peak:
        raise _refuse("mechanism", "its blocks turn at different rates (several bodies): the nonlinear kinematic "
                                   "check here is of one body turning about a hinge")
    centres = centroids + np.column_stack((-mech[:, 1], mech[:, 0])) / phi[:, None]
    if np.max(np.abs(centres - centres[0])) > RIGID_TOLERANCE * size:
        raise _refuse("mechanism", "its blocks do not turn about one point (several bodies, or sliding): the "
                                   "nonlinear kinematic check here is of one body turning about a hinge")
    hinge = centres.mean(axis=0)
    work = float(np.asarray(model.weights, dtype=np.float64)[blocks] @ mech[:, 0])
    sense = int(np.sign(phi[0])) * (1 if work >= 0 else -1)
    return (float(hinge[0]), float(hinge[1])), sense


def alpha_of_rotation(weights: Any, points: Any, hinge: Tuple[float, float], sense: int, theta: Any) -> np.ndarray:
    """alpha(theta) of weights P_i [N] at ``points`` (k, 2) [m] turned by ``theta`` [rad] about ``hinge`` in the
    ``sense`` (+1 counterclockwise, -1 clockwise): -sum P_i (x_i - H_x) / sum P_i (y_i - H_y) at the turned position
    (virtual work of the horizontal forces alpha P_i and the weights)."""
    P = np.asarray(weights, dtype=np.float64)
    r = np.asarray(points, dtype=np.float64) - np.asarray(hinge)
    t = sense * np.atleast_1d(np.asarray(theta, dtype=np.float64))[:, None]
    x = r[:, 0] * np.cos(t) - r[:, 1] * np.sin(t)
    y = r[:, 0] * np.sin(t) + r[:, 1] * np.cos(t)
    return -(x @ P) / (y @ P)  # type: ignore[no-any-return]


def nonlinear_demand(parameters: AssessmentParameters, Ts: float) -> Tuple[float, float]:
    """(at ground level, at height) of the nonlinear check's displacement demand [m] at the secant period ``Ts`` [s]
    (Circolare 617/2009 C8A.4.2.3; NaN at height for a mechanism at ground level)."""
    spectrum = parameters.spectrum
    ground = float(spectrum.displacement(Ts))
    if not parameters.at_height:
        return ground, math.nan
    T1 = parameters.building_period()
    top = float(spectrum.displacement(T1)) * parameters.modal_shape() * parameters.participation()
    if Ts >= 1.5 * T1:
        return ground, top
    ratio = Ts / T1
    return ground, top * ratio**2 / math.sqrt((1.0 - ratio) ** 2 + 0.02 * ratio)


def nonlinear_check(model: Any, results: Any, parameters: AssessmentParameters,
                    gravity: Optional[float] = None) -> NonlinearCheck:
    """The nonlinear kinematic check of the collapse mechanism of ``results``, one rigid body turning about a hinge
    (a wall in the plane; ``gravity`` [m/s2] the model's). Refuses (InputError "mechanism") a mechanism of several
    bodies or one that slides, and what :func:`masonry_dem.assessment.mechanism_weights` refuses."""
    lumped = mechanism_weights(model, results, gravity)
    hinge, sense = rigid_hinge(model, results, lumped.blocks)
    P, points, g = lumped.weights, lumped.points[:, :2], lumped.gravity
    r = points - np.asarray(hinge)
    G = (P @ r) / P.sum()  # the weights' centroid from the hinge
    theta0 = sense * (math.pi / 2 - math.atan2(G[1], G[0]))  # G over the hinge: its angle turned to pi / 2
    if not (G[1] > 0 and theta0 > 0):
        raise _refuse("mechanism", "the body's weights are not above its hinge on the side the mechanism turns from")
    dx = -sense * r[:, 1]  # the virtual horizontal displacements per unit rotation
    dx_k = -sense * G[1]
    _, e_star = participating_mass(P, dx, g)
    to_star = float(P @ (dx * dx)) / (dx_k * float(P @ dx))
    fc = parameters.confidence_factor

    def d_star(theta: np.ndarray) -> np.ndarray:
        t = sense * theta
        return (G[0] * np.cos(t) - G[1] * np.sin(t) - G[0]) * to_star  # type: ignore[no-any-return]

    theta = np.linspace(0.0, theta0, CURVE_POINTS)
    a_star = alpha_of_rotation(P, points, hinge, sense, theta) * g / (e_star * fc)
    d0 = float(d_star(np.array([theta0]))[0])
    du = ULTIMATE_FRACTION * d0
    ds = ULTIMATE_FRACTION * du
    lo, hi = 0.0, theta0  # d*(theta) rises from 0 to d*_0 while G turns over the hinge
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if float(d_star(np.array([mid]))[0]) < ds:
            lo = mid
        else:
            hi = mid
    theta_s = 0.5 * (lo + hi)
    a_s = float(alpha_of_rotation(P, points, hinge, sense, theta_s)[0]) * g / (e_star * fc)
    Ts = 2.0 * math.pi * math.sqrt(ds / a_s)
    ground, height = nonlinear_demand(parameters, Ts)
    demand = ground if math.isnan(height) else max(ground, height)
    ratio = du / demand
    return NonlinearCheck(hinge=hinge, sense=sense, theta0=theta0, d0_star=d0, du_star=du, ds_star=ds, as_star=a_s,
                          Ts=Ts, demand_ground=ground, demand_height=height, demand=demand, ratio=ratio,
                          verdict="pass" if ratio >= 1.0 else "fail", theta=theta, d_star=d_star(theta),
                          a_star=a_star)
