"""Ferris & Tin-Loi wall 1 under the El Centro 1940 NS record, scaled up until the wall collapses.

Runs examples/ferris-tinloi-wall1-elcentro.toml (``Case.simulate``, as ``masonry-dem simulate`` does) at the
scales of SCALES, in order, until one collapses; prints a table of scale -> peak ground acceleration, peak drift,
peak drift across the wall, largest block rotation; writes the response figure at the collapse scale to
docs/elcentro-wall1.png and its animation to docs/elcentro-wall1.gif (kept under 2 MB).

Collapse (a definition of this script, not of the solver), at any record of the time history:

* a wall block has turned by more than ROTATION_LIMIT = 0.25 rad (14 degrees) relative to the ground: it is
  tipping over; or
* the top course has moved, on average, relative to the bottom course by more than DRIFT_LIMIT = 25% of the wall
  height (0.26 m for wall 1's 1.05 m, more than half a block length: the blocks of a course no longer rest on
  those below them); or
* two blocks have slid along their joint by more than SLIP_LIMIT = 25% of its length (the joints between wall
  blocks; the base's excepted: the wall may slide on its foundation).

The drift printed as "peak drift" is ``masonry-dem simulate``'s: the control block's (the highest block at the
right end) horizontal displacement relative to the ground over the wall height; it includes the sliding of the
whole wall on its base, which is not a collapse, hence the criterion on the drift across the wall. A run whose
solver fails (status "failed") stops the ladder without a collapse. The contacts are found again as the blocks
move (the contact update, ``Model.simulate``'s default): a block that slides off another loses their contact and
falls onto what is below; the figure stops 0.3 s after the collapse (its deformed wall drawn at the collapse), the
animation 3 s after it, the contacts the update made drawn in red.

Each run of the 31 s record takes 30 to 55 s on a 2-core machine (4.8 million steps of 6.5 us); the whole ladder
some 8 minutes. Run from the repository:  python examples/elcentro_wall1.py [--scales 1,2,4,8] [--out DIR]
(``--scales 9`` makes the figures of the collapse scale alone).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any, Dict, Optional

import numpy as np

import masonry_dem as md
from masonry_dem.plot import response_figure, write_animation
from masonry_dem.response import peaks

HERE = Path(__file__).resolve().parent
CASE = HERE / "ferris-tinloi-wall1-elcentro.toml"
DOCS = HERE.parent / "docs"

#: The scales tried, in order, until a collapse.
SCALES = (1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 12.0)
#: A wall block turned by more than this [rad] is tipping over.
ROTATION_LIMIT = 0.25
#: The top course displaced relative to the bottom course by more than this fraction of the wall height.
DRIFT_LIMIT = 0.25
#: Two blocks slid along their joint by more than this fraction of its length no longer rest on each other.
SLIP_LIMIT = 0.25
#: The largest animation written [bytes].
GIF_LIMIT = 2 * 2**20


def courses(model: Any) -> Dict[str, np.ndarray]:
    """The wall blocks of the bottom and of the top course (indices)."""
    rects = np.asarray(model.rects, dtype=np.float64)[: int(model.n_blocks)]
    return {"bottom": np.flatnonzero(np.isclose(rects[:, 1], rects[:, 1].min())),
            "top": np.flatnonzero(np.isclose(rects[:, 3], rects[:, 3].max()))}


def joint_slips(model: Any, history: Any) -> np.ndarray:
    """(k,) the largest slip of two wall blocks along their joint, relative to the joint's length, at each record:
    the tangential gap opened at the joint's centre by the blocks' rigid motions (finite rotations)."""
    pairs = np.asarray(model.interface_blocks)
    geo = np.asarray(model.interface_geometry, dtype=np.float64)
    families = np.asarray(model.interface_family)
    keep = families != "base"
    pairs, geo = pairs[keep], geo[keep]
    rects = np.asarray(model.rects, dtype=np.float64)
    centroids = np.column_stack([(rects[:, 0] + rects[:, 2]) / 2, (rects[:, 1] + rects[:, 3]) / 2])
    disp = np.asarray(history.displacements, dtype=np.float64)
    tangent = np.column_stack([geo[:, 3], -geo[:, 2]])

    def moved(block: np.ndarray) -> np.ndarray:  # (k, m, 2): where each block carries the joint's centre
        r = geo[None, :, :2] - centroids[None, block]
        phi = disp[:, block, 2]
        c, s = np.cos(phi), np.sin(phi)
        rotated = np.stack([c * r[..., 0] - s * r[..., 1], s * r[..., 0] + c * r[..., 1]], axis=-1)
        return centroids[None, block] + disp[:, block, :2] + rotated

    gap = moved(pairs[:, 1]) - moved(pairs[:, 0])
    slip = np.abs(np.einsum("kmi,mi->km", gap, tangent)) / geo[None, :, 4]
    return slip.max(axis=1) if slip.size else np.zeros(len(disp))


def assess(model: Any, history: Any) -> Dict[str, Any]:
    """The peaks of a run and whether (and when) it collapsed by the definition of the module docstring."""
    p = peaks(model, history)
    n_wall = int(model.n_blocks)
    disp = np.asarray(history.displacements, dtype=np.float64)[:, :n_wall]
    times = np.asarray(history.times, dtype=np.float64)
    rows = courses(model)
    across = (disp[:, rows["top"], 0].mean(axis=1) - disp[:, rows["bottom"], 0].mean(axis=1)) / p["wall_height"]
    rotation = np.abs(disp[:, :, 2]).max(axis=1)
    slips = joint_slips(model, history)
    over = np.flatnonzero((rotation > ROTATION_LIMIT) | (np.abs(across) > DRIFT_LIMIT) | (slips > SLIP_LIMIT))
    finite = history.status != "failed"
    return {
        "peaks": p,
        "across": float(np.abs(across).max()) if len(across) else float("nan"),
        "rotation": float(rotation.max()) if len(rotation) else float("nan"),
        "slip": float(slips.max()) if len(slips) else float("nan"),
        "collapse_time": float(times[over[0]]) if finite and len(over) else None,
    }


def main(argv: Optional[list] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scales", help="comma-separated scales (default: " + ",".join(f"{s:g}" for s in SCALES) + ")")
    parser.add_argument("--out", type=Path, default=DOCS, help="folder of elcentro-wall1.png and .gif (default docs/)")
    args = parser.parse_args(argv)
    scales = [float(s) for s in args.scales.split(",")] if args.scales else list(SCALES)

    case = md.load_case(CASE)
    model = case.build_model()
    record = case.ground_motion.horizontal
    print(f"{case.title}: {record.describe()}")
    print(f"collapse: a block turned by > {ROTATION_LIMIT} rad, the top course moved relative to the bottom one "
          f"by > {DRIFT_LIMIT:.0%} of the wall height, or two blocks slid by > {SLIP_LIMIT:.0%} of their joint")
    print(f"{'scale':>6} {'PGA [g]':>8} {'peak drift [%]':>15} {'across wall [%]':>16} {'rotation [rad]':>15} "
          f"{'joint slip [%]':>15} {'time [s]':>9}  outcome")
    collapsed = None
    for scale in scales:
        start = time.perf_counter()
        history = case.simulate(model, scale=scale)
        elapsed = time.perf_counter() - start
        a = assess(model, history)
        drift = a["peaks"]["drift"]["value"]
        outcome = ("solver failed: " + str(history.error) if history.status == "failed"
                   else f"COLLAPSE at t = {a['collapse_time']:.2f} s" if a["collapse_time"] is not None
                   else "stands")
        print(f"{scale:6g} {record.peak * scale / record.gravity:8.3f} {abs(drift) * 100 if drift is not None else float('nan'):15.3g} "
              f"{a['across'] * 100:16.3g} {a['rotation']:15.3g} {a['slip'] * 100:15.3g} {elapsed:9.1f}  {outcome}",
              flush=True)
        if history.status == "failed":
            print("stopped: the solver failed before a collapse (see its error above)")
            return 1
        if a["collapse_time"] is not None:
            collapsed = (scale, history, a)
            break
    if collapsed is None:
        print("no collapse up to the largest scale tried")
        return 0

    scale, history, a = collapsed
    # the figure and the animation show the run up to 3 s after the collapse (the model's interfaces are those of
    # the wall at rest: a block that has slid off another is still held by their interface, so what follows a
    # collapse is not to be believed); the same run again, that long
    stop = min(float(history.times[-1]), a["collapse_time"] + 3.0)
    shown = case.simulate(model, scale=scale, duration=stop)
    args.out.mkdir(parents=True, exist_ok=True)
    title = f"{case.title} x{scale:g} (PGA {record.peak * scale / record.gravity:.2f} g), collapse at {a['collapse_time']:.2f} s"
    # the figure ends just after the collapse, its deformed wall drawn at the collapse: the mechanism forming
    onset = min(stop, a["collapse_time"] + 0.3)
    figure_run = case.simulate(model, scale=scale, duration=onset)
    response_figure(model, figure_run, motion=record.scaled(scale), title=title, path=args.out / "elcentro-wall1.png",
                    at=a["collapse_time"])
    print(f"wrote {args.out / 'elcentro-wall1.png'} (0 to {onset:.1f} s)")
    gif = args.out / "elcentro-wall1.gif"
    for fps, dpi in ((10, 64), (8, 64), (8, 56), (6, 48)):  # as many frames as 2 MB allow
        write_animation(model, shown, gif, fps=fps, dpi=dpi, title=f"{case.title} x{scale:g}")
        if gif.stat().st_size <= GIF_LIMIT:
            break
    print(f"wrote {gif} ({gif.stat().st_size / 2**20:.2f} MB, 0 to {stop:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
