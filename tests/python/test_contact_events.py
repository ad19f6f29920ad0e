"""The contact update of time histories seen from Python (``Model.simulate``'s default, docs/case-format.md,
``[time_history] contact_update``): its counts and events on the TimeHistory, the contacts at any record
(``masonry_dem.history.contacts_at``), and the outputs that show them appearing and vanishing: the ParaView series'
contacts part, the animation and the summary. The case: a 0.4 m block tipping off a ledge 1 m above a step
(as tests/contact_update.rs, where its energy balance is checked): it lands on the step, where it had no contact."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

import masonry_dem as md
from masonry_dem.history import contact_sets, contacts_at
from masonry_dem.response import history_dict, summary_text


def ledge() -> md.Model:
    """The block (block 0) on the ledge (support 1, its top at y = 1) and the step (support 2, its top at y = 0)."""
    return md.Model([[-0.15, 1.0, 0.25, 1.4]], supports=[[-2.0, 0.0, 0.0, 1.0], [0.0, -0.5, 3.0, 0.0]], base=False,
                    density=2000.0, joints={"default": md.dry_joint(0.6, stiffness=1e8)})


@pytest.fixture(scope="module")
def fallen() -> tuple:
    model = ledge()
    return model, model.simulate(1.5, record_interval=0.01)


def test_the_update_is_on_by_default_and_counts_what_it_did(fallen: tuple) -> None:
    model, h = fallen
    searches, created, dropped, renewed = h.contact_counts
    assert h.status == "completed" and searches > 1 and created >= 1
    assert h.ground_level is not None
    ev = h.contact_events
    change = list(ev["change"])
    assert change.count("created") == created and change.count("dropped") == dropped
    assert change.count("renewed") == renewed
    assert np.all(np.diff(ev["time"]) >= 0)
    # the created contacts are numbered after the model's interfaces, each once
    m = len(np.asarray(model.interface_blocks))
    new = np.asarray(ev["id"])[np.array(change) == "created"]
    assert np.all(new >= m) and len(set(new.tolist())) == len(new)
    # off: no search, no event
    off = model.simulate(0.05, record_interval=0.01, contact_update=False)
    assert off.contact_counts == (0, 0, 0, 0) and len(off.contact_events["time"]) == 0 and off.ground_level is None


def test_the_contacts_at_the_end_lie_on_the_step_under_the_block(fallen: tuple) -> None:
    model, h = fallen
    last = len(h.times) - 1
    c = contacts_at(model, h, last)
    # the block's contacts with the step (support 2, block index 2): made by the update, along the step's top
    # (y = 0, within the gap tolerance 2% of 0.4 m), within the block's moved bottom edge
    on_step = [i for i, (a, b) in enumerate(c.blocks) if {int(a), int(b)} == {0, 2}]
    assert on_step and all(c.created[i] for i in on_step)
    ends = c.ends[on_step].reshape(-1, 2)
    assert np.all(np.abs(ends[:, 1]) < 0.008), ends
    u = h.displacements[last][0]
    x0 = model.centroids[0][0] + u[0]
    assert np.all(np.abs(ends[:, 0] - x0) <= 0.2 + 0.008), (ends, x0)
    # at the start, the model's interfaces where the model puts them (no block has moved)
    first = contacts_at(model, h, 0)
    geom = np.asarray(model.interface_geometry)
    for i, cid in enumerate(first.ids):
        if cid < len(geom):
            mid = first.ends[i].mean(axis=0)
            np.testing.assert_allclose(mid, geom[cid, :2], atol=1e-6)
    # the sets of every record in one pass are those of each record alone
    all_sets = list(contact_sets(model, h, range(len(h.times))))
    for k in (0, len(h.times) // 2, last):
        assert list(all_sets[k].ids) == list(contacts_at(model, h, k).ids)


def test_the_paraview_series_has_the_contacts_as_part_one(fallen: tuple, tmp_path: Path) -> None:
    model, h = fallen
    pvd, blocks = md.write_vtk(model, h, tmp_path / "fall")
    root = ET.parse(pvd).getroot()
    parts = [d.get("part") for d in root.iter("DataSet")]
    assert parts.count("0") == len(h.times) and parts.count("1") == len(h.times)
    last = meshio.read(tmp_path / f"fall-contacts-{len(h.times) - 1:04d}.vtu")
    c = contacts_at(model, h, len(h.times) - 1)
    assert len(last.cells_dict["line"]) == len(c.ids)
    np.testing.assert_array_equal(last.cell_data["created"][0], c.created.astype(np.int32))


def test_the_animation_and_the_summary_show_them(fallen: tuple, tmp_path: Path) -> None:
    model, h = fallen
    gif = md.write_animation(model, h, tmp_path / "fall.gif", fps=10)
    assert gif.stat().st_size > 0
    searches, created, dropped, renewed = h.contact_counts
    text = summary_text(model, h, "fall")
    assert f"contact update:      {searches:,} searches; {created:,} contacts created, {dropped:,} dropped" in text
    out = history_dict(model, h, "fall")
    assert out["contact_update"]["created"] == created and out["contact_update"]["searches"] == searches
