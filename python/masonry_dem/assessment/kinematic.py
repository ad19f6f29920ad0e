"""The linear kinematic check of a collapse mechanism (Circolare 617/2009 C8A.4.1 and C8A.4.2.3; the quantities are
those of the 2019 Circolare's C8.7.1 too): the mechanism's weights and their virtual displacements
(:func:`mechanism_weights`), the participating mass and its fraction (:func:`participating_mass`), the spectral
acceleration that activates the mechanism, the demand and the verdict (:func:`linear_check`).

Weights are lumped at each block's centroid: a wall of many courses that turns as one body gives the "sliced" e*
of its blocks (a bare rectangular wall turning about its toe: e* -> 3/4 as the courses grow thin, against 1 for
the same wall lumped at its own centroid). A load a block carries (``Model(carried=...)``, ``[[loads.carried]]``) is
a weight of its own at its point, moving with its block. The blocks that do not move in the mechanism are left out;
a block moves when its largest corner motion exceeds :data:`masonry_dem._mechanism.MOVING_FRACTION` of the largest
(the rule of the mechanism's description, ``masonry-dem run``).

The multiplier alpha0 is the analysis's collapse multiplier of the live load "horizontal_weight" (lambda times
every block's weight, horizontal): with horizontal forces proportional to the weights, the virtual-work alpha0 of
C8A.4.1 is the limit-analysis multiplier. g in a0* = alpha0 g / (e* FC) is the model's gravity, the one its
weights are made with (9.81 m/s2 by default).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Optional, Tuple

import numpy as np

from .._core import InputError
from .._mechanism import MOVING_FRACTION
from .._shapes import area_centroid, shapes
from ..report import corner_motion as corner_motion_2d
from ..space.report import all_boxes, dof_points, own_centroids, vertex_motion
from .parameters import AssessmentParameters
from .spectra import Spectrum, _refuse


@dataclass(frozen=True, eq=False)
class MechanismWeights:
    """The weights of a mechanism and their virtual displacements, lumped at the blocks' centroids, and the loads
    the moving blocks carry, each at its point.

    Attributes:
        blocks: (k,) the block of each weight (indices into the model's blocks): the moving blocks, then the block
            of each load they carry.
        weights: (k,) the weights P_i [N]: each block's own (without its loads), then the loads'.
        dx: (k,) the horizontal virtual displacements of their points along the live load, scaled so that the
            largest is 1 and sum P_i dx_i > 0.
        points: (k, 2) or (k, 3) their points [m]: the blocks' own centroids, then the loads' points.
        gravity: the model's gravity [m/s2].
    """

    blocks: np.ndarray
    weights: np.ndarray
    dx: np.ndarray
    points: np.ndarray
    gravity: float


def participating_mass(weights: Any, dx: Any, gravity: float) -> Tuple[float, float]:
    """(M* [kg], e*) of weights P_i [N] moving by dx_i (Circolare 617/2009 eqs. C8A.4.2, C8A.4.3):
    M* = (sum P_i dx_i)^2 / (g sum P_i dx_i^2), e* = g M* / sum P_i. Any scale of dx gives the same."""
    P = np.asarray(weights, dtype=np.float64).reshape(-1)
    d = np.asarray(dx, dtype=np.float64).reshape(-1)
    work = float(P @ d)
    if not (math.isfinite(work) and work != 0.0):
        raise _refuse("mechanism", "its weights have no horizontal virtual displacement (sum P_i dx_i = 0): the "
                                   "mechanism is not one of the horizontal load")
    mass = work * work / (gravity * float(P @ (d * d)))
    return mass, gravity * mass / float(P.sum())


def block_weights(model: Any, blocks: np.ndarray) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The weights of ``blocks`` (distinct indices) and of the loads they carry (``model.carried``): (the block of
    each (k,), the weights P_i [N] (k,), their points [m] (k, 2) or (k, 3)): each block's own weight (its weight
    without its loads) at its own centroid (its polygon's, its box's or its polyhedron's), then each load at its
    point."""
    weights = np.array(model.weights, dtype=np.float64)  # with the loads the blocks carry
    if int(getattr(model, "dimension", 2)) == 3:
        boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)
        points = 0.5 * (boxes[:, :3] + boxes[:, 3:])
        if not all_boxes(model):  # a polyhedron's own centroid: its centre of mass without the loads it carries
            points = own_centroids(model, points)
    else:
        every = shapes(model)
        points = np.array([area_centroid(every.polygon(int(i))) for i in range(len(every))]).reshape(-1, 2)
    carried = list(getattr(model, "carried", None) or [])
    owner = np.array([c[0] for c in carried], dtype=np.int64)
    loads = np.array([c[2] for c in carried], dtype=np.float64)
    at = np.array([c[1] for c in carried], dtype=np.float64).reshape(-1, points.shape[1])
    np.subtract.at(weights, owner, loads)  # each block's own weight
    on = np.isin(owner, blocks)
    return (np.concatenate([blocks, owner[on]]), np.concatenate([weights[blocks], loads[on]]),
            np.concatenate([points[blocks], at[on]]))


def mechanism_weights(model: Any, results: Any, gravity: Optional[float] = None) -> MechanismWeights:
    """The moving blocks of ``results.mechanism`` (the velocities of limit analysis, or the last increment of a
    static or explicit collapse) with their weights and horizontal virtual displacements along the live load.

    ``gravity`` [m/s2]: the model's gravity; a 3D model tells its own, a wall in the plane (:class:`masonry_dem.Model`)
    does not, and needs it given. Refuses (InputError) a run without a collapse, a live load that is not
    "horizontal_weight", a mechanism in which no block moves, and a missing gravity."""
    status = str(results.status)
    if status != "collapse" or not math.isfinite(float(results.collapse_multiplier)):
        raise _refuse("mechanism", f"no collapse mechanism to check: the analysis ended with status {status!r}")
    live = str(getattr(model, "live", "horizontal_weight"))
    if live != "horizontal_weight":
        raise InputError(f'loads.live: a seismic check needs the live load "horizontal_weight" (lambda times the '
                         f'weights), got "{live}"', "loads.live")
    g = getattr(model, "gravity", None) if gravity is None else gravity
    if g is None:
        raise _refuse("gravity", "a wall in the plane's Model does not tell its gravity: give the one it was built "
                                 "with (Model(gravity=...), 9.81 m/s2 by default)")
    g = float(g)
    if not (math.isfinite(g) and g > 0):
        raise _refuse("gravity", f"must be > 0, got {g!r}")
    three_d = int(getattr(model, "dimension", 2)) == 3
    mech = np.asarray(results.mechanism, dtype=np.float64)
    # the dofs are at the centres of mass (the blocks' centroids, moved by the loads they carry): the virtual
    # displacement along the live load of a point p of block i is that of the small motion at the dofs
    if three_d:
        dofs = dof_points(model)
        corner = vertex_motion(model, mech)
        angle = math.radians(float(getattr(model, "direction", 0.0) or 0.0))
        along = np.array([math.cos(angle), math.sin(angle), 0.0])

        def dx_at(i: np.ndarray, p: np.ndarray) -> np.ndarray:
            return (mech[i, :3] + np.cross(mech[i, 3:], p - dofs[i])) @ along  # type: ignore[no-any-return]
    else:
        blocks = shapes(model)  # convex polygons: rectangles among them
        dofs = blocks.centroids
        corner = corner_motion_2d(blocks, mech)

        def dx_at(i: np.ndarray, p: np.ndarray) -> np.ndarray:
            return mech[i, 0] - mech[i, 2] * (p[:, 1] - dofs[i, 1])  # type: ignore[no-any-return]
    bodies = np.arange(int(model.n_blocks))
    if model.top_index is not None:
        bodies = np.append(bodies, int(model.top_index))
    peak = float(np.max(corner[bodies])) if len(bodies) else 0.0
    if not (math.isfinite(peak) and peak > 0):
        raise _refuse("mechanism", "no block moves in the mechanism")
    moving = bodies[corner[bodies] > MOVING_FRACTION * peak]
    which, P, where = block_weights(model, moving)
    d = dx_at(which, where)
    scale = float(np.max(np.abs(d)))
    if scale > 0:  # else participating_mass refuses it: no horizontal displacement
        d = d / (scale if float(P @ d) >= 0 else -scale)
    return MechanismWeights(blocks=which, weights=P, dx=d, points=where, gravity=g)


@dataclass(frozen=True)
class LinearCheck:
    """The linear kinematic check of a mechanism (Circolare 617/2009 C8A.4.1, C8A.4.2.3).

    Attributes:
        alpha0: the multiplier that activates the mechanism.
        weight: sum P_i [N] of the moving blocks.
        participating_mass: M* [kg]; mass_fraction: e* = g M* / sum P_i.
        gravity: g [m/s2], the model's.
        confidence_factor: FC; q: the behaviour factor.
        a0_star: a0* = alpha0 g / (e* FC) [m/s2], the spectral acceleration that activates the mechanism.
        demand_ground: a_g S / q [m/s2] (S_e(0) / q).
        demand_height: the demand at height [m/s2] (NaN at ground level): S_e(T1) psi(Z) gamma / q by the 2009 rule,
            a_Z(Z) / q by the 2019 rule.
        T1: the building's period [s]; psi: psi(Z) = Z / H; gamma: 3 N / (2 N + 1) (NaN at ground level).
        height_rule: "circ2009" or "circ2019"; floor_acceleration: a_Z(Z) = S_e(T1, xi_1) gamma psi(Z)
            sqrt(1 + 0.0004 xi_1^2) [m/s2] (xi_1 in percent) of the 2019 rule (NaN otherwise).
        demand: the demand [m/s2]: demand_ground, and at height the larger of the two.
        ratio: a0* / demand (capacity over demand); verdict: "pass" when ratio >= 1, else "fail".
        moving_blocks: how many blocks move.
    """

    alpha0: float
    weight: float
    participating_mass: float
    mass_fraction: float
    gravity: float
    confidence_factor: float
    q: float
    a0_star: float
    demand_ground: float
    demand_height: float
    T1: float
    psi: float
    gamma: float
    demand: float
    ratio: float
    verdict: str
    moving_blocks: int
    height_rule: str = "circ2009"
    floor_acceleration: float = math.nan


def floor_acceleration(spectrum: Spectrum, parameters: AssessmentParameters) -> float:
    """a_Z(Z) [m/s2], the peak acceleration at the mechanism's height of the building's first mode (Circolare 2019
    eqs. C7.2.7, C7.2.8, the first mode only as C7.2.3 allows): S_e(T1, xi_1) |gamma psi(Z)| sqrt(1 + 0.0004 xi_1^2),
    xi_1 the building's damping in percent, S_e(T1, xi_1) the ground's spectrum at that damping, T1 the given period
    or 0.05 H^(3/4) (eq. C7.3.2), psi(Z) = Z / H and gamma = 3 N / (2 N + 1) (eq. C7.2.10)."""
    xi = parameters.building_damping
    T1, psi, gamma = parameters.building_period(), parameters.modal_shape(), parameters.participation()
    damped = spectrum.with_damping(xi)
    return float(damped.acceleration(T1)) * abs(gamma * psi) * math.sqrt(1.0 + 0.0004 * (100.0 * xi) ** 2)


def linear_demand(spectrum: Spectrum, parameters: AssessmentParameters) -> Tuple[float, float, float, float, float]:
    """(at ground level, at height, T1, psi, gamma) of the linear check's demand [m/s2]: a_g S / q (S_e(0) / q),
    and for a mechanism at height Z in a building of height H and N storeys, T1 = 0.05 H^(3/4), psi = Z / H and
    gamma = 3 N / (2 N + 1): by the 2009 rule S_e(T1) psi(Z) gamma / q (Circolare 617/2009 C8A.4.2.3), by the 2019 rule
    a_Z(Z) / q (:func:`floor_acceleration`; Circolare 2019 C8.7.1.2.1.7: a_g,SLV = q a_g,SLD, the ground acceleration
    at which a_Z reaches a0*, read here on the site's spectrum held in shape); NaN at ground level."""
    q = parameters.q
    ground = spectrum.peak_ground_acceleration / q
    if not parameters.at_height:
        return ground, math.nan, math.nan, math.nan, math.nan
    T1, psi, gamma = parameters.building_period(), parameters.modal_shape(), parameters.participation()
    if parameters.height_rule == "circ2019":
        return ground, floor_acceleration(spectrum, parameters) / q, T1, psi, gamma
    return ground, float(spectrum.acceleration(T1)) * psi * gamma / q, T1, psi, gamma


def linear_check_of(alpha0: float, weights: Any, dx: Any, gravity: float,
                    parameters: AssessmentParameters) -> LinearCheck:
    """The linear check of a mechanism given by its multiplier ``alpha0``, its weights P_i [N] (blocks and the
    loads they carry) and their horizontal virtual displacements dx_i (any scale), under ``gravity`` [m/s2]."""
    mass, fraction = participating_mass(weights, dx, gravity)
    fc = parameters.confidence_factor
    a0 = alpha0 * gravity / (fraction * fc)
    ground, height, T1, psi, gamma = linear_demand(parameters.spectrum, parameters)
    demand = ground if math.isnan(height) else max(ground, height)
    ratio = a0 / demand
    rule = parameters.height_rule
    floor = height * parameters.q if rule == "circ2019" and math.isfinite(height) else math.nan
    return LinearCheck(alpha0=float(alpha0), weight=float(np.sum(weights)), participating_mass=mass,
                       mass_fraction=fraction, gravity=float(gravity), confidence_factor=fc, q=parameters.q,
                       a0_star=a0, demand_ground=ground, demand_height=height, T1=T1, psi=psi, gamma=gamma,
                       demand=demand, ratio=ratio, verdict="pass" if ratio >= 1.0 else "fail",
                       moving_blocks=int(np.size(weights)), height_rule=rule, floor_acceleration=floor)


def linear_check(model: Any, results: Any, spectrum: Any, q: float = 2.0, confidence_factor: float = 1.35,
                 mechanism_height: float = 0.0, building_height: Optional[float] = None,
                 storeys: Optional[int] = None, gravity: Optional[float] = None, height_rule: str = "circ2009",
                 building_damping: float = 0.05, T1: Optional[float] = None) -> LinearCheck:
    """The linear kinematic check of the collapse mechanism of ``results`` (of ``model``) against ``spectrum`` (a
    :class:`masonry_dem.assessment.Spectrum`, or an :class:`AssessmentParameters` that holds it and the other
    parameters, which are then ignored): alpha0, M*, e*, a0* = alpha0 g / (e* FC), the demand at ground level
    (a_g S / q) or at height, the ratio a0* / demand and the verdict.

    ``gravity`` [m/s2]: the model's gravity, needed for a wall in the plane (its Model does not tell it).
    ``height_rule``: the demand at height by Circolare 617/2009 ("circ2009") or the 2019 Circolare's floor
    acceleration ("circ2019", with the building's damping ratio ``building_damping``); ``T1`` [s]: the building's
    period, by default 0.05 H^(3/4).
    Raises InputError naming what is refused: no collapse, no moving block, q or confidence_factor below 1, a height
    above the building, ..."""
    if isinstance(spectrum, AssessmentParameters):
        parameters = spectrum
    else:
        parameters = AssessmentParameters(spectrum=spectrum, q=q, confidence_factor=confidence_factor,
                                          mechanism_height=mechanism_height, building_height=building_height,
                                          storeys=storeys, height_rule=height_rule, building_damping=building_damping,
                                          T1=T1)
    lumped = mechanism_weights(model, results, gravity)
    check = linear_check_of(float(results.collapse_multiplier), lumped.weights, lumped.dx, lumped.gravity, parameters)
    return replace(check, moving_blocks=int(np.unique(lumped.blocks).size))  # a block with loads counted once
