"""Ferris & Tin-Loi wall 1 from Python, without a case file: static and explicit solvers side by side.

Run from the repository root:

    .venv/bin/python examples/script_example.py [OUT.png]

It prints both collapse multipliers, how far they agree, and writes a figure (default out/script_example.png).
SI units throughout: m, N, Pa, kg, s. Reference (docs/references.md, section 2): 0.6429 with associative flow.
"""

import sys
from pathlib import Path

import masonry_dem as md
from masonry_dem.compare import agreement
from masonry_dem.plot import plot_comparison

# 1. The wall: 0.4 x 0.175 m blocks in running bond, 6 courses, 2.0 m long (33 blocks; the lowest course starts
#    with a half block). The generator returns an (n, 4) array of rectangles [x0, y0, x1, y1] in m.
blocks = md.running_bond(block_length=0.4, block_height=0.175, courses=6, length=2.0, first_course="half")

# 2. The model: 1 m thick, 1000 kg/m3, on a fixed base (base=True), g = 10 m/s2 as in the paper.
#    Dry joints: friction 0.65, no cohesion nor tensile strength, associative flow (dilatancy = friction).
#    The stiffnesses [N/m3] are a penalty: the collapse load does not depend on them.
dry_joint = {
    "normal_stiffness": 1e10,
    "shear_stiffness": 1e10,
    "friction": 0.65,
    "cohesion": 0.0,
    "tensile_strength": 0.0,
    "dilatancy": 0.65,
}
model = md.Model(
    blocks,
    thickness=1.0,
    density=1000.0,
    base=True,
    joints={"default": dry_joint},
    gravity=10.0,
    live="horizontal_weight",  # the live load: lambda * W_i horizontally on every block, towards +x
)
print(f"{model.n_blocks} blocks, {model.n_interfaces} interfaces")

# 3. Raise lambda until collapse, with the static solver (Newton) and then the explicit one (molecular
#    dynamics with local damping; a few seconds on this wall).
static = model.solve_static(control="load")
dynamic = model.solve_dynamic(control="load")

# 4. Both multipliers, and their agreement: relative difference of the multipliers and how many failed
#    (open or sliding) joints the two collapse patterns share (Jaccard index).
agree = agreement(static, dynamic)
print(f"static   : {static.status}, lambda = {static.collapse_multiplier:.4f} ({static.elapsed_s:.2f} s)")
print(f"explicit : {dynamic.status}, lambda = {dynamic.collapse_multiplier:.4f} ({dynamic.elapsed_s:.2f} s)")
print(f"difference {100 * agree['multiplier_relative_difference']:+.2f}%, failed joints in common: "
      f"{agree['failed_common']} of {agree['failed_static']} / {agree['failed_dynamic']} "
      f"(Jaccard {agree['jaccard']:.2f})")
print(f"reference 0.6429: static error {100 * abs(static.collapse_multiplier / 0.6429 - 1):.2f}%")

# 5. A figure: both walls with their mechanisms and joint states, and the two load curves overlaid.
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out") / "script_example.png"
out.parent.mkdir(parents=True, exist_ok=True)
plot_comparison(model, static, dynamic, title="Ferris & Tin-Loi wall 1", path=out)
print(f"wrote {out}")
