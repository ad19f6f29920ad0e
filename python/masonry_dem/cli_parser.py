"""The command line's arguments: :func:`build_parser` with one function per subcommand, and the exit
statuses and defaults the commands share (:mod:`masonry_dem.cli` runs them)."""

from __future__ import annotations

import argparse
import math
import os
import textwrap
from typing import Any, NoReturn, Optional

from ._core import __version__
from .atomic import prefix_problem
from .case import DEFAULT_REFERENCE_TOLERANCE, METHODS
from .validate import METHOD_CHOICES, default_folder

PROG = "masonry-dem"
EXIT_OK, EXIT_FAILURE, EXIT_INPUT, EXIT_INTERRUPTED = 0, 1, 2, 130
DEMO_PLOT = os.path.join("out", "demo.png")


class _Parser(argparse.ArgumentParser):
    """argparse, with its errors on one line (the usage is for --help)."""

    def error(self, message: str) -> NoReturn:
        self.exit(EXIT_INPUT, f"{PROG}: error: {message} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``masonry-dem`` (subcommands ``run``, ``compare``, ``demo``, ``validate``, ``study``,
    ``simulate`` and ``assess``)."""
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
              masonry-dem simulate examples/ferris-tinloi-wall1-elcentro.toml --plot out/ec.png   a ground motion
              masonry-dem assess examples/ferris-tinloi-wall1.toml --plot out/a.png   a seismic check

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
    _add_simulate(sub)
    _add_assess(sub)
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
    compare.add_argument("--json", type=_output_file, metavar="OUT.json", help="write both results and their agreement (JSON)")
    compare.add_argument(
        "--plot",
        type=_output_file,
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
            "Run every case file (*.toml) of DIR, or the one case file given, that carries a [reference]\n"
            "table with the static solver, the explicit one and/or limit analysis, and print a table: case,\n"
            "reference (with its relative tolerance), static, explicit and limit collapse multipliers, error\n"
            "(the largest relative error), time of each method, verdict. Case files without a [reference]\n"
            "table are skipped and listed."
        ),
        epilog=f"""\
            examples:
              masonry-dem validate                       the examples shipped with masonry-dem, the three methods
              masonry-dem validate --method static       the static solver only (a second or so)
              masonry-dem validate --method both         the static and the explicit solver
              masonry-dem validate my-cases/ --method dynamic
              masonry-dem validate examples/leaf-out-of-plane.toml   one case file

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
        help=f"folder of case files, or one case file (default: the examples shipped with masonry-dem, {default_folder()})",
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
    study.add_argument("--out", type=_output_file, metavar="OUT.parquet", help="the results (Parquet; default: out/STUDY.parquet)")
    study.add_argument("--resume", action="store_true", help="keep the rows already in OUT and compute the others")
    study.add_argument("--csv", type=_output_file, metavar="OUT.csv", help="also write the results as CSV")
    study.add_argument("--plot", type=_output_file, metavar="OUT.png", help="write the summary figure: the multiplier's histogram and "
                       "distribution, against each varied parameter, the weakest analyses' mechanisms (PNG)")
    _add_quiet(study)


def _scale(text: str) -> float:
    """A --scale factor: a finite number."""
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def _duration(text: str) -> float:
    """A --duration: a finite number > 0 [s]."""
    x = _scale(text)
    if x <= 0:
        raise argparse.ArgumentTypeError(f"expected a time > 0 [s], got {text!r}")
    return x


def _add_simulate(sub: Any) -> None:
    what = (
        "Run the time history of a case file under its ground motion ([ground_motion]: a record file, .csv or\n"
        "PEER .AT2, or a built-in one-sine or Ricker pulse; [time_history]: duration, record interval, damping;\n"
        "docs/case-format.md) with the explicit solver, and print a summary: duration, time step, status, peak\n"
        "drift, peak rotation, peak base shear, energy balance error."
    )
    examples = """\
            examples:
              masonry-dem simulate examples/ferris-tinloi-wall1-elcentro.toml --plot out/ec.png
              masonry-dem simulate examples/ferris-tinloi-wall1-elcentro.toml --scale 2 --gif out/ec.gif
              masonry-dem simulate CASE.toml --duration 5 --csv out/h.csv --vtk out/h --json out/h.json

            --vtk out/h writes out/h-blocks-0000.vtu, ... (one per record) and out/h.pvd: open the .pvd in
            ParaView and play it. Displacements are relative to the ground.
            exit status: 0 completed, 1 the solver failed, 2 bad input, 130 interrupted."""
    simulate = _subcommand(sub, "simulate", "run a case's time history under its ground motion", what, examples)
    simulate.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1) with a [ground_motion] table")
    simulate.add_argument("--scale", metavar="F", type=_scale, help="the factor on the ground motion, replacing "
                          "[ground_motion] scale (the vertical component follows it unless the case gives "
                          "vertical_scale)")
    simulate.add_argument("--duration", metavar="S", type=_duration, help="the length of the time history [s], "
                          "replacing [time_history] duration (default: the record's, or 3 periods of a pulse)")
    simulate.add_argument("--json", type=_output_file, metavar="OUT.json", help="write the summary, the peaks and the response at "
                          "each record (JSON)")
    simulate.add_argument("--plot", type=_output_file, metavar="OUT.png", help="write the response figure: rotation, drift, base "
                          "shear and ground acceleration against time, and the wall at the largest drift (PNG)")
    simulate.add_argument("--csv", type=_output_file, metavar="OUT.csv", help="write a row per record: time, displacement and "
                          "rotation of the control block, largest translation, energies (CSV)")
    simulate.add_argument("--vtk", type=_output_prefix, metavar="PREFIX", help="write PREFIX-blocks-NNNN.vtu per record and PREFIX.pvd "
                          "(a time series for ParaView)")
    simulate.add_argument("--gif", type=_output_file, metavar="OUT.gif", help="write an animation of the blocks over time (GIF; "
                          "an .mp4 name writes an MP4 where ffmpeg is installed)")
    _add_quiet(simulate)


def _add_assess(sub: Any) -> None:
    what = (
        "Run the analysis of a case file (limit analysis unless --method says otherwise) and check it against the\n"
        "site's demand spectrum of its [assessment] table (docs/assessment.md): the linear kinematic check of the\n"
        "collapse mechanism (alpha0, M*, e*, a0*, the demand, the ratio and the verdict), the nonlinear one when\n"
        "the mechanism is rigid bodies turning about hinges, and on a static or explicit pushover's curve the\n"
        "N2 method of EN 1998-1 Annex B; print a table of each quantity with its unit and clause."
    )
    examples = """\
            examples:
              masonry-dem assess examples/ferris-tinloi-wall1.toml
              masonry-dem assess examples/ferris-tinloi-wall1.toml --json out/a.json --plot out/a.png
              masonry-dem assess CASE.toml --method static      the collapse's mechanism and the N2 method

            --json writes the result file with an "assessment" object (docs/case-format.md, "Result file").
            exit status: 0 checked (whatever the verdict), 1 the analysis failed or found no collapse to check,
            2 bad input (no [assessment] table, a parameter out of range, a mechanism in which no block moves)."""
    assess = _subcommand(sub, "assess", "check a case's collapse against a seismic demand spectrum", what, examples)
    assess.add_argument("case", metavar="CASE.toml", help="case file (TOML, format 1) with an [assessment] table")
    assess.add_argument("--method", choices=METHODS, help="the analysis (default: limit): limit, static or dynamic; "
                        "a static or explicit one also gives the N2 method on its curve")
    assess.add_argument("--json", type=_output_file, metavar="OUT.json", help="write the results with the assessment "
                        "(JSON, format 1)")
    assess.add_argument("--plot", type=_output_file, metavar="OUT.png", help="write the capacity against the demand "
                        "spectrum in ADRS form, and the displaced shape used for M* (PNG)")
    _add_quiet(assess)


def _output_file(name: str) -> str:
    """An output file name: not empty, not a folder (an existing one, or a name ending with a separator)."""
    if name == "":
        raise argparse.ArgumentTypeError("an empty file name")
    if name.endswith(("/", os.sep)) or os.path.isdir(name):
        raise argparse.ArgumentTypeError(f"{name} is a folder: give a file name")
    return name


def _output_prefix(name: str) -> str:
    """An output prefix (PREFIX-blocks.vtu ...): not empty, not a folder (files inside a folder are named
    FOLDER/NAME)."""
    problem = prefix_problem(name)
    if problem:
        raise argparse.ArgumentTypeError(problem)
    return name


def _add_outputs(parser: argparse.ArgumentParser, plot_default: Optional[str]) -> None:
    parser.add_argument("--json", type=_output_file, metavar="OUT.json", help="write the results (JSON, format 1)")
    parser.add_argument(
        "--plot",
        type=_output_file,
        metavar="OUT.png",
        default=plot_default,
        help="write a one-page report figure: crack pattern (joint states), collapse mechanism, deformed "
        "shape and load curve (PNG)" + (f"; default {plot_default}" if plot_default else ""),
    )
    parser.add_argument(
        "--vtk",
        type=_output_prefix,
        metavar="PREFIX",
        help="write PREFIX-blocks.vtu (blocks: displacement, rotation, mechanism) and PREFIX-interfaces.vtu "
        "(interfaces: forces, states) for ParaView",
    )
    parser.add_argument(
        "--csv", type=_output_file, metavar="OUT.csv", help="write the load curve (CSV: multiplier,displacement_m)"
    )
    _add_quiet(parser)


def _add_quiet(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        help="no progress bar (it is drawn on stderr only when that is a terminal)",
    )
