"""Vaults and domes of convex polyhedra against walls of boxes: limit analysis of as many blocks and contacts, and
the least thickness of finer domes.

``speed``: limit analysis of a semicircular barrel vault of 10,000 polyhedral blocks (``masonry_dem.barrel_vault``:
50 voussoirs, span 8 m, ring 0.6 m, 40 m long in courses of 0.2 m blocks staggered by half a block, on its
abutments, pushed across its axis; its multiplier the plane's arch's, printed) against a leaf of boxes in running bond of as many blocks and about as many
contacts (``masonry_dem.running_bond_3d``: 50 courses of 0.2 m cubes, 40 m long, on its base, pushed
along its length), dry associative joints mu = 0.65, g = 10; the two analyses alternate, ``--reps`` each, the models
built once, the solver's call timed; the medians side by side.

``dome``: the least thickness t / R of hemispherical domes of meridian and parallel joints under their own weight
(friction 2: no joint slides; R the middle surface's radius), by bisection on the thickness to 1e-4 with limit
analysis along gravity, for finer and finer domes (Heyman's continuous dome without hoop tension: 0.042).

    .venv/bin/python benches/vaults.py speed --reps 3
    .venv/bin/python benches/vaults.py dome
"""

from __future__ import annotations

import argparse
import time
from typing import Any, Dict

MU = 0.65


def joints(mu: float = MU) -> Dict[str, Any]:
    return {"default": {"friction": mu, "dilatancy": mu}}


def vault() -> Any:
    import masonry_dem as md

    v = md.barrel_vault("semicircular", 0.6, 50, 40.0, block_length=0.2, span=8.0)
    return md.Model3D(polyhedra=v["polyhedra"], supports=v["supports"], base=False, gravity=10.0, joints=joints())


def boxes() -> Any:
    import masonry_dem as md

    return md.Model3D(md.running_bond_3d(40.0, 10.0, 0.2, 0.2, 0.2, first_course="full"), gravity=10.0,
                      joints=joints())


def bench_speed(reps: int) -> None:
    import masonry_dem as md
    from stone_wall import alternate

    models = {"boxes": boxes(), "vault": vault()}
    for name, model in models.items():
        print(f"{name}: {model.n_blocks} blocks, {model.n_interfaces} contacts", flush=True)
    medians = alternate(models, reps)
    print(f"medians: boxes {medians['boxes']:.3f} s, vault {medians['vault']:.3f} s, "
          f"ratio {medians['vault'] / medians['boxes']:.3f}", flush=True)
    # pushed across its axis the vault is a row of arches: the plane's arch's multiplier
    a = md.arch("semicircular", 0.6, 50, span=8.0)
    arch = md.Model(a["blocks"], supports=a["supports"], base=False, gravity=10.0, joints=joints())
    print(f"the plane's arch: lambda {arch.solve_limit().collapse_multiplier:.6f}", flush=True)


def bench_dome() -> None:
    import masonry_dem as md

    for meridians, parallels in ((12, 6), (24, 12), (48, 24)):
        def stands(t: float) -> bool:
            d = md.dome("hemispherical", t, meridians, parallels, radius=1.0)
            model = md.Model3D(polyhedra=d["polyhedra"], gravity=10.0, joints=joints(2.0))
            r = model.solve_limit(along_gravity=True)
            assert r.status in ("unbounded", "no_equilibrium"), (t, r.status, r.error)
            return bool(r.status == "unbounded")

        lo, hi = 0.02, 0.08
        assert not stands(lo) and stands(hi)
        start = time.perf_counter()
        while hi - lo > 1e-4:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if stands(mid) else (mid, hi)
        print(f"{meridians} meridians x {parallels} parallels: least t / R in ({lo:.4f}, {hi:.4f}] "
              f"({time.perf_counter() - start:.1f} s)", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="bench", required=True)
    s = sub.add_parser("speed")
    s.add_argument("--reps", type=int, default=3)
    sub.add_parser("dome")
    args = parser.parse_args()
    if args.bench == "speed":
        bench_speed(args.reps)
    else:
        bench_dome()


if __name__ == "__main__":
    main()
