"""What a seismic check is made with, checked: the demand spectrum and the parameters of the code's rules
(:class:`AssessmentParameters`), from Python or from a case file's [assessment] table (:func:`read_assessment`).

Every refusal names its parameter, which is the case file's key of [assessment] (``q``, ``confidence_factor``,
``mechanism_height``, ``building_height``, ``storeys``, and the spectrum's keys of :mod:`.spectra`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Dict, Optional, Union

from .._core import InputError
from ..case.table import _non_negative, _positive
from .spectra import Spectrum, _number, _refuse, ec8_spectrum, ntc2018_spectrum, read_spectrum

PathLike = Union[str, "os.PathLike[str]"]

#: The keys of a case file's [assessment] table (docs/case-format.md, "[assessment]").
ASSESSMENT_KEYS = (
    "spectrum", "ag", "ground_type", "spectrum_type", "importance", "damping", "F0", "Tc_star", "soil", "topography",
    "spectrum_units", "Tc", "q", "confidence_factor", "mechanism_height", "building_height", "storeys",
    "height_rule", "building_damping", "T1",
)
#: The keys of each kind of spectrum (``spectrum``: "ec8", "ntc2018", or a file's name).
SPECTRUM_KEYS = {
    "ec8": ("ag", "ground_type", "spectrum_type", "importance", "damping"),
    "ntc2018": ("ag", "F0", "Tc_star", "soil", "topography", "damping"),
    "file": ("spectrum_units", "Tc"),
}
#: The behaviour factor of the linear kinematic check (Circolare 617/2009 C8A.4.2.3: q = 2).
DEFAULT_Q = 2.0
#: The confidence factor of the knowledge level LC1 (Circolare 2019 C8.5.4, Table C8.5.IV: 1.35, 1.20 and 1.00 for
#: LC1, LC2, LC3).
DEFAULT_CONFIDENCE_FACTOR = 1.35
#: The coefficient C1 of the building's period T1 = C1 H^(3/4) for a masonry building (Circolare 2019 C7.3.3.2, eq.
#: C7.3.2: 0.050 "for masonry buildings or any other type of structure").
MASONRY_C1 = 0.05
#: The rules of the demand on a mechanism at height: "circ2009" (Circolare 617/2009 C8A.4.2.3: S_e(T1) psi(Z)
#: gamma / q) or "circ2019" (the 2019 Circolare's floor acceleration, C8.7.1.2.1.7 with C7.2.7 and C7.2.8).
HEIGHT_RULES = ("circ2009", "circ2019")


@dataclass(frozen=True)
class AssessmentParameters:
    """The demand spectrum and the parameters of a seismic check, checked.

    Attributes:
        spectrum: the elastic spectrum of the site (:class:`masonry_dem.assessment.Spectrum`).
        q: the behaviour factor of the linear kinematic check (>= 1; default 2).
        confidence_factor: FC (>= 1; default 1.35, knowledge level LC1).
        mechanism_height: Z [m], the height above the foundation of the mechanism's hinges (>= 0; 0: a mechanism at
            ground level).
        building_height: H [m], the building's height above its foundation (needed when Z > 0; >= Z).
        storeys: N, the building's storeys (an integer >= 1, needed when Z > 0).
        height_rule: the rule of the demand at height, "circ2009" (default) or "circ2019" (:data:`HEIGHT_RULES`).
        building_damping: xi_1, the building's first mode's equivalent viscous damping ratio (0.05 for 5%, the
            default), which the 2019 rule's floor acceleration takes (0 <= xi_1 < 1).
        T1: the building's first period [s] (> 0) from a model of it (NTC 2018 eq. 7.3.6, to which the 2019
            Circolare's C7.2.3 points), or None: then C1 H^(3/4).
    """

    spectrum: Spectrum
    q: float = DEFAULT_Q
    confidence_factor: float = DEFAULT_CONFIDENCE_FACTOR
    mechanism_height: float = 0.0
    building_height: Optional[float] = None
    storeys: Optional[int] = None
    height_rule: str = "circ2009"
    building_damping: float = 0.05
    T1: Optional[float] = None

    def __post_init__(self) -> None:
        if not isinstance(self.spectrum, Spectrum):
            raise _refuse("spectrum", f"expected a masonry_dem.assessment.Spectrum, got {type(self.spectrum).__name__}")
        q = _number("q", self.q)
        if q < 1:
            raise _refuse("q", f"the behaviour factor must be >= 1, got {self.q!r}")
        fc = _number("confidence_factor", self.confidence_factor)
        if fc < 1:
            raise _refuse("confidence_factor", f"must be >= 1 (1.35, 1.20, 1.00 for the knowledge levels LC1, LC2, "
                                               f"LC3), got {self.confidence_factor!r}")
        z = _number("mechanism_height", self.mechanism_height, minimum=0.0)
        h = None if self.building_height is None else _number("building_height", self.building_height, positive=True)
        n = self.storeys
        if n is not None and (isinstance(n, bool) or not isinstance(n, int) or n < 1):
            raise _refuse("storeys", f"expected an integer >= 1, got {n!r}")
        if z > 0:
            if h is None:
                raise _refuse("building_height", f"a mechanism at height (mechanism_height = {z:g} m) needs the "
                                                 "building's height H [m]")
            if n is None:
                raise _refuse("storeys", f"a mechanism at height (mechanism_height = {z:g} m) needs the building's "
                                         "number of storeys N")
        if h is not None and z > h:
            raise _refuse("mechanism_height", f"{z:g} m is above the building (building_height = {h:g} m)")
        if self.height_rule not in HEIGHT_RULES:
            raise _refuse("height_rule", f"expected one of {', '.join(repr(r) for r in HEIGHT_RULES)}, got "
                                         f"{self.height_rule!r}")
        xi = _number("building_damping", self.building_damping, minimum=0.0)
        if xi >= 1.0:
            raise _refuse("building_damping", f"is the damping ratio, 0 <= building_damping < 1 (0.05 for 5%), got "
                                              f"{self.building_damping!r}")
        if self.height_rule == "circ2019" and z > 0 and xi != 0.05 and self.spectrum.code == "file":
            raise _refuse("building_damping", "a spectrum from a file is at its own damping: the 2019 rule's S_e(T1, "
                                              "xi_1) needs a code's spectrum for a damping other than 5%")
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "confidence_factor", fc)
        object.__setattr__(self, "mechanism_height", z)
        object.__setattr__(self, "building_height", h)
        object.__setattr__(self, "building_damping", xi)
        if self.T1 is not None:
            object.__setattr__(self, "T1", _number("T1", self.T1, positive=True))

    @property
    def at_height(self) -> bool:
        """Whether the mechanism is above ground level (Z > 0): its demand follows the building's first mode."""
        return self.mechanism_height > 0

    def building_period(self) -> float:
        """T1 [s]: the one given, else C1 H^(3/4), C1 = 0.05 for masonry (Circolare 2019 eq. C7.3.2); NaN without
        either."""
        if self.T1 is not None:
            return self.T1
        return MASONRY_C1 * self.building_height ** 0.75 if self.building_height is not None else math.nan

    def modal_shape(self) -> float:
        """psi(Z) = Z / H (Circolare 617/2009 C8A.4.2.3; the 2019 Circolare's linear first mode normalised to the top,
        C7.2.3), the first mode normalised to 1 at the top; 0 at ground level."""
        return self.mechanism_height / self.building_height if self.building_height else 0.0

    def participation(self) -> float:
        """gamma = 3 N / (2 N + 1) (Circolare 617/2009 C8A.4.2.3; Circolare 2019 eq. C7.2.10), the first mode's
        participation; NaN without N."""
        return 3.0 * self.storeys / (2.0 * self.storeys + 1.0) if self.storeys is not None else math.nan


def read_assessment(table: Any, base_dir: Optional[PathLike] = None) -> AssessmentParameters:
    """A case file's [assessment] table (a checked :class:`masonry_dem.case.table._Table` with the keys of
    :data:`ASSESSMENT_KEYS`): the spectrum ("ec8", "ntc2018", or a file relative to ``base_dir``) with its keys, and
    the check's parameters. Each refusal is an InputError that starts with the file's name and names the key
    (``assessment.F0``)."""
    kind = table.string("spectrum", "ec8")
    family = kind if kind in ("ec8", "ntc2018") else "file"
    if not kind:
        raise table.key_error("spectrum", 'expected "ec8", "ntc2018" or the name of a spectrum file, got ""')
    for key in sorted(set(k for keys in SPECTRUM_KEYS.values() for k in keys) - set(SPECTRUM_KEYS[family])):
        if key in table:
            what = f'spectrum = "{kind}"' if family != "file" else "a spectrum from a file"
            raise table.key_error(key, f"does not apply to {what} (it takes {', '.join(SPECTRUM_KEYS[family])})")
    args: Dict[str, Any] = {}
    try:
        if family == "ec8":
            args = dict(ag=table.number("ag", unit="acceleration"), ground_type=table.string("ground_type", "A"),
                        spectrum_type=table.integer("spectrum_type", 1), importance=table.number("importance", 1.0),
                        damping=table.number("damping", 0.05))
            spectrum = ec8_spectrum(**args)
        elif family == "ntc2018":
            args = dict(ag=table.number("ag", unit="acceleration"), F0=table.number("F0"),
                        Tc_star=table.number("Tc_star", unit="time"), soil=table.string("soil", "A"),
                        topography=table.string("topography", "T1"), damping=table.number("damping", 0.05))
            spectrum = ntc2018_spectrum(**args)
        else:
            units = table.string("spectrum_units", None, ("g", "m/s2"))
            if units is None:
                raise table.error(f"missing key 'spectrum_units' in [{table.path}] (the units of the file's "
                                  'accelerations: "g" or "m/s2")', table.where("spectrum_units"))
            path = Path(kind)
            if base_dir is not None and not path.is_absolute():
                path = Path(base_dir) / path
            tc = table.number("Tc", None, _positive, unit="time")
            try:
                spectrum = read_spectrum(path, units, TC=tc)
            except OSError as exc:
                raise table.key_error("spectrum", f"cannot read {path}: {exc.strerror or exc}") from None
            except InputError as exc:
                raise table.key_error("spectrum", _problem(exc, "spectrum")) from None
        return AssessmentParameters(
            spectrum=spectrum,
            q=table.number("q", DEFAULT_Q),
            confidence_factor=table.number("confidence_factor", DEFAULT_CONFIDENCE_FACTOR),
            mechanism_height=table.number("mechanism_height", 0.0, _non_negative, unit="length"),
            building_height=table.number("building_height", None, unit="length"),
            storeys=table.integer("storeys", None),
            height_rule=table.string("height_rule", "circ2009", HEIGHT_RULES),
            building_damping=table.number("building_damping", 0.05),
            T1=table.number("T1", None, unit="time"),
        )
    except InputError as exc:  # a refusal of the spectrum or of the parameters, named by its key: in the file's words
        key = getattr(exc, "key", None)
        if key in ASSESSMENT_KEYS and not str(exc).startswith(f"{table.source}: "):
            raise table.key_error(key, _problem(exc, key)) from None
        raise


def _problem(exc: InputError, key: str) -> str:
    """The message of ``exc`` without the name of ``key`` in front ("F0: must be >= 2.2" -> "must be >= 2.2")."""
    text = str(exc)
    return text[len(key) + 2:] if text.startswith(f"{key}: ") else text
