"""Elastic response spectra of the codes a seismic check is made against, in acceleration and in displacement.

* :func:`ec8_spectrum`: EN 1998-1, 3.2.2.2 (the four branches, eqs. 3.2 to 3.5), ground types A to E of Tables 3.2
  (type 1) and 3.3 (type 2), the importance factor (a_g = gamma_I a_gR, 3.2.1) and the damping correction eta
  (eq. 3.6); the displacement spectrum of 3.2.2.4 (eq. 3.7) and, beyond T_E, of Annex A (Table A.1).
* :func:`ntc2018_spectrum`: NTC 2018, 3.2.3.2.1 (eq. 3.2.2), a_g, F0 and T*_C of the site and limit state, the soil
  categories A to E of Table 3.2.IV (S_S and C_C), the topographic categories T1 to T4 of Table 3.2.V (S_T, its value
  at the top of the slope), T_C = C_C T*_C, T_B = T_C / 3, T_D = 4 a_g / g + 1.6 (eqs. 3.2.5 to 3.2.7), with the
  g = 9.81 m/s2 the text gives for a_g / g (:data:`NTC_GRAVITY`); the displacement spectrum of 3.2.3.2.3 (eqs. 3.2.10
  and 3.2.11, T_E and T_F of Table 3.2.VII; d_g of 3.2.3.3, eq. 3.2.12).
* :func:`tabulated_spectrum` and :func:`read_spectrum`: a spectrum given as periods and accelerations (a site
  study's), linear between the samples.

No package on PyPI was taken for these: the one that implements the NTC 2018 spectrum (norma-ntc) is pre-alpha,
needs Python 3.10 (this package runs on 3.9) and has no Eurocode spectrum; the one with the Eurocode's
(eurocodepy) needs Python 3.12 and installs a documentation and notebook stack with it. The formulas are written
once here and tested at every corner period against hand values (tests/python/test_assessment.py).

Accelerations are in m/s2 and periods in s; ``damping`` is the viscous damping ratio (0.05 for 5%), which the
codes' eta takes in percent. A ground acceleration written in g (``"0.25 g"`` in a case file) is in units of the
standard gravity, :data:`masonry_dem.units.STANDARD_GRAVITY` = 9.80665 m/s2; the ratio a_g / g in the NTC's
S_S (Table 3.2.IV) and T_D (eq. 3.2.7) is taken with the text's own g = 9.81 m/s2 (:data:`NTC_GRAVITY`).
"""

from __future__ import annotations

import inspect
import math
import os
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Mapping, Optional, Union

import numpy as np
import numpy.typing as npt

from .._core import InputError
from ..units import STANDARD_GRAVITY

PathLike = Union[str, "os.PathLike[str]"]
ArrayOrFloat = Union[float, np.ndarray]

#: The codes of :func:`spectrum`: the Eurocode's, the Italian one's, and a table of periods and accelerations.
CODES = ("ec8", "ntc2018", "file")

#: EN 1998-1 Table 3.2 (type 1) and Table 3.3 (type 2): ground type -> (S, T_B [s], T_C [s], T_D [s]).
EC8_GROUND = {
    1: {"A": (1.0, 0.15, 0.4, 2.0), "B": (1.2, 0.15, 0.5, 2.0), "C": (1.15, 0.20, 0.6, 2.0),
        "D": (1.35, 0.20, 0.8, 2.0), "E": (1.4, 0.15, 0.5, 2.0)},
    2: {"A": (1.0, 0.05, 0.25, 1.2), "B": (1.35, 0.05, 0.25, 1.2), "C": (1.5, 0.10, 0.25, 1.2),
        "D": (1.8, 0.10, 0.30, 1.2), "E": (1.6, 0.05, 0.25, 1.2)},
}
#: EN 1998-1 Annex A, Table A.1: ground type -> (T_E [s], T_F [s]) of the long-period displacement spectrum.
EC8_LONG_PERIODS = {"A": (4.5, 10.0), "B": (5.0, 10.0), "C": (6.0, 10.0), "D": (6.0, 10.0), "E": (6.0, 10.0)}

#: NTC 2018 Table 3.2.IV: soil category -> (S_S = a - b F0 a_g / g, clamped to [lo, hi]; C_C = c (T*_C)^e):
#: (a, b, lo, hi, c, e).
NTC_SOIL = {
    "A": (1.0, 0.0, 1.0, 1.0, 1.0, 0.0),
    "B": (1.40, 0.40, 1.00, 1.20, 1.10, -0.20),
    "C": (1.70, 0.60, 1.00, 1.50, 1.05, -0.33),
    "D": (2.40, 1.50, 0.90, 1.80, 1.25, -0.50),
    "E": (2.00, 1.10, 1.00, 1.60, 1.15, -0.40),
}
#: NTC 2018 Table 3.2.V: topographic category -> S_T at the top of the relief (it falls linearly to 1 at its foot:
#: a site part way up is given the category of a lower one or its own study).
NTC_TOPOGRAPHY = {"T1": 1.0, "T2": 1.2, "T3": 1.2, "T4": 1.4}
#: NTC 2018 Table 3.2.VII: soil category -> (T_E [s], T_F [s]) of the displacement spectrum.
NTC_LONG_PERIODS = {"A": (4.5, 10.0), "B": (5.0, 10.0), "C": (6.0, 10.0), "D": (6.0, 10.0), "E": (6.0, 10.0)}
#: NTC 2018, 3.2.3.2.1: the g of a_g / g in Table 3.2.IV ("g = 9,81 m/s2 is the acceleration of gravity"), used
#: for T_D = 4 a_g / g + 1.6 (eq. 3.2.7) too.
NTC_GRAVITY = 9.81
#: NTC 2018, 3.2.3.2.1: F0 is never below 2.2.
NTC_F0_MIN = 2.2
#: The floor of the damping correction, EN 1998-1 eq. 3.6 and NTC 2018 eq. 3.2.4.
ETA_MIN = 0.55


def _refuse(key: str, problem: str) -> InputError:
    """The InputError of an argument (a case file's key of [assessment]) out of range: "key: problem"."""
    return InputError(f"{key}: {problem}", key)


def _number(key: str, value: Any, positive: bool = False, minimum: Optional[float] = None) -> float:
    """``value`` as a finite float (> 0 if ``positive``, >= ``minimum`` if given), else InputError naming ``key``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _refuse(key, f"expected a number, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise _refuse(key, f"expected a finite number, got {value!r}")
    if positive and not x > 0:
        raise _refuse(key, f"must be > 0, got {value!r}")
    if minimum is not None and x < minimum:
        raise _refuse(key, f"must be >= {minimum:g}, got {value!r}")
    return x


def _choice(key: str, value: Any, choices: Mapping[Any, Any], note: str = "") -> Any:
    if value not in choices:
        listed = ", ".join(repr(c) for c in choices)
        raise _refuse(key, f"expected one of {listed}, got {value!r}{note}")
    return value


def damping_correction(damping: float) -> float:
    """eta = sqrt(10 / (5 + xi)) >= 0.55, xi the damping in percent (EN 1998-1 eq. 3.6, NTC 2018 eq. 3.2.4);
    ``damping`` is the ratio (0.05 for 5%, eta = 1). Refuses a ratio outside [0, 1) by name ("damping")."""
    xi = _number("damping", damping, minimum=0.0)
    if xi >= 1.0:
        raise _refuse("damping", f"is the damping ratio, 0 <= damping < 1 (0.05 for 5%), got {damping!r}")
    return max(math.sqrt(10.0 / (5.0 + 100.0 * xi)), ETA_MIN)


@dataclass(frozen=True, eq=False)
class Spectrum:
    """An elastic response spectrum: the pseudo-acceleration S_e(T) [m/s2] and the displacement S_De(T) [m].

    A code's spectrum (``code`` "ec8" or "ntc2018") has four branches on its corner periods:

    * 0 <= T < T_B: a_g S eta F0 [T / T_B + (1 - T / T_B) / (eta F0)]  (= a_g S [1 + T / T_B (eta F0 - 1)])
    * T_B <= T < T_C: a_g S eta F0
    * T_C <= T < T_D: a_g S eta F0 T_C / T
    * T_D <= T: a_g S eta F0 T_C T_D / T^2

    with F0 = 2.5 in the Eurocode; S_De(T) = S_e(T) (T / 2 pi)^2 up to T_E, then linear to d_g = 0.025 a_g S T_C T_D
    at T_F and d_g beyond (EN 1998-1 Annex A, NTC 2018 3.2.3.2.3). A tabulated spectrum (``code`` "file") is linear
    between its samples and S_De = S_e (T / 2 pi)^2; it has no corner periods but ``TC`` when given.

    Attributes:
        code: "ec8", "ntc2018" or "file".
        ag: the design ground acceleration on rock, a_g [m/s2] (EC8: gamma_I a_gR); for a file, S_e(0) / S.
        S: the soil (and topography) factor; 1 for a file.
        eta: the damping correction; 1 for a file.
        F0: the plateau's amplification (2.5 in the Eurocode); for a file, NaN.
        TB, TC, TD, TE, TF: the corner periods [s]; NaN for a file (TC as given, else NaN).
        parameters: what the spectrum was made from, for reports (name -> value, accelerations in m/s2).
        periods, accelerations: the samples of a tabulated spectrum [s], [m/s2] (empty for a code's).
    """

    code: str
    ag: float
    S: float
    eta: float
    F0: float
    TB: float = math.nan
    TC: float = math.nan
    TD: float = math.nan
    TE: float = math.nan
    TF: float = math.nan
    parameters: Mapping[str, Any] = field(default_factory=dict)
    periods: np.ndarray = field(default_factory=lambda: np.zeros(0))
    accelerations: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def peak_ground_acceleration(self) -> float:
        """a_g S = S_e(0) [m/s2], the ground's peak acceleration at the site."""
        return float(self.acceleration(0.0))

    @property
    def plateau(self) -> float:
        """a_g S eta F0 [m/s2], the plateau of a code's spectrum (the largest sample of a file's)."""
        if self.code == "file":
            return float(np.max(self.accelerations))
        return self.ag * self.S * self.eta * self.F0

    @property
    def design_displacement(self) -> float:
        """d_g = 0.025 a_g S T_C T_D [m] (EN 1998-1 eq. 3.12, NTC 2018 eq. 3.2.12); NaN for a file."""
        return 0.025 * self.ag * self.S * self.TC * self.TD

    def _periods(self, T: npt.ArrayLike, name: str = "T") -> np.ndarray:
        t = np.asarray(T, dtype=np.float64)
        if not np.all(np.isfinite(t)) or np.any(t < 0):
            raise _refuse(name, "periods must be finite and >= 0")
        if self.code == "file" and np.any(t > self.periods[-1]):
            raise _refuse(name, f"the spectrum's file ends at T = {self.periods[-1]:g} s; it was asked for "
                                f"T = {float(np.max(t)):g} s")
        return t

    def with_damping(self, damping: float) -> "Spectrum":
        """The same spectrum at the viscous damping ratio ``damping`` (its eta recomputed, EN 1998-1 eq. 3.6, NTC
        2018 eq. 3.2.4); a spectrum from a file is at its own damping and is returned as it is for 0.05 only."""
        eta = damping_correction(damping)
        if self.code == "file":
            if float(damping) != 0.05:
                raise _refuse("damping", "a spectrum from a file is at its own damping (taken as 5%)")
            return self
        return replace(self, eta=eta, parameters={**self.parameters, "damping": float(damping)})

    def acceleration(self, T: npt.ArrayLike) -> ArrayOrFloat:
        """S_e(T) [m/s2] at the periods ``T`` [s] (a float for a float, an array for an array)."""
        t = self._periods(T)
        if self.code == "file":
            out = np.interp(t, self.periods, self.accelerations)
        else:
            plateau = self.plateau
            with np.errstate(divide="ignore", invalid="ignore"):
                out = np.where(
                    t < self.TB, plateau * (t / self.TB + (1.0 - t / self.TB) / (self.eta * self.F0)),
                    np.where(t < self.TC, plateau,
                             np.where(t < self.TD, plateau * self.TC / t, plateau * self.TC * self.TD / t**2)))
        return float(out) if out.ndim == 0 else out

    def displacement(self, T: npt.ArrayLike) -> ArrayOrFloat:
        """S_De(T) [m] at the periods ``T`` [s]: S_e(T) (T / 2 pi)^2, and for a code's spectrum beyond T_E the
        long-period branches (linear from T_E to d_g at T_F, then d_g)."""
        t = self._periods(T)
        out = np.asarray(self.acceleration(t)) * (t / (2.0 * math.pi)) ** 2
        if self.code != "file":
            d_g = self.design_displacement
            peak = self.eta * self.F0
            long = d_g * (peak + (1.0 - peak) * (np.minimum(t, self.TF) - self.TE) / (self.TF - self.TE))
            out = np.where(t <= self.TE, out, long)
        return float(out) if out.ndim == 0 else out

    def describe(self) -> str:
        """One line on the spectrum: its code and parameters, e.g. "EN 1998-1 type 1, ground B, a_g = 2.452 m/s2
        (0.250 g), S = 1.2, eta = 1"."""
        g = STANDARD_GRAVITY
        if self.code == "file":
            source = self.parameters.get("file", "a table")
            return f"tabulated spectrum ({source}), S_e(0) = {self.peak_ground_acceleration:.4g} m/s2"
        p = self.parameters
        head = (f"EN 1998-1 type {p['spectrum_type']}, ground {p['ground_type']}" if self.code == "ec8" else
                f"NTC 2018, soil {p['soil']}, topography {p['topography']}, F0 = {self.F0:g}, "
                f"T*_C = {p['Tc_star']:g} s")
        return (f"{head}, a_g = {self.ag:.4g} m/s2 ({self.ag / g:.3f} g), S = {self.S:.4g}, eta = {self.eta:.4g}, "
                f"T_B = {self.TB:.4g} s, T_C = {self.TC:.4g} s, T_D = {self.TD:.4g} s")


def ec8_spectrum(ag: float, ground_type: str = "A", spectrum_type: int = 1, importance: float = 1.0,
                 damping: float = 0.05) -> Spectrum:
    """The horizontal elastic spectrum of EN 1998-1 (3.2.2.2).

    Args:
        ag: the reference peak ground acceleration on type A ground, a_gR [m/s2].
        ground_type: "A" to "E" (Tables 3.2 and 3.3; S1 and S2 need a study of their own and are refused).
        spectrum_type: 1 or 2 (the recommended type 2 where the surface-wave magnitude is at most 5.5).
        importance: the importance factor gamma_I (> 0; 0.8, 1.0, 1.2, 1.4 for classes I to IV): a_g = gamma_I a_gR.
        damping: the viscous damping ratio (0.05: eta = 1).
    Raises:
        masonry_dem.InputError: a parameter out of range, named (ag, ground_type, spectrum_type, importance,
            damping).
    """
    a_gr = _number("ag", ag, positive=True)
    gamma = _number("importance", importance, positive=True)
    kind = _choice("spectrum_type", spectrum_type, EC8_GROUND)
    note = " (S1 and S2 need a study of their own)" if ground_type in ("S1", "S2") else ""
    ground = _choice("ground_type", ground_type, EC8_GROUND[kind], note)
    eta = damping_correction(damping)
    S, TB, TC, TD = EC8_GROUND[kind][ground]
    TE, TF = EC8_LONG_PERIODS[ground]
    return Spectrum("ec8", a_gr * gamma, S, eta, 2.5, TB, TC, TD, TE, TF,
                    parameters={"ag": a_gr, "ground_type": ground, "spectrum_type": kind, "importance": gamma,
                                "damping": float(damping)})


def ntc2018_spectrum(ag: float, F0: float, Tc_star: float, soil: str = "A", topography: str = "T1",
                     damping: float = 0.05) -> Spectrum:
    """The horizontal elastic spectrum of NTC 2018 (3.2.3.2.1).

    Args:
        ag: a_g of the site and limit state, on rock [m/s2].
        F0: the plateau's amplification of the site (>= 2.2).
        Tc_star: T*_C of the site [s] (> 0).
        soil: the subsoil category, "A" to "E" (Table 3.2.IV: S_S and C_C).
        topography: "T1" to "T4" (Table 3.2.V: S_T at the top of the relief).
        damping: the viscous damping ratio (0.05: eta = 1).
    Raises:
        masonry_dem.InputError: a parameter out of range, named (ag, F0, Tc_star, soil, topography, damping).
    """
    a_g = _number("ag", ag, positive=True)
    f0 = _number("F0", F0, minimum=NTC_F0_MIN)
    tc_star = _number("Tc_star", Tc_star, positive=True)
    soil = _choice("soil", soil, NTC_SOIL)
    topography = _choice("topography", topography, NTC_TOPOGRAPHY)
    eta = damping_correction(damping)
    a, b, lo, hi, c, e = NTC_SOIL[soil]
    S_S = min(max(a - b * f0 * a_g / NTC_GRAVITY, lo), hi)
    C_C = c * tc_star ** e
    TC = C_C * tc_star
    TE, TF = NTC_LONG_PERIODS[soil]
    return Spectrum("ntc2018", a_g, S_S * NTC_TOPOGRAPHY[topography], eta, f0, TC / 3.0, TC,
                    4.0 * a_g / NTC_GRAVITY + 1.6, TE, TF,
                    parameters={"ag": a_g, "F0": f0, "Tc_star": tc_star, "soil": soil, "topography": topography,
                                "damping": float(damping), "S_S": S_S, "S_T": NTC_TOPOGRAPHY[topography],
                                "C_C": C_C})


def tabulated_spectrum(periods: npt.ArrayLike, accelerations: npt.ArrayLike, TC: Optional[float] = None,
                       source: str = "a table") -> Spectrum:
    """A spectrum given by its samples: ``periods`` [s] from 0, increasing, and ``accelerations`` S_e [m/s2] (>= 0),
    linear between them; ``TC`` [s]: the corner period at the end of the plateau, which only the N2 method's
    short-period rule needs (EN 1998-1 B.5). Refuses samples that do not start at T = 0 (S_e(0) is the ground's
    peak acceleration, which the check of a mechanism at ground level needs)."""
    t = np.array(periods, dtype=np.float64).reshape(-1)
    a = np.array(accelerations, dtype=np.float64).reshape(-1)
    if len(t) != len(a) or len(t) < 2:
        raise _refuse("spectrum", f"expected at least 2 periods with an acceleration each, got {len(t)} periods and "
                                  f"{len(a)} accelerations")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(a))):
        raise _refuse("spectrum", "periods and accelerations must be finite numbers")
    if t[0] != 0.0:
        raise _refuse("spectrum", f"the periods must start at T = 0 (S_e(0) is the ground's peak acceleration), "
                                  f"got {t[0]:g} s")
    if np.any(np.diff(t) <= 0):
        raise _refuse("spectrum", "the periods must increase")
    if np.any(a < 0):
        raise _refuse("spectrum", "the accelerations must be >= 0")
    tc = math.nan if TC is None else _number("Tc", TC, positive=True)
    t.setflags(write=False)
    a.setflags(write=False)
    return Spectrum("file", float(a[0]), 1.0, 1.0, math.nan, TC=tc, parameters={"file": source},
                    periods=t, accelerations=a)


def read_spectrum(path: PathLike, units: str, TC: Optional[float] = None) -> Spectrum:
    """A spectrum from a text file of two columns, period [s] and S_e, in ``units`` "g" (times the standard
    gravity) or "m/s2"; the file's format is that of a ground-motion record (:func:`masonry_dem.ground_motion.
    read_csv`: commas, semicolons or blanks; ``#`` comments; an optional header line). ``TC`` as in
    :func:`tabulated_spectrum`."""
    from ..ground_motion import read_csv

    table = read_csv(path, units=units, g=STANDARD_GRAVITY)
    return tabulated_spectrum(table.times, table.acceleration, TC, source=os.fspath(path))


def spectrum(code: str = "ec8", **parameters: Any) -> Spectrum:
    """The spectrum of ``code``: "ec8" (:func:`ec8_spectrum`'s parameters), "ntc2018" (:func:`ntc2018_spectrum`'s)
    or "file" (``path``, ``units`` and optionally ``TC``: :func:`read_spectrum`)."""
    _choice("code", code, {c: None for c in CODES})
    build: Callable[..., Spectrum] = {"ec8": ec8_spectrum, "ntc2018": ntc2018_spectrum, "file": read_spectrum}[code]
    takes = inspect.signature(build).parameters
    for name in parameters:
        if name not in takes:
            raise _refuse(name, f"is not a parameter of the {code!r} spectrum (it takes {', '.join(takes)})")
    return build(**parameters)  # type: ignore[no-any-return]


def elastic_spectrum(T: npt.ArrayLike, code: str = "ec8", **parameters: Any) -> ArrayOrFloat:
    """S_e(T) [m/s2] of the spectrum of ``code`` and ``parameters`` (:func:`spectrum`), e.g.
    ``elastic_spectrum(0.3, code="ec8", ag=0.25 * 9.80665, ground_type="B", spectrum_type=1)``."""
    return spectrum(code, **parameters).acceleration(T)


def displacement_spectrum(T: npt.ArrayLike, code: str = "ec8", **parameters: Any) -> ArrayOrFloat:
    """S_De(T) [m] of the spectrum of ``code`` and ``parameters`` (:func:`spectrum`)."""
    return spectrum(code, **parameters).displacement(T)
