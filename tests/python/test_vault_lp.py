"""Vaults and domes of convex polyhedra (a barrel vault, a dome, a cross vault) against an independent linear program:
the static theorem written here from the model's contacts (their blocks, frames and corners) and the blocks' weights
and centroids, with a friction pyramid of many sides at each corner in place of Coulomb's cone, solved by HiGHS
(scipy.optimize.linprog), not by the product's interior point.

The program, for the blocks free to move (the wall's; the base and the supports fixed):
- at each corner p of each contact (normal n from block a into block b, tangents t1, t2), the force on b
  sum_k alpha_k (n + mu_s (cos(2 pi k / s) t1 + sin(2 pi k / s) t2)), alpha_k >= 0 (and its opposite on a): a
  pyramid of s sides inscribed in Coulomb's cone |T| <= mu N for mu_s = mu, circumscribed about it for
  mu_s = mu / cos(pi / s). The product's cone lies between the two, so its multiplier (its least thickness) lies
  between theirs;
- the equilibrium of each free block, forces and moments about its centroid, under its weight W_i along -z and the
  live load lambda W_i (cos d, sin d, 0);
- maximise lambda (the least thickness: the blocks stand under their weight where lambda >= 0 is feasible).
"""

from __future__ import annotations

import math
from typing import Any, Tuple

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import linprog

import masonry_dem as md
from masonry_dem import _core

GRAVITY = 10.0


def _program(model: Any, mu: float, sides: int, outer: bool) -> Tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """A_eq of the pyramids' multipliers (one column per corner and side), the dead loads and the live loads of the
    free blocks' 6 equations each (forces, moments about the centroid)."""
    n_free = model.n_blocks
    mu_s = mu / math.cos(math.pi / sides) if outer else mu
    angles = 2 * math.pi * np.arange(sides) / sides
    pairs, corners = model.interface_blocks, model.interface_corners
    # the generators of each contact (m, s, 3), the same at each of its corners: (m, 4, s, 3)
    g = (model.interface_normals[:, None, :] + mu_s * (np.cos(angles)[None, :, None] * model.interface_t1[:, None, :]
                                                       + np.sin(angles)[None, :, None] * model.interface_t2[:, None, :]))
    g = np.broadcast_to(g[:, None, :, :], (len(pairs), 4, sides, 3))
    present = np.broadcast_to(~np.isnan(corners[:, :, 0])[:, :, None], g.shape[:3])
    column = (np.cumsum(present.ravel()) - 1).reshape(g.shape[:3])
    rows, cols, vals = [], [], []
    for side, sign in ((1, 1.0), (0, -1.0)):  # the force on b, its opposite on a
        block = pairs[:, side]
        arm = corners - model.centroids[block][:, None, :]  # (m, 4, 3)
        f = sign * g
        moment = np.cross(arm[:, :, None, :], f)
        keep = (block < n_free)[:, None, None] & present
        row = np.broadcast_to(6 * block[:, None, None], g.shape[:3])
        for k, part in enumerate((f[..., 0], f[..., 1], f[..., 2], moment[..., 0], moment[..., 1], moment[..., 2])):
            rows.append(row[keep] + k)
            cols.append(column[keep])
            vals.append(part[keep])
    a_eq = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(6 * n_free, int(column.max()) + 1))
    w = model.weights[:n_free] / model.weights[:n_free].max()  # scaled: HiGHS is surer of O(1) loads
    dead = np.zeros(6 * n_free)
    dead[2::6] = -w
    live = np.zeros(6 * n_free)
    d = math.radians(model.direction)
    live[0::6], live[1::6] = w * math.cos(d), w * math.sin(d)
    return a_eq, dead, live


def independent_lambda(model: Any, mu: float, sides: int, outer: bool) -> float:
    """The largest lambda of the pyramids' program, A alpha + dead + lambda live = 0 with alpha >= 0, or nan if no
    lambda balances the dead loads."""
    a_eq, dead, live = _program(model, mu, sides, outer)
    n = a_eq.shape[1]
    a = sp.hstack([a_eq, sp.csr_matrix(live.reshape(-1, 1))]).tocsr()
    c = np.zeros(n + 1)
    c[-1] = -1.0
    res = linprog(c, A_eq=a, b_eq=-dead, bounds=[(0, None)] * n + [(None, None)], method="highs-ipm")
    assert res.status in (0, 2), res.message
    return float(res.x[-1]) if res.status == 0 else math.nan


def joints(mu: float) -> dict:
    return {"default": {"friction": mu, "dilatancy": mu}}


def test_a_barrel_vault_pushed_along_its_axis_lies_between_the_inscribed_and_circumscribed_pyramids() -> None:
    # a semicircular vault in staggered courses on abutments, pushed along its axis (y): the blocks slide and rock
    # along it, every corner's shear turned out of the arch's plane, where the cone and the pyramids differ most
    mu, sides = 0.6, 32
    v = md.barrel_vault("semicircular", 0.2, 9, 1.2, block_length=0.4, radius=1.0)
    for direction in (90.0, 60.0):
        model = md.Model3D(polyhedra=v["polyhedra"], supports=v["supports"], base=False, gravity=GRAVITY,
                           joints=joints(mu), direction=direction)
        r = model.solve_limit(tolerance=1e-10)
        assert r.status == "collapse", r.error
        inner = independent_lambda(model, mu, sides, outer=False)
        outer = independent_lambda(model, mu, sides, outer=True)
        assert inner * (1 - 1e-7) <= r.collapse_multiplier <= outer * (1 + 1e-7), (inner, r.collapse_multiplier, outer)
        assert outer / inner - 1 < 0.01, (inner, outer)  # the bracket, within 1%


def _least(stands: Any, lo: float, hi: float, rel: float) -> float:
    """The least thickness in (lo, hi) at which stands(t), by bisection to rel of it (lo must not stand, hi must)."""
    assert not stands(lo) and stands(hi), (lo, hi)
    while hi - lo > rel * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if stands(mid) else (mid, hi)
    return hi


def test_the_least_thickness_of_a_hemispherical_dome_agrees_with_the_independent_program() -> None:
    # a coarse dome (12 meridians, 6 parallels: 72 voussoirs) on the base, friction 2 (associative) so that no joint
    # slides, under its own weight: the least thickness t at which it stands (R = 1 m, the middle surface's radius).
    # Assumptions of both programs: meridian and parallel joints (planar voussoirs), no tension, compressive hoop
    # forces through the meridian joints, no hoop tension (the meridian joints run through every ring), friction 2.
    # The product is asked with the live load along gravity ("unbounded": it stands), the independent program with
    # the horizontal one (it stands where a multiplier >= 0 is feasible): near the least thickness the horizontal
    # multiplier rises steeply (from none to 0.18 within 1% of it), where the product's interior point may fail to
    # prove either answer on the horizontal program.
    mu, sides, radius = 2.0, 12, 1.0

    def model(t: float) -> Any:
        d = md.dome("hemispherical", t, 12, 6, radius=radius)
        return md.Model3D(polyhedra=d["polyhedra"], gravity=GRAVITY, joints=joints(mu))

    def product(t: float) -> bool:
        r = model(t).solve_limit(along_gravity=True)
        assert r.status in ("unbounded", "no_equilibrium"), (t, r.status, r.error)
        return bool(r.status == "unbounded")

    def independent(outer: bool) -> Any:
        return lambda t: independent_lambda(model(t), mu, sides, outer) >= 0  # nan (no equilibrium): False

    t_product = _least(product, 0.03, 0.05, 2e-3)
    # more friction stands thinner: the circumscribed pyramid's least thickness is the smaller
    t_inner = _least(independent(False), 0.03, 0.05, 2e-3)
    t_outer = _least(independent(True), 0.03, 0.05, 2e-3)
    assert t_outer * (1 - 2e-3) <= t_product <= t_inner * (1 + 2e-3), (t_outer, t_product, t_inner)
    assert abs(t_product / t_inner - 1) < 0.02 and t_inner / t_outer - 1 < 0.01, (t_outer, t_product, t_inner)
    # where it stands, the product's horizontal multiplier lies between the pyramids'
    m = model(1.05 * t_inner)
    r = m.solve_limit(tolerance=1e-10)
    inner, outer = independent_lambda(m, mu, sides, False), independent_lambda(m, mu, sides, True)
    assert inner * (1 - 1e-7) <= r.collapse_multiplier <= outer * (1 + 1e-7), (inner, r.collapse_multiplier, outer)


def test_a_cross_vault_lies_between_the_pyramids_pushed_and_under_its_weight() -> None:
    # a semicircular cross vault on its four corner supports (R = 1 m, the centreline's radius), its voussoirs cut at
    # the groins: pushed along x and at 45 deg, the product's multiplier lies between the inscribed and circumscribed
    # pyramids' (of 64 sides: the bracket within 1%); under its own weight (16 voussoirs, friction 10: no joint
    # slides), its least thickness between theirs (about 0.069 R, where the three agree within 1%)
    mu, sides = 0.6, 64

    def model(t: float, n: int, friction: float, direction: float = 0.0) -> Any:
        v = md.cross_vault("semicircular", t, n, radius=1.0)
        return md.Model3D(polyhedra=v["polyhedra"], supports=v["supports"], base=False, gravity=GRAVITY,
                          joints=joints(friction), direction=direction)

    for direction in (0.0, 45.0):
        m = model(0.2, 9, mu, direction)
        r = m.solve_limit(tolerance=1e-10)
        assert r.status == "collapse", r.error
        inner, outer = independent_lambda(m, mu, sides, outer=False), independent_lambda(m, mu, sides, outer=True)
        assert inner * (1 - 1e-7) <= r.collapse_multiplier <= outer * (1 + 1e-7), (inner, r.collapse_multiplier, outer)
        assert outer / inner - 1 < 0.01, (inner, outer)

    friction, sides = 10.0, 12

    def product(t: float) -> bool:
        r = model(t, 16, friction).solve_limit(along_gravity=True)
        assert r.status in ("unbounded", "no_equilibrium"), (t, r.status, r.error)
        return bool(r.status == "unbounded")

    def independent(outer: bool) -> Any:
        return lambda t: independent_lambda(model(t, 16, friction), friction, sides, outer) >= 0

    t_product = _least(product, 0.03, 0.12, 2e-3)
    t_inner = _least(independent(False), 0.03, 0.12, 2e-3)
    t_outer = _least(independent(True), 0.03, 0.12, 2e-3)
    assert t_outer * (1 - 2e-3) <= t_product <= t_inner * (1 + 2e-3), (t_outer, t_product, t_inner)
    assert t_inner / t_outer - 1 < 0.02, (t_outer, t_inner)
    # thinner than the semicircular arch's least thickness, 0.1075 R (tests/arch_thickness.rs): the groins carry it
    assert t_inner < 0.1
