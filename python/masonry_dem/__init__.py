"""masonry-dem: nonlinear in-plane analysis of masonry walls of rigid blocks with Mohr-Coulomb joints, and limit
analysis of 3D walls of boxes.

SI units throughout (m, N, Pa, kg, s). The compiled core (Rust) provides the wall generators, the
:class:`Model` and the solvers; this package adds case files, result files, plots and the command line:

>>> import masonry_dem as md
>>> case = md.load_case("examples/ferris-tinloi-wall1.toml")   # doctest: +SKIP
>>> results = case.run()                                        # doctest: +SKIP
>>> results.collapse_multiplier                                 # doctest: +SKIP
0.6429...

Two solvers share one model: ``Model.solve_static`` (incremental, Newton) and ``Model.solve_dynamic``
(explicit, molecular dynamics; ``Model.simulate`` gives time histories); ``Model.solve_limit`` is limit
analysis on the same model (the collapse multiplier as a linear program, with ``Results.certificate``).
Case files choose one with [analysis] method ("static", "dynamic", "limit"); :mod:`masonry_dem.compare`
sets their results side by side.

Two dimensions: a wall in the plane is a :class:`Model` (rectangles [x0, y0, x1, y1]); a 3D wall of boxes
[x0, y0, z0, x1, y1, z1], z up, is a :class:`Model3D` (:mod:`masonry_dem.space`: the generators ``running_bond_3d``,
``u_wall``, ``corner_wall``, ``buttressed_wall``, and of convex polyhedra ``barrel_vault``, ``cross_vault`` and
``dome``; plots and VTK in 3D), analysed
by limit analysis (``Model3D.solve_limit``) and the explicit solver (``Model3D.solve_dynamic``, load control; ``Model3D.simulate`` gives time histories) with the live
load in any direction in plan. Both give the same :class:`Results` and :class:`TimeHistory` (``dimension``: 2 or 3);
a case file whose [geometry] gives boxes is 3D (method "limit" or "dynamic").

Plots (:mod:`masonry_dem.plot`, matplotlib, imported on first use): panels ``plot_wall``,
``plot_deformed``, ``plot_cracks``, ``plot_mechanism``, ``plot_curve``, the one-page ``report_figure``,
and ``plot_results`` / ``plot_comparison``. Exports: :func:`write_vtk` (two .vtu files for ParaView,
meshio) and :func:`write_curve_csv`. A ``TimeHistory`` is a result for all three (``report_figure``: the
response against time; ``write_vtk``: a .vtu per record and a .pvd; ``write_curve_csv(history, path,
model=model)``: a row per record), its displacements relative to the ground (:mod:`masonry_dem.history`).
Progress bars: :mod:`masonry_dem.progress` (tqdm, optional).

Units (:mod:`masonry_dem.units`): ``md.MPa``, ``md.mm``, ``md.kN``, ``md.N_per_mm3``, ... are the SI values of
the units (``0.25 * md.MPa`` is 250000.0 Pa); :func:`parse_quantity` reads "0.25 MPa" into SI. A drawing's
rectangles become blocks with :func:`masonry_dem.dxf.read_dxf` (a DXF file; ezdxf, the extra ``dxf``).

Modal analysis (:mod:`masonry_dem.modal`): :func:`modes` gives the natural frequencies [Hz] and mass-normalized
mode shapes of the elastic model, :func:`rayleigh_damping` Rayleigh coefficients from two of them, and
:func:`plot_modes` draws the shapes as deformed walls.

Ground motions (:mod:`masonry_dem.ground_motion`): :class:`GroundMotion` records read from a two-column CSV or a
PEER NGA .AT2 file (:func:`read_ground_motion`, :func:`read_at2`; in g or m/s2) or built in (:func:`one_sine`,
:func:`ricker`), scaled, for ``Model.simulate(base_acceleration=..., vertical_acceleration=...)``; a case file's
[ground_motion] and [time_history] tables run with ``Case.simulate`` (``masonry-dem simulate``).
:mod:`masonry_dem.response` gives the peaks of the response (drift, rotation, base shear, energy balance);
:func:`masonry_dem.plot.response_figure`, :func:`masonry_dem.plot.plot_energy` and :func:`write_animation` (a GIF,
or an MP4 with ffmpeg) draw it.

Studies (:mod:`masonry_dem.study`, Dask, pandas and pyarrow, imported on first use): :func:`load_study` reads a
study file (docs/study-format.md), :func:`run_study` runs its analyses on a Dask cluster (local by default),
one row each in a Parquet file, :func:`read_results` reads them back.
"""

from typing import TYPE_CHECKING

from ._core import (
    ConvergenceError,
    InputError,
    MasonryError,
    MechanismError,
    Results,
    TimeHistory,
    __version__,
    arch,
    gable,
    stone_wall,
)
from ._checked import Model, pattern, running_bond

if TYPE_CHECKING:  # what the names below resolve to (type checkers, IDEs); imported on first use at run time
    from .case import Case, load_case, parse_case, result_dict, run_case, write_result_json
    from .export import write_curve_csv, write_vtk
    from .modal import Modes, modes, rayleigh_damping
    from .plot.modes import plot_modes
    from .api import (
        GroundMotion,
        curve_columns,
        dry_joint,
        interface_columns,
        interfaces_dataframe,
        mortar_joint,
        one_sine,
        read_at2,
        read_ground_motion,
        ricker,
        to_dataframe,
        to_dict,
        to_json,
        parse_quantity,
        m,
        cm,
        mm,
        km,
        s,
        ms,
        kg,
        N,
        kN,
        MN,
        Pa,
        kPa,
        MPa,
        GPa,
        N_per_m3,
        kN_per_m3,
        MN_per_m3,
        N_per_mm3,
        N_per_m,
        N_per_mm,
        J_per_m2,
        kg_per_m3,
        t_per_m3,
        m_per_s2,
    )
    from .plot.animation import write_animation
    from .space import Model3D, barrel_vault, buttressed_wall, corner_wall, cross_vault, dome, running_bond_3d, u_wall
    from .study import load_study, read_results, run_study

__all__ = [
    "Model",
    "Model3D",
    "Results",
    "TimeHistory",
    "running_bond",
    "pattern",
    "arch",
    "gable",
    "stone_wall",
    "running_bond_3d",
    "u_wall",
    "corner_wall",
    "buttressed_wall",
    "barrel_vault",
    "cross_vault",
    "dome",
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
    "write_vtk",
    "write_curve_csv",
    "Modes",
    "modes",
    "rayleigh_damping",
    "plot_modes",
    # the functions of api.__all__, listed as literals: type checkers read a package's re-exports (py.typed)
    # from a literal __all__ only (tests/python/test_api.py::test_exports checks that the lists agree)
    "mortar_joint",
    "dry_joint",
    "to_dict",
    "to_json",
    "to_dataframe",
    "interfaces_dataframe",
    "curve_columns",
    "interface_columns",
    "GroundMotion",
    "read_ground_motion",
    "read_at2",
    "one_sine",
    "ricker",
    # units (masonry_dem.units): md.MPa, md.mm, md.kN, ... are the SI values of the units (0.25 * md.MPa is in Pa)
    "parse_quantity",
    "m",
    "cm",
    "mm",
    "km",
    "s",
    "ms",
    "kg",
    "N",
    "kN",
    "MN",
    "Pa",
    "kPa",
    "MPa",
    "GPa",
    "N_per_m3",
    "kN_per_m3",
    "MN_per_m3",
    "N_per_mm3",
    "N_per_m",
    "N_per_mm",
    "J_per_m2",
    "kg_per_m3",
    "t_per_m3",
    "m_per_s2",
    # the animation of a time history, imported on first use (matplotlib)
    "write_animation",
    # studies, imported on first use (Dask, pandas and pyarrow take a while to import)
    "load_study",
    "run_study",
    "read_results",
]

# Where each name of __all__ not imported above lives: imported when first asked for, so that `import
# masonry_dem` loads the core and the model alone (not numpy, and not matplotlib, meshio, Dask, pandas or
# pyarrow, which the modules below import on their own first use).
_LAZY = {
    **dict.fromkeys(("Case", "load_case", "parse_case", "result_dict", "run_case", "write_result_json"), ".case"),
    **dict.fromkeys(("write_curve_csv", "write_vtk"), ".export"),
    **dict.fromkeys(("Modes", "modes", "rayleigh_damping"), ".modal"),
    "plot_modes": ".plot.modes",
    "write_animation": ".plot.animation",
    **dict.fromkeys(("Model3D", "running_bond_3d", "u_wall", "corner_wall", "buttressed_wall", "barrel_vault",
                    "cross_vault", "dome"), ".space"),
    **dict.fromkeys(("load_study", "run_study", "read_results"), ".study"),
}


def __getattr__(name: str):  # type: ignore[no-untyped-def]
    """The names of ``__all__`` not imported with the package (see ``_LAZY``; the rest of ``__all__``,
    from :mod:`masonry_dem.api`) and the package's modules, imported when first asked for."""
    import importlib

    if name in _LAZY or (name in __all__ and name not in globals()):
        module = importlib.import_module(_LAZY.get(name, ".api"), __name__)
        value = getattr(module, name)
        globals()[name] = value
        return value
    if not name.startswith("_"):
        try:
            return importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as e:
            if e.name != f"{__name__}.{name}":
                raise
    raise AttributeError(f"module 'masonry_dem' has no attribute {name!r}")


def __dir__() -> list:
    return sorted(set(globals()) | set(__all__))
