"""A U of dry masonry from Python, without a case file: limit analysis in 3D in four directions in plan.

Run from the repository root:

    .venv/bin/python examples/u_wall_3d.py [OUT.png]

It prints the collapse multiplier of each direction, checks the free leaf of the same slenderness against its
closed form t / H, and draws the weakest direction's mechanism (default out/u_wall_3d.png) with a VTK file of the
blocks for ParaView beside it. SI units throughout: m, N, kg, s. The same wall is examples/u-wall.toml.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import masonry_dem as md
from masonry_dem.export import write_vtk
from masonry_dem.space.plot import plot_mechanism_3d

# 1. The wall: a facade 3 m long along x (y from 0 to 0.25 m), two return walls 1.5 m deep along +y at its ends,
#    2.5 m high, of 0.5 x 0.25 m blocks 0.25 m thick; the courses interlock at the corners. The generator returns
#    an (n, 6) array of boxes [x0, y0, z0, x1, y1, z1] in m, z up.
boxes = md.u_wall(facade=3.0, height=2.5, returns=1.5, thickness=0.25, block_length=0.5, block_height=0.25)

# 2. Dry joints: friction 0.7, associative (dilatancy = friction): limit analysis gives the exact multiplier of the
#    model, with Coulomb's cone at each corner of a contact, as Model3D.solve_dynamic's explicit pushover has it
#    (3D takes dry joints in this version). A fixed base under the footprint (base=True).
joints = {"default": {"friction": 0.7, "dilatancy": 0.7}}

# 3. The horizontal load lambda * W_i on every block, along a direction in plan (degrees from +x towards +y):
#    along the facade (0, 180), towards the returns (90) and away from them (270, out of the facade's plane).
results = {}
for direction in (0.0, 90.0, 180.0, 270.0):
    model = md.Model3D(boxes, density=2000.0, joints=joints, gravity=9.81, direction=direction)
    res = model.solve_limit()
    results[direction] = (model, res)
    print(f"direction {direction:5.1f} deg: {res.status}, lambda = {res.collapse_multiplier:.4f} "
          f"({res.certificate['iterations']} iterations, {res.elapsed_s:.3f} s)")
weakest = min(results, key=lambda d: results[d][1].collapse_multiplier)
model, res = results[weakest]
print(f"{model.n_blocks} blocks, {model.n_interfaces} contacts; weakest direction {weakest:.0f} deg")

# 4. The facade alone, a free leaf of the same slenderness, overturns about its base edge at t / H.
leaf = md.Model3D(md.running_bond_3d(3.0, 2.5, 0.25, 0.5, 0.25), joints=joints, direction=270.0)
lam_leaf = leaf.solve_limit().collapse_multiplier
print(f"free leaf: lambda = {lam_leaf:.6f}, t / H = {0.25 / 2.5:.6f}")

# 5. The mechanism of the weakest direction, and the blocks with their mechanism for ParaView.
out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("out/u_wall_3d.png")
out.parent.mkdir(parents=True, exist_ok=True)
fig = plt.figure(figsize=(7, 6))
ax = fig.add_subplot(projection="3d")
plot_mechanism_3d(ax, model, res, colorbar=True)
ax.set_title(f"U wall, load at {weakest:.0f} deg: lambda = {res.collapse_multiplier:.4f}")
fig.savefig(out, dpi=120)
written = write_vtk(model, res, out.with_suffix(""))
print("wrote", out, *written)
