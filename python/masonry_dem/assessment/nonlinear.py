"""The nonlinear kinematic check (Circolare 617/2009 C8A.4.2) of a mechanism of rigid bodies turning about hinges in
a wall in the plane: one body (a single block, or blocks that move as one), or several bodies each hinged to the
ground or to another moving body (an open chain or tree of hinges: a stack hinging at its base and between blocks).

The bodies are found in the mechanism (blocks that move as one rigid body are one body), and each body's hinge: the
point about which it turns relative to the ground or to another body (their relative instantaneous centre), which
must lie on the outlines of both (a corner where they touch). The mechanism is then followed at finite rotation
with each body's rotation held in the mechanism's proportion to the others' (its shape kept) and every hinge kept:
body k's points move as X_k(x) = X_parent(h_k) + R(theta_k) (x - h_k), the geometry updated; no other contact is made
or lost. Virtual work at each position, with the horizontal forces alpha P_i at the blocks' centroids (and at the
points of the loads they carry, :func:`masonry_dem.assessment.kinematic.block_weights`), gives
alpha(theta) = sum P_i dy_i / sum P_i dx_i, dx_i and dy_i the centroids' velocities along the path there. For a block
of base b and height h about its toe this is tan(atan(b / h) - theta); the curve goes to zero at theta_0.

The equivalent system (C8A.4.2.1), the control point k being the weights' centroid G: d* = d_k sum P_i dx_i^2 / (dx_k
sum P_i dx_i) (dx_i the virtual displacements at theta = 0), a* = alpha g / (e* FC); d*_0 where a* = 0; d*_u = 0.4 d*_0
(C8A.4.2.2); d*_s = 0.4 d*_u, a*_s the curve's a* there, T_s = 2 pi sqrt(d*_s / a*_s) (C8A.4.2.3; the exact curve,
where the Circolare allows a straight line). The check: d*_u >= S_De(T_s) at ground level; at height Z, d*_u >= S_De(T1)
psi(Z) gamma (T_s / T1)^2 / sqrt((1 - T_s / T1)^2 + 0.02 T_s / T1) for T_s < 1.5 T1, S_De(T1) psi(Z) gamma beyond, the
demand being the larger of this and the ground's.

Not covered, and refused by name ("mechanism"): a mechanism that slides (a body with no hinge), a closed chain (a body
held by two hinges, e.g. a wall restrained at its top: its bodies' rotations change in proportion as it moves, which
holding them fixed would not follow), walls in 3D, and a mechanism at height under the 2019 Circolare's floor spectra.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Optional, Tuple

import numpy as np

from .._shapes import shapes
from .kinematic import block_weights, mechanism_weights, participating_mass
from .parameters import AssessmentParameters
from .spectra import _refuse

#: Two blocks turn as one when their rotation rates and their velocities agree to this fraction (of the largest rate
#: and speed); a hinge lies on a body's outline within this fraction of the mechanism's size.
RIGID_TOLERANCE = 1e-4
#: d*_u = 0.4 d*_0 and d*_s = 0.4 d*_u (Circolare 617/2009 C8A.4.2.2, C8A.4.2.3).
ULTIMATE_FRACTION = 0.4
#: Points of the capacity curve kept for the plots.
CURVE_POINTS = 101
#: The samples on which the curve's zero is first bracketed (up to a quarter turn of the fastest body).
SCAN_POINTS = 2001


@dataclass(frozen=True)
class NonlinearCheck:
    """The nonlinear kinematic check of a mechanism of rigid bodies (Circolare 617/2009 C8A.4.2).

    Attributes:
        hinge: (x, y) [m], the hinge on the ground of the first body; sense: +1 counterclockwise, -1 clockwise, its
            rotation in the mechanism's direction.
        bodies: how many rigid bodies move; hinges: ((x, y), ...) [m] every body's hinge (on the ground or on the
            body it turns on), in the order the bodies are followed.
        theta0: the rotation [rad] of the fastest-turning body at which alpha falls to 0.
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
    bodies: int = 1
    hinges: Tuple[Tuple[float, float], ...] = ()
    theta: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    d_star: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)
    a_star: np.ndarray = field(default_factory=lambda: np.zeros(0), repr=False)


@dataclass(frozen=True, eq=False)
class Chain:
    """A mechanism of rigid bodies hinged to the ground or to one another (an open chain or a tree), to be followed
    at finite rotation.

    Attributes:
        weights: (k,) the weights P_i [N]; points: (k, 2) where they act, at rest [m]; body: (k,) the body of each.
        hinges: (m, 2) each body's hinge at rest [m]; parent: (m,) the body each turns on (-1: the ground), every
            parent before its children.
        rates: (m,) each body's rotation per unit of the path's parameter (counterclockwise positive), the largest
            magnitude 1, in the direction in which the horizontal forces do positive work.
    """

    weights: np.ndarray
    points: np.ndarray
    body: np.ndarray
    hinges: np.ndarray
    parent: np.ndarray
    rates: np.ndarray

    def _turn(self, k: int, t: np.ndarray, r: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """(R r, w J R r) of arms r (..., 2) of body k turned by rates[k] t, at every t: (len(t), ..., 2)."""
        c, s = np.cos(self.rates[k] * t), np.sin(self.rates[k] * t)
        x = np.multiply.outer(c, r[..., 0]) - np.multiply.outer(s, r[..., 1])
        y = np.multiply.outer(s, r[..., 0]) + np.multiply.outer(c, r[..., 1])
        return np.stack((x, y), axis=-1), self.rates[k] * np.stack((-y, x), axis=-1)

    def _hinges(self, t: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
        """(where, how fast) each body's hinge is at ``t``: (len(t), m, 2) each."""
        m = len(self.hinges)
        origin = np.zeros((len(t), m, 2))
        speed = np.zeros((len(t), m, 2))
        for k in range(m):
            p = int(self.parent[k])
            if p < 0:
                origin[:, k] = self.hinges[k]
            else:
                arm, rate = self._turn(p, t, self.hinges[k] - self.hinges[p])
                origin[:, k] = origin[:, p] + arm
                speed[:, k] = speed[:, p] + rate
        return origin, speed

    def motion(self, t: Any) -> Tuple[np.ndarray, np.ndarray]:
        """(positions, velocities), each (len(t), k, 2) [m], [m per unit of t]: the weights' points at the path's
        parameters ``t`` (body k turned by rates[k] t about its hinge, which moves with its parent) and their
        derivatives along the path."""
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        origin, speed = self._hinges(t)
        positions = np.zeros((len(t), len(self.weights), 2))
        velocities = np.zeros_like(positions)
        for k in range(len(self.hinges)):
            mine = np.nonzero(self.body == k)[0]
            arm, rate = self._turn(k, t, self.points[mine] - self.hinges[k])
            positions[:, mine] = origin[:, k][:, None, :] + arm
            velocities[:, mine] = speed[:, k][:, None, :] + rate
        return positions, velocities

    def resultant(self, t: Any) -> Tuple[np.ndarray, np.ndarray]:
        """(sum P_i x_i, sum P_i v_i), each (len(t), 2): the weights' first moments of :meth:`motion`, from each
        body's weight and first moment about its hinge (no loop over the blocks)."""
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        origin, speed = self._hinges(t)
        moment = np.zeros((len(t), 2))
        rate = np.zeros((len(t), 2))
        for k in range(len(self.hinges)):
            mine = self.body == k
            weight = float(self.weights[mine].sum())
            arm, turning = self._turn(k, t, self.weights[mine] @ (self.points[mine] - self.hinges[k]))
            moment += weight * origin[:, k] + arm
            rate += weight * speed[:, k] + turning
        return moment, rate

    def alpha(self, t: Any) -> np.ndarray:
        """alpha at the path's parameters ``t``: sum P_i dy_i / sum P_i dx_i, virtual work of the horizontal forces
        alpha P_i and the weights at the turned position."""
        _, v = self.resultant(t)
        return v[:, 1] / v[:, 0]  # type: ignore[no-any-return]


def _boundary_distance(point: np.ndarray, polygon: np.ndarray) -> float:
    """The distance [m] from ``point`` to the outline of ``polygon`` (k, 2)."""
    a, b = polygon, np.roll(polygon, -1, axis=0)
    d = b - a
    length2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    s = np.clip(np.einsum("ij,ij->i", point - a, d) / length2, 0.0, 1.0)
    return float(np.min(np.hypot(*(a + s[:, None] * d - point).T)))


def mechanism_chain(model: Any, results: Any, blocks: np.ndarray) -> Chain:
    """The moving ``blocks`` of a wall in the plane's mechanism as rigid bodies and their hinges (:class:`Chain`);
    refuses (InputError "mechanism") a mechanism that slides, a closed chain of bodies, and a 3D wall."""
    if int(getattr(model, "dimension", 2)) == 3:
        raise _refuse("mechanism", "the nonlinear kinematic check is of a wall in the plane in this version")
    every = shapes(model)  # convex polygons: rectangles among them
    mech = np.asarray(results.mechanism, dtype=np.float64)
    c = every.centroids[blocks]
    u, w = mech[blocks, :2], mech[blocks, 2]
    bounds = every.bounds[blocks]
    size = float(np.max(bounds[:, 2:].max(axis=0) - bounds[:, :2].min(axis=0)))
    rate_scale = float(np.max(np.abs(w)))
    speed = float(np.max(np.hypot(u[:, 0], u[:, 1])) + rate_scale * size)
    if not rate_scale * size > RIGID_TOLERANCE * speed:
        raise _refuse("mechanism", "it slides: the nonlinear kinematic check here is of bodies turning about hinges")
    # bodies: blocks with the same rigid motion (rate, and velocity at each other's centroid)
    body = np.full(len(blocks), -1)
    rep: list = []
    for i in range(len(blocks)):
        for k, j in enumerate(rep):
            at_i = u[j] + w[j] * np.array([-(c[i, 1] - c[j, 1]), c[i, 0] - c[j, 0]])
            if abs(w[i] - w[j]) <= RIGID_TOLERANCE * rate_scale and np.hypot(*(at_i - u[i])) <= RIGID_TOLERANCE * speed:
                body[i] = k
                break
        else:
            body[i] = len(rep)
            rep.append(i)
    m = len(rep)
    polygons = [[every.polygon(int(blocks[i])) for i in np.nonzero(body == k)[0]] for k in range(m)]
    moving = set(int(b) for b in blocks)
    ground = [every.polygon(i) for i in range(len(every)) if i not in moving]
    tol = RIGID_TOLERANCE * size

    def origin_velocity(k: int) -> np.ndarray:  # the velocity of the point (0, 0) in body k's motion
        j = rep[k]
        return u[j] - w[j] * np.array([-c[j, 1], c[j, 0]])

    def on(point: np.ndarray, outlines: list) -> bool:
        return any(_boundary_distance(point, q) <= tol for q in outlines)

    def centre(a: int, b: int) -> Optional[np.ndarray]:  # the relative instantaneous centre of a (b = -1: the ground)
        wa, wb = w[rep[a]], (w[rep[b]] if b >= 0 else 0.0)
        if abs(wa - wb) <= RIGID_TOLERANCE * rate_scale:
            return None  # a relative translation: a slide, not a hinge
        dv = (origin_velocity(b) if b >= 0 else np.zeros(2)) - origin_velocity(a)
        return np.array([dv[1], -dv[0]]) / (wa - wb)  # J p (wa - wb) = dv, J^-1 = -J

    links = []  # (body, other body or -1, hinge)
    for a in range(m):
        p = centre(a, -1)
        if p is not None and on(p, polygons[a]) and on(p, ground):
            links.append((a, -1, p))
        for b in range(a + 1, m):
            p = centre(a, b)
            if p is not None and on(p, polygons[a]) and on(p, polygons[b]):
                links.append((a, b, p))
    if len(links) > m:
        raise _refuse("mechanism", f"its {m} bodies are held by {len(links)} hinges (a closed chain): the nonlinear "
                                   "kinematic check here follows bodies hinged to the ground or to one another "
                                   "without a loop")
    order, parent, hinge = [], {}, {}
    frontier = [-1]
    while frontier:
        nxt = []
        for f in frontier:
            for a, b, p in links:
                for child, other in ((a, b), (b, a)):
                    if other == f and child >= 0 and child not in parent:
                        parent[child], hinge[child] = f, p
                        order.append(child)
                        nxt.append(child)
        frontier = nxt
    if len(order) < m:
        raise _refuse("mechanism", "a body of it turns about no hinge on the ground or on another body (it slides, "
                                   "or is held by a slide): the nonlinear kinematic check here is of bodies turning "
                                   "about hinges")
    index = {k: n for n, k in enumerate(order)}
    rates = np.array([w[rep[k]] for k in order]) / rate_scale
    # the weights: each block's own at its centroid, and the loads it carries at their points, on its body
    owner, weights, points = block_weights(model, blocks)
    slot = {int(b): n for n, b in enumerate(blocks)}
    on_body = np.array([index[int(body[slot[int(b)]])] for b in owner])
    chain = Chain(weights=weights, points=points, body=on_body, hinges=np.array([hinge[k] for k in order]),
                  parent=np.array([index.get(parent[k], -1) for k in order]), rates=rates)
    if float(chain.motion(0.0)[1][0, :, 0] @ weights) < 0:  # the direction in which the horizontal forces work
        chain = Chain(weights=weights, points=points, body=chain.body, hinges=chain.hinges, parent=chain.parent,
                      rates=-rates)
    return chain


def alpha_of_rotation(weights: Any, points: Any, hinge: Tuple[float, float], sense: int, theta: Any) -> np.ndarray:
    """alpha(theta) of weights P_i [N] at ``points`` (k, 2) [m] of one body turned by ``theta`` [rad] about ``hinge``
    in the ``sense`` (+1 counterclockwise, -1 clockwise): -sum P_i (x_i - H_x) / sum P_i (y_i - H_y) at the turned
    position (virtual work of the horizontal forces alpha P_i and the weights)."""
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


def _bisect(f: Any, lo: float, hi: float) -> float:
    """The root of ``f`` in [lo, hi] (f(lo) > 0 >= f(hi)) to the last bit, by bisection."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if f(mid) > 0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def chain_curve(chain: Chain, gravity: float, confidence_factor: float) -> Tuple[float, Any, Any, float]:
    """(t_0, d*(t), a*(t), e*) of a mechanism followed at finite rotation: the parameter t_0 (the fastest body's
    rotation [rad]) at which alpha falls to 0, the equivalent system's displacement d* [m] and acceleration a*
    [m/s2] as functions of t, and e*. Refuses (InputError "mechanism") a curve that does not reach 0 within a
    quarter turn, or whose control point does not move forwards up to there."""
    P = chain.weights
    positions0, v0 = chain.motion(0.0)
    dx = v0[0, :, 0]
    _, e_star = participating_mass(P, dx, gravity)
    dx_k = float(P @ dx) / float(P.sum())  # the weights' centroid G is the control point
    to_star = float(P @ (dx * dx)) / (dx_k * float(P @ dx))
    x0 = float(P @ positions0[0, :, 0]) / float(P.sum())

    def d_star(t: Any) -> np.ndarray:
        return (chain.resultant(t)[0][:, 0] / float(P.sum()) - x0) * to_star  # type: ignore[no-any-return]

    def a_star(t: Any) -> np.ndarray:
        return chain.alpha(t) * gravity / (e_star * confidence_factor)  # type: ignore[no-any-return]

    scan = np.linspace(0.0, math.pi / 2, SCAN_POINTS)
    alpha = chain.alpha(scan)
    if not alpha[0] > 0:
        raise _refuse("mechanism", "its multiplier at rest is not positive along the mechanism")
    below = np.nonzero(alpha <= 0)[0]
    if not len(below):
        raise _refuse("mechanism", "its capacity curve does not fall to 0 within a quarter turn")
    t0 = _bisect(lambda t: float(chain.alpha(t)[0]), float(scan[below[0] - 1]), float(scan[below[0]]))
    if np.any(np.diff(d_star(np.linspace(0.0, t0, SCAN_POINTS))) <= 0):
        raise _refuse("mechanism", "its control point (the weights' centroid) does not move forwards all the way to "
                                   "the curve's end")
    return t0, d_star, a_star, e_star


def nonlinear_check(model: Any, results: Any, parameters: AssessmentParameters,
                    gravity: Optional[float] = None) -> NonlinearCheck:
    """The nonlinear kinematic check of the collapse mechanism of ``results``: rigid bodies turning about hinges on
    the ground or on one another, in a wall in the plane (``gravity`` [m/s2] the model's). Refuses (InputError
    "mechanism") a mechanism that slides, a closed chain of bodies, a mechanism at height under the 2019 Circolare's
    rule, and what :func:`masonry_dem.assessment.mechanism_weights` refuses."""
    lumped = mechanism_weights(model, results, gravity)
    if parameters.at_height and parameters.height_rule != "circ2009":
        raise _refuse("mechanism", "at height, the nonlinear check follows Circolare 617/2009 only (the 2019 "
                                   "Circolare's floor displacement spectra, C8.7.1.2.1.8, are not implemented)")
    chain = mechanism_chain(model, results, np.unique(lumped.blocks))  # a block with loads once
    g = lumped.gravity
    t0, d_star, a_star, _ = chain_curve(chain, g, parameters.confidence_factor)
    d0 = float(d_star(t0)[0])
    du = ULTIMATE_FRACTION * d0
    ds = ULTIMATE_FRACTION * du
    theta_s = _bisect(lambda t: ds - float(d_star(t)[0]), 0.0, t0)  # d*(t) rises from 0 to d*_0
    a_s = float(a_star(theta_s)[0])
    Ts = 2.0 * math.pi * math.sqrt(ds / a_s)
    ground, height = nonlinear_demand(parameters, Ts)
    demand = ground if math.isnan(height) else max(ground, height)
    ratio = du / demand
    theta = np.linspace(0.0, t0, CURVE_POINTS)
    first = int(np.nonzero(chain.parent < 0)[0][0])
    hinges = tuple((float(h[0]), float(h[1])) for h in chain.hinges)
    return NonlinearCheck(hinge=hinges[first], sense=int(np.sign(chain.rates[first])), theta0=t0, d0_star=d0,
                          du_star=du, ds_star=ds, as_star=a_s, Ts=Ts, demand_ground=ground, demand_height=height,
                          demand=demand, ratio=ratio, verdict="pass" if ratio >= 1.0 else "fail",
                          bodies=len(chain.hinges), hinges=hinges, theta=theta, d_star=d_star(theta),
                          a_star=a_star(theta))
