"""Seismic assessment: a collapse mechanism or a pushover turned into a check against a code's demand spectrum.

* :mod:`.spectra` (the input): the elastic spectra of EN 1998-1 (:func:`ec8_spectrum`, types 1 and 2) and of
  NTC 2018 (:func:`ntc2018_spectrum`), or a tabulated one (:func:`tabulated_spectrum`, :func:`read_spectrum`), in
  acceleration and displacement (:class:`Spectrum`); :func:`elastic_spectrum` and :func:`displacement_spectrum`
  give S_e(T) and S_De(T) of a code's parameters.

>>> from masonry_dem import assessment
>>> round(assessment.elastic_spectrum(0.3, code="ec8", ag=2.5, ground_type="B", spectrum_type=1), 6)
7.5

Accelerations in m/s2, periods in s, masses in kg (docs/assessment.md).
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # what the names below resolve to (type checkers, IDEs); imported on first use at run time
    from .spectra import (
        Spectrum,
        displacement_spectrum,
        ec8_spectrum,
        elastic_spectrum,
        ntc2018_spectrum,
        read_spectrum,
        spectrum,
        tabulated_spectrum,
    )

__all__ = [
    "Spectrum",
    "spectrum",
    "ec8_spectrum",
    "ntc2018_spectrum",
    "tabulated_spectrum",
    "read_spectrum",
    "elastic_spectrum",
    "displacement_spectrum",
]

# Where each name lives, imported when first asked for (masonry_dem._lazy): the package imports none of its modules,
# so that the case reader (input) imports the spectra without the checks (results) or the plots (output).
_LAZY = {
    **dict.fromkeys(("Spectrum", "spectrum", "ec8_spectrum", "ntc2018_spectrum", "tabulated_spectrum",
                     "read_spectrum", "elastic_spectrum", "displacement_spectrum"), ".spectra"),
}

__getattr__, __dir__ = lazy_package(__name__, _LAZY, __all__)
