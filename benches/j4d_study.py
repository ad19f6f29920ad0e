"""The J4D shear wall study behind examples/j4d-shear-wall.toml and docs/j4d.md.

Runs the case as given (softening joints, beam held vertically), then the variants: the brittle joint law,
the beam free to rise under a constant vertical force, and the joint stiffness of Lourenco's calibration
without the rigid brick's elasticity in series. It prints a table and draws the curves over the experiment.

    .venv/bin/python benches/j4d_study.py [--plot docs/j4d.png] [--explicit-stages 40]
"""

from __future__ import annotations

import argparse
import copy
import time
from pathlib import Path

import numpy as np

import masonry_dem as md

CASE = Path(__file__).resolve().parent.parent / "examples" / "j4d-shear-wall.toml"
PEAK, AT_3MM = 57e3, 35e3  # experimental figures of docs/references.md, section 3 [N]


def variant(case: md.Case, *, brittle: bool = False, free: bool = False, lourenco_k: bool = False) -> md.Case:
    c = copy.deepcopy(case)
    kw = c.model_kwargs
    joints = kw["joints"]
    if brittle:
        for law in joints.values():
            law.pop("fracture_energy_tension", None)
            law.pop("fracture_energy_shear", None)
    if free:
        kw["top_vertical"] = "free"
    if lourenco_k:  # the interface stiffness of a model with elastic bricks, used as is
        joints["default"].update(normal_stiffness=82e9, shear_stiffness=36e9)
        joints["head"].update(normal_stiffness=82e9, shear_stiffness=36e9)
    return c


def beam_reaction(model, res) -> float:
    """The vertical force on the beam [N] in the last converged state."""
    t = model.top_index
    f = np.asarray(res.interface_forces)
    ib = np.asarray(model.interface_blocks)
    return float(-f[(ib[:, 0] == t) | (ib[:, 1] == t), 0].sum())


def run(case: md.Case, method: str, stages: int | None = None):
    model = case.build_model()
    kw = case.solver_kwargs(method)
    if stages:
        kw["steps"] = stages
    t0 = time.perf_counter()
    solve = model.solve_static if method == "static" else model.solve_dynamic
    res = solve(**kw)
    dt = time.perf_counter() - t0
    u = (np.asarray(res.curve_displacement) - res.curve_displacement[0]) * 1e3
    h = np.asarray(res.curve_multiplier)
    return model, res, u, h, dt


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--plot", default=None, help="write the curves to this PNG")
    ap.add_argument("--explicit-stages", type=int, default=40, help="displacement stages of the explicit run")
    a = ap.parse_args()
    base = md.load_case(CASE)
    rows = [
        ("softening, beam held (the example)", base, "static", None),
        ("softening, beam held, explicit solver", base, "dynamic", a.explicit_stages),
        ("brittle, beam held", variant(base, brittle=True), "static", None),
        ("softening, vertical force constant", variant(base, free=True), "static", None),
        ("brittle, vertical force constant", variant(base, brittle=True, free=True), "static", None),
        ("softening, beam held, kN = 82, kT = 36 N/mm3", variant(base, lourenco_k=True), "static", None),
    ]
    print(f"{'variant':46s} {'status':9s} {'peak kN':>8s} {'at mm':>6s} {'error':>7s} {'3 mm kN':>8s} {'N end kN':>9s} {'time s':>7s}")
    curves = []
    for name, case, method, stages in rows:
        model, res, u, h, dt = run(case, method, stages)
        k = int(np.argmax(h))
        j = int(np.searchsorted(u, 3.0 - 1e-9))
        at3 = f"{h[j] / 1e3:8.2f}" if j < len(u) else f"{'-':>8s}"
        err = (h[k] - PEAK) / PEAK
        print(f"{name:46s} {res.status:9s} {h[k] / 1e3:8.2f} {u[k]:6.2f} {err:+7.1%} {at3} {beam_reaction(model, res) / 1e3:9.2f} {dt:7.1f}")
        curves.append((name, u, h))
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
        styles = ["-", "--", "-", "-", "-", ":"]
        for (name, u, h), ls in zip(curves, styles):
            ax.plot(u, h / 1e3, ls, label=name, lw=1.6)
        ax.plot([1.0], [PEAK / 1e3], "k*", ms=14, label="experiment: peak about 57 kN near 1 mm")
        ax.plot([3.0], [AT_3MM / 1e3], "kX", ms=10, label="experiment: about 35 kN at 3 mm")
        ax.axhspan(0.85 * PEAK / 1e3, 1.15 * PEAK / 1e3, color="0.9", zorder=0, label="57 kN +-15%")
        ax.set_xlabel("horizontal displacement of the top beam [mm]")
        ax.set_ylabel("horizontal force on the top beam H [kN]")
        ax.set_title("J4D shear wall (Raijmakers & Vermeltfoort): rigid blocks, Mohr-Coulomb joints")
        ax.set_xlim(0, 4)
        ax.set_ylim(0, 75)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
        Path(a.plot).parent.mkdir(parents=True, exist_ok=True)
        fig.savefig(a.plot, dpi=120)
        print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
