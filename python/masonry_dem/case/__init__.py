"""Case files (TOML, format 1) and result files (JSON, format 1).

The keys are a public contract, described in ``docs/case-format.md``; this package follows it exactly:

* :func:`load_case` reads a case file, :func:`parse_case` a TOML string, :func:`case_from_dict` an
  already parsed table (:mod:`.reader`, with the tables checked key by key in :mod:`.table`). Every key
  and type is checked by name before anything is computed; a bad case raises
  :class:`masonry_dem.InputError` with a one-line message that starts with the file name and names the
  key with its table path, e.g. ``wall.toml: unknown key 'frictoin' in [joints.bed]``.
* :class:`Case` maps the case onto the core (:mod:`.mapping`): ``build_model()`` gives a
  :class:`masonry_dem.Model`, ``run()`` the :class:`masonry_dem.Results` of the analysis, with the static
  solver (``Model.solve_static``), the explicit one (``Model.solve_dynamic``) or limit analysis
  (``Model.solve_limit``). Its parameters are :class:`ModelParameters` and :class:`AnalysisParameters`;
  a key the file leaves out is left to the core's default.
* :func:`result_dict` / :func:`write_result_json` produce the result file (:mod:`.result_file`).
* A case whose [geometry] gives boxes (``boxes``, ``[geometry.leaf]``, ``[geometry.u_wall]``,
  ``[geometry.corner]``) is a 3D wall: its model is a :class:`masonry_dem.Model3D`
  (:class:`masonry_dem.space.case.ModelParameters3D`), analysed by limit analysis or the explicit solver
  (method "limit" or "dynamic", load control) in this version; ``Case.dimension`` is 3.
* A case with a [ground_motion] (a record file, read with the case, or a pulse) and a [time_history] runs its
  time history with :meth:`Case.simulate` (``masonry-dem simulate``): :class:`GroundMotionParameters`,
  :class:`TimeHistoryParameters`.

Units are SI throughout: m, N, Pa, kg, s.
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # what the names below resolve to (type checkers, IDEs); imported on first use at run time
    from .mapping import (
        CORE_DEFAULTS as CORE_DEFAULTS,
        EXPLICIT_OPTIONS as EXPLICIT_OPTIONS,
        INCREMENTAL_OPTIONS as INCREMENTAL_OPTIONS,
        METHODS,
        AnalysisParameters,
        Case,
        GroundMotionParameters,
        ModelParameters,
        TimeHistoryParameters,
    )
    from .reader import (
        ANALYSIS_KEYS as ANALYSIS_KEYS,
        DAMPINGS as DAMPINGS,
        DEFAULT_REFERENCE_TOLERANCE as DEFAULT_REFERENCE_TOLERANCE,
        DYNAMIC_KEYS as DYNAMIC_KEYS,
        FAMILIES as FAMILIES,
        GEOMETRY_KINDS as GEOMETRY_KINDS,
        GEOMETRY_KINDS_3D as GEOMETRY_KINDS_3D,
        GROUND_MOTION_KEYS as GROUND_MOTION_KEYS,
        LAW_KEYS as LAW_KEYS,
        MAX_CASE_BYTES as MAX_CASE_BYTES,
        PULSES as PULSES,
        REFERENCE_KEYS as REFERENCE_KEYS,
        TIME_HISTORY_KEYS as TIME_HISTORY_KEYS,
        case_from_dict,
        load_case,
        parse_case,
        run_case,
    )
    from .result_file import (
        CERTIFICATE_KEYS,
        ERROR_STATUSES as ERROR_STATUSES,
        FORMAT,
        JOINT_STATE_KEYS as JOINT_STATE_KEYS,
        NOTE_STATUSES as NOTE_STATUSES,
        UNFINISHED_STATUSES as UNFINISHED_STATUSES,
        certificate_dict,
        result_dict,
        write_result_json,
    )

__all__ = [
    "FORMAT",
    "METHODS",
    "CERTIFICATE_KEYS",
    "Case",
    "ModelParameters",
    "AnalysisParameters",
    "GroundMotionParameters",
    "TimeHistoryParameters",
    "load_case",
    "parse_case",
    "case_from_dict",
    "run_case",
    "result_dict",
    "certificate_dict",
    "write_result_json",
]

# Where each name lives, imported when first asked for (see masonry_dem._lazy): the package imports none of its
# modules, so that a lower layer imports one of them (space.case: case.table, case.common) without the others.
_LAZY = {
    **dict.fromkeys(("CORE_DEFAULTS", "EXPLICIT_OPTIONS", "INCREMENTAL_OPTIONS", "METHODS", "AnalysisParameters",
                     "Case", "GroundMotionParameters", "ModelParameters", "TimeHistoryParameters"), ".mapping"),
    **dict.fromkeys(("ANALYSIS_KEYS", "DAMPINGS", "DEFAULT_REFERENCE_TOLERANCE", "DYNAMIC_KEYS", "FAMILIES",
                     "GEOMETRY_KINDS", "GEOMETRY_KINDS_3D", "GROUND_MOTION_KEYS", "LAW_KEYS", "MAX_CASE_BYTES",
                     "PULSES", "REFERENCE_KEYS", "TIME_HISTORY_KEYS", "case_from_dict", "load_case", "parse_case",
                     "run_case"), ".reader"),
    **dict.fromkeys(("CERTIFICATE_KEYS", "ERROR_STATUSES", "FORMAT", "JOINT_STATE_KEYS", "NOTE_STATUSES",
                     "UNFINISHED_STATUSES", "certificate_dict", "result_dict", "write_result_json"), ".result_file"),
}

__getattr__, __dir__ = lazy_package(__name__, _LAZY, __all__)
