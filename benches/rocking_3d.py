"""Free rocking of a block in 3D against the same block in the plane and Housner's model: the impact times, and a
figure of the two rotation histories.

Run, from the repository's root, in a venv where `make develop` built masonry_dem:

    python benches/rocking_3d.py docs/rocking-3d.png

The block: 0.4 m wide, 1.0 m high (0.4 m deep in 3D), on a fixed base, friction 2 (it rocks without sliding), the
default restitution; released at rest, tilted by half its slenderness about its left toe (about the -y axis in
3D), for 1.7 s. The plane's rocking test (tests/rocking.rs) holds these impacts within 2% of Housner's; the 3D
test (tests/space_explicit.rs) holds the 3D block's within 2% of the plane's. Housner's reference here is the
exact rocking equation with its own restitution 1 - 1.5 sin^2(alpha), integrated by RK4.
"""

from __future__ import annotations

import math
import sys

import numpy as np

import masonry_dem as md

B, H, D, G = 0.4, 1.0, 0.4, 9.81
JOINTS = {"default": {"friction": 2.0}}


def tilt(th0: float) -> tuple[float, float]:
    """The centroid's displacement (horizontal, vertical) of the block turned by th0 about its left toe."""
    r = (B / 2, H / 2)
    c, s = math.cos(th0), math.sin(th0)
    return c * r[0] - s * r[1] - r[0], s * r[0] + c * r[1] - r[1]


def sign_changes(t: np.ndarray, x: np.ndarray) -> list[float]:
    k = np.nonzero((x[:-1] != 0) & (x[:-1] * x[1:] < 0))[0]
    return [float(t[i] + (t[i + 1] - t[i]) * x[i] / (x[i] - x[i + 1])) for i in k]


def housner(th0: float, t_end: float, h: float = 1e-5) -> list[float]:
    alpha = math.atan(B / H)
    p2 = 3 * G / (4 * 0.5 * math.hypot(B, H))
    r = 1 - 1.5 * math.sin(alpha) ** 2
    th, w, t, out = th0, 0.0, 0.0, []

    def acc(th: float) -> float:
        return -p2 * math.sin(alpha * math.copysign(1.0, th) - th)

    while t < t_end:
        k1 = (w, acc(th))
        k2 = (w + 0.5 * h * k1[1], acc(th + 0.5 * h * k1[0]))
        k3 = (w + 0.5 * h * k2[1], acc(th + 0.5 * h * k2[0]))
        k4 = (w + h * k3[1], acc(th + h * k3[0]))
        th1 = th + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        w1 = w + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        if th1 * th < 0:
            s = th / (th - th1)
            t, th, w = t + s * h, 0.0, r * (w + s * (w1 - w))
            out.append(t)
            th = 1e-15 * math.copysign(1.0, w)
            continue
        t, th, w = t + h, th1, w1
    return out


def main(png: str | None) -> None:
    th0 = 0.5 * math.atan(B / H)
    dx, dz = tilt(th0)
    plane = md.Model([[0.0, 0.0, B, H]], joints=JOINTS, gravity=G)
    h2 = plane.simulate(1.7, initial_displacements=[[dx, dz, th0], [0.0, 0.0, 0.0]], record_every=1)
    space = md.Model3D([[0.0, 0.0, 0.0, B, D, H]], joints=JOINTS, gravity=G)
    h3 = space.simulate(1.7, initial_displacements=[[dx, 0.0, dz, 0.0, -th0, 0.0], [0.0] * 6], record_every=1)
    phi2 = h2.displacements[:, 0, 2]
    phi3 = -h3.displacements[:, 0, 4]
    t2, t3 = sign_changes(h2.times, phi2), sign_changes(h3.times, phi3)
    ref = housner(th0, 1.7)
    print("| impact | Housner [s] | plane [s] | 3D [s] | 3D against the plane |")
    print("|---|---|---|---|---|")
    for k in range(min(5, len(t2), len(t3), len(ref))):
        print(f"| {k + 1} | {ref[k]:.4f} | {t2[k]:.4f} | {t3[k]:.4f} | {100 * (t3[k] / t2[k] - 1):+.2f}% |")
    print(f"time steps: plane {h2.steps} in {h2.elapsed_s:.3f} s, 3D {h3.steps} in {h3.elapsed_s:.3f} s")
    if png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 3.6), layout="constrained")
        ax.plot(h2.times, phi2, lw=2.5, color="0.75", label="plane (Model.simulate)")
        ax.plot(h3.times, phi3, lw=1.0, color="C3", label="3D, about -y (Model3D.simulate)")
        for k, t in enumerate(ref[:5]):
            ax.axvline(t, color="C0", lw=0.6, ls=":", label="Housner's impacts" if k == 0 else None)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("rotation [rad]")
        ax.set_title("Free rocking of a 0.4 x 1.0 m block released from half its slenderness")
        ax.legend(loc="upper right", fontsize=8)
        fig.savefig(png, dpi=110)
        print(f"wrote {png}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
