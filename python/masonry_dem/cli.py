"""The ``masonry-dem`` command line.

    masonry-dem run CASE.toml [--method static|dynamic|limit] [--json OUT.json] [--plot OUT.png]
                    [--vtk PREFIX] [--csv OUT.csv] [--quiet]
    masonry-dem compare CASE.toml [--json OUT.json] [--plot OUT.png] [--quiet]
    masonry-dem demo [--plot OUT.png] [--json OUT.json] [--vtk PREFIX] [--csv OUT.csv] [--quiet]
    masonry-dem validate [DIR] [--method static|dynamic|limit|both|all] [--quiet]
    masonry-dem study STUDY.toml [--scheduler ADDRESS] [--workers N] [--out OUT.parquet] [--resume]
                      [--csv OUT.csv] [--plot OUT.png] [--quiet]

``study`` runs the many analyses of a study file (docs/study-format.md) on Dask, writing one row per
analysis to a Parquet file as they finish (see :mod:`masonry_dem.study`); ``--resume`` finishes a study
that was stopped, computing only the rows missing. It exits 0 once every row is written (the rows of
failed analyses included, with their error), 130 when interrupted (the rows done are kept).

``validate`` runs every case file of DIR (default: the repository's examples/) that carries a [reference]
table and prints a table of its collapse multipliers against the reference (see :mod:`masonry_dem.validate`);
it exits 1 if any is outside its tolerance or failed.

``compare`` runs the static solver, the explicit (dynamic) one and limit analysis on one case and prints
them side by side (see :mod:`masonry_dem.compare`).

``--method limit`` is limit analysis (``Model.solve_limit``): the collapse multiplier as a linear program,
with its certificate; no load path (the curve is empty, the CSV has its header only).

Output files (--json, --csv, --vtk, --plot) are checked before the analysis: one that exists and is not a
regular file (a folder, a device, a FIFO), the case file itself, or a file given for two outputs is refused
(exit status 2). Each is written atomically (:mod:`masonry_dem.atomic`: a temporary file in its folder,
then renamed; a failure or Ctrl-C keeps the previous file), all of them before the summary is printed. A
plot name without a suffix gets ".png" ("wrote" names the file written). A closed stdout (``| head -1``) is
not an error, and a character stdout cannot show is printed as "?".

A progress bar (tqdm, if installed) is drawn on stderr while a solver runs, when stderr is a terminal
and ``--quiet`` is not given.

Exit status: 0 on success; 1 when an analysis fails or gives no collapse multiplier (status "failed",
"no_equilibrium" / "unbounded" of a limit analysis, "stalled": a static path that stopped below the
limit-analysis multiplier, or "displacement_limit": a path that left the small-displacement model with
lambda still rising; the reason is printed, the JSON and plot are still written) or another error occurs; 2 for bad input (an invalid case file, a missing
file, bad arguments); 130 when interrupted (Ctrl-C stops a solver within a fraction of a second, status
"interrupted"; ``run`` still prints and writes the result file and the CSV of what was computed, but draws
no plot and writes no VTK; ``compare`` and ``validate`` start no further run and write nothing). Errors are one line on stderr, ``masonry-dem: error: ...``.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import signal
import sys
import textwrap
from pathlib import Path
from typing import Any, Iterator, List, NoReturn, Optional, Sequence, Tuple

from ._core import InputError, MasonryError, __version__
from .case import (
    DEFAULT_REFERENCE_TOLERANCE,
    ERROR_STATUSES,
    METHODS,
    UNFINISHED_STATUSES,
    Case,
    load_case,
    write_result_json,
)
from .progress import progress_bar
from .report import summary
from .validate import METHOD_CHOICES

__all__ = ["main", "build_parser"]

PROG = "masonry-dem"
EXIT_OK, EXIT_FAILURE, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
DEMO_PLOT = os.path.join("out", "demo.png")
#: The default folder of ``masonry-dem validate``: examples/ of the repository holding this package.
EXAMPLES_DIR = Path(__file__).resolve().parents[2] / "examples"


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors on one line (the usage is for --help)."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_INPUT, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``masonry-dem`` (subcommands ``run``, ``compare``, ``demo`` and ``validate``)."""
    parser = _Parser(
        prog=PROG,
        description="Nonlinear in-plane analysis of masonry walls of rigid blocks with Mohr-Coulomb joints.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(
            """\
            examples:
              masonry-dem demo                                  Ferris & Tin-Loi wall 1, plot in out/demo.png
              masonry-dem run examples/ferris-tinloi-wall1.toml --json out/wall1.json --plot out/wall1.png
              masonry-dem run CASE.toml --method dynamic         the explicit (molecular dynamics) solver
              masonry-dem run CASE.toml --method limit           limit analysis (a linear program, certified)
              masonry-dem run CASE.toml --vtk out/w --csv out/curve.csv   ParaView files and the curve
              masonry-dem compare CASE.toml --plot out/compare.png   static, dynamic and limit side by side
              masonry-dem validate --method static              check examples/ against their reference values
              masonry-dem study examples/studies/wall1-fragility.toml --plot out/fragility.png   1,000 analyses on Dask

            Case files are TOML (format 1, SI units); see examples/*.toml.
            exit status: 0 ok, 1 analysis failed or other error, 2 bad input (case file, arguments)."""
        ),
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    _add_run(sub)
    _add_compare(sub)
    _add_demo(sub)
    _add_validate(sub)
    _add_study(sub)
    return parser


def _subcommand(sub: Any, name: str, help: str, description: str, epilog: str) -> argparse.ArgumentParser:
    """A subcommand's parser, its description and its epilog (dedented) printed as written."""
    return sub.add_parser(  # type: ignore[no-any-return]
        name,
        help=help,
        description=description,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=textwrap.dedent(epilog),
    )


def _add_run(sub: Any) -> None:
    run = _subcommand(
        sub,
        "run",
        help="run a case file",
        description="Run the analysis of a case file and print a summary "
        "(collapse multiplier, joint states, mechanism).",
        epilog="""\
            examples:
              masonry-dem run examples/ferris-tinloi-wall1.toml
              masonry-dem run examples/ferris-tinloi-wall2.toml --json out/wall2.json --plot out/wall2.png
              masonry-dem run examples/ferris-tinloi-wall1.toml --vtk out/wall1 --csv out/wall1.csv
              masonry-dem run examples/ferris-tinloi-wall1.toml --method limit --json out/wall1-limit.json

            --vtk out/wall1 writes out/wall1-blocks.vtu and out/wall1-interfaces.vtu (open them in ParaView).""",
    )
    run.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1)")
    run.add_argument(
        "--method",
        choices=METHODS,
        help="solution method, overriding [analysis] method of the case (default: the case's, else static): "
        "static (incremental, Newton), dynamic (explicit, molecular dynamics) or limit (limit analysis: "
        "a linear program; the case's other [analysis] keys are ignored)",
    )
    _add_outputs(run, plot_default=None)


def _add_compare(sub: Any) -> None:
    compare = _subcommand(
        sub,
        "compare",
        help="run a case with the three methods and compare them",
        description=(
            "Run a case file with the static solver, the explicit (dynamic) one and limit analysis, and print\n"
            "them side by side: collapse multipliers and their relative differences from the static one, status,\n"
            "failed joints (open or sliding at collapse; of the mechanism for limit analysis) of each and in\n"
            "common with the static ones (Jaccard index), iterations and time steps, time."
        ),
        epilog="""\
            examples:
              masonry-dem compare examples/single-block-rocking.toml
              masonry-dem compare examples/ferris-tinloi-wall1.toml --json out/cmp.json --plot out/cmp.png

            --json writes {"format": 1, "title", "static": <result>, "dynamic": <result>, "limit": <result>,
            "agreement": {...}}.""",
    )
    compare.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1)")
    compare.add_argument("--json", metavar="OUT.json", help="write both results and their agreement (JSON)")
    compare.add_argument(
        "--plot",
        metavar="OUT.png",
        help="write a figure: the three walls with their crack patterns, and the load curves overlaid, the "
        "limit multiplier as a horizontal line (PNG)",
    )
    _add_quiet(compare)


def _add_demo(sub: Any) -> None:
    demo = _subcommand(
        sub,
        "demo",
        help="run the built-in demo case (Ferris & Tin-Loi wall 1) and plot it",
        description=(
            "Run the built-in demo case, Ferris & Tin-Loi wall 1 (33 dry-joint blocks in running bond,\n"
            "friction 0.65, associative flow; reference collapse multiplier 0.6429), and write a plot."
        ),
        epilog="""\
            examples:
              masonry-dem demo
              masonry-dem demo --plot wall1.png --json wall1.json""",
    )
    _add_outputs(demo, plot_default=DEMO_PLOT)


def _add_validate(sub: Any) -> None:
    validate = _subcommand(
        sub,
        "validate",
        help="run every case with a reference value and check it",
        description=(
            "Run every case file (*.toml) of DIR that carries a [reference] table with the static solver, the\n"
            "explicit one and/or limit analysis, and print a table: case, reference (with its relative\n"
            "tolerance), static, explicit and limit collapse multipliers, error (the largest relative error),\n"
            "time of each method, verdict. Case files without a [reference] table are skipped and listed."
        ),
        epilog=f"""\
            examples:
              masonry-dem validate                       examples/ of the repository, the three methods
              masonry-dem validate --method static       the static solver only (a second or so)
              masonry-dem validate --method both         the static and the explicit solver
              masonry-dem validate my-cases/ --method dynamic

            [reference] table of a case file:
              collapse_multiplier = 0.6429   # a force in N with live = "top_horizontal"
              tolerance = 0.01               # relative, 0 < x < 1 (default {DEFAULT_REFERENCE_TOLERANCE:g})
              source = "where the value comes from"
            exit status: 0 all within tolerance, 1 one is outside its tolerance or failed, 2 bad input.""",
    )
    validate.add_argument(
        "directory",
        metavar="DIR",
        nargs="?",
        help=f"folder of case files (default: the repository's examples/, {EXAMPLES_DIR})",
    )
    validate.add_argument(
        "--method",
        choices=METHOD_CHOICES,
        default="all",
        help="the methods to run: static, dynamic (explicit), limit (limit analysis), both (static and "
        "dynamic) or all three (default)",
    )
    _add_quiet(validate)


def _add_study(sub: Any) -> None:
    what = (
        "Run every analysis of a study file (a base case, a grid or random samples of its parameters,\n"
        "textures, the load direction; docs/study-format.md) on Dask, one row per analysis in a Parquet file\n"
        "written as they finish, and print a summary of the collapse multipliers."
    )
    examples = """\
            examples:
              masonry-dem study examples/studies/wall1-fragility.toml --plot out/fragility.png
              masonry-dem study study.toml --workers 8 --out out/s.parquet --resume   finish a stopped study
              masonry-dem study study.toml --scheduler tcp://10.0.0.5:8786            on a cluster

            a cluster: `dask scheduler` on one machine, `dask worker tcp://HOST:8786 --nthreads 1` on each
            of the others (masonry-dem installed there too), then --scheduler tcp://HOST:8786."""
    study = _subcommand(sub, "study", "run a study (many analyses of one wall) on Dask", what, examples)
    study.add_argument("study", metavar="STUDY.toml", help="study file (TOML, format 1)")
    study.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786); default: a "
                       "local cluster of --workers processes")
    study.add_argument("--workers", metavar="N", type=int, help="processes of the local cluster (default: one per "
                       "core); not with --scheduler")
    study.add_argument("--out", metavar="OUT.parquet", help="the results (Parquet; default: out/STUDY.parquet)")
    study.add_argument("--resume", action="store_true", help="keep the rows already in OUT and compute the others")
    study.add_argument("--csv", metavar="OUT.csv", help="also write the results as CSV")
    study.add_argument("--plot", metavar="OUT.png", help="write the summary figure: the multiplier's histogram and "
                       "distribution, against each varied parameter, the weakest analyses' mechanisms (PNG)")
    _add_quiet(study)


def _study(args: Any) -> int:
    """``masonry-dem study``: run the study, write its rows (and plot), print its summary."""
    from .study import load_study, run_study
    from .study.progress import study_bar
    from .study.summary import summary_figure, summary_text

    if args.workers is not None and (args.workers < 1 or args.scheduler):
        raise InputError("--workers: expected a number of processes >= 1, without --scheduler")
    try:
        study = load_study(args.study)
    except OSError as exc:
        return _error(f"cannot read {args.study}: {exc.strerror or exc}", EXIT_INPUT)
    out = args.out or os.path.join("out", Path(args.study).stem + ".parquet")
    targets, plot_file = _output_targets(None, args.plot, None, args.csv)
    _check_outputs([out] + targets, study.inputs + (args.study,))
    for target in [out] + targets:
        _prepare(target)
    interrupted = False
    label = study.title if len(study.title) <= 32 else study.title[:31] + "…"
    with study_bar(label, study.size, enabled=_show_progress(args.quiet)) as bar:
        try:
            frame = run_study(study, out, csv=args.csv, resume=args.resume, scheduler=args.scheduler,
                              workers=args.workers, progress=bar)
        except KeyboardInterrupt as exc:
            frame, interrupted = getattr(exc, "results", None), True
            if frame is None:
                raise

    def outputs() -> Iterator[Any]:
        yield from [p for p in (out, args.csv) if p]
        if plot_file is not None and not interrupted:
            summary_figure(frame, study, plot_file)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(summary_text(frame, study), wrote, write_error)
    if failed_to_write is not None:
        return failed_to_write
    if interrupted:
        return _error(f"interrupted: {len(frame):,} of {study.size:,} analyses written to {out}; "
                      "run again with --resume to finish", EXIT_INTERRUPTED)
    return EXIT_OK


def _add_outputs(parser: argparse.ArgumentParser, plot_default: Optional[str]) -> None:
    parser.add_argument("--json", metavar="OUT.json", help="write the results (JSON, format 1)")
    parser.add_argument(
        "--plot",
        metavar="OUT.png",
        default=plot_default,
        help="write a one-page report figure: crack pattern (joint states), collapse mechanism, deformed "
        "shape and load curve (PNG)" + (f"; default {plot_default}" if plot_default else ""),
    )
    parser.add_argument(
        "--vtk",
        metavar="PREFIX",
        help="write PREFIX-blocks.vtu (blocks: displacement, rotation, mechanism) and PREFIX-interfaces.vtu "
        "(interfaces: forces, states) for ParaView",
    )
    parser.add_argument(
        "--csv", metavar="OUT.csv", help="write the load curve (CSV: multiplier,displacement_m)"
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
    live = case.live_load(model)
    unit = "iterations" if method == "limit" else "steps"
    with progress_bar(method, live=live, enabled=_show_progress(quiet), unit=unit) as bar:
        return case.solve(model, method, progress=bar or None)


def _error(message: str, status: int) -> int:
    """Print one error line on stderr and return the exit status."""
    line = " ".join(str(message).split())  # one line, whatever the message holds
    print(f"{PROG}: error: {line}", file=sys.stderr)
    return status


def _prepare(path: Any) -> None:
    """Create the folder of an output file."""
    parent = Path(path).parent
    if str(parent):
        parent.mkdir(parents=True, exist_ok=True)


def _print(text: str = "", flush: bool = False) -> None:
    """Print a line on stdout. A closed stdout (``| head -1``) is not an error: the rest of the output goes
    to the null device and the command goes on (files written, exit status as if printed)."""
    try:
        print(text, flush=flush)
    except BrokenPipeError:
        _stdout_to_devnull()


def _stdout_to_devnull() -> None:
    """Point stdout at the null device (so that later prints and the flush at exit do not fail)."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, AttributeError, ValueError):
        sys.stdout = open(os.devnull, "w")  # noqa: SIM115 (until exit)


def _tolerant_output() -> None:
    """Never fail on a character stdout's encoding cannot show (an ASCII stdout and a title with an
    accent): it is printed as "?" (stderr already escapes it)."""
    reconfigure = getattr(sys.stdout, "reconfigure", None)
    if reconfigure is not None:
        try:
            reconfigure(errors="replace")
        except (ValueError, OSError, TypeError):
            pass


@contextlib.contextmanager
def _terminate_raises() -> Iterator[None]:
    """While the output files are written, SIGTERM (``kill``) raises KeyboardInterrupt, so that a
    temporary file is removed and the previous target is kept (SIGKILL cannot be caught)."""

    def handler(signum: int, frame: Any) -> None:
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, handler)
    except (ValueError, OSError, AttributeError):  # not the main thread, or no SIGTERM
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _check_outputs(targets: Sequence[Any], inputs: Sequence[Any]) -> None:
    """Refuse, before any analysis, an output file that cannot be written safely (not a regular file,
    the case file itself) and a file given for two outputs (InputError). Other errors (a folder that is a
    file, no permission) are left to the writing, which reports them (exit status 1)."""
    from .atomic import check_target

    seen = {}
    for target in targets:
        try:
            resolved = os.path.realpath(check_target(target, inputs))
        except OSError:  # e.g. its folder is a file: reported when it is written
            continue
        if resolved in seen:
            also = "" if str(seen[resolved]) == str(target) else f" (also as {seen[resolved]})"
            raise InputError(f"{target} is given for two outputs{also}")
        seen[resolved] = target


def _output_targets(
    json_path: Optional[str], plot_path: Optional[str], vtk_prefix: Optional[str] = None, csv_path: Optional[str] = None
) -> Tuple[List[Any], Optional[Any]]:
    """The files the outputs go to, and the plot's file (".png" added when the name has no suffix)."""
    targets: List[Any] = [p for p in (json_path, csv_path) if p]
    if vtk_prefix:
        prefix = vtk_prefix[: -len(".vtu")] if vtk_prefix.endswith(".vtu") else vtk_prefix
        targets += [prefix + "-blocks.vtu", prefix + "-interfaces.vtu"]
    plot_file = None
    if plot_path:
        from .plot import figure_path

        plot_file = figure_path(plot_path)
        targets.append(plot_file)
    return targets, plot_file


def _write_outputs(outputs: Iterator[Any]) -> Tuple[List[Any], Optional[str]]:
    """Write the output files: ``outputs`` writes them one by one, yielding each file written. SIGTERM
    raises KeyboardInterrupt meanwhile (:func:`_terminate_raises`). Returns the files written and, when
    one could not be written, the error that stopped them (else None)."""
    wrote: List[Any] = []
    try:
        with _terminate_raises():
            wrote.extend(outputs)
    except OSError as exc:
        return wrote, f"cannot write {exc.filename or 'the output'}: {exc.strerror or exc}"
    return wrote, None


def _print_report(text: str, wrote: Sequence[Any], write_error: Optional[str]) -> Optional[int]:
    """Print the report of an analysis and the files written; the exit status of a write error, if any."""
    _print(text, flush=True)
    for written in wrote:
        _print(f"  wrote {written}")
    return None if write_error is None else _error(write_error, EXIT_FAILURE)


def _execute(
    case: Case,
    method: Optional[str],
    json_path: Optional[str],
    plot_path: Optional[str],
    quiet: bool = False,
    vtk_prefix: Optional[str] = None,
    csv_path: Optional[str] = None,
    inputs: Sequence[Any] = (),
) -> int:
    """Build, solve, write the outputs, then report; return the exit status (errors are raised).

    The output files are checked before the analysis (``inputs``: the case file, never overwritten) and
    written before the summary is printed, so that a closed stdout cannot lose them."""
    method = case.check_method(method)
    targets, plot_file = _output_targets(json_path, plot_path, vtk_prefix, csv_path)
    _check_outputs(targets, inputs)
    model = case.build_model()
    interrupted = False
    try:
        results = _solve(case, model, method, quiet)
    except KeyboardInterrupt as exc:
        # Ctrl-C: the solver stopped at once; keep what it computed (the result file and the curve),
        # but draw nothing after the interrupt
        results = getattr(exc, "results", None)
        if results is None:
            raise
        interrupted = True
    # a run stopped by the user: status "interrupted" (a core before it: "failed", and KeyboardInterrupt)
    interrupted = interrupted or results.status == "interrupted"
    live = case.live_load(model)

    def outputs() -> Iterator[Any]:
        if json_path:
            _prepare(json_path)
            write_result_json(json_path, results, model, case.title, inputs=inputs)
            yield json_path
        if csv_path:
            from .export import write_curve_csv

            yield write_curve_csv(results, csv_path, inputs=inputs)
        if vtk_prefix and not interrupted:
            from .export import write_vtk

            yield from write_vtk(model, results, vtk_prefix, inputs=inputs)
        if plot_path and not interrupted:
            from .plot import report_figure

            _prepare(plot_file)
            report_figure(model, results, title=case.title, path=plot_file, live=live)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(summary(case.title, model, results, live), wrote, write_error)
    if failed_to_write is not None:
        return failed_to_write
    if interrupted:
        skipped = [name for name, given in (("plot", plot_path), ("VTK files", vtk_prefix)) if given]
        return _error("interrupted" + (f" (no {' or '.join(skipped)} drawn)" if skipped else ""), EXIT_INTERRUPTED)
    if results.status == "failed":
        return _error(f"the analysis failed: {results.error or 'unknown reason'}", EXIT_FAILURE)
    if results.status in ERROR_STATUSES:  # no_equilibrium, unbounded: no collapse multiplier
        return _error(f"no collapse multiplier ({results.status}): {results.error or 'no reason given'}", EXIT_FAILURE)
    return EXIT_OK


def _compare(
    case: Case, json_path: Optional[str], plot_path: Optional[str], quiet: bool = False, inputs: Sequence[Any] = ()
) -> int:
    """Run the three methods on one model, write the outputs, print them side by side; return the exit status."""
    from .compare import comparison_text, write_comparison_json

    targets, plot_file = _output_targets(json_path, plot_path)
    _check_outputs(targets, inputs)
    model = case.build_model()
    # Ctrl-C during a run raises KeyboardInterrupt: the next is not started, nothing is written
    static = _solve(case, model, "static", quiet)
    dynamic = _solve(case, model, "dynamic", quiet)
    limit = _solve(case, model, "limit", quiet)
    live = case.live_load(model)

    def outputs() -> Iterator[Any]:
        if json_path:
            _prepare(json_path)
            write_comparison_json(json_path, static, dynamic, model, case.title, limit=limit, inputs=inputs)
            yield json_path
        if plot_path:
            from .plot import plot_comparison

            _prepare(plot_file)
            plot_comparison(model, static, dynamic, title=case.title, path=plot_file, live=live, limit=limit)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    text = comparison_text(static, dynamic, model, case.title, live, limit=limit)
    failed_to_write = _print_report(text, wrote, write_error)
    if failed_to_write is not None:
        return failed_to_write

    runs = (("static", static), ("dynamic", dynamic), ("limit", limit))
    failed = [
        f"{name}: {'' if res.status in UNFINISHED_STATUSES else res.status + ': '}{res.error or 'unknown reason'}"
        for name, res in runs
        if res.status in ERROR_STATUSES
    ]
    if failed:
        return _error("the analysis failed (" + "; ".join(failed) + ")", EXIT_FAILURE)
    return EXIT_OK


def _validate(directory: Optional[str], method: str, quiet: bool = False) -> int:
    """``masonry-dem validate``: print the validation table; 1 if a case is outside its tolerance or failed."""
    from .validate import validate_folder

    folder = Path(directory) if directory else EXAMPLES_DIR
    if not folder.is_dir():
        what = "no such folder" if not folder.exists() else "not a folder"
        hint = "" if directory else " (the default, examples/ of the repository; give DIR)"
        return _error(f"{what}: {folder}{hint}", EXIT_INPUT)

    def solve(case: Case, model: Any, method: str) -> Any:
        return _solve(case, model, method, quiet)  # Ctrl-C raises KeyboardInterrupt: the table stops

    def echo(line: str) -> None:
        _print(line, flush=True)

    from .validate import collect

    cases, _skipped = collect(folder)  # reads and checks every case file before running any
    if not cases:
        return _error(f"no case file with a [reference] table in {folder}", EXIT_INPUT)
    rows, _ = validate_folder(folder, method, solve=solve, echo=echo)
    return EXIT_OK if all(row.passed for row in rows) else EXIT_FAILURE


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Run the command line with ``argv`` (default: ``sys.argv[1:]``); return the exit status."""
    _tolerant_output()
    try:
        return _main(argv)
    except BrokenPipeError:  # stdout closed while argparse printed (--help | head -1): not an error
        _stdout_to_devnull()
        return EXIT_OK


def _main(argv: Optional[Sequence[str]]) -> int:
    args = build_parser().parse_args(argv)
    try:
        if args.command in ("run", "compare"):
            try:
                case = load_case(args.case)
            except OSError as exc:
                return _error(f"cannot read {args.case}: {exc.strerror or exc}", EXIT_INPUT)
            inputs = [args.case]
            if args.command == "compare":
                return _compare(case, args.json, args.plot, args.quiet, inputs=inputs)
            return _execute(case, args.method, args.json, args.plot, args.quiet, args.vtk, args.csv, inputs=inputs)
        if args.command == "validate":
            return _validate(args.directory, args.method, args.quiet)
        if args.command == "study":
            return _study(args)
        from .default_case import default_case

        return _execute(default_case(), None, args.json, args.plot, args.quiet, args.vtk, args.csv)
    except InputError as exc:
        return _error(str(exc), EXIT_INPUT)
    except MasonryError as exc:
        return _error(str(exc), EXIT_FAILURE)
    except KeyboardInterrupt:
        return _error("interrupted", EXIT_INTERRUPTED)


if __name__ == "__main__":
    sys.exit(main())
