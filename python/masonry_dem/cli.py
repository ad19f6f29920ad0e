"""The ``masonry-dem`` command line.

    masonry-dem run CASE.toml [--method static|dynamic] [--json OUT.json] [--plot OUT.png] [--quiet]
    masonry-dem compare CASE.toml [--json OUT.json] [--plot OUT.png] [--quiet]
    masonry-dem demo [--plot OUT.png] [--json OUT.json] [--quiet]

``compare`` runs the static and then the explicit (dynamic) solver on one case and prints them side by
side (see :mod:`masonry_dem.compare`).

A progress bar (tqdm, if installed) is drawn on stderr while a solver runs, when stderr is a terminal
and ``--quiet`` is not given.

Exit status: 0 on success; 1 when an analysis fails (the solver's reason is printed, the JSON and
plot are still written) or another error occurs; 2 for bad input (an invalid case file, a missing
file, bad arguments); 130 when interrupted (Ctrl-C; ``run`` still prints and writes what was
computed, ``compare`` does not start the second method). Errors are one line on stderr, ``masonry-dem: error: ...``.
"""

from __future__ import annotations

import argparse
import os
import sys
import textwrap
from pathlib import Path
from typing import Any, Optional, Sequence

from ._core import InputError, MasonryError, __version__
from .case import Case, load_case, write_result_json
from .progress import progress_bar
from .report import summary

__all__ = ["main", "build_parser"]

PROG = "masonry-dem"
EXIT_OK, EXIT_FAILURE, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
DEMO_PLOT = os.path.join("out", "demo.png")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``masonry-dem`` (subcommands ``run``, ``compare`` and ``demo``)."""
    parser = argparse.ArgumentParser(
        prog=PROG,
        description="Nonlinear in-plane analysis of masonry walls of rigid blocks with Mohr-Coulomb joints.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(
            """\
            examples:
              masonry-dem demo                                  Ferris & Tin-Loi wall 1, plot in out/demo.png
              masonry-dem run examples/ferris-tinloi-wall1.toml --json out/wall1.json --plot out/wall1.png
              masonry-dem run CASE.toml --method dynamic         the explicit (molecular dynamics) solver
              masonry-dem compare CASE.toml --plot out/compare.png   static and dynamic side by side

            Case files are TOML (format 1, SI units); see examples/*.toml.
            exit status: 0 ok, 1 analysis failed or other error, 2 bad input (case file, arguments)."""
        ),
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    run = sub.add_parser(
        "run",
        help="run a case file",
        description="Run the analysis of a case file and print a summary "
        "(collapse multiplier, joint states, mechanism).",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(
            """\
            examples:
              masonry-dem run examples/ferris-tinloi-wall1.toml
              masonry-dem run examples/ferris-tinloi-wall2.toml --json out/wall2.json --plot out/wall2.png"""
        ),
    )
    run.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1)")
    run.add_argument(
        "--method",
        choices=("static", "dynamic"),
        help="solution method, overriding [analysis] method of the case (default: the case's, else static): "
        "static (incremental, Newton) or dynamic (explicit, molecular dynamics)",
    )
    _add_outputs(run, plot_default=None)

    compare = sub.add_parser(
        "compare",
        help="run a case with both methods and compare them",
        description=(
            "Run a case file with the static solver, then with the explicit (dynamic) one, and print them\n"
            "side by side: collapse multipliers and their relative difference, status, failed joints (open or\n"
            "sliding at collapse) of each and in common (Jaccard index), iterations and time steps, time."
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(
            """\
            examples:
              masonry-dem compare examples/single-block-rocking.toml
              masonry-dem compare examples/ferris-tinloi-wall1.toml --json out/cmp.json --plot out/cmp.png

            --json writes {"format": 1, "title", "static": <result>, "dynamic": <result>, "agreement": {...}}."""
        ),
    )
    compare.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1)")
    compare.add_argument("--json", metavar="OUT.json", help="write both results and their agreement (JSON)")
    compare.add_argument(
        "--plot",
        metavar="OUT.png",
        help="write a figure: both walls with their crack patterns, and both load curves overlaid (PNG)",
    )
    _add_quiet(compare)

    demo = sub.add_parser(
        "demo",
        help="run the built-in demo case (Ferris & Tin-Loi wall 1) and plot it",
        description=(
            "Run the built-in demo case, Ferris & Tin-Loi wall 1 (33 dry-joint blocks in running bond,\n"
            "friction 0.65, associative flow; reference collapse multiplier 0.6429), and write a plot."
        ),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(
            """\
            examples:
              masonry-dem demo
              masonry-dem demo --plot wall1.png --json wall1.json"""
        ),
    )
    _add_outputs(demo, plot_default=DEMO_PLOT)
    return parser


def _add_outputs(parser: argparse.ArgumentParser, plot_default: Optional[str]) -> None:
    parser.add_argument("--json", metavar="OUT.json", help="write the results (JSON, format 1)")
    parser.add_argument(
        "--plot",
        metavar="OUT.png",
        default=plot_default,
        help="write a figure: the wall with mechanism and joint states, and the load curve (PNG)"
        + (f"; default {plot_default}" if plot_default else ""),
    )
    _add_quiet(parser)


def _add_quiet(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        help="no progress bar (it is drawn on stderr only when that is a terminal)",
    )


def _show_progress(quiet: bool) -> bool:
    """Whether to draw a progress bar: not --quiet, and stderr is a terminal."""
    if quiet:
        return False
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):  # no stderr, or a closed one
        return False


def _solve(case: Case, model: Any, method: str, quiet: bool) -> Any:
    """Run one analysis, with a progress bar on stderr when wanted."""
    live = str(case.model_kwargs.get("live", "horizontal_weight"))
    with progress_bar(method, live=live, enabled=_show_progress(quiet)) as bar:
        return case.solve(model, method, progress=bar or None)


def _interrupted(results: Any) -> bool:
    """Whether a run was stopped by Ctrl-C (the core returns what it had, status "failed")."""
    return results.status == "failed" and "interrupted" in str(results.error or "")


def _error(message: str, status: int) -> int:
    """Print one error line on stderr and return the exit status."""
    line = " ".join(str(message).split())  # one line, whatever the message holds
    print(f"{PROG}: error: {line}", file=sys.stderr)
    return status


def _prepare(path: str) -> None:
    """Create the folder of an output file."""
    parent = Path(path).parent
    if str(parent):
        parent.mkdir(parents=True, exist_ok=True)


def _execute(
    case: Case, method: Optional[str], json_path: Optional[str], plot_path: Optional[str], quiet: bool = False
) -> int:
    """Build, solve, report and write the outputs; return the exit status (errors are raised)."""
    method = case.check_method(method)
    model = case.build_model()
    results = _solve(case, model, method, quiet)
    live = str(case.model_kwargs.get("live", "horizontal_weight"))
    print(summary(case.title, model, results, live), flush=True)

    try:
        if json_path:
            _prepare(json_path)
            write_result_json(json_path, results, model, case.title)
            print(f"  wrote {json_path}")
        if plot_path:
            from .plot import plot_results

            _prepare(plot_path)
            plot_results(model, results, title=case.title, path=plot_path, live=live)
            print(f"  wrote {plot_path}")
    except OSError as exc:
        return _error(f"cannot write {exc.filename or 'the output'}: {exc.strerror or exc}", EXIT_FAILURE)

    if _interrupted(results):
        return _error("interrupted", EXIT_INTERRUPTED)
    if results.status == "failed":
        return _error(f"the analysis failed: {results.error or 'unknown reason'}", EXIT_FAILURE)
    return EXIT_OK


def _compare(case: Case, json_path: Optional[str], plot_path: Optional[str], quiet: bool = False) -> int:
    """Run both methods on one model, print them side by side, write the outputs; return the exit status."""
    from .compare import comparison_text, write_comparison_json

    model = case.build_model()
    static = _solve(case, model, "static", quiet)
    if _interrupted(static):  # Ctrl-C during the first run: do not start the second
        raise KeyboardInterrupt
    dynamic = _solve(case, model, "dynamic", quiet)
    live = str(case.model_kwargs.get("live", "horizontal_weight"))
    print(comparison_text(static, dynamic, model, case.title, live), flush=True)

    try:
        if json_path:
            _prepare(json_path)
            write_comparison_json(json_path, static, dynamic, model, case.title)
            print(f"  wrote {json_path}")
        if plot_path:
            from .plot import plot_comparison

            _prepare(plot_path)
            plot_comparison(model, static, dynamic, title=case.title, path=plot_path, live=live)
            print(f"  wrote {plot_path}")
    except OSError as exc:
        return _error(f"cannot write {exc.filename or 'the output'}: {exc.strerror or exc}", EXIT_FAILURE)

    if _interrupted(dynamic):
        return _error("interrupted", EXIT_INTERRUPTED)
    runs = (("static", static), ("dynamic", dynamic))
    failed = [f"{name}: {res.error or 'unknown reason'}" for name, res in runs if res.status == "failed"]
    if failed:
        return _error("the analysis failed (" + "; ".join(failed) + ")", EXIT_FAILURE)
    return EXIT_OK


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line with ``argv`` (default: ``sys.argv[1:]``); return the exit status."""
    args = build_parser().parse_args(argv)
    try:
        if args.command in ("run", "compare"):
            try:
                case = load_case(args.case)
            except OSError as exc:
                return _error(f"cannot read {args.case}: {exc.strerror or exc}", EXIT_INPUT)
            if args.command == "compare":
                return _compare(case, args.json, args.plot, args.quiet)
            return _execute(case, args.method, args.json, args.plot, args.quiet)
        from .default_case import default_case

        return _execute(default_case(), None, args.json, args.plot, args.quiet)
    except InputError as exc:
        return _error(str(exc), EXIT_INPUT)
    except MasonryError as exc:
        return _error(str(exc), EXIT_FAILURE)
    except KeyboardInterrupt:
        return _error("interrupted", EXIT_INTERRUPTED)


if __name__ == "__main__":
    sys.exit(main())
