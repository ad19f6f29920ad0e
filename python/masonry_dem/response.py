"""The response of a wall to a ground motion, from its time history (``Model.simulate``): drift, rotations,
base shear, the energy balance and their peaks, as ``masonry-dem simulate`` prints them and writes them (JSON).

* the **drift** is the horizontal displacement of the control block (the model's default: the top beam, else
  the highest wall block at the right end; :func:`masonry_dem.history.default_control_block`) over the height
  of the wall blocks; displacements are relative to the ground (:mod:`masonry_dem.history`);
* the **rotation** is the control block's phi [rad]; the largest rotation of any wall block is given too;
* the **base shear** [N] is the horizontal force of the wall on its base, +x positive (``TimeHistory.base_shear``);
* the **energy balance error** is the largest |``TimeHistory.energy_error``| (initial energy + external work -
  kinetic - elastic - dissipated) over the largest of the energies [J], a check of the time integration.

Of a 3D wall (``Model3D.simulate``): the control block is the highest wall block, its displacement and rotation
the lengths of its horizontal displacement and of its rotation vector (>= 0), the base shear and the ground's
acceleration the lengths of their horizontal vectors (x, y); the JSON records add ``base_shear_y`` and
``ground_acceleration_y``.

Quantities a TimeHistory does not carry (an older core) are NaN / None.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional

import numpy as np

from ._shapes import shapes
from .history import control_response, default_control_block

__all__ = [
    "wall_height",
    "drift",
    "peaks",
    "energy_scale",
    "energy_balance_error",
    "history_dict",
    "summary_text",
    "ENERGY_TERMS",
]

#: The energies of the balance ((k,) arrays of a TimeHistory [J]) and their labels, in the order the energy
#: plot draws them (:func:`masonry_dem.plot.plot_energy`).
ENERGY_TERMS = (
    ("external_work", "work of the ground motion and loads"),
    ("kinetic_energy", "kinetic"),
    ("elastic_energy", "elastic (joints)"),
    ("friction_dissipation", "dissipated by friction"),
    ("damping_dissipation", "dissipated by damping"),
    ("impact_dissipation", "dissipated by impacts"),
)


def _array(history: Any, name: str) -> Optional[np.ndarray]:
    """The (k,) or (k, ...) array ``name`` of ``history``, or None when it has none."""
    value = getattr(history, name, None)
    return None if value is None else np.asarray(value, dtype=np.float64)


def _three(model: Any) -> bool:
    return int(getattr(model, "dimension", 2)) == 3


def wall_height(model: Any) -> float:
    """The height of the wall blocks [m] (the base and the top beam not counted)."""
    if _three(model):
        boxes = np.asarray(model.boxes, dtype=np.float64).reshape(-1, 6)[: int(model.n_blocks)]
        return float(boxes[:, 5].max() - boxes[:, 2].min())
    wall = shapes(model).bounds[: int(model.n_blocks)]
    return float(wall[:, 3].max() - wall[:, 1].min())


def _horizontal(model: Any, history: Any, name: str) -> Optional[np.ndarray]:
    """(k,) the record ``name`` (``base_shear``, or the horizontal column of ``ground_acceleration``); of a 3D
    history the length of the vector with its ``_y`` record."""
    x = _array(history, name)
    if x is None:
        return None
    x = x.reshape(len(x), -1)[:, 0] if x.ndim > 1 else x
    y = _array(history, name + "_y") if _three(model) else None
    if y is None or y.size != x.size:
        return x
    return np.hypot(x, y.reshape(-1))


def drift(model: Any, history: Any) -> np.ndarray:
    """(k,) the drift: the control block's horizontal displacement relative to the ground over the wall
    height [-] (multiply by 100 for %)."""
    u, _ = control_response(model, history)
    return u / wall_height(model)


def _peak(values: Optional[np.ndarray], times: np.ndarray) -> Dict[str, Optional[float]]:
    """{"value": the signed value of largest magnitude, "time": its time [s]} (None when there is none)."""
    if values is None or values.size == 0 or not np.any(np.isfinite(values)):
        return {"value": None, "time": None}
    k = int(np.nanargmax(np.abs(values)))
    return {"value": float(values[k]), "time": float(times[k])}


def energy_scale(history: Any) -> float:
    """The largest of the energies of the balance over the history [J] (:data:`ENERGY_TERMS`, and the total
    dissipated), the scale of :func:`energy_balance_error`; 0 for a history at rest."""
    names = [name for name, _ in ENERGY_TERMS] + ["dissipated"]
    arrays = [a for a in (_array(history, n) for n in names) if a is not None and a.size]
    return float(max((np.nanmax(np.abs(a)) for a in arrays), default=0.0))


def energy_balance_error(history: Any) -> float:
    """max |``TimeHistory.energy_error``| / :func:`energy_scale` [-]; NaN when the history carries no
    ``energy_error``, has no energy at all, or its energies are not finite (a run that diverged)."""
    error = _array(history, "energy_error")
    scale = energy_scale(history)
    if error is None or error.size == 0 or not (scale > 0 and math.isfinite(scale)):
        return math.nan
    return float(np.nanmax(np.abs(error)) / scale)


def peaks(model: Any, history: Any) -> Dict[str, Any]:
    """The peaks of the response, each ``{"value", "time"}`` (the signed value of largest magnitude and its
    time [s]): ``drift`` [-], ``displacement`` [m] and ``rotation`` [rad] of the control block,
    ``block_rotation`` [rad] (of any wall block; with ``block``, its index), ``base_shear`` [N] and
    ``ground_acceleration`` [m/s2] (horizontal); with ``control_block``, ``wall_height`` [m], ``weight`` [N]
    (of the blocks that move: all but the base) and ``energy_balance_error`` (:func:`energy_balance_error`)."""
    times = np.asarray(history.times, dtype=np.float64).reshape(-1)
    u, phi = control_response(model, history)
    disp = np.asarray(history.displacements, dtype=np.float64)
    n_wall = int(model.n_blocks)
    if not disp.size:
        rotations = np.zeros((len(times), 0))
    elif _three(model):
        rotations = np.linalg.norm(disp[:, :n_wall, 3:6], axis=-1)
    else:
        rotations = disp[:, :n_wall, 2]
    block_rotation: Dict[str, Any] = {"value": None, "time": None, "block": None}
    if rotations.size:
        k, b = np.unravel_index(int(np.argmax(np.abs(rotations))), rotations.shape)
        block_rotation = {"value": float(rotations[k, b]), "time": float(times[k]), "block": int(b)}
    weights = np.asarray(model.weights, dtype=np.float64).reshape(-1)
    if model.base_index is not None:
        weights = np.delete(weights, int(model.base_index))
    return {
        "control_block": default_control_block(model),
        "wall_height": wall_height(model),
        "weight": float(weights.sum()),
        "drift": _peak(u / wall_height(model), times),
        "displacement": _peak(u, times),
        "rotation": _peak(phi, times),
        "block_rotation": block_rotation,
        "base_shear": _peak(_horizontal(model, history, "base_shear"), times),
        "ground_acceleration": _peak(_horizontal(model, history, "ground_acceleration"), times),
        "energy_balance_error": energy_balance_error(history),
    }


def _floats(a: Optional[np.ndarray]) -> Optional[List[Any]]:
    """A list of floats for JSON (NaN as None), or None."""
    if a is None:
        return None
    return [float(x) if math.isfinite(x) else None for x in np.asarray(a, dtype=np.float64).reshape(-1)]


def _clean(value: Any) -> Any:
    """``value`` with NaN and infinities as None (JSON has none)."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def history_dict(model: Any, history: Any, title: str, motion: Any = None) -> Dict[str, Any]:
    """The time history as a dict for JSON (``masonry-dem simulate --json``): ``format`` 1, ``kind``
    "time_history", ``title``, ``status``, ``error``, ``time_step`` [s], ``steps``, ``elapsed_s``,
    ``ground_motion`` (name, source, units, scale, peak [m/s2], duration [s] of ``motion``, the horizontal
    :class:`masonry_dem.ground_motion.GroundMotion`, when given), ``peaks`` (:func:`peaks`), and the records:
    ``times`` [s], ``displacement`` [m], ``rotation`` [rad] and ``drift`` [-] of the control block,
    ``base_shear`` [N], ``ground_acceleration`` ([[horizontal, vertical]] [m/s2]) and the energies [J]
    (those the history carries; NaN written as null); with the contact update, ``contact_update``: the searches
    made and the contacts created, dropped and renewed (taken again), and the ground plane's ``ground_level`` [m]."""
    times = np.asarray(history.times, dtype=np.float64).reshape(-1)
    u, phi = control_response(model, history)
    out: Dict[str, Any] = {
        "format": 1,
        "kind": "time_history",
        "title": title,
        "status": str(history.status),
        "error": history.error,
        "time_step": float(history.time_step),
        "steps": int(history.steps),
        "elapsed_s": float(history.elapsed_s),
        "blocks": int(model.n_blocks),
        "interfaces": int(model.n_interfaces),
    }
    if motion is not None:
        out["ground_motion"] = _clean({
            "name": motion.name, "source": motion.source, "units": motion.units, "scale": float(motion.scale),
            "peak": motion.peak, "duration": motion.duration,
        })
    out["peaks"] = _clean(peaks(model, history))
    searches, created, dropped, renewed = history.contact_counts
    if searches:
        out["contact_update"] = _clean({"searches": searches, "created": created, "dropped": dropped,
                                        "renewed": renewed, "ground_level": history.ground_level})
    records: Dict[str, Any] = {
        "times": _floats(times),
        "displacement": _floats(u),
        "rotation": _floats(phi),
        "drift": _floats(u / wall_height(model)),
        "base_shear": _floats(_array(history, "base_shear")),
    }
    ground = _array(history, "ground_acceleration")
    if ground is not None:
        records["ground_acceleration"] = [[float(x) if math.isfinite(x) else None for x in row]
                                          for row in ground.reshape(len(times), -1)]
    if _three(model):
        records["base_shear_y"] = _floats(_array(history, "base_shear_y"))
        records["ground_acceleration_y"] = _floats(_array(history, "ground_acceleration_y"))
    for name in [n for n, _ in ENERGY_TERMS] + ["gravity_work", "dissipated", "energy_error"]:
        records[name] = _floats(_array(history, name))
    out["records"] = {k: v for k, v in records.items() if v is not None}
    return out


def _at(peak: Dict[str, Any], fmt: str, factor: float = 1.0, unit: str = "") -> str:
    if peak.get("value") is None:
        return "-"
    return f"{peak['value'] * factor:{fmt}}{unit} at t = {peak['time']:.4g} s"


def summary_text(model: Any, history: Any, title: str, motion: Any = None) -> str:
    """The summary ``masonry-dem simulate`` prints (several lines, no trailing newline): the ground motion,
    the duration and time step, the status, the peak drift, the peak rotations, the peak base shear, the contact
    update's searches and changes (when it ran) and the energy balance error."""
    p = peaks(model, history)
    times = np.asarray(history.times, dtype=np.float64)
    status = str(history.status)
    if history.error:
        status += f" ({' '.join(str(history.error).split())})"
    lines = [title]
    if motion is not None:
        lines.append(f"  ground motion:       {motion.describe()}")
    duration = float(times[-1]) if len(times) else 0.0
    lines += [
        f"  duration:            {duration:.4g} s ({int(history.steps):,} steps of {float(history.time_step):.3g} s, "
        f"{len(times):,} records, {float(history.elapsed_s):.3g} s elapsed)",
        f"  status:              {status}",
        f"  peak drift:          {_at(p['drift'], '.3g', 100.0, ' %')} (control block {p['control_block']}, "
        f"wall height {p['wall_height']:.4g} m; displacement {_at(p['displacement'], '.4g', 1e3, ' mm')})",
        f"  peak rotation:       {_at(p['rotation'], '.3g', 1.0, ' rad')} (control block); any block: "
        + (f"{_at(p['block_rotation'], '.3g', 1.0, ' rad')} (block {p['block_rotation']['block']})"
           if p["block_rotation"]["value"] is not None else "-"),
    ]
    shear = p["base_shear"]
    if shear["value"] is not None:
        ratio = f" ({abs(shear['value']) / p['weight']:.3g} x the weight)" if p["weight"] > 0 else ""
        lines.append(f"  peak base shear:     {_at(shear, '.4g', 1e-3, ' kN')}{ratio}")
    else:
        lines.append("  peak base shear:     - (not recorded by this core)")
    searches, created, dropped, renewed = history.contact_counts
    if searches:
        lines.append(f"  contact update:      {searches:,} search{'es' if searches != 1 else ''}; {created:,} contacts created, "
                     f"{dropped:,} dropped, {renewed:,} taken again from the moved blocks")
    error = p["energy_balance_error"]
    if math.isfinite(error):
        lines.append(f"  energy balance:      error {error * 100:.3g} % of the largest energy ({energy_scale(history):.4g} J)")
    elif getattr(history, "energy_error", None) is None:
        lines.append("  energy balance:      - (no energy_error in this history)")
    else:
        lines.append("  energy balance:      - (no finite energy to compare it with)")
    return "\n".join(lines)
