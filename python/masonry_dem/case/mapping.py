"""A checked case mapped onto the core: :class:`Case` builds the :class:`masonry_dem.Model` (of a 3D wall the
:class:`masonry_dem.Model3D`) and runs its analysis with the static solver (``Model.solve_static``; not in 3D), the
explicit one (``solve_dynamic``) or limit analysis (``solve_limit``).

A case holds what its file gives in two frozen objects: :class:`ModelParameters` (the wall, the arguments
of ``Model``) and :class:`AnalysisParameters` (the options of the solvers); a case with a ground motion also
:class:`GroundMotionParameters` (its [ground_motion], the records read) and :class:`TimeHistoryParameters`
(its [time_history]), which :meth:`Case.simulate` hands to ``Model.simulate``. A parameter the file leaves out
is None there and is left out of the call, so that the core's own default applies (the bindings fill it in
from the Rust ``Default``s). :data:`CORE_DEFAULTS` holds the few defaults Python has to show or to check
a key against, read from the core (``_core.DEFAULTS``); nothing passes them back to it.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass, field, fields, replace
from types import MappingProxyType
from typing import (Any, Callable, ClassVar, Dict, Iterator, List, Mapping, MutableMapping, Optional, Sequence, Tuple,
                    Union)

import numpy as np

from .. import _core
from .._core import InputError, MasonryError
from ..assessment.parameters import AssessmentParameters
from ..ground_motion import GroundMotion, simulate_arguments
from ..space.model import CORE_DEFAULTS_3D, IN_3D, LOAD_CONTROL_3D, METHODS_3D, ModelParameters3D
from .table import _quote

#: The methods of a case, each the name of one of the core's solvers.
METHODS = ("static", "dynamic", "limit")

#: The options of both incremental solvers (``solve_static`` and ``solve_dynamic``) a case may give.
INCREMENTAL_OPTIONS = ("control", "steps", "max_displacement", "control_block", "tolerance")
#: The options of the explicit solver only (``solve_dynamic``); the static solver ignores them.
EXPLICIT_OPTIONS = ("damping", "damping_coefficient", "time_step", "unbalanced_ratio", "threads", "large_rotations", "contact_update")
#: The options of limit analysis in either dimension: along the mechanism (``Model.solve_limit``,
#: ``Model3D.solve_limit``).
LIMIT_OPTIONS = ("follow_mechanism", "follow_step", "follow_steps")
#: The options of a support's movement, in the plane: limit analysis along it, or the explicit solver driving it.
MOVEMENT_OPTIONS = ("move_support", "move_direction")
#: The options each method takes from a case: limit analysis has no load path and takes none of the load
#: path's, only whether to follow its mechanism (:data:`LIMIT_OPTIONS`); in 3D it takes ``threads`` too
#: (:data:`LIMIT_3D_OPTIONS`).
SOLVER_OPTIONS = {"static": INCREMENTAL_OPTIONS, "dynamic": INCREMENTAL_OPTIONS + EXPLICIT_OPTIONS + MOVEMENT_OPTIONS,
                  "limit": LIMIT_OPTIONS + MOVEMENT_OPTIONS}
#: The options limit analysis in 3D takes from a case (``Model3D.solve_limit``).
LIMIT_3D_OPTIONS = ("threads",) + LIMIT_OPTIONS

#: The core's defaults (``ModelSpec::default()``; ``StaticOptions`` / ``ExplicitOptions::default()``) of
#: the parameters Python shows when a case leaves them out (:attr:`Case.model_kwargs`,
#: :attr:`Case.analysis_kwargs`, :meth:`Case.solver_kwargs`) or checks a key against (the damping kind of
#: ``damping_coefficient``; the live load when the core's ``Model`` does not tell its own). None for
#: top_rotation, joints, max_displacement and control_block: left out.
CORE_DEFAULTS: Mapping[str, Any] = MappingProxyType(dict(_core.DEFAULTS))

Progress = Callable[[int, float, float, float], None]

#: The length of a time history under a built-in pulse when [time_history] gives no ``duration``, in periods
#: of the pulse.
PULSE_PERIODS = 3.0


def _in_file(exc: MasonryError, source: str) -> MasonryError:
    """The core's error ``exc`` again, of its class, with the case file's name in front (and the key it
    concerns kept: ``InputError.key``)."""
    again = type(exc)(f"{source}: {exc}")
    if isinstance(exc, InputError):
        again.key = exc.key
    return again


def _given(parameters: Any, names: Sequence[str]) -> Dict[str, Any]:
    """The parameters of ``names`` that are given (not None), by name."""
    values = ((name, getattr(parameters, name)) for name in names)
    return {name: value for name, value in values if value is not None}


#: The blocks of a wall in the plane as :class:`masonry_dem.Model` takes them: an (n, 4) array of rectangles [x0, y0,
#: x1, y1] (m), or a list of rectangles and polygons (each an array of vertices [x, y], m).
Blocks = Union[np.ndarray, List[Any]]


@dataclass(frozen=True, eq=False)
class ModelParameters:
    """The wall of a case, as the arguments of :class:`masonry_dem.Model`.

    ``blocks`` is an (n, 4) array of rectangles [x0, y0, x1, y1] (m), or a list of rectangles and polygons
    (:data:`Blocks`); the others are those the case gives, None when it leaves them out (the core's default; for
    top_rotation: no top beam; for joints: the default law everywhere; for supports: none): thickness [m], density
    [kg/m3], base, top_rotation, top_force [N], joints, gravity [m/s2], live, top_vertical, supports (polygons, each
    an array of vertices (x, y) in m: fixed blocks), carried (the loads carried by wall blocks: (block, [x, y] m,
    weight N)).
    """

    dimension: ClassVar[int] = 2

    blocks: Blocks
    thickness: Optional[float] = None
    density: Optional[float] = None
    base: Optional[bool] = None
    top_rotation: Optional[str] = None
    top_force: Optional[List[float]] = None
    joints: Optional[Dict[str, Dict[str, float]]] = None
    gravity: Optional[float] = None
    live: Optional[str] = None
    top_vertical: Optional[str] = None
    supports: Optional[List[Any]] = None
    carried: Optional[List[Tuple[int, List[float], float]]] = None

    def arguments(self) -> Dict[str, Any]:
        """The keyword arguments of ``Model``: blocks and the parameters given."""
        return _given(self, [f.name for f in fields(self)])


@dataclass(frozen=True)
class AnalysisParameters:
    """The solver options of a case's [analysis] table, None when it leaves them out (the solver's own
    default; max_displacement None: the static solver goes on until collapse).

    :data:`INCREMENTAL_OPTIONS` (control, steps, max_displacement [m], control_block, tolerance) are those
    of both incremental solvers, :data:`EXPLICIT_OPTIONS` (damping, damping_coefficient, time_step [s],
    unbalanced_ratio, threads, large_rotations, contact_update) the explicit solver's only; limit analysis takes none of them, but in 3D
    threads (:data:`LIMIT_3D_OPTIONS`). :data:`LIMIT_OPTIONS` (follow_mechanism, follow_step [m],
    follow_steps) are limit analysis's in either dimension: its mechanism followed to the end. :data:`MOVEMENT_OPTIONS`
    (move_support, move_direction) a support's movement, in the plane: followed by limit analysis, or driven by
    the explicit solver.
    """

    control: Optional[str] = None
    steps: Optional[int] = None
    max_displacement: Optional[float] = None
    control_block: Optional[int] = None
    tolerance: Optional[float] = None
    damping: Optional[str] = None
    damping_coefficient: Optional[float] = None
    time_step: Optional[float] = None
    unbalanced_ratio: Optional[float] = None
    threads: Optional[int] = None
    large_rotations: Optional[bool] = None
    contact_update: Optional[bool] = None
    follow_mechanism: Optional[bool] = None
    follow_step: Optional[float] = None
    follow_steps: Optional[int] = None
    move_support: Optional[int] = None
    move_direction: Optional[str] = None

    def arguments(self, method: str, dimension: int = 2) -> Dict[str, Any]:
        """The keyword arguments of the solver of ``method`` in ``dimension``: the options given that it takes."""
        if method == "limit" and dimension == 3:
            return _given(self, LIMIT_3D_OPTIONS)
        return _given(self, SOLVER_OPTIONS[method])


@dataclass(frozen=True, eq=False)
class GroundMotionParameters:
    """The ground motion of a case ([ground_motion]): the records as read, unscaled, and their factors.

    Attributes:
        horizontal: the horizontal component (:class:`masonry_dem.ground_motion.GroundMotion`) [m/s2].
        scale: the factor on the horizontal component (``scale``, default 1).
        vertical: the vertical component (``vertical_file``), upward positive, or None.
        vertical_scale: the factor on the vertical component; None: the horizontal's ``scale``.
        files: the record files read (never to be overwritten by an output).
        pulse: "one-sine" or "ricker" for a built-in pulse, else None.
        period: the pulse's period [s], else None.
        direction: of a 3D case, the horizontal component's direction in plan [deg] from +x towards +y; None:
            along x.
    """

    horizontal: GroundMotion
    scale: float = 1.0
    vertical: Optional[GroundMotion] = None
    vertical_scale: Optional[float] = None
    files: tuple = ()
    pulse: Optional[str] = None
    period: Optional[float] = None
    direction: Optional[float] = None

    def components(self, scale: Optional[float] = None) -> "tuple[GroundMotion, Optional[GroundMotion]]":
        """(horizontal, vertical or None), scaled: the horizontal by ``scale`` (default: the case's), the
        vertical by ``vertical_scale``, or by the horizontal's factor when the case gives none."""
        factor = self.scale if scale is None else float(scale)
        horizontal = self.horizontal.scaled(factor)
        if self.vertical is None:
            return horizontal, None
        return horizontal, self.vertical.scaled(factor if self.vertical_scale is None else self.vertical_scale)

    @property
    def default_duration(self) -> float:
        """The length of a time history left to its default [s]: the records' (the last sample of either
        component), or :data:`PULSE_PERIODS` periods of a pulse (at least the pulse's own length)."""
        ends = [self.horizontal.duration] + ([self.vertical.duration] if self.vertical is not None else [])
        if self.pulse is not None and self.period is not None:
            ends.append(PULSE_PERIODS * self.period)
        return float(max(ends))


@dataclass(frozen=True)
class TimeHistoryParameters:
    """The options of a time history ([time_history]), None when the case leaves them out: duration [s]
    (default: the ground motion's, :attr:`GroundMotionParameters.default_duration`), and record_interval [s],
    damping, damping_coefficient, time_step [s], large_rotations and contact_update (default: the core's, of
    ``Model.simulate``); with damping "rayleigh", damping_ratio: the ratio of Rayleigh damping at the elastic
    model's first two modes."""

    duration: Optional[float] = None
    record_interval: Optional[float] = None
    damping: Optional[str] = None
    damping_coefficient: Optional[float] = None
    damping_ratio: Optional[float] = None
    time_step: Optional[float] = None
    large_rotations: Optional[bool] = None
    contact_update: Optional[bool] = None


class _Arguments(MutableMapping):  # type: ignore[type-arg]
    """Some parameters of a case as a dict of keyword arguments (``Case.model_kwargs``, ``analysis_kwargs``,
    ``dynamic_kwargs``): each of ``names`` that the case gives, and each of ``shown`` with the core's
    default (:data:`CORE_DEFAULTS`) when it does not. Setting a key sets that parameter on the case (a new
    frozen object), deleting one leaves it out."""

    def __init__(self, case: "Case", attribute: str, names: Sequence[str], shown: Sequence[str] = (),
                 defaults: Mapping[str, Any] = CORE_DEFAULTS) -> None:
        self._case, self._attribute, self._names, self._shown = case, attribute, tuple(names), tuple(shown)
        self._defaults = defaults

    def _values(self) -> Dict[str, Any]:
        parameters = getattr(self._case, self._attribute)
        out = {}
        for name in self._names:
            value = getattr(parameters, name)
            if value is None and name in self._shown:
                value = copy.deepcopy(self._defaults[name])
            if value is not None or name in self._shown:
                out[name] = value
        return out

    def __getitem__(self, key: str) -> Any:
        return self._values()[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._values())

    def __len__(self) -> int:
        return len(self._values())

    def __setitem__(self, key: str, value: Any) -> None:
        if key not in self._names:
            raise KeyError(key)
        setattr(self._case, self._attribute, replace(getattr(self._case, self._attribute), **{key: value}))

    def __delitem__(self, key: str) -> None:
        self[key] = None

    def __repr__(self) -> str:
        return repr(self._values())


def generate_blocks(kind: str, geometry: Mapping[str, Any], source: str) -> Blocks:
    """The blocks of a checked [geometry] of ``kind`` ("running_bond", "pattern", "blocks", "gable" or
    "stone_wall"), from the arguments given (None: left out, the generator's default): an (n, 4) array of
    rectangles, or with ``polygons`` (kind "blocks") the rectangles then the polygons in a list, or the polygons of a
    gable or a stone wall in a list (:data:`Blocks`). The core's generators
    may still refuse them (their message, which names the key, gets the file name in front)."""
    arguments = {key: value for key, value in geometry.items() if value is not None}
    try:
        if kind == "running_bond":
            return _core.running_bond(**arguments)
        if kind == "pattern":
            return _core.pattern(**arguments)
        if kind == "gable":
            return _core.gable(**arguments)  # type: ignore[no-any-return]
        if kind == "stone_wall":
            return _core.stone_wall(**arguments)  # type: ignore[no-any-return]
        if geometry.get("polygons"):
            return [list(map(float, r)) for r in geometry["blocks"]] + list(geometry["polygons"])
        return np.asarray(geometry["blocks"], dtype=np.float64)
    except MasonryError as exc:
        raise _in_file(exc, source) from exc  # the core names the key (geometry.<kind>.<key>)


def generate_arch(arguments: Mapping[str, Any], source: str) -> Dict[str, Any]:
    """The arch of a checked [geometry.arch] (the core's generator ``arch``, the arguments given; None: left out):
    {"blocks": the voussoirs then the piers' blocks, "supports": the abutments, "intrados", "extrados": the joints'
    ends along each}, each a list of vertices or points [x, y] [m], and "carried": the backfill's weights, a list of
    (voussoir, [x, y], weight [N]) (empty without a backfill). The generator's refusals (of a rise that does not
    fit the span, abutments and piers both, ...), which name the key, get the file name in front."""
    try:
        made = _core.arch(**{key: value for key, value in arguments.items() if value is not None})
    except MasonryError as exc:
        again = _in_file(exc, source)
        named = re.match(r"geometry\.arch(\.\w+)?", str(exc))
        if isinstance(again, InputError) and again.key is None and named:
            again.key = named.group(0)  # the key the message starts with
        raise again from exc
    made_lists = {key: [np.asarray(p, dtype=np.float64).tolist() for p in made[key]] for key in
                  ("blocks", "supports", "intrados", "extrados")}
    return {**made_lists, "carried": [(int(k), [float(v) for v in p], float(w)) for k, p, w in made["carried"]]}


@dataclass
class Case:
    """One wall and one analysis, as read from a case file.

    Attributes:
        title: the case title.
        model: the wall, the arguments of :class:`masonry_dem.Model` (:class:`ModelParameters`), or of a 3D wall
            those of :class:`masonry_dem.Model3D` (:class:`masonry_dem.space.case.ModelParameters3D`).
        analysis: the options of the incremental solvers, :meth:`masonry_dem.Model.solve_static` and
            :meth:`masonry_dem.Model.solve_dynamic` (:class:`AnalysisParameters`); limit analysis
            (:meth:`masonry_dem.Model.solve_limit`) ignores them.
        method: "static", "dynamic" or "limit".
        source: where the case came from (file name), the first word of every error message.
        reference: the optional [reference] table, or None: ``{"collapse_multiplier": float,
            "tolerance": float, "source": str, "methods": tuple}`` (the multiplier is a force in N with
            live = "top_horizontal"; tolerance is relative, default 0.01; source may be ""; methods are
            those the reference applies to). ``masonry-dem validate`` checks the case against it.
        ground_motion: the optional [ground_motion] (:class:`GroundMotionParameters`, the records read), or
            None; ``masonry-dem simulate`` and :meth:`simulate` run the wall under it.
        time_history: the [time_history] options (:class:`TimeHistoryParameters`; all None when left out).
        assessment: the optional [assessment] (:class:`masonry_dem.assessment.AssessmentParameters`: the demand
            spectrum and the check's parameters), or None; ``masonry-dem assess`` checks the analysis against it.
        arch: of a [geometry.arch], what the arch generator gives besides the blocks (its ``intrados`` and
            ``extrados``, lists of points (x, y) in m), by which the report names an arch's hinges; else None.

    The same parameters as dicts of keyword arguments: :attr:`model_kwargs`, :attr:`analysis_kwargs`,
    :attr:`dynamic_kwargs` and :meth:`solver_kwargs`.
    """

    title: str
    model: Union[ModelParameters, ModelParameters3D]
    analysis: AnalysisParameters = field(default_factory=AnalysisParameters)
    method: str = "static"
    source: str = "<case>"
    reference: Optional[Dict[str, Any]] = None
    ground_motion: Optional[GroundMotionParameters] = None
    time_history: TimeHistoryParameters = field(default_factory=TimeHistoryParameters)
    assessment: Optional[AssessmentParameters] = None
    arch: Optional[Dict[str, Any]] = None

    @property
    def dimension(self) -> int:
        """2 for a wall in the plane, 3 for a wall of boxes (its model a :class:`masonry_dem.Model3D`)."""
        return int(self.model.dimension)

    @property
    def model_kwargs(self) -> MutableMapping[str, Any]:
        """The keyword arguments of :class:`masonry_dem.Model` as a dict: blocks, thickness, density, base,
        top_rotation, top_force, joints, gravity, live, top_vertical, supports, carried (the core's default for
        those the case leaves out); of a 3D wall, those of :class:`masonry_dem.Model3D` (boxes, density, base, top,
        joints, gravity, live, direction, carried). Setting a key sets that parameter of the case."""
        names = [f.name for f in fields(self.model)]
        if self.dimension == 3:
            return _Arguments(self, "model", names, shown=names, defaults=CORE_DEFAULTS_3D)
        return _Arguments(self, "model", names, shown=names)

    @property
    def analysis_kwargs(self) -> MutableMapping[str, Any]:
        """The options common to both incremental solvers as a dict: control, steps, max_displacement,
        control_block (the core's default for those the case leaves out; max_displacement None: until
        collapse), and tolerance when the case gives it. Setting a key sets that option of the case."""
        return _Arguments(self, "analysis", INCREMENTAL_OPTIONS, shown=INCREMENTAL_OPTIONS[:4])

    @property
    def dynamic_kwargs(self) -> MutableMapping[str, Any]:
        """The explicit solver's own options that the case gives, as a dict (damping, damping_coefficient,
        time_step [s], unbalanced_ratio, threads, large_rotations, contact_update); the static solver ignores
        them."""
        return _Arguments(self, "analysis", EXPLICIT_OPTIONS)

    def live_load(self, model: Any = None) -> str:
        """The live load, "horizontal_weight" or "top_horizontal": ``Model.live`` of ``model`` (built by
        :meth:`build_model`) when the core tells it, else the case's."""
        live = getattr(model, "live", None)
        return str(live if live is not None else self.model_kwargs["live"])

    def build_model(self) -> Any:
        """Build the model (a :class:`masonry_dem.Model`, or a :class:`masonry_dem.Model3D` of a 3D wall); errors of
        the core are re-raised with the file name in front."""
        try:
            if self.dimension == 3:
                return _core.Model3D(**self.model.arguments())
            return _core.Model(**self.model.arguments())
        except MasonryError as exc:
            raise _in_file(exc, self.source) from exc

    def check_method(self, method: Optional[str] = None) -> str:
        """The method to use, ``method`` ("static" | "dynamic" | "limit") overriding the case's.

        Raises:
            masonry_dem.InputError: an unknown method; for a 3D wall, "static" (it takes "limit" and "dynamic"), or
                "dynamic" with displacement control; "static" for a support's movement.
        """
        method = self.method if method is None else method
        if method not in METHODS:
            expected = ", ".join(_quote(m) for m in METHODS)
            raise InputError(f"{self.source}: method: expected one of {expected}, got {_quote(method)}")
        if self.dimension == 3 and method not in METHODS_3D:
            raise InputError(f"{self.source}: method {_quote(method)}: {IN_3D} (this case is 3D)", "analysis.method")
        if self.dimension == 3 and method == "dynamic" and self.analysis.control == "displacement":
            raise InputError(f'{self.source}: analysis.control = "displacement": {LOAD_CONTROL_3D} (this case is 3D)',
                             "analysis.control")
        if method == "static" and self.analysis.move_support is not None:
            raise InputError(f'{self.source}: analysis.move_support: a support\'s movement is taken by method "limit" '
                             'or "dynamic", not "static"', "analysis.move_support")
        return method

    @property
    def movement(self) -> Optional[Tuple[int, str]]:
        """The support's movement of [analysis] (move_support, move_direction), or None."""
        a = self.analysis
        return None if a.move_support is None or a.move_direction is None else (a.move_support, a.move_direction)

    def solver_kwargs(self, method: Optional[str] = None) -> Dict[str, Any]:
        """The keyword arguments of the solver of ``method`` (default: the case's), without ``progress``, as
        :attr:`analysis_kwargs` shows them (and :attr:`dynamic_kwargs` for "dynamic"); a max_displacement
        left out is left out.

        Limit analysis takes none of the case's [analysis] keys that describe a load path (control,
        steps, max_displacement, and tolerance, the precision of the incremental solvers' multiplier);
        ``Model.solve_limit`` runs with its own defaults, in 3D on the case's ``threads`` if it gives them."""
        method = self.check_method(method)
        if method == "limit":
            return self.analysis.arguments(method, self.dimension)
        kwargs = {k: v for k, v in self.analysis_kwargs.items() if not (k == "max_displacement" and v is None)}
        if method == "dynamic":
            kwargs.update(self.dynamic_kwargs)
        return kwargs

    def solve(
        self, model: "_core.Model", method: Optional[str] = None, progress: Optional[Progress] = None
    ) -> "_core.Results":
        """Run the analysis of this case on ``model`` (built by :meth:`build_model`).

        ``method`` overrides the case's [analysis] method: "static" calls ``Model.solve_static``,
        "dynamic" ``Model.solve_dynamic``, "limit" ``Model.solve_limit``, each with the options the case
        gives (the others take the solver's defaults). ``progress``, if given, is the solvers' progress
        callback ``(step, multiplier, displacement, fraction)`` (limit analysis: the interior-point
        iteration, the current multiplier, NaN, NaN). The solvers never raise for a solver failure: check
        ``Results.status`` and ``Results.error``. Errors of the core about the input (e.g. a time_step
        above the stability limit) are re-raised with the file name in front.
        """
        method = self.check_method(method)
        kwargs = self.analysis.arguments(method, self.dimension)
        if progress is not None:
            kwargs["progress"] = progress
        if self.dimension == 3:  # limit analysis or the explicit solver (check_method refuses the static one)
            solver = {"dynamic": model.solve_dynamic, "limit": model.solve_limit}[method]
        else:
            solver = {"static": model.solve_static, "dynamic": model.solve_dynamic, "limit": model.solve_limit}[method]
        try:
            return solver(**kwargs)
        except MasonryError as exc:
            raise _in_file(exc, self.source) from exc

    def run(self, method: Optional[str] = None, progress: Optional[Progress] = None) -> "_core.Results":
        """Build the model and run the analysis; ``method`` overrides the case's method."""
        method = self.check_method(method)
        return self.solve(self.build_model(), method, progress)

    def simulate_kwargs(
        self, scale: Optional[float] = None, duration: Optional[float] = None, model: Optional["_core.Model"] = None
    ) -> Dict[str, Any]:
        """The keyword arguments of ``Model.simulate`` for this case's time history, without ``progress``:
        ``duration`` [s] (the argument, else [time_history] duration, else the ground motion's),
        ``base_acceleration`` (and ``vertical_acceleration``) scaled by ``scale`` (default: the case's
        [ground_motion] scale; see :meth:`GroundMotionParameters.components`), and the [time_history] options
        given (record_interval [s], damping, damping_coefficient, time_step [s], large_rotations; the others are
        left to the core's defaults). Rayleigh damping (damping "rayleigh") is ``rayleigh=(alpha, beta)`` for
        damping_ratio at the first two modes of ``model`` (:func:`masonry_dem.rayleigh_damping`), which it needs.
        Of a 3D case, ``Model3D.simulate``'s: the horizontal component along x, or split along x and y
        (``base_acceleration_y``) by [ground_motion] direction.

        Raises:
            masonry_dem.InputError: the case has no [ground_motion], or ``scale`` / ``duration`` is not a
                finite number (duration > 0), or Rayleigh damping without ``model``.
        """
        if self.ground_motion is None:
            raise InputError(f"{self.source}: no [ground_motion] table: a time history needs a ground motion "
                             "(a record file or a pulse)", "ground_motion")
        if scale is not None:
            scale = _checked_number("scale", scale, self.source, positive=False)
        if duration is not None:
            duration = _checked_number("duration", duration, self.source, positive=True)
        options = self.time_history
        length = duration if duration is not None else options.duration
        if length is None:
            length = self.ground_motion.default_duration
        kwargs: Dict[str, Any] = {"duration": float(length)}
        kwargs.update(simulate_arguments(*self.ground_motion.components(scale)))
        if self.ground_motion.direction is not None and "base_acceleration" in kwargs:
            times, values = kwargs.pop("base_acceleration")
            c, s = _cos_sin_deg(self.ground_motion.direction)
            if c != 0.0:
                kwargs["base_acceleration"] = (times, values * c)
            if s != 0.0:
                kwargs["base_acceleration_y"] = (times, values * s)
        kwargs.update(_given(options, ("record_interval", "damping", "damping_coefficient", "time_step",
                                       "large_rotations", "contact_update")))
        if options.damping == "rayleigh":
            if model is None:
                raise InputError(f"{self.source}: [time_history] damping = \"rayleigh\" is set from the model's "
                                 "modes: simulate_kwargs needs model=", "time_history.damping")
            from ..modal import rayleigh_damping

            del kwargs["damping"]
            kwargs["rayleigh"] = rayleigh_damping(model, float(options.damping_ratio))  # type: ignore[arg-type]
        return kwargs

    def simulate(
        self,
        model: "_core.Model",
        scale: Optional[float] = None,
        duration: Optional[float] = None,
        progress: Optional[Progress] = None,
    ) -> "_core.TimeHistory":
        """Run this case's time history on ``model`` (built by :meth:`build_model`): ``Model.simulate`` with
        :meth:`simulate_kwargs` (``scale``: the factor on the ground motion, replacing [ground_motion] scale;
        ``duration`` [s], replacing [time_history] duration). ``progress``: the solvers' callback. The
        solver does not raise for a failure: check ``TimeHistory.status``. Errors of the core about the input
        are re-raised with the file name in front."""
        kwargs = self.simulate_kwargs(scale, duration, model)
        if progress is not None:
            kwargs["progress"] = progress
        try:
            return model.simulate(**kwargs)
        except MasonryError as exc:
            raise _in_file(exc, self.source) from exc


def _cos_sin_deg(degrees: float) -> "tuple[float, float]":
    """(cos, sin) of an angle in degrees, exact at the multiples of 90 (a motion along y has no x part at all)."""
    import math

    quarter = degrees / 90.0
    if quarter == round(quarter):
        return ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(round(quarter)) % 4]
    a = math.radians(degrees)
    return math.cos(a), math.sin(a)


def _checked_number(name: str, value: Any, source: str, positive: bool) -> float:
    """``value`` as a finite float (> 0 if ``positive``), else InputError naming ``name``."""
    import math

    try:
        x = float(value) if not isinstance(value, bool) else math.nan
    except (TypeError, ValueError):
        x = math.nan
    if not math.isfinite(x) or (positive and x <= 0):
        raise InputError(f"{source}: {name}: expected a finite number{' > 0' if positive else ''}, got {value!r}", name)
    return x
