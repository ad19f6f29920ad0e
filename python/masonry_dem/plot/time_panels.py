"""The panels of a time history (``Model.simulate``), each drawn on a matplotlib ``Axes``: a quantity of the
response against time (:func:`plot_response`: the control block's displacement or rotation, the drift, the base
shear, the ground acceleration) and the energy balance (:func:`plot_energy`).
"""

from __future__ import annotations

from typing import Any, List, Optional, Tuple

import numpy as np

from ..history import default_control_block

#: The quantities :func:`plot_response` draws: (axis label, factor from the history's unit, component of the
#: control block's (u1, u2, phi), or None for a quantity that is not one of them).
RESPONSE_QUANTITIES = {
    "displacement": ("horizontal displacement [mm]", 1e3, 0),
    "rotation": ("rotation [rad]", 1.0, 2),
    "drift": ("drift (top displacement / height) [%]", 100.0, None),
    "base_shear": ("base shear [kN]", 1e-3, None),
    "ground_acceleration": ("ground acceleration [m/s²]", 1.0, None),
}


def response_values(model: Any, history: Any, quantity: str, motion: Any = None) -> Tuple[np.ndarray, List[Tuple[str, np.ndarray]]]:
    """(times [s], [(label, values)]) of a quantity of :data:`RESPONSE_QUANTITIES` in its plotted unit:
    the control block's displacement [mm] or rotation [rad]; the drift [%] (its displacement over the wall
    height); the base shear [kN] (``TimeHistory.base_shear``); the ground acceleration [m/s²], horizontal and,
    when it is not zero throughout, vertical (``TimeHistory.ground_acceleration``, else sampled from
    ``motion``, the horizontal :class:`masonry_dem.ground_motion.GroundMotion`). Empty list: the history
    does not carry the quantity."""
    if quantity not in RESPONSE_QUANTITIES:
        raise ValueError(f"quantity must be one of {sorted(RESPONSE_QUANTITIES)}, not {quantity!r}")
    _, factor, dof = RESPONSE_QUANTITIES[quantity]
    times = np.asarray(history.times, dtype=np.float64).reshape(-1)
    if dof is not None:
        values = np.asarray(history.displacements, dtype=np.float64)[:, default_control_block(model), dof] * factor
        return times, [("", values)]
    if quantity == "drift":
        from ..response import drift

        return times, [("", drift(model, history) * factor)]
    if quantity == "base_shear":
        shear = getattr(history, "base_shear", None)
        return times, [] if shear is None else [("", np.asarray(shear, dtype=np.float64).reshape(-1) * factor)]
    ground = getattr(history, "ground_acceleration", None)
    if ground is not None:
        g = np.asarray(ground, dtype=np.float64).reshape(len(times), -1)
        series = [("horizontal", g[:, 0])]
        if g.shape[1] > 1 and np.any(g[:, 1] != 0):
            series.append(("vertical", g[:, 1]))
        return times, series
    if motion is not None:
        return times, [("horizontal", motion.at(times))]
    return times, []


def plot_response(
    ax: Any, model: Any, history: Any, quantity: str = "displacement", mark: Optional[int] = None,
    motion: Any = None,
) -> None:
    """Draw a response to a time history (``Model.simulate``) on ``ax`` against time [s]
    (:func:`response_values`): the control block's horizontal displacement [mm] (``quantity =
    "displacement"``) or rotation [rad] (``"rotation"``), the drift [%] (``"drift"``: its displacement over the
    wall height), the base shear [kN] (``"base_shear"``, the horizontal force of the wall on its base), or the
    ground acceleration [m/s²] (``"ground_acceleration"``: the history's input, else ``motion``'s; the vertical
    component too when there is one). Displacements are relative to the ground (:mod:`masonry_dem.history`).
    ``mark``: a record to mark with a dot (the one the deformed shape shows). The control block is the model's
    default one (the top beam, else the highest wall block at the right end)."""
    label = RESPONSE_QUANTITIES[quantity][0] if quantity in RESPONSE_QUANTITIES else ""
    times, series = response_values(model, history, quantity, motion)
    colors = {"": "#1f77b4", "horizontal": "#555555", "vertical": "#9467bd"}
    for name, values in series:
        ax.plot(times, values, color=colors.get(name, "#1f77b4"), linewidth=1.2 if name != "vertical" else 0.9,
                label=name or None)
    ax.axhline(0.0, color="#808080", linewidth=0.6)
    if series and mark is not None and 0 <= mark < len(times):
        values = series[0][1]
        ax.plot([times[mark]], [values[mark]], "o", color="#d62728", markersize=5, zorder=3)
    if not series:
        ax.text(0.5, 0.5, f"no {quantity.replace('_', ' ')} in this time history", transform=ax.transAxes,
                ha="center", va="center", fontsize=9, color="#808080")
    elif len(series) > 1:
        ax.legend(loc="upper right", fontsize=8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(label)
    ax.grid(True, linewidth=0.4, alpha=0.6)


#: The colour of each energy of :func:`plot_energy` (the names of :data:`masonry_dem.response.ENERGY_TERMS`).
ENERGY_COLORS = {
    "kinetic_energy": "#1f77b4",
    "elastic_energy": "#2ca02c",
    "friction_dissipation": "#d62728",
    "damping_dissipation": "#ff7f0e",
    "impact_dissipation": "#9467bd",
    "dissipated": "#d62728",
}


def plot_energy(history: Any, ax: Any = None, title: Optional[str] = None) -> Any:
    """Draw the energy balance of a time history (``Model.simulate``) against time [s], in J: the energy
    dissipated by friction, by damping and by impacts, the elastic energy of the joints and the kinetic energy
    stacked in that order (where the energy went), the work of the external loads and the ground motion as a black line over
    them (what came in), and the balance error (``TimeHistory.energy_error``: the initial energy + the external
    work - kinetic - elastic - dissipated) as a red dashed line. From rest, the gap between the stack and the black
    line is that error. A history without the split of the dissipation stacks
    its total (``dissipated``).

    ``ax``: the axes to draw on; None: a new figure (through pyplot). ``title``: the panel title (default:
    "energy balance" and the largest error relative to the largest energy). Returns the axes."""
    from ..response import ENERGY_TERMS, energy_balance_error

    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots(figsize=(8.0, 4.5), layout="constrained")
    times = np.asarray(history.times, dtype=np.float64).reshape(-1)
    labels = dict(ENERGY_TERMS)
    split = [n for n in ("friction_dissipation", "damping_dissipation", "impact_dissipation")
             if getattr(history, n, None) is not None]
    names = (split or ["dissipated"]) + ["elastic_energy", "kinetic_energy"]  # the growing dissipation at the bottom
    stacks = [np.asarray(getattr(history, n), dtype=np.float64).reshape(-1) for n in names]
    ax.stackplot(times, *stacks, labels=[labels.get(n, "dissipated") for n in names],
                 colors=[ENERGY_COLORS[n] for n in names], alpha=0.55, linewidth=0)
    work = getattr(history, "external_work", None)
    if work is not None:
        ax.plot(times, np.asarray(work, dtype=np.float64).reshape(-1), color="black", linewidth=1.3,
                label=labels["external_work"])
    error = getattr(history, "energy_error", None)
    if error is not None:
        ax.plot(times, np.asarray(error, dtype=np.float64).reshape(-1), color="#d62728", linestyle="--",
                linewidth=1.1, label="balance error")
    ax.axhline(0.0, color="#808080", linewidth=0.6)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("energy [J]")
    ax.grid(True, linewidth=0.4, alpha=0.6)
    ax.legend(loc="upper left", fontsize=8)
    if title is None:
        e = energy_balance_error(history)
        title = "energy balance" + (f": largest error {e * 100:.3g} % of the largest energy" if np.isfinite(e) else "")
    ax.set_title(title, fontsize=10)
    return ax
