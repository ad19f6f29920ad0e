"""The cost of the contact update in a 3D time history: a wall of about 10^3 boxes shaken along x and y by the
El Centro record, with contact_update on and off, side by side (a run that forms no new contact: the cost of the
check per step and of the searches).

Run, from the repository's root, in a venv where `make develop` built masonry_dem:

    python benches/space_contact_update.py [--duration 0.5] [--repeats 3] [--scale 1.0] [--threads 1]

The wall: a single leaf in running bond, 12 m long, 8 m high, 0.4 m thick, of 0.4 x 0.2 m blocks (1,230 boxes), dry
joints of friction 0.65 and 1e10 N/m3 (as the plane's benchmark, benches/contact_update.py), on a fixed base; the record examples/elcentro-1940-ns.csv (in g at 0.02 s)
times --scale along x and half of it along y, its first --duration seconds. Each repeat runs the two one after the
other (on, off), both at the time step of the run with the update (stable for a block touching along every face),
so that the ratio is the update's own cost; the medians of the solver's own wall-clock time
(TimeHistory.elapsed_s) are printed with their ratio, and the largest difference of the two runs' displacements.
"""

from __future__ import annotations

import masonry_dem as md
from contact_update import JOINTS, arguments, record, side_by_side  # the plane's benchmark, beside this script


def main() -> None:
    args = arguments(__doc__, 0.5)
    boxes = md.running_bond_3d(12.0, 8.0, 0.4, 0.4, 0.2, "half")
    model = md.Model3D(boxes, density=1000.0, joints=JOINTS)
    t, a = record(args.duration, args.scale)
    ground = {"base_acceleration": (t, a), "base_acceleration_y": (t, 0.5 * a)}
    on, off, runs, diff = side_by_side(lambda update, step: model.simulate(
        args.duration, time_step=step, record_interval=0.01, threads=args.threads, contact_update=update, **ground),
        args.repeats)
    print(f"{len(boxes)} blocks, {args.duration} s of El Centro x {args.scale}, {args.threads} thread(s), "
          f"{args.repeats} repeats, {runs[True].steps} steps of {runs[True].time_step:.3e} s each")
    print(f"update on:  median {on:.3f} s")
    print(f"update off: median {off:.3f} s")
    print(f"ratio on / off: {on / off:.3f}; largest difference of the displacements {diff:.3e}")


if __name__ == "__main__":
    main()
