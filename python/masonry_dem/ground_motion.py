"""Ground motions for time histories (``Model.simulate``): base acceleration records read from a file, and pulses.

A :class:`GroundMotion` is one component of a ground acceleration: its sample times [s] and accelerations
[m/s2], linear between samples and zero outside them (as ``Model.simulate`` reads ``base_acceleration`` and
``vertical_acceleration``). Records come from

* :func:`read_csv`: a two-column text file, time [s] and acceleration (in g or in m/s2), comma-separated (or
  separated by blanks or semicolons), with an optional header line and ``#`` comment lines;
* :func:`read_at2`: the PEER NGA ``.AT2`` format (four header lines: title; date and component; the units
  line ``ACCELERATION TIME SERIES IN UNITS OF G``; ``NPTS=  7998, DT=   .0050 SEC`` or the older
  ``7998    0.0050    NPTS, DT``; then the values in g, in rows of any number of columns), the first value
  at t = 0;
* :func:`read`, which picks one of them by the file's suffix (``.csv``, ``.txt``, ``.dat``: CSV; ``.at2``);

and pulses are built in: :func:`one_sine` (a_g(t) = A sin(2 pi t / T) for 0 <= t <= T, zero after) and
:func:`ricker` (the Ricker wavelet). :func:`simulate_arguments` turns a horizontal component and an optional
vertical one into the keyword arguments of ``Model.simulate``:

>>> import masonry_dem as md
>>> from masonry_dem import ground_motion as gm
>>> record = gm.read("examples/elcentro-1940-ns.csv", units="g").scaled(1.5)   # doctest: +SKIP
>>> history = model.simulate(record.duration, **gm.simulate_arguments(record))  # doctest: +SKIP

Accelerations given in g are converted with :data:`G` (the core's default gravity, 9.81 m/s2), or with the
``g`` the reader is given (a case file passes its own ``[loads] gravity``, so that the ratio of the ground
acceleration to gravity, which a rigid block responds to, is the record's). A horizontal acceleration is
positive towards +x, a vertical one upwards.

Every error about a file is a :class:`masonry_dem.InputError` whose message starts with the file name and,
for a bad value, names its line.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from . import _core
from ._core import InputError
from ._files import read_bytes

__all__ = [
    "G",
    "UNITS",
    "GroundMotion",
    "read",
    "read_csv",
    "read_at2",
    "one_sine",
    "ricker",
    "simulate_arguments",
]

PathLike = Union[str, "os.PathLike[str]"]

#: The acceleration of gravity used to convert a record given in g [m/s2]: the core's default gravity
#: (``Model(gravity=...)`` left out), 9.81 m/s2. A reader given ``g=`` uses that one instead.
G: float = float(_core.DEFAULTS["gravity"])

#: The units a CSV record may be given in: "g" (multiplied by ``g``, :data:`G` by default) or "m/s2".
UNITS = ("g", "m/s2")

#: Samples per period of the built-in pulses (:func:`one_sine`, :func:`ricker`) by default.
SAMPLES_PER_PERIOD = 200

#: The largest record file read [bytes] (a record of a million samples takes about 20 MB as text).
MAX_RECORD_BYTES = 256 * 2**20


@dataclass(frozen=True, eq=False)
class GroundMotion:
    """One component of a ground acceleration.

    Attributes:
        times: (n,) sample times [s], strictly increasing, n >= 2.
        acceleration: (n,) the ground acceleration at those times [m/s2], linear between samples and zero
            outside them; horizontal positive towards +x, or vertical positive upwards.
        name: what it is (the record's title, or the pulse).
        source: where it comes from (the file, or "one-sine pulse"), for reports.
        units: a note on the units of the source ("g (x 9.81 m/s2)", "m/s2").
        scale: the factor applied to the source's accelerations by :meth:`scaled` (1 as read).
        gravity: the acceleration of gravity [m/s2] that converted a record given in g (:data:`G` by default),
            and that :meth:`describe` divides the peak by.
    """

    times: np.ndarray
    acceleration: np.ndarray
    name: str = ""
    source: str = ""
    units: str = "m/s2"
    scale: float = 1.0
    gravity: float = G

    def __post_init__(self) -> None:
        times = np.array(self.times, dtype=np.float64).reshape(-1)
        acc = np.array(self.acceleration, dtype=np.float64).reshape(-1)
        where = self.source or self.name or "ground motion"
        if len(times) != len(acc):
            raise InputError(f"{where}: {len(times)} times but {len(acc)} accelerations")
        if len(times) < 2:
            raise InputError(f"{where}: a ground motion needs at least 2 samples, got {len(times)}")
        if not (np.all(np.isfinite(times)) and np.all(np.isfinite(acc))):
            raise InputError(
                f"{where}: times and accelerations must be finite numbers (in m/s2: an acceleration beyond "
                f"{np.finfo(np.float64).max:.3g} m/s2 is not)"
            )
        steps = np.diff(times)
        if np.any(steps <= 0):
            k = int(np.argmax(steps <= 0))
            raise InputError(
                f"{where}: times must increase, but sample {k + 1} is at {times[k + 1]:g} s after {times[k]:g} s"
            )
        times.setflags(write=False)
        acc.setflags(write=False)
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "acceleration", acc)

    def scaled(self, factor: float) -> "GroundMotion":
        """The same motion with every acceleration multiplied by ``factor`` (a finite number; the times
        unchanged); :attr:`scale` records the product of the factors."""
        f = _finite("scale", factor)
        with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused by the constructor
            return replace(self, acceleration=self.acceleration * f, scale=self.scale * f)

    @property
    def peak(self) -> float:
        """The peak ground acceleration max |a| [m/s2] (PGA of a horizontal record)."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def duration(self) -> float:
        """The time of the last sample [s]: the length of a time history (which starts at t = 0) that
        takes in the whole motion."""
        return float(self.times[-1])

    @property
    def time_step(self) -> float:
        """The smallest interval between two samples [s]."""
        return float(np.min(np.diff(self.times)))

    def at(self, t: Any) -> np.ndarray:
        """The acceleration [m/s2] at the times ``t`` [s]: linear between samples, zero outside them (as
        ``Model.simulate`` reads it)."""
        return np.interp(np.asarray(t, dtype=np.float64), self.times, self.acceleration, left=0.0, right=0.0)

    def as_tuple(self) -> Tuple[np.ndarray, np.ndarray]:
        """(times [s], accelerations [m/s2]) as ``Model.simulate(base_acceleration=...)`` (or
        ``vertical_acceleration=``) takes them (copies)."""
        return self.times.copy(), self.acceleration.copy()

    def describe(self) -> str:
        """One line: name, samples, duration, PGA in m/s2 and in g, and the scale."""
        scale = f", scaled x{self.scale:g}" if self.scale != 1.0 else ""
        name = self.name or self.source or "ground motion"
        return (
            f"{name}: {len(self.times):,} samples over {self.duration:.4g} s, peak {self.peak:.4g} m/s2 "
            f"({self.peak / self.gravity:.3g} g){scale}"
        )


def simulate_arguments(
    horizontal: Optional[GroundMotion] = None, vertical: Optional[GroundMotion] = None
) -> Dict[str, Tuple[np.ndarray, np.ndarray]]:
    """The keyword arguments of ``Model.simulate`` for a horizontal and an optional vertical component:
    ``base_acceleration`` and ``vertical_acceleration``, each (times [s], accelerations [m/s2]). A component
    given as None is left out (no acceleration in that direction)."""
    out: Dict[str, Tuple[np.ndarray, np.ndarray]] = {}
    if horizontal is not None:
        out["base_acceleration"] = horizontal.as_tuple()
    if vertical is not None:
        out["vertical_acceleration"] = vertical.as_tuple()
    return out


# --------------------------------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------------------------------


def _finite(name: str, value: Any, positive: bool = False) -> float:
    """``value`` as a finite float (> 0 if ``positive``), else InputError naming ``name``."""
    if isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name}: expected a number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(x) or (positive and x <= 0):
        raise InputError(f"{name}: expected a finite number{' > 0' if positive else ''}, got {value!r}")
    return x


def _lines(path: PathLike) -> List[str]:
    """The lines of a text file (UTF-8 or Latin-1, at most :data:`MAX_RECORD_BYTES`). OSError when it cannot be
    read, InputError when it is not a regular file (a FIFO, a device, a folder) or too large."""
    data = read_bytes(path, MAX_RECORD_BYTES, "record")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # old records carry the odd accented name in their title
    return text.lstrip("\ufeff").splitlines()


def _unit_factor(units: str, g: float, where: str) -> Tuple[float, str]:
    """(factor to m/s2, note) of ``units``."""
    if units == "g":
        return g, f"g (x {g:g} m/s2)"
    if units in ("m/s2", "m/s^2"):
        return 1.0, "m/s2"
    raise InputError(f"{where}: units: expected one of \"g\", \"m/s2\", got {units!r}", "units")


_SPLIT = re.compile(r"[,;\s]+")


def read_csv(
    path: PathLike,
    units: str = "g",
    time_column: int = 0,
    accel_column: int = 1,
    g: float = G,
    name: Optional[str] = None,
) -> GroundMotion:
    """Read a record from a text file of columns: time [s] and acceleration.

    Columns are separated by commas (or semicolons, or blanks). Blank lines and lines starting with ``#``
    are skipped; the first other line may be a header (it is one when its columns are not numbers). The
    times must increase.

    Args:
        path: the file.
        units: of the accelerations: "g" (multiplied by ``g``) or "m/s2".
        time_column, accel_column: the columns (from 0) of the time [s] and of the acceleration.
        g: the acceleration of gravity for ``units = "g"`` [m/s2] (default :data:`G`, 9.81).
        name: the record's name (default: the file's name without its suffix).
    Raises:
        OSError: the file cannot be read.
        masonry_dem.InputError: a bad line (the message names the file and the line), too few rows, times
            that do not increase, bad units or columns.
    """
    where = os.fspath(path)
    factor, note = _unit_factor(units, _finite("g", g, positive=True), where)
    for label, col in (("time_column", time_column), ("accel_column", accel_column)):
        if isinstance(col, bool) or not isinstance(col, (int, np.integer)) or col < 0:
            raise InputError(f"{where}: {label}: expected an integer >= 0, got {col!r}")
    need = max(time_column, accel_column) + 1
    times: List[float] = []
    values: List[float] = []
    header_allowed = True
    for line_no, line in enumerate(_lines(path), start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        cells = [c for c in _SPLIT.split(text) if c]
        try:
            if len(cells) < need:
                raise ValueError
            t, a = float(cells[time_column]), float(cells[accel_column])
        except ValueError:
            if header_allowed and not _numeric(cells):
                header_allowed = False  # the header line
                continue
            shown = text if len(text) <= 60 else text[:57] + "..."
            raise InputError(
                f"{where}, line {line_no}: expected numbers in columns {time_column + 1} (time [s]) and "
                f"{accel_column + 1} (acceleration [{units}]), got {shown!r}"
            ) from None
        if not (math.isfinite(t) and math.isfinite(a)):
            raise InputError(f"{where}, line {line_no}: expected finite numbers, got {text!r}")
        if times and t <= times[-1]:
            raise InputError(f"{where}, line {line_no}: the time {t:g} s does not follow {times[-1]:g} s (times must increase)")
        header_allowed = False
        times.append(t)
        values.append(a)
    if len(times) < 2:
        raise InputError(f"{where}: expected at least 2 rows of time and acceleration, found {len(times)}")
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below, by name
        acceleration = np.array(values) * factor
    return GroundMotion(
        np.array(times),
        acceleration,
        name=name if name is not None else Path(path).stem,
        source=where,
        units=note,
        gravity=g,
    )


def _numeric(cells: List[str]) -> bool:
    """Whether any of ``cells`` is a number (a header has none)."""
    for c in cells:
        try:
            float(c)
            return True
        except ValueError:
            pass
    return False


_NPTS_NEW = re.compile(r"NPTS\s*=\s*(\d+)\s*,?\s*DT\s*=\s*([-+0-9.EeDd]+)", re.IGNORECASE)
_NPTS_OLD = re.compile(r"^\s*(\d+)\s+([-+0-9.EeDd]+)\s+NPTS\s*,?\s*DT", re.IGNORECASE)
_UNITS_LINE = re.compile(r"UNITS\s+OF\s+([A-Z/0-9*^]+)", re.IGNORECASE)


def read_at2(path: PathLike, g: float = G, name: Optional[str] = None) -> GroundMotion:
    """Read a record in the PEER NGA ``.AT2`` format (accelerations in g, at equal steps).

    Line 1 is the title, line 2 the date and component (``1940-05-19, IMPERIAL VALLEY, 180``), line 3 the units
    (``ACCELERATION TIME SERIES IN UNITS OF G``; another unit is refused), line 4 the number of points and the
    step, ``NPTS=  7998, DT=   .0050 SEC`` (or the older ``7998    0.0050    NPTS, DT``); then NPTS values
    in rows of any number of columns. The samples are at t = 0, DT, 2 DT, ... [s].

    Args:
        path: the file.
        g: the acceleration of gravity [m/s2] the values in g are multiplied by (default :data:`G`, 9.81).
        name: the record's name (default: its title and component lines).
    Raises:
        OSError: the file cannot be read.
        masonry_dem.InputError: a header line not as above, a value that is not a number (the message names
            the line), or a number of values other than NPTS.
    """
    where = os.fspath(path)
    g = _finite("g", g, positive=True)
    lines = _lines(path)
    if len(lines) < 4:
        raise InputError(f"{where}: an AT2 file has 4 header lines (title, date and component, units, NPTS and DT), "
                         f"found {len(lines)} lines")
    found = _UNITS_LINE.search(lines[2])
    if not found:
        raise InputError(f"{where}, line 3: expected the units line 'ACCELERATION TIME SERIES IN UNITS OF G', "
                         f"got {lines[2].strip()[:60]!r}")
    if found.group(1).upper() != "G":
        raise InputError(f"{where}, line 3: the values are in units of {found.group(1)}; an AT2 record must be in g")
    head = _NPTS_NEW.search(lines[3]) or _NPTS_OLD.search(lines[3])
    if not head:
        raise InputError(f"{where}, line 4: expected 'NPTS= n, DT= dt SEC' (or 'n dt NPTS, DT'), "
                         f"got {lines[3].strip()[:60]!r}")
    npts = int(head.group(1))
    try:
        dt = float(head.group(2).replace("D", "E").replace("d", "e"))
    except ValueError:
        raise InputError(f"{where}, line 4: DT is not a number: {head.group(2)!r}") from None
    if not (math.isfinite(dt) and dt > 0):
        raise InputError(f"{where}, line 4: DT must be > 0, got {head.group(2)}")
    if npts < 2:
        raise InputError(f"{where}, line 4: NPTS must be at least 2, got {npts}")
    values: List[float] = []
    for line_no, line in enumerate(lines[4:], start=5):
        for cell in line.split():
            try:
                x = float(cell.replace("D", "E").replace("d", "e"))
            except ValueError:
                raise InputError(f"{where}, line {line_no}: expected numbers (accelerations in g), got {cell!r}") from None
            if not math.isfinite(x):
                raise InputError(f"{where}, line {line_no}: expected finite numbers, got {cell!r}")
            values.append(x)
    if len(values) != npts:
        raise InputError(f"{where}: line 4 gives NPTS = {npts}, but the file holds {len(values)} values")
    title = " ".join(lines[0].split())
    component = " ".join(lines[1].split())
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below, by name
        acceleration = np.array(values) * g
    return GroundMotion(
        np.arange(npts) * dt,
        acceleration,
        name=name if name is not None else ", ".join(p for p in (title, component) if p) or Path(path).stem,
        source=where,
        units=f"g (x {g:g} m/s2)",
        gravity=g,
    )


#: The suffixes :func:`read` knows (lower case) and the reader of each.
SUFFIXES = {".csv": "csv", ".txt": "csv", ".dat": "csv", ".at2": "at2"}


def read(path: PathLike, units: Optional[str] = None, g: float = G, **kwargs: Any) -> GroundMotion:
    """Read a record, by its suffix: ``.at2`` (any case) with :func:`read_at2` (in g: ``units`` must be None
    or "g"), ``.csv``, ``.txt`` or ``.dat`` with :func:`read_csv` (``units`` default "g"); ``kwargs`` go to
    the reader. Another suffix is an InputError."""
    where = os.fspath(path)
    kind = SUFFIXES.get(Path(path).suffix.lower())
    if kind is None:
        raise InputError(f"{where}: unknown record format {Path(path).suffix!r}: expected a .csv (or .txt, .dat) "
                         "file of time and acceleration, or a PEER NGA .AT2 file")
    if kind == "at2":
        if units not in (None, "g"):
            raise InputError(f"{where}: units: an AT2 record is in g, got {units!r}", "units")
        return read_at2(path, g=g, **kwargs)
    return read_csv(path, units="g" if units is None else units, g=g, **kwargs)


# --------------------------------------------------------------------------------------------------
# Pulses
# --------------------------------------------------------------------------------------------------


def _samples(period: float, samples_per_period: Any) -> int:
    if isinstance(samples_per_period, bool) or not isinstance(samples_per_period, (int, np.integer)) \
            or samples_per_period < 4:
        raise InputError(f"samples_per_period: expected an integer >= 4, got {samples_per_period!r}")
    return int(samples_per_period)


def _pad(times: np.ndarray, acc: np.ndarray, duration: Optional[float]) -> Tuple[np.ndarray, np.ndarray]:
    """The pulse with a last sample of zero at ``duration`` [s] when that is after its end."""
    if duration is None:
        return times, acc
    d = _finite("duration", duration, positive=True)
    if d > times[-1]:
        return np.append(times, d), np.append(acc, 0.0)
    return times, acc


def one_sine(
    amplitude: float,
    period: float,
    duration: Optional[float] = None,
    samples_per_period: int = SAMPLES_PER_PERIOD,
) -> GroundMotion:
    """A one-sine pulse: a_g(t) = A sin(2 pi t / T) for 0 <= t <= T, zero after.

    Args:
        amplitude: A [m/s2] (negative: the pulse starts towards -x).
        period: T [s], > 0.
        duration: optionally a time [s] after T up to which the record runs with zeros (the pulse is zero
            after T anyway: ``Model.simulate`` takes a record as zero outside its samples).
        samples_per_period: samples over T (default 200); the last is at T exactly, with a_g = 0.
    """
    a = _finite("amplitude", amplitude)
    T = _finite("period", period, positive=True)
    n = _samples(T, samples_per_period)
    times = np.linspace(0.0, T, n + 1)
    acc = a * np.sin(2.0 * np.pi * times / T)
    acc[0] = acc[-1] = 0.0  # exact zeros at 0 and T (sin(2 pi) is -2.4e-16)
    times, acc = _pad(times, acc, duration)
    return GroundMotion(times, acc, name=f"one-sine pulse, A = {a:g} m/s2, T = {T:g} s", source="one-sine pulse",
                        units="m/s2")


def ricker(
    amplitude: float,
    period: Optional[float] = None,
    frequency: Optional[float] = None,
    t0: Optional[float] = None,
    duration: Optional[float] = None,
    samples_per_period: int = SAMPLES_PER_PERIOD,
) -> GroundMotion:
    """A Ricker wavelet: a_g(t) = A (1 - 2 pi^2 f^2 (t - t0)^2) exp(-pi^2 f^2 (t - t0)^2).

    Its peak, A at t = t0, is flanked by two troughs of -2 A exp(-3/2) (about -0.446 A) at
    t0 +- sqrt(3/2) / (pi f); it crosses zero at t0 +- 1 / (sqrt(2) pi f).

    Args:
        amplitude: A [m/s2], the central peak.
        period: T = 1 / f [s] (give ``period`` or ``frequency``, not both).
        frequency: the peak frequency f [Hz] of its spectrum.
        t0: the time of the peak [s]; default 1.5 T, where the wavelet has decayed to below 1e-8 A.
        duration: the record's end [s]; default 2 t0 (the wavelet symmetric about its peak).
        samples_per_period: samples per period T (default 200).
    """
    a = _finite("amplitude", amplitude)
    if (period is None) == (frequency is None):
        raise InputError("ricker: give either period [s] or frequency [Hz]")
    T = _finite("period", period, positive=True) if period is not None else 1.0 / _finite("frequency", frequency, positive=True)
    f = 1.0 / T
    center = 1.5 * T if t0 is None else _finite("t0", t0)
    if center < 0:
        raise InputError(f"t0: expected a time >= 0 [s], got {t0!r}")
    end = 2.0 * center if duration is None else _finite("duration", duration, positive=True)
    if end <= 0:  # a peak at t = 0: the half after it
        end = 1.5 * T
    n = max(2, int(math.ceil(end / T * _samples(T, samples_per_period))))
    times = np.linspace(0.0, end, n + 1)
    if 0 < center < end:  # the nearest sample moved onto the peak exactly
        times[int(np.argmin(np.abs(times - center)))] = center
    x = (np.pi * f * (times - center)) ** 2
    acc = a * (1.0 - 2.0 * x) * np.exp(-x)
    return GroundMotion(times, acc, name=f"Ricker wavelet, A = {a:g} m/s2, T = {T:g} s, t0 = {center:g} s",
                        source="Ricker wavelet", units="m/s2")
