"""Our 3D limit analysis and explicit solver side by side with a peer, LMGC90 (non-smooth contact dynamics), on two
dry-joint walls.

Run, from the repository's root, in a venv where `make develop` built masonry_dem:

    pip install compas-lmgc90            # the PyPI wheel (0.1.11 tested) binding LMGC90's 3D rigid-body solver
    python benches/peer_lmgc90.py        # both walls, about 3 minutes on 2 cores
    python benches/peer_lmgc90.py --wall wall1 --verbose     # one wall, each LMGC90 run logged

What it measures, for each wall:

* ours: `Model3D(boxes, joints={"default": {"friction": mu, "dilatancy": mu}}).solve_limit()`, the collapse
  multiplier of the associative model with Coulomb's cone (a second-order cone program), and its own
  time (Results.elapsed_s); the explicit solver's quasi-static pushover (`solve_dynamic()`, load control, Coulomb's
  cone itself) with the same joints, and with dilatancy 0, LMGC90's law (its time: Results.elapsed_s; joints of
  1e9 N/m3).
* LMGC90: the same boxes as rigid polyhedra (POLYR) on a fixed base box (the footprint box our Model3D puts under
  the wall), density 2000 kg/m3, contact law IQS_CLB (Signorini with inelastic shocks, Coulomb friction mu,
  no cohesion), theta = 0.5, time step 1e-3 s. The live load is a force lambda * m_i * g on each block's centre
  of mass along the push direction, held constant. Each load level is a fresh simulation from the wall at rest:
  gravity and lambda * weight applied together at t = 0 and held for 0.5 s. A level *collapses* when, at the end
  of the hold, the fastest block moves faster than 1 mm/s and no slower than at half the hold (motion that
  grows, not a settling that dies out), or as soon as a block has moved 20 mm. The bracket [last stable, first
  collapsing] starts at [0, 1] (both checked: the wall stands under gravity alone, and falls at lambda = 1) and
  is halved until narrower than 0.005. Time is the wall-clock of all the LMGC90 runs (set-up included), steps
  their time steps added up.

The walls, both from our generators:

* wall1: Ferris & Tin-Loi wall 1 (running_bond(0.4, 0.175, 6, 2.0, "half"), 33 blocks) extruded to 3D, one block
  through a thickness of 1.0 m (the 2D model's unit thickness), friction 0.65, pushed in its plane (+x,
  direction 0). Reference 0.6429 (associative); 0.640 non-associative.
* u_wall: u_wall(3.0, 2.5, 1.5, 0.25, 0.5, 0.25), a 3 m facade 2.5 m high with 1.5 m returns, 0.25 m thick, blocks
  0.5 x 0.25 m, 115 blocks, friction 0.7, pushed out of the facade's plane away from the returns (-y, direction
  270). Ours 0.2960.

The explicit solver with dilatancy 0 takes LMGC90's law (Coulomb friction without dilatancy); the last column
compares them. Limit analysis differs in what it assumes: it is associative (dilatancy = friction: a joint may
slide only while it opens by at least friction times the slip), contact dynamics has Coulomb friction without
dilatancy (non-associative: a joint that opens carries nothing, however it slides), which can only lower the
collapse load. It also sees inertia, and its multiplier depends a little on the hold time, the collapse threshold
and the time step (--hold, --speed, --dt to check; on the U wall dt = 5e-4 agrees at 0.27 and 0.275, and 2e-3
calls 0.27 a collapse).

The figures and what they show are in BENCHMARKS.md ("Limit analysis in 3D").

LMGC90's own solver settings are fixed inside the compas_lmgc90 wheel and not reachable from Python: non-linear
Gauss-Seidel with tolerance 1.666e-4 on the QM/16 norm, relaxation 0.1, at most 50 x 500 iterations a step,
gravity 9.81 m/s2 along -z, contact detection 'STO' (the alert distance, 1e-3 m, is set here). Gravity is
measured from the base's reactions in the lambda = 0 run, and the horizontal forces use that value.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

import masonry_dem as md

DENSITY = 2000.0  # [kg/m3], both solvers (the multiplier does not depend on it)
ALERT = 1e-3  # [m] LMGC90's contact detection distance

# The six faces of a box with corners numbered (x0y0z0, x1y0z0, x1y1z0, x0y1z0, then the same at z1), wound outwards.
BOX_FACES = [[3, 2, 1, 0], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]


def wall1_boxes(thickness=1.0):
    """Ferris & Tin-Loi wall 1 extruded along y: (33, 6) boxes [x0, y0, z0, x1, y1, z1]."""
    rects = np.asarray(md.running_bond(0.4, 0.175, 6, 2.0, "half"), dtype=float)
    n = len(rects)
    return np.column_stack([rects[:, 0], np.zeros(n), rects[:, 1], rects[:, 2], np.full(n, thickness), rects[:, 3]])


def u_wall_boxes():
    return np.asarray(md.u_wall(3.0, 2.5, 1.5, 0.25, 0.5, 0.25), dtype=float)


CASES = [
    # name, boxes, friction, gravity of our model [m/s2], push direction in plan [deg]
    ("wall1", "Ferris & Tin-Loi wall 1, 3D, in plane", wall1_boxes, 0.65, 10.0, 0.0),
    ("u_wall", "U wall 3 x 2.5 m, returns 1.5 m, out of plane", u_wall_boxes, 0.7, 9.81, 270.0),
]


def ours(boxes, friction, gravity, direction, dilatancy=None, method="limit"):
    dilatancy = friction if dilatancy is None else dilatancy
    joint = {"friction": friction, "dilatancy": dilatancy, "normal_stiffness": 1e9, "shear_stiffness": 1e9}
    model = md.Model3D(boxes, density=DENSITY, joints={"default": joint}, gravity=gravity, direction=direction)
    res = model.solve_limit() if method == "limit" else model.solve_dynamic()
    base = np.asarray(model.boxes)[model.base_index]
    return res, base


def _multiplier(res):
    """The collapse multiplier, or the last equilibrium marked with the status where there is no collapse."""
    if res.status == "collapse":
        return f"{res.collapse_multiplier:.4f}"
    return f"{res.last_equilibrium:.4f} ({res.status})"


# --------------------------------------------------------------------------------------------------------------------
# LMGC90 through compas_lmgc90


def _box_mesh(b):
    x0, y0, z0, x1, y1, z1 = (float(v) for v in b)
    vertices = [
        [x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
        [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1],
    ]  # fmt: skip
    return {"vertices": vertices, "faces": BOX_FACES}


class Lmgc90Level:
    """One LMGC90 simulation of the wall at rest under gravity plus lambda times each block's weight, held."""

    def __init__(self, boxes, base, friction, direction, *, dt, hold, speed, stop_disp, g_horizontal):
        self.boxes = np.asarray(boxes, dtype=float)
        self.base = base
        self.friction = friction
        self.direction = direction
        self.dt = dt
        self.hold = hold
        self.speed = speed
        self.stop_disp = stop_disp
        self.g_horizontal = g_horizontal

    def run(self, lam):
        """Returns a dict: collapsed, max displacement, speeds at mid-hold and at the end, steps, seconds, g."""
        from compas_lmgc90.solver import Solver

        t0 = time.perf_counter()
        volumes = np.prod(self.boxes[:, 3:] - self.boxes[:, :3], axis=1)
        solver = Solver(dt=self.dt, theta=0.5, density=DENSITY)
        solver.geometry_from_v_f([_box_mesh(self.base)] + [_box_mesh(b) for b in self.boxes])
        # the base (body 0) is fixed: its six velocities are driven to zero
        solver.v_drvdof[0] = {dof: np.zeros((1, 6)) for dof in range(1, 7)}
        ux, uy = math.cos(math.radians(self.direction)), math.sin(math.radians(self.direction))
        if lam != 0.0:
            for i, vol in enumerate(volumes):
                force = lam * DENSITY * vol * self.g_horizontal
                if abs(ux) > 1e-12:
                    solver.apply_force(i + 1, "Fx", float(force * ux))
                if abs(uy) > 1e-12:
                    solver.apply_force(i + 1, "Fy", float(force * uy))
        solver.contact_law("IQS_CLB", self.friction, alert=ALERT)
        solver.preprocess()
        x0 = np.array(solver.lmgc90.get_initial_state().bodies, dtype=float)[1:]

        n_steps = int(round(self.hold / self.dt))
        window = max(1, int(round(0.05 / self.dt)))  # speeds are taken over 0.05 s
        mid = n_steps // 2
        samples = {}
        disp = 0.0
        steps = 0
        result = None
        for k in range(1, n_steps + 1):
            result = solver.lmgc90.compute_one_step()
            steps = k
            if k in (mid - window, mid, n_steps - window, n_steps) or k % window == 0:
                x = np.array(result.bodies, dtype=float)[1:]
                samples[k] = x
                disp = float(np.linalg.norm(x - x0, axis=1).max())
                if disp > self.stop_disp:
                    break

        def speed(k):
            if k in samples and k - window in samples:
                return float(np.linalg.norm(samples[k] - samples[k - window], axis=1).max() / (window * self.dt))
            return math.nan

        g_measured = math.nan
        if lam == 0.0 and result is not None:
            # the base's vertical reaction over the wall's mass: the gravity LMGC90 applies
            bodies = np.asarray(result.interaction_bodies)
            forces = np.asarray(result.interaction_force_global, dtype=float)
            on_base = (bodies == 1).any(axis=1)
            g_measured = abs(forces[on_base, 2].sum()) / (DENSITY * volumes.sum())
        solver.finalize()
        elapsed = time.perf_counter() - t0

        if disp > self.stop_disp:
            collapsed, v_mid, v_end = True, math.nan, math.nan
        else:
            v_mid, v_end = speed(mid), speed(n_steps)
            collapsed = v_end > self.speed and v_end >= v_mid
        return {
            "lam": lam,
            "collapsed": collapsed,
            "disp": disp,
            "v_mid": v_mid,
            "v_end": v_end,
            "steps": steps,
            "seconds": elapsed,
            "g": g_measured,
        }


def lmgc90_bracket(boxes, base, friction, direction, *, dt, hold, speed, stop_disp, tol, verbose):
    """Bisects lambda between a standing and a falling level. Returns (lo, hi, seconds, steps, runs, g)."""
    level = Lmgc90Level(
        boxes, base, friction, direction, dt=dt, hold=hold, speed=speed, stop_disp=stop_disp, g_horizontal=9.81
    )
    total_s, total_steps, runs = 0.0, 0, 0

    def check(lam):
        nonlocal total_s, total_steps, runs
        out = level.run(lam)
        total_s += out["seconds"]
        total_steps += out["steps"]
        runs += 1
        if verbose:
            print(
                f"    lambda {lam:.5f}: {'collapses' if out['collapsed'] else 'stands   '}  max displacement "
                f"{out['disp']:.2e} m, speed mid {out['v_mid']:.1e} end {out['v_end']:.1e} m/s, "
                f"{out['steps']} steps, {out['seconds']:.1f} s",
                file=sys.stderr,
                flush=True,
            )
        return out

    first = check(0.0)
    g = first["g"]
    if first["collapsed"]:
        raise RuntimeError("LMGC90: the wall does not stand under gravity alone")
    if math.isfinite(g) and g > 0:
        level.g_horizontal = g
    lo, hi = 0.0, 1.0
    while not check(hi)["collapsed"]:
        lo, hi = hi, 2 * hi
        if hi > 8:
            raise RuntimeError("LMGC90: no collapse up to lambda = 8")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if check(mid)["collapsed"]:
            hi = mid
        else:
            lo = mid
    return lo, hi, total_s, total_steps, runs, g


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--wall", choices=[c[0] for c in CASES] + ["all"], default="all")
    ap.add_argument("--dt", type=float, default=1e-3, help="LMGC90 time step [s] (default 1e-3)")
    ap.add_argument("--hold", type=float, default=0.5, help="time each load level is held [s] (default 0.5)")
    ap.add_argument("--speed", type=float, default=1e-3, help="collapse: end speed above this [m/s] (default 1e-3)")
    ap.add_argument("--stop", type=float, default=0.02, help="collapse: a block moved this far [m] (default 0.02)")
    ap.add_argument("--tol", type=float, default=0.005, help="width of LMGC90's final bracket (default 0.005)")
    ap.add_argument("--verbose", action="store_true", help="log every LMGC90 run on stderr")
    args = ap.parse_args(argv)

    try:
        import compas_lmgc90  # noqa: F401
    except ImportError:
        compas_lmgc90 = None
        print("compas_lmgc90 is not installed (pip install compas-lmgc90): showing ours only.", file=sys.stderr)

    print(
        "| wall | blocks | limit analysis | explicit | explicit, dilatancy 0 | LMGC90: lambda bracket | LMGC90: time "
        "| LMGC90: steps (runs) | difference (explicit, dilatancy 0) |"
    )
    print("|---|---|---|---|---|---|---|---|---|", flush=True)
    for key, name, make, friction, gravity, direction in CASES:
        if args.wall not in ("all", key):
            continue
        boxes = make()
        res, base = ours(boxes, friction, gravity, direction)
        ex, _ = ours(boxes, friction, gravity, direction, method="dynamic")
        ex0, _ = ours(boxes, friction, gravity, direction, dilatancy=0.0, method="dynamic")
        # LMGC90's law is Coulomb's without dilatancy: the explicit solver's with dilatancy 0 is the one to compare
        lam = ex0.collapse_multiplier if ex0.status == "collapse" else ex0.last_equilibrium
        row = (
            f"| {name} | {len(boxes)} | {_multiplier(res)} in {res.elapsed_s:.3f} s | {_multiplier(ex)} in "
            f"{ex.elapsed_s:.2f} s | {_multiplier(ex0)} in {ex0.elapsed_s:.2f} s "
        )
        if compas_lmgc90 is None:
            print(row + "| n/a | n/a | n/a | n/a |", flush=True)
            continue
        if args.verbose:
            print(f"  {name}: LMGC90 runs", file=sys.stderr, flush=True)
        lo, hi, secs, steps, runs, g = lmgc90_bracket(
            boxes,
            base,
            friction,
            direction,
            dt=args.dt,
            hold=args.hold,
            speed=args.speed,
            stop_disp=args.stop,
            tol=args.tol,
            verbose=args.verbose,
        )
        if args.verbose:
            print(f"  LMGC90 gravity measured from the base's reactions: {g:.4f} m/s2", file=sys.stderr)
        mid = 0.5 * (lo + hi)
        inside = "ours inside" if lo <= lam <= hi else "ours outside"
        print(
            row + f"| [{lo:.4f}, {hi:.4f}] | {secs:.1f} s | {steps} ({runs}) "
            f"| {100 * (mid - lam) / lam:+.1f}% (midpoint; {inside}) |",
            flush=True,
        )


if __name__ == "__main__":
    main()
