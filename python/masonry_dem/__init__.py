"""masonry-dem: nonlinear in-plane analysis of masonry walls of rigid blocks with Mohr-Coulomb joints.

SI units throughout (m, N, Pa, kg, s). The compiled core (Rust) provides the wall generators, the
:class:`Model` and the solvers; this package adds case files, result files, plots and the command line:

>>> import masonry_dem as md
>>> case = md.load_case("examples/ferris-tinloi-wall1.toml")   # doctest: +SKIP
>>> results = case.run()                                        # doctest: +SKIP
>>> results.collapse_multiplier                                 # doctest: +SKIP
0.6429...

Plots: :func:`masonry_dem.plot.plot_results` (imports matplotlib on first use).
"""

from ._core import (
    ConvergenceError,
    InputError,
    MasonryError,
    MechanismError,
    Model,
    Results,
    __version__,
    pattern,
    running_bond,
)
from .case import Case, load_case, parse_case, result_dict, run_case, write_result_json

__all__ = [
    "Model",
    "Results",
    "running_bond",
    "pattern",
    "MasonryError",
    "InputError",
    "ConvergenceError",
    "MechanismError",
    "__version__",
    "Case",
    "load_case",
    "parse_case",
    "run_case",
    "result_dict",
    "write_result_json",
]
