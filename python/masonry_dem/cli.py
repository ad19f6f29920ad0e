"""The ``masonry-dem`` command line.

    masonry-dem run CASE.toml [--method static|dynamic|limit] [--json OUT.json] [--plot OUT.png]
                    [--vtk PREFIX] [--csv OUT.csv] [--quiet]
    masonry-dem compare CASE.toml [--json OUT.json] [--plot OUT.png] [--quiet]
    masonry-dem demo [--plot OUT.png] [--json OUT.json] [--vtk PREFIX] [--csv OUT.csv] [--quiet]
    masonry-dem validate [DIR | CASE.toml] [--method static|dynamic|limit|both|all] [--quiet]
    masonry-dem study STUDY.toml [--scheduler ADDRESS] [--workers N] [--out OUT.parquet] [--resume]
                      [--csv OUT.csv] [--plot OUT.png] [--quiet]
    masonry-dem simulate CASE.toml [--scale F] [--duration S] [--json OUT.json] [--plot OUT.png]
                         [--csv OUT.csv] [--vtk PREFIX] [--gif OUT.gif] [--quiet]
    masonry-dem assess CASE.toml [--method static|dynamic|limit] [--json OUT.json] [--plot OUT.png] [--quiet]

``assess`` runs the case's analysis (limit analysis by default) and checks it against the demand spectrum of its
[assessment] table (:mod:`masonry_dem.assessment`): the linear kinematic check of the mechanism, the nonlinear one
of a mechanism of rigid bodies turning about hinges, and on a pushover's curve the N2 method; it prints the summary and a table of
the checks (each quantity with its unit and clause), and exits 0 whatever the verdict, 1 when the analysis gives
nothing to check.

``simulate`` runs the time history of a case under its ground motion ([ground_motion], [time_history]; see
:mod:`masonry_dem.ground_motion`) and prints the peaks of the response (:mod:`masonry_dem.response`); it exits 1
when the solver fails. Its outputs: the response figure (``--plot``), the animation (``--gif``), a row per record
(``--csv``), a VTK time series (``--vtk``) and the JSON of :func:`masonry_dem.response.history_dict`.

``study`` runs the many analyses of a study file (docs/study-format.md) on Dask, writing one row per
analysis to a Parquet file as they finish (see :mod:`masonry_dem.study`); ``--resume`` finishes a study
that was stopped, computing only the rows missing. It exits 0 once every row is written (the rows of
failed analyses included, with their error), 130 when interrupted (the rows done are kept).

``validate`` runs every case file of DIR, or the one case file given (default: the examples shipped with the
package, whatever the current directory; in the repository, its examples/; the first line names the folder), that
carries a [reference] table and prints a table of its collapse multipliers against the reference (see
:mod:`masonry_dem.validate`); it exits 1 if any is outside its tolerance or failed.

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
lambda still rising; the reason is printed, the JSON and plot are still written) or another error occurs (a
limit analysis of joints with dilatancy below friction ends "estimate", exit status 0: its number is printed as
an estimate, never as a collapse multiplier); 2 for bad input (an invalid case file, a missing
file, a FIFO or a device given as a file, bad arguments, an empty or folder output name, a file that cannot be
read or a study folder that cannot be written, a model too large for the memory); 130 when interrupted (Ctrl-C stops a solver within a fraction of a second, status
"interrupted"; ``run`` still prints and writes the result file and the CSV of what was computed, but draws
no plot and writes no VTK; ``compare`` and ``validate`` start no further run and write nothing). Errors are one line on stderr, ``masonry-dem: error: ...``.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from pathlib import Path
from typing import Any, Callable, Iterator, List, Optional, Sequence, Tuple

from ._core import InputError, MasonryError
from .case import (
    ERROR_STATUSES,
    UNFINISHED_STATUSES,
    Case,
    load_case,
    write_result_json,
)
from .cli_parser import (
    EXIT_FAILURE,
    EXIT_INPUT,
    EXIT_INTERRUPTED,
    EXIT_OK,
    PROG,
    build_parser,
)
from .progress import progress_bar
from .report import summary

__all__ = ["main", "build_parser"]



def _study(args: Any) -> int:
    """``masonry-dem study``: run the study, write its rows (and plot), print its summary."""
    try:
        from .study import load_study, run_study
    except ImportError as exc:  # the extra "studies" is not installed: the message says how to install it
        return _error(str(exc), EXIT_FAILURE)
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


def _simulate(args: Any) -> int:
    """``masonry-dem simulate``: run the case's time history, write the outputs, print the summary."""
    from .response import history_dict, summary_text

    try:
        case = load_case(args.case)
    except OSError as exc:
        return _error(f"cannot read {args.case}: {exc.strerror or exc}", EXIT_INPUT)
    if case.ground_motion is None:
        raise InputError(f"{args.case}: no [ground_motion] table: simulate needs a ground motion (a record file "
                         "or a pulse; see docs/case-format.md)")
    if case.dimension == 3:
        planar = [name for name, given in (("--plot", args.plot), ("--csv", args.csv), ("--gif", args.gif)) if given]
        if planar:
            raise InputError(f"{args.case}: simulate {planar[0]}: the figures, the animation and the curve of a time "
                             "history are the plane's in this version (this case is 3D: --json and --vtk write its "
                             "response and its motion)")
    inputs = [args.case] + [str(p) for p in case.ground_motion.files]
    kwargs = case.simulate_kwargs(args.scale, args.duration)  # checks the arguments before any run
    targets, plot_file = _output_targets(args.json, args.plot, None, args.csv)
    vtk_prefix = args.vtk
    if vtk_prefix:
        for ending in (".vtu", ".pvd"):
            if vtk_prefix.endswith(ending):
                vtk_prefix = vtk_prefix[: -len(ending)]
        targets.append(vtk_prefix + ".pvd")
    if args.gif:
        from .plot.animation import check_animation_format

        check_animation_format(args.gif)
        targets.append(args.gif)
    _check_outputs(targets, inputs)
    model = case.build_model()
    motion, _ = case.ground_motion.components(args.scale)
    if not args.quiet:
        # the memory the records will take, before the run (the time step as simulate chooses it)
        records, size = model.record_size(kwargs["duration"], time_step=kwargs.get("time_step"),
                                          record_interval=kwargs.get("record_interval"))
        blocks = len(model.boxes) if case.dimension == 3 else len(model.rects)
        print(f"recording {records:,} states of the {blocks:,} blocks: {size / 2**20:.1f} MB", file=sys.stderr)
    label = f"simulate {kwargs['duration']:.4g} s"
    with progress_bar(label, enabled=_show_progress(args.quiet), time_history=True) as bar:
        history, interrupted = _interruptible(lambda: case.simulate(model, args.scale, args.duration,
                                                                    progress=bar or None))
    title = case.title + (f" (ground motion x{motion.scale:g})" if motion.scale != 1.0 else "")

    def outputs() -> Iterator[Any]:
        if args.json:
            from .case.result_file import write_json

            _prepare(args.json)
            write_json(args.json, history_dict(model, history, case.title, motion), inputs=inputs)
            yield args.json
        if args.csv:
            from .export import write_curve_csv

            yield write_curve_csv(history, args.csv, inputs=inputs, model=model)
        if vtk_prefix and not interrupted and len(history.times):
            from .export import write_vtk

            pvd, _ = write_vtk(model, history, vtk_prefix, inputs=inputs)
            yield pvd
        if plot_file is not None and not interrupted:
            from .plot import response_figure

            _prepare(plot_file)
            response_figure(model, history, motion=motion, title=title, path=plot_file)
            yield plot_file
        if args.gif and not interrupted and len(history.times):
            from .plot import write_animation

            yield write_animation(model, history, args.gif, title=title, inputs=inputs)

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(summary_text(model, history, title, motion), wrote, write_error)
    if failed_to_write is not None:
        return failed_to_write
    if interrupted:
        return _error("interrupted (no plot, VTK files or animation drawn)", EXIT_INTERRUPTED)
    if history.status == "failed":
        return _error(f"the time history failed: {history.error or 'unknown reason'}", EXIT_FAILURE)
    return EXIT_OK


def _assess(args: Any) -> int:
    """``masonry-dem assess``: run the case's analysis, check it against its [assessment], write the outputs, print
    the summary and the table of the checks."""
    from .assessment.verdict import assess, assessment_dict, assessment_table

    try:
        case = load_case(args.case)
    except OSError as exc:
        return _error(f"cannot read {args.case}: {exc.strerror or exc}", EXIT_INPUT)
    if case.assessment is None:
        raise InputError(f"{args.case}: no [assessment] table: assess needs the site's demand spectrum "
                         "(docs/case-format.md, \"[assessment]\")", "assessment")
    method = case.check_method(args.method or "limit")
    spectrum = case.assessment.spectrum
    inputs = [args.case] + ([spectrum.parameters["file"]] if spectrum.code == "file" else [])
    targets, plot_file = _output_targets(args.json, args.plot)
    _check_outputs(targets, inputs)
    model = case.build_model()
    results, interrupted = _interruptible(lambda: _solve(case, model, method, args.quiet))
    report = summary(case.title, model, results, case.live_load(model))
    if interrupted:
        _print(report)
        return _error("interrupted (nothing checked, nothing written)", EXIT_INTERRUPTED)
    has_curve = method != "limit" and len(results.curve_displacement) > 1
    if results.status != "collapse" and not has_curve:
        _print(report)
        return _error(f"no collapse mechanism to check ({results.status}): {results.error or 'no collapse'}",
                      EXIT_FAILURE)
    checked = assess(model, results, case.assessment, gravity=case.model_kwargs["gravity"])

    def outputs() -> Iterator[Any]:
        if args.json:
            from .case.result_file import result_dict, write_json

            data = result_dict(results, model, case.title)
            data["assessment"] = assessment_dict(checked)
            _prepare(args.json)
            write_json(args.json, data, inputs=inputs)
            yield args.json
        if plot_file is not None:
            from .assessment.plot import assessment_figure

            _prepare(plot_file)
            assessment_figure(model, checked, title=case.title, path=plot_file)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(report + "\n" + assessment_table(checked, case.title), wrote, write_error)
    return failed_to_write if failed_to_write is not None else EXIT_OK


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
    # Ctrl-C: keep what the solver computed (the result file and the curve), but draw nothing after it
    results, interrupted = _interruptible(lambda: _solve(case, model, method, quiet))
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
            report_figure(model, results, title=case.title, path=plot_file, live=live, thrust=case.arch is not None,
                          movement=case.movement is not None)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(summary(case.title, model, results, live, case.arch, case.movement), wrote,
                                    write_error)
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
    """Run the three methods on one model, write the outputs, print them side by side; return the exit status.
    A 3D wall: its limit analysis alone is run and printed (:func:`_compare_limit_only`)."""
    from .compare import comparison_text, write_comparison_json

    targets, plot_file = _output_targets(json_path, plot_path)
    _check_outputs(targets, inputs)
    model = case.build_model()
    if case.dimension == 3:
        return _compare_limit_only(case, model, json_path, plot_file, quiet, inputs)
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


def _compare_limit_only(
    case: Case, model: Any, json_path: Optional[str], plot_file: Any, quiet: bool, inputs: Sequence[Any]
) -> int:
    """``compare`` of a 3D wall: its limit analysis alone (:data:`masonry_dem.compare.LIMIT_ONLY_NOTE`), its outputs
    (the comparison file with the limit analysis only, the 3D mechanism's plot) and its exit status."""
    from .case.result_file import write_json
    from .compare import limit_only_dict, limit_only_text

    limit = _solve(case, model, "limit", quiet)
    live = case.live_load(model)

    def outputs() -> Iterator[Any]:
        if json_path:
            _prepare(json_path)
            write_json(json_path, limit_only_dict(limit, model, case.title), inputs=inputs)
            yield json_path
        if plot_file is not None:
            from .plot import report_figure

            _prepare(plot_file)
            report_figure(model, limit, title=case.title, path=plot_file, live=live)
            yield plot_file

    wrote, write_error = _write_outputs(outputs())
    failed_to_write = _print_report(limit_only_text(limit, model, case.title, live), wrote, write_error)
    if failed_to_write is not None:
        return failed_to_write
    if limit.status in ERROR_STATUSES:
        reason = f"{'' if limit.status in UNFINISHED_STATUSES else limit.status + ': '}{limit.error or 'unknown reason'}"
        return _error(f"the analysis failed (limit: {reason})", EXIT_FAILURE)
    return EXIT_OK


def _validate(directory: Optional[str], method: str, quiet: bool = False) -> int:
    """``masonry-dem validate``: print the validation table; 1 if a case is outside its tolerance or failed."""
    from .validate import default_folder, validate_folder

    folder = Path(directory) if directory else default_folder()
    if not (folder.is_dir() or (directory and folder.is_file())):
        what = "no such folder or case file" if not folder.exists() else "not a folder or a case file"
        hint = "" if directory else " (the default, the examples shipped with masonry-dem: is the package complete? give DIR)"
        return _error(f"{what}: {folder}{hint}", EXIT_INPUT)

    def solve(case: Case, model: Any, method: str) -> Any:
        return _solve(case, model, method, quiet)  # Ctrl-C raises KeyboardInterrupt: the table stops

    def echo(line: str) -> None:
        _print(line, flush=True)

    from .validate import collect

    cases, _skipped = collect(folder)  # reads and checks every case file before running any
    if not cases:
        why = f"no case file with a [reference] table in {folder}" if folder.is_dir() else f"{folder} has no [reference] table"
        return _error(why, EXIT_INPUT)
    if not directory:
        echo(f"cases of {folder} (the examples shipped with masonry-dem)")
    rows, _ = validate_folder(folder, method, solve=solve, echo=echo)
    # a case whose reference applies to none of the methods run is not run: neither passed nor failed
    return EXIT_OK if all(row.passed or not row.ran for row in rows) else EXIT_FAILURE


def _interruptible(run: Callable[[], Any]) -> Tuple[Any, bool]:
    """``run()``'s result and whether the user stopped it: Ctrl-C stops a solver at once, and its partial result
    comes as the ``results`` of the KeyboardInterrupt (raised again when there is none); a result with status
    "interrupted" was stopped too."""
    try:
        result = run()
    except KeyboardInterrupt as exc:
        result = getattr(exc, "results", None)
        if result is None:
            raise
        return result, True
    return result, result.status == "interrupted"


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
        if args.command == "simulate":
            return _simulate(args)
        if args.command == "assess":
            return _assess(args)
        from .default_case import default_case

        return _execute(default_case(), None, args.json, args.plot, args.quiet, args.vtk, args.csv)
    except InputError as exc:
        return _error(str(exc), EXIT_INPUT)
    except MasonryError as exc:
        return _error(str(exc), EXIT_FAILURE)
    except KeyboardInterrupt:
        return _error("interrupted", EXIT_INTERRUPTED)
    except MemoryError as exc:  # a model or a record too large for this machine's memory: said in one line
        reason = " ".join(str(exc).split()) or "the analysis needs more memory than is available"
        return _error(f"out of memory: {reason}", EXIT_INPUT)
    except OSError as exc:  # a file that cannot be read or written: named, in one line
        name = f"{exc.filename}: " if exc.filename else ""
        return _error(f"{name}{exc.strerror or exc}", EXIT_INPUT)


if __name__ == "__main__":
    sys.exit(main())
