"""Units: SI constants to multiply by, and :func:`parse_quantity` for values written with their unit.

masonry-dem computes in SI (m, N, Pa, kg, s). A constant here is the SI value of one unit, so that a value is
written as an engineer would and multiplied into SI:

>>> import masonry_dem as md
>>> 0.25 * md.MPa                      # a tensile strength [Pa]
250000.0
>>> 82 * md.N_per_mm3                  # a joint stiffness [N/m3]
82000000000.0
>>> 10 * md.kN                         # a force [N]
10000.0

(a product is rounded as floats are: ``175 * md.mm`` is 0.17500000000000002; :func:`parse_quantity` gives
the float nearest the decimal value, 0.175).

:func:`parse_quantity` reads a string with its unit, as case files accept them (docs/case-format.md, "Units"), and
refuses a unit of another kind:

>>> parse_quantity("0.25 MPa", "stress")
250000.0
>>> parse_quantity("175 mm", "length")
0.175
>>> parse_quantity("0.25 m", "stress", what="joints.tensile_strength")  # doctest: +IGNORE_EXCEPTION_DETAIL
Traceback (most recent call last):
...
InputError: '0.25 m' is a length; joints.tensile_strength is a stress (Pa, kPa, MPa, GPa, N/mm2)

Units are case sensitive ("MPa", not "mpa": a milli-pascal is not a mega-pascal); exponents may be written
``m3``, ``m^3`` or ``m³``, and products with ``*`` or ``·`` are not needed by any unit here.
"""

from __future__ import annotations

import difflib
import math
import re
from fractions import Fraction
from typing import Any, Dict, Optional, Tuple

from ._core import InputError

__all__ = [
    "m", "cm", "mm", "km", "s", "ms", "kg", "N", "kN", "MN", "Pa", "kPa", "MPa", "GPa",
    "N_per_m3", "kN_per_m3", "MN_per_m3", "N_per_mm3", "N_per_m", "N_per_mm", "J_per_m2",
    "kg_per_m3", "t_per_m3", "m_per_s2", "STANDARD_GRAVITY",
    "KINDS", "UNITS", "parse_quantity", "unit_names",
]

# -- constants: the SI value of one unit ---------------------------------------------------------------------

m = 1.0  #: metre [m]
cm = 0.01  #: centimetre [m]
mm = 0.001  #: millimetre [m]
km = 1000.0  #: kilometre [m]
s = 1.0  #: second [s]
ms = 0.001  #: millisecond [s]
kg = 1.0  #: kilogram [kg]
N = 1.0  #: newton [N]
kN = 1.0e3  #: kilonewton [N]
MN = 1.0e6  #: meganewton [N]
Pa = 1.0  #: pascal [Pa]
kPa = 1.0e3  #: kilopascal [Pa]
MPa = 1.0e6  #: megapascal [Pa] (= N/mm2)
GPa = 1.0e9  #: gigapascal [Pa]
N_per_m3 = 1.0  #: joint stiffness, newton per cubic metre [N/m3] (stress per unit of opening or slip)
kN_per_m3 = 1.0e3  #: joint stiffness [N/m3]
MN_per_m3 = 1.0e6  #: joint stiffness [N/m3]
N_per_mm3 = 1.0e9  #: joint stiffness as engineers write it, N/mm3 [N/m3]
N_per_m = 1.0  #: fracture energy, N/m = J/m2 [N/m]
N_per_mm = 1.0e3  #: fracture energy, N/mm [N/m]
J_per_m2 = 1.0  #: fracture energy [N/m]
kg_per_m3 = 1.0  #: mass density [kg/m3]
t_per_m3 = 1.0e3  #: mass density, tonnes per cubic metre [kg/m3]
m_per_s2 = 1.0  #: acceleration [m/s2]
#: The standard acceleration of gravity [m/s2], the unit "g" of an acceleration written with its unit ("0.25 g"), as
#: the seismic codes write ground accelerations. (A model's own gravity is its ``gravity``, 9.81 by default.)
STANDARD_GRAVITY = 9.80665

# -- the kinds of quantity and the units of each, with their exact SI factors ------------------------------

#: The kinds of quantity :func:`parse_quantity` reads, with their names in messages.
KINDS: Dict[str, str] = {
    "length": "a length",
    "force": "a force",
    "stress": "a stress",
    "stiffness": "a joint stiffness (stress per length)",
    "fracture_energy": "a fracture energy (force per length)",
    "density": "a mass density",
    "acceleration": "an acceleration",
    "time": "a time",
}

_F = Fraction
#: Every unit read: its text -> (kind, SI value of one unit, exact). The first units of a kind are those a
#: message suggests.
UNITS: Dict[str, Tuple[str, Fraction]] = {
    "m": ("length", _F(1)), "cm": ("length", _F(1, 100)), "mm": ("length", _F(1, 1000)),
    "km": ("length", _F(1000)),
    "N": ("force", _F(1)), "kN": ("force", _F(1000)), "MN": ("force", _F(10**6)),
    "Pa": ("stress", _F(1)), "kPa": ("stress", _F(1000)), "MPa": ("stress", _F(10**6)),
    "GPa": ("stress", _F(10**9)), "N/mm2": ("stress", _F(10**6)), "N/m2": ("stress", _F(1)),
    "kN/m2": ("stress", _F(1000)),
    "N/m3": ("stiffness", _F(1)), "N/mm3": ("stiffness", _F(10**9)), "kN/m3": ("stiffness", _F(1000)),
    "MN/m3": ("stiffness", _F(10**6)), "GN/m3": ("stiffness", _F(10**9)), "MPa/mm": ("stiffness", _F(10**9)),
    "N/m": ("fracture_energy", _F(1)), "N/mm": ("fracture_energy", _F(1000)), "J/m2": ("fracture_energy", _F(1)),
    "kN/m": ("fracture_energy", _F(1000)),
    "kg/m3": ("density", _F(1)), "t/m3": ("density", _F(1000)),
    "m/s2": ("acceleration", _F(1)), "mm/s2": ("acceleration", _F(1, 1000)), "cm/s2": ("acceleration", _F(1, 100)),
    "g": ("acceleration", _F("9.80665")),
    "s": ("time", _F(1)), "ms": ("time", _F(1, 1000)),
}

# the units a message lists for a kind (the others are still read)
_SHOWN = {
    "length": ("m", "cm", "mm"),
    "force": ("N", "kN", "MN"),
    "stress": ("Pa", "kPa", "MPa", "GPa", "N/mm2"),
    "stiffness": ("N/m3", "N/mm3", "MN/m3", "GN/m3"),
    "fracture_energy": ("N/m", "N/mm", "J/m2"),
    "density": ("kg/m3", "t/m3"),
    "acceleration": ("m/s2", "g"),
    "time": ("s", "ms"),
}

_NUMBER = re.compile(r"\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$", re.DOTALL)
_SUPERSCRIPTS = str.maketrans({"²": "2", "³": "3"})


def unit_names(kind: str) -> str:
    """The usual units of ``kind`` for a message, e.g. ``"Pa, kPa, MPa, GPa, N/mm2"``."""
    return ", ".join(_SHOWN[kind])


def _normal_unit(text: str) -> str:
    """A unit as written, with ``^`` and superscript exponents and blanks around ``/`` removed."""
    unit = text.translate(_SUPERSCRIPTS).replace("^", "")
    return re.sub(r"\s*/\s*", "/", unit).replace("m/s/s", "m/s2")


def parse_quantity(text: Any, kind: str, what: Optional[str] = None) -> float:
    """The SI value of ``text``, a number and its unit of ``kind`` ("0.25 MPa" -> 250000.0).

    ``kind`` is one of :data:`KINDS` ("length", "force", "stress", "stiffness", "fracture_energy", "density",
    "acceleration", "time"); ``what`` names the value in messages (a case file's key, e.g.
    "joints.tensile_strength"). A number (int or float, not bool) is taken as SI already and returned as a
    float. The value is the float nearest the exact product (the decimal number times the unit's exact
    factor): "175 mm" is 0.175, "62.9 N/mm3" is 62.9e9.

    >>> parse_quantity("82 N/mm3", "stiffness")
    82000000000.0
    >>> parse_quantity("10 kN", "force"), parse_quantity("18 N/m", "fracture_energy")
    (10000.0, 18.0)

    Raises:
        InputError: not a number with a unit, an unknown unit, or a unit of another kind (the message names
            the kind of each, e.g. "'0.25 m' is a length; joints.tensile_strength is a stress (Pa, kPa,
            MPa, GPa, N/mm2)").
        ValueError: ``kind`` is not one of :data:`KINDS` (a programming error).
    """
    if kind not in KINDS:
        raise ValueError(f"unknown kind of quantity {kind!r} (expected one of {', '.join(KINDS)})")
    name = what or "the value"
    expected = f"{KINDS[kind]} ({unit_names(kind)})"
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text)
    if not isinstance(text, str):
        raise InputError(f"{name}: expected a number or a string with a unit, got {type(text).__name__}")
    shown = text if len(text) <= 40 else text[:37] + "..."
    found = _NUMBER.fullmatch(text)
    if not found:
        raise InputError(f"{name}: expected a number, got string \"{shown}\" (or {expected} with its unit, like "
                         f"\"{_example(kind)}\")")
    number, unit_text = found.groups()
    if not unit_text:
        raise InputError(f"{name}: expected a number, got string \"{shown}\" without a unit (write the number "
                         f"in SI without quotes, or {expected} with its unit, like \"{_example(kind)}\")")
    unit = _normal_unit(unit_text)
    if unit not in UNITS:
        close = difflib.get_close_matches(unit, list(UNITS), n=1, cutoff=0.6)
        folded = [u for u in UNITS if u.lower() == unit.lower()]
        if folded:
            extra = f" (did you mean '{folded[0]}'? units are case sensitive)"
        else:
            extra = f" (did you mean '{close[0]}'?)" if close else ""
        raise InputError(f"{name}: unknown unit '{unit_text}' in \"{shown}\"{extra}; {name} is {expected}")
    unit_kind, factor = UNITS[unit]
    if unit_kind != kind:
        raise InputError(f"'{shown}' is {KINDS[unit_kind]}; {name} is {expected}")
    exponent = re.search(r"[eE]([+-]?\d+)$", number)
    try:
        # exact unless the number is so long, or its exponent so large, that the fraction would be huge
        if len(number) > 400 or (exponent and abs(int(exponent.group(1))) > 400):
            value = float(number) * float(factor)
        else:
            value = float(Fraction(number) * factor)
    except OverflowError:
        value = math.inf
    if not math.isfinite(value):
        raise InputError(f"{name}: \"{shown}\" is beyond the range of a float")
    return value


def _example(kind: str) -> str:
    return {"length": "175 mm", "force": "10 kN", "stress": "0.25 MPa", "stiffness": "82 N/mm3",
            "fracture_energy": "18 N/m", "density": "1900 kg/m3", "acceleration": "9.81 m/s2",
            "time": "0.01 s"}[kind]
