"""Both solvers side by side on the benchmark walls, as a Markdown table for BENCHMARKS.md.

    .venv/bin/python benches/compare_methods.py            # after `make develop`

Default options of each solver: static load control with precision 1e-4, explicit bracket 1e-3 with local damping
0.8 and an unbalanced-force ratio of 1e-5. Times are the solvers' own (Results.elapsed_s), on
one thread for the explicit solver (the walls are too small for two to pay)."""

from pathlib import Path

import masonry_dem as md
from masonry_dem.compare import agreement

ROOT = Path(__file__).resolve().parents[1]
CASES = [
    ("Ferris & Tin-Loi wall 1, associative", "ferris-tinloi-wall1.toml", {"dilatancy": 0.65}),
    ("Ferris & Tin-Loi wall 2, associative", "ferris-tinloi-wall2.toml", {"dilatancy": 0.65}),
    ("Ferris & Tin-Loi wall 2, non-associative", "ferris-tinloi-wall2.toml", {"dilatancy": 0.0}),
    ("LACT3 wall, openings, phi = 26 deg", "lact3-tilting-wall.toml", {}),
]


def main():
    print(
        "| wall | blocks | static lambda | iterations | static time | explicit lambda | time steps "
        "| explicit time | difference | failed joints static / explicit / common |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, path, law in CASES:
        case = md.load_case(ROOT / "examples" / path)
        kw = dict(case.model_kwargs)
        joints = {k: dict(v) for k, v in (kw.get("joints") or {}).items()}
        for fam in joints.values():
            fam.update(law)
        kw["joints"] = joints
        model = md.Model(**kw)
        s = model.solve_static()
        d = model.solve_dynamic(threads=1)
        a = agreement(s, d)
        diff = 100 * a["multiplier_relative_difference"]
        print(
            f"| {name} | {model.n_blocks} | {s.collapse_multiplier:.4f} | {s.iterations} | {s.elapsed_s:.3f} s "
            f"| {d.collapse_multiplier:.4f} | {d.iterations} | {d.elapsed_s:.1f} s | {diff:+.2f}% "
            f"| {a['failed_static']} / {a['failed_dynamic']} / {a['failed_common']} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
