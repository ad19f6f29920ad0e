"""Seismic assessment: a collapse mechanism or a pushover turned into a check against a code's demand spectrum.

* :mod:`.spectra` (the input): the elastic spectra of EN 1998-1 (:func:`ec8_spectrum`, types 1 and 2) and of
  NTC 2018 (:func:`ntc2018_spectrum`), or a tabulated one (:func:`tabulated_spectrum`, :func:`read_spectrum`), in
  acceleration and displacement (:class:`Spectrum`); :func:`elastic_spectrum` and :func:`displacement_spectrum`
  give S_e(T) and S_De(T) of a code's parameters.
* :mod:`.parameters` (the input): :class:`AssessmentParameters`, the spectrum with q, FC and the mechanism's height in
  the building, checked; :func:`read_assessment` reads them from a case file's [assessment] table.
* :mod:`.kinematic` (the results): :func:`linear_check`, the linear kinematic check of a collapse mechanism (alpha0,
  M*, e*, a0*, the demand, the ratio and the verdict); :func:`mechanism_weights` and :func:`participating_mass` the
  steps of it, :func:`linear_check_of` the same from weights and virtual displacements given directly.
* :mod:`.nonlinear` (the results): :func:`nonlinear_check`, the nonlinear kinematic check of a mechanism of rigid
  bodies turning about hinges on the ground or on one another (alpha(theta) at finite rotation, d*_0, d*_u, T_s, the
  displacement demand).
* :mod:`.pushover` (the results): the N2 method of EN 1998-1 Annex B on a capacity curve given directly (:func:`n2`) or
  on a static or explicit pushover, in the plane or in 3D (:func:`pushover_n2`).
* :mod:`.verdict` (the results): :func:`assess`, the checks that apply to an analysis's results; the result file's
  ``assessment`` object (:func:`assessment_dict`) and the plain-text table of a calculation report
  (:func:`assessment_table`).
* :mod:`.plot` (the output, matplotlib): the ADRS figure and the displaced shape used for M*
  (:func:`assessment_figure`, :func:`plot_adrs`, :func:`plot_displaced_shape`).

From a case file: its [assessment] table (docs/case-format.md) and ``masonry-dem assess CASE``.

>>> from masonry_dem import assessment
>>> round(assessment.elastic_spectrum(0.3, code="ec8", ag=2.5, ground_type="B", spectrum_type=1), 6)
7.5

Accelerations in m/s2, periods in s, masses in kg (docs/assessment.md).
"""

from typing import TYPE_CHECKING

from .._lazy import lazy_package

if TYPE_CHECKING:  # what the names below resolve to (type checkers, IDEs); imported on first use at run time
    from .kinematic import (
        LinearCheck,
        MechanismWeights,
        linear_check,
        linear_check_of,
        mechanism_weights,
        participating_mass,
    )
    from .pushover import N2Check, n2, pushover_n2
    from .nonlinear import NonlinearCheck, alpha_of_rotation, nonlinear_check
    from .parameters import AssessmentParameters, read_assessment
    from .plot import assessment_figure, plot_adrs, plot_displaced_shape
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
    from .verdict import Assessment, assess, assessment_dict, assessment_table

__all__ = [
    "AssessmentParameters",
    "read_assessment",
    "LinearCheck",
    "MechanismWeights",
    "linear_check",
    "linear_check_of",
    "mechanism_weights",
    "participating_mass",
    "NonlinearCheck",
    "nonlinear_check",
    "alpha_of_rotation",
    "N2Check",
    "n2",
    "pushover_n2",
    "Assessment",
    "assess",
    "assessment_dict",
    "assessment_table",
    "assessment_figure",
    "plot_adrs",
    "plot_displaced_shape",
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
    **dict.fromkeys(("AssessmentParameters", "read_assessment"), ".parameters"),
    **dict.fromkeys(("LinearCheck", "MechanismWeights", "linear_check", "linear_check_of", "mechanism_weights",
                     "participating_mass"), ".kinematic"),
    **dict.fromkeys(("N2Check", "n2", "pushover_n2"), ".pushover"),
    **dict.fromkeys(("NonlinearCheck", "nonlinear_check", "alpha_of_rotation"), ".nonlinear"),
    **dict.fromkeys(("Assessment", "assess", "assessment_dict", "assessment_table"), ".verdict"),
    **dict.fromkeys(("assessment_figure", "plot_adrs", "plot_displaced_shape"), ".plot"),
    **dict.fromkeys(("Spectrum", "spectrum", "ec8_spectrum", "ntc2018_spectrum", "tabulated_spectrum",
                     "read_spectrum", "elastic_spectrum", "displacement_spectrum"), ".spectra"),
}

__getattr__, __dir__ = lazy_package(__name__, _LAZY, __all__)
