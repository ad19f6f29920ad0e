"""Studies: many analyses of one wall, run on Dask, from one laptop to a cluster (docs/study-format.md).

A study is a base case (a case file, a case table, or a ``Model`` builder), variations (a full grid over
named parameters, seeded random samples of any joint-law or geometry parameter, random textures, the load
direction) and one or several methods ("static", "dynamic", "limit"):

>>> import masonry_dem as md
>>> study = md.load_study("examples/wall1-fragility.toml")          # doctest: +SKIP
>>> table = md.run_study(study, "out/wall1.parquet", workers=2)      # doctest: +SKIP
>>> table["collapse_multiplier"].describe()                          # doctest: +SKIP

* :mod:`.spec` reads and checks study files (:func:`load_study`, :func:`parse_study`, :func:`study_from_dict`);
* :mod:`.model` is the study as data (:class:`Study`, its :class:`Variation` s and :class:`Texture`, the
  analyses it holds and the case of each, the mirrored wall of the -x direction);
* :mod:`.worker` runs analyses into rows, in the Dask workers;
* :mod:`.runner` runs a study on Dask (:func:`run_study`: a ``LocalCluster`` by default, or any scheduler);
* :mod:`.store` writes the rows to Parquet as they come and reads them back to resume (:func:`read_results`);
* :mod:`.summary` prints the summary and draws the summary figure (matplotlib, imported on first use).
"""

import importlib.util as _util

#: The packages studies need beyond masonry-dem's own: its extra "studies" (pyproject.toml).
_NEEDS = {"dask": "dask[distributed]", "distributed": "dask[distributed]", "pandas": "pandas", "pyarrow": "pyarrow"}
_MISSING = list(dict.fromkeys(pip for module, pip in _NEEDS.items() if _util.find_spec(module) is None))
if _MISSING:
    raise ImportError(
        f"masonry-dem's studies need {', '.join(_MISSING)}, not installed here: "
        "pip install 'masonry-dem[studies]'"
    )

from .model import DIRECTIONS, DISTRIBUTIONS, Item, Study, Texture, Variation
from .runner import run_study
from .spec import load_study, parse_study, study_from_dict
from .store import read_results
from .worker import FAILED_STATUSES, STUDY_STATUSES

__all__ = [
    "Study",
    "Variation",
    "Texture",
    "Item",
    "DIRECTIONS",
    "DISTRIBUTIONS",
    "FAILED_STATUSES",
    "STUDY_STATUSES",
    "load_study",
    "parse_study",
    "study_from_dict",
    "run_study",
    "read_results",
]
