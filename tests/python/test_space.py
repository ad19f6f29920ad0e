"""3D walls from Python: ``Model3D`` and the generators (masonry_dem.space), the one ``Results`` of both dimensions,
the case files' 3D tables and their refusals, and the command line on a 3D case (docs/case-format.md, "3D walls";
docs/references.md, section 5)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import masonry_dem as md
from masonry_dem import cli

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
LEAF = EXAMPLES / "leaf-out-of-plane.toml"
PNG = b"\x89PNG\r\n\x1a\n"
DRY = {"default": {"friction": 0.7, "dilatancy": 0.7}}  # dry, associative: limit analysis is exact


def limit(boxes, **kwargs):
    model = md.Model3D(boxes, **{"joints": DRY, **kwargs})
    return model, model.solve_limit()


# --------------------------------------------------------------------------------------------------
# The API
# --------------------------------------------------------------------------------------------------


def test_generators_give_boxes() -> None:
    leaf = md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175)
    assert leaf.shape == (33, 6) and leaf.dtype == np.float64
    volume = lambda b: float(np.prod(b[:, 3:] - b[:, :3], axis=1).sum())  # noqa: E731
    assert volume(leaf) == pytest.approx(2.0 * 1.05 * 0.1, rel=1e-12)
    # the leaf's courses are the 2D running bond's, extruded over the thickness
    rects = md.running_bond(0.4, 0.175, courses=6, length=2.0)
    extruded = np.c_[rects[:, 0], np.zeros(len(rects)), rects[:, 1], rects[:, 2], np.full(len(rects), 0.1), rects[:, 3]]
    assert np.allclose(np.sort(leaf, axis=0), np.sort(extruded, axis=0))
    full = md.running_bond_3d(1.2, 0.4, 0.1, 0.4, 0.2, first_course="full")
    assert len(full) == 3 + 4  # three whole blocks, then a half, two whole and a half
    u = md.u_wall(3.0, 2.5, 1.5, 0.25, 0.5, 0.25)
    assert u.shape[1] == 6 and volume(u) == pytest.approx((3.0 + 2 * 1.25) * 0.25 * 2.5, rel=1e-12)
    corner = md.corner_wall(3.0, 2.5, 1.5, 0.25, 0.5, 0.25)
    assert volume(corner) == pytest.approx((3.0 + 1.25) * 0.25 * 2.5, rel=1e-12)
    cut = md.space.cut_openings(leaf, [[0.5, 0.35, 1.3, 0.7]])
    assert volume(cut) == pytest.approx((2.0 * 1.05 - 0.8 * 0.35) * 0.1, rel=1e-12)
    opened = md.u_wall(3.0, 2.5, 1.5, 0.25, 0.5, 0.25, openings=[[1.0, 0.5, 2.0, 1.75]])
    assert volume(opened) == pytest.approx(volume(u) - 1.0 * 1.25 * 0.25, rel=1e-12)


def test_model3d_arrays() -> None:
    boxes = md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175)
    model = md.Model3D(boxes, density=1800.0, top=0.2, gravity=10.0, direction=90)
    n, m = model.n_blocks, model.n_interfaces
    assert (n, model.dimension, model.live, model.direction, model.gravity) == (33, 3, "horizontal_weight", 90.0, 10.0)
    assert (model.base_index, model.top_index) == (33, 34)
    assert model.boxes.shape == (35, 6) and np.array_equal(model.boxes[:n], boxes)
    assert model.centroids.shape == (35, 3) and model.mass.shape == (35,)
    assert model.interface_blocks.shape == (m, 2)
    for name in ("interface_normals", "interface_t1", "interface_t2", "interface_centroids"):
        assert getattr(model, name).shape == (m, 3), name
    assert model.interface_corners.shape == (m, 4, 3) and model.interface_areas.shape == (m,)
    assert set(model.interface_family) == {"bed", "head", "base", "top"}
    t1, t2, normal = model.interface_t1, model.interface_t2, model.interface_normals
    assert np.allclose(np.cross(t1, t2), normal)
    # the wall and the beam weigh, the base does not
    w = model.weights
    assert w[33] == 0.0 and w[:33].sum() == pytest.approx(1800.0 * 10.0 * 2.0 * 1.05 * 0.1, rel=1e-12)
    assert w[34] == pytest.approx(1800.0 * 10.0 * 2.0 * 0.1 * 0.2, rel=1e-12)
    assert repr(model) == f"Model3D(33 blocks, {m} interfaces)"


@pytest.mark.parametrize("direction, b", [(0, 0.3), (90, 0.2), (180, 0.3), (270, 0.2)])
def test_a_box_overturns_at_b_over_h(direction: float, b: float) -> None:
    """A 0.3 x 0.2 x 0.9 m box (x, y, z) pushed along x or y in plan rocks at b/h, b its side along the load."""
    model, r = limit([[0.0, 0.0, 0.0, 0.3, 0.2, 0.9]], direction=direction)
    assert r.status == "collapse" and r.dimension == 3 and r.method == "limit"
    assert r.collapse_multiplier == pytest.approx(b / 0.9, abs=1e-6)
    # the mechanism turns the box about the leeward edge of its base: its top moves with the load
    v = r.mechanism[0]
    d = np.radians(direction)
    assert v[0] * np.cos(d) + v[1] * np.sin(d) > 0
    assert r.mechanism.shape == (2, 6) and r.interface_forces.shape == (1, 6) and r.displacements.shape == (2, 6)


def test_the_same_results_class_holds_both_dimensions() -> None:
    plane = md.Model([[0.0, 0.0, 0.2, 0.6]], joints={"default": {"friction": 0.7, "dilatancy": 0.7}})
    r2 = plane.solve_limit()
    _, r3 = limit([[0.0, 0.0, 0.0, 0.2, 1.0, 0.6]])
    assert type(r2) is type(r3) is md.Results
    assert (r2.dimension, r3.dimension, plane.dimension) == (2, 3, 2)
    assert r2.mechanism.shape[1] == 3 and r3.mechanism.shape[1] == 6
    assert r3.collapse_multiplier == pytest.approx(r2.collapse_multiplier, abs=1e-6)
    for name in ("status", "error", "iterations", "steps", "joint_states", "certificate", "bracket"):
        assert type(getattr(r2, name)) is type(getattr(r3, name)), name
    assert "dimension=3" in repr(r3) and "dimension" not in repr(r2)


def test_an_extruded_wall_collapses_as_in_the_plane() -> None:
    """Ferris & Tin-Loi wall 1 extruded over its thickness and pushed along its plane: the 2D multiplier."""
    rects = md.running_bond(0.4, 0.175, courses=6, length=2.0)
    law = {"friction": 0.65, "dilatancy": 0.65}
    plane = md.Model(rects, thickness=0.3, gravity=10.0, joints={"default": law}).solve_limit()
    boxes = np.c_[rects[:, 0], np.zeros(len(rects)), rects[:, 1], rects[:, 2], np.full(len(rects), 0.3), rects[:, 3]]
    model = md.Model3D(boxes, gravity=10.0, joints={"default": law}, direction=0)
    space = model.solve_limit()
    assert plane.collapse_multiplier == pytest.approx(0.642857, abs=1e-5)
    assert space.collapse_multiplier == pytest.approx(plane.collapse_multiplier, abs=1e-6)


def test_wrong_argument_types_are_input_errors() -> None:
    boxes = [[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]]
    with pytest.raises(md.InputError, match=r"boxes: expected a list of \[x0, y0, z0, x1, y1, z1\] rows"):
        md.Model3D("boxes")
    with pytest.raises(md.InputError, match="boxes must be real numbers"):
        md.Model3D(np.ones((1, 6), dtype=bool))
    with pytest.raises(md.InputError, match=r"boxes\[0\]: expected 6 numbers"):
        md.Model3D([[0.0, 0.0, 1.0, 1.0]])
    with pytest.raises(md.InputError, match="Model3D: 'density'"):
        md.Model3D(boxes, density="heavy")
    with pytest.raises(md.InputError, match="running_bond_3d"):
        md.running_bond_3d("2 m", 1.0, 0.1, 0.4, 0.2)
    with pytest.raises(md.InputError, match="first_course"):
        md.running_bond_3d(2.0, 1.0, 0.1, 0.4, 0.2, first_course="third")
    with pytest.raises(md.InputError, match="u_wall"):
        md.u_wall(3.0, 2.5, 1.5, 0.25, 0.5, None)
    with pytest.raises(md.InputError, match="live"):
        md.Model3D(boxes, live="top_horizontal")
    with pytest.raises(md.InputError, match="direction applies"):
        md.Model3D(boxes, live="none", direction=90)
    with pytest.raises(md.InputError, match="max_iterations"):
        md.Model3D(boxes).solve_limit(max_iterations="many")
    # mortar: the core's 3D limit analysis takes it at its peak strengths, and says so
    mortar = md.Model3D(boxes, joints={"default": {"cohesion": 1e5, "friction": 0.65, "dilatancy": 0.65}}).solve_limit()
    assert mortar.status == "collapse" and mortar.certificate is not None and mortar.certificate["peak_strengths"] is True


def test_limit_analysis_on_threads_gives_the_same_results_to_the_bit(tmp_path: Path) -> None:
    """From 2,000 contacts the interior point's passes run on the threads asked for (a U wall of 2,240 contacts, the
    Rust test `the_threads_give_the_same_results_to_the_bit` checks the core): the same iterates whatever their
    number; a case's analysis.threads reaches a 3D limit analysis."""
    model = md.Model3D(md.u_wall(12.0, 5.0, 4.0, 0.25, 0.5, 0.25), joints=DRY, direction=90)
    one, two = model.solve_limit(threads=1), model.solve_limit(threads=2)
    assert one.status == "collapse" and one.iterations == two.iterations
    assert one.collapse_multiplier == two.collapse_multiplier
    assert np.array_equal(one.mechanism, two.mechanism) and np.array_equal(one.interface_forces, two.interface_forces)
    with pytest.raises(md.InputError, match="threads must be >= 0"):
        model.solve_limit(threads=-1)
    path = tmp_path / "box.toml"
    path.write_text('format = 1\ntitle = "box"\n[geometry]\nboxes = [[0, 0, 0, 0.3, 0.2, 0.9]]\n'
                    "[joints]\nfriction = 0.7\ndilatancy = 0.7\n[loads]\ndirection = 90\n[analysis]\nthreads = 1\n")
    case = md.load_case(path)
    assert (case.dimension, case.method, case.solver_kwargs()) == (3, "limit", {"threads": 1})
    assert abs(case.run().collapse_multiplier - 0.2 / 0.9) <= 1e-6 * 0.2 / 0.9


def test_a_progress_callback_that_raises_stops_the_analysis() -> None:
    model = md.Model3D(md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), joints=DRY, direction=90)
    calls = []

    def progress(step, multiplier, _displacement, _fraction):
        calls.append(step)
        if step == 3:
            raise ValueError("enough")

    with pytest.raises(ValueError, match="enough") as info:
        model.solve_limit(progress=progress)
    assert calls == [1, 2, 3]
    partial = info.value.results
    assert partial.status == "interrupted" and partial.dimension == 3 and np.isnan(partial.collapse_multiplier)
    assert partial.mechanism.shape == (34, 6)


def test_to_dict_and_json_round_trip(tmp_path: Path) -> None:
    model, r = limit(md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), direction=90)
    data = json.loads(json.dumps(md.to_dict(r, model, title="leaf")))
    assert data["dimension"] == 3 and data["status"] == "collapse"
    assert np.array(data["mechanism"]).shape == (34, 6) and np.array(data["interface_forces"]).shape == (83, 6)
    assert np.array(data["block_boxes"]).shape == (34, 6) and len(data["interface_areas"]) == 83
    assert np.allclose(np.array(data["mechanism"]), r.mechanism)
    written = md.to_json(r, tmp_path / "leaf.json", model, title="leaf")
    assert json.loads((tmp_path / "leaf.json").read_text()) == written
    # the result file: the keys of a 2D limit analysis's and "dimension"
    plane = md.Model([[0.0, 0.0, 0.2, 0.6]], joints=DRY)
    keys_2d = set(md.result_dict(plane.solve_limit(), plane, "block"))
    assert set(written) == keys_2d | {"dimension"} and "dimension" not in keys_2d
    assert written["collapse_multiplier"] == pytest.approx(0.1 / 1.05, abs=1e-9)
    columns = md.api.interface_columns(r, model)
    assert list(columns) == list(md.api.INTERFACE_COLUMNS_3D) and len(columns["N_N"]) == 83
    with pytest.raises(md.InputError, match="does not match"):
        md.to_dict(r, plane)


# --------------------------------------------------------------------------------------------------
# The explicit solver in 3D: quasi-static (Model3D.solve_dynamic) and time histories (Model3D.simulate)
# --------------------------------------------------------------------------------------------------

# joints 100 times softer than the default (1e10 N/m3): the explicit solver's time step is 10 times longer, and the
# collapse multiplier of rigid blocks does not depend on the stiffness
SOFT_DRY = {"default": {"friction": 0.7, "dilatancy": 0.7, "normal_stiffness": 1e8, "shear_stiffness": 1e8}}


def test_the_explicit_solver_finds_the_limit_analysis_multiplier_of_a_u_wall() -> None:
    """A small U (facade 2 m, returns 1 m, 1 m high, 0.2 m thick, 47 blocks of 0.4 x 0.2 m) pushed away from its
    returns (-y): the explicit pushover's collapse multiplier within 2% of limit analysis's (0.4633; measured 0.4575,
    -1.3%, in about 4 s on two cores)."""
    model = md.Model3D(md.u_wall(2.0, 1.0, 1.0, 0.2, 0.4, 0.2), joints=SOFT_DRY, direction=270)
    exact = model.solve_limit().collapse_multiplier
    r = model.solve_dynamic(steps=50, tolerance=3e-3)
    assert (r.method, r.status, r.dimension) == ("dynamic", "collapse", 3), r.error
    assert r.collapse_multiplier == pytest.approx(exact, rel=0.02)
    lower, upper = r.bracket
    assert lower == r.collapse_multiplier <= upper <= exact * 1.02
    n_all, m = model.n_blocks + 1, model.n_interfaces
    assert r.displacements.shape == r.mechanism.shape == (n_all, 6) and r.interface_forces.shape == (m, 6)
    assert r.iterations > 0 and len(r.curve_multiplier) == len(r.curve_displacement) == r.steps
    # the curve follows the highest block along y (the load's direction, 270, is nearer y than x), away from the returns
    top = int(np.argmax(model.boxes[: model.n_blocks, 5]))
    assert r.control_block == top and r.curve_displacement[-1] == r.displacements[top, 1] < 0
    assert np.all(np.diff(r.curve_multiplier) > 0)
    # checked against limit analysis (dry associative joints): its certificate is the evidence
    assert r.certificate is not None and r.certificate["multiplier"] == pytest.approx(exact, rel=1e-9)


def test_a_box_overturns_at_b_over_h_with_the_explicit_solver() -> None:
    """The box of test_a_box_overturns_at_b_over_h, pushed out of its plane (+y): lambda = b / h = 0.2 / 0.9 within
    the bracket's tolerance; its progress callback stops it, with the partial Results."""
    model = md.Model3D([[0.0, 0.0, 0.0, 0.3, 0.2, 0.9]], joints=SOFT_DRY, direction=90)
    r = model.solve_dynamic()
    assert r.status == "collapse" and r.collapse_multiplier == pytest.approx(0.2 / 0.9, rel=2e-3)
    assert r.displacements[0, 1] > 0 and r.displacements[0, 3] < 0  # towards +y, turning about -x
    assert model.critical_time_step() > 0
    calls = []

    def progress(step, multiplier, _displacement, _fraction):
        calls.append(multiplier)
        if len(calls) == 3:
            raise ValueError("enough")

    with pytest.raises(ValueError, match="enough") as info:
        model.solve_dynamic(progress=progress)
    partial = info.value.results
    assert partial.status == "interrupted" and partial.dimension == 3 and partial.method == "dynamic"
    assert len(partial.curve_multiplier) >= 3 and partial.displacements.shape == (2, 6)


def test_a_time_history_in_3d_slides_a_box_along_the_ground_motion(tmp_path: Path) -> None:
    """A flat box (1 x 1 x 0.2 m, friction 0.3) under a base acceleration of 5 m/s2 for 0.2 s, along y, then along x:
    it slides against the ground's motion along that axis only, by the rigid block's 0.0699 m (relative acceleration
    a - mu g for 0.2 s, then friction stopping it; within 2%), the base carrying mu W along the axis while it slides."""
    law = {"friction": 0.3, "dilatancy": 0.0, "normal_stiffness": 1e8, "shear_stiffness": 1e8}
    model = md.Model3D([[0.0, 0.0, 0.0, 1.0, 1.0, 0.2]], joints={"default": law}, live="none")
    a, mu, g, t1 = 5.0, 0.3, 9.81, 0.2
    pulse = ([0.0, t1, t1 + 1e-4], [a, a, 0.0])
    slid = 0.5 * (a - mu * g) * t1**2 + ((a - mu * g) * t1) ** 2 / (2 * mu * g)
    weight = model.weights[0]
    for axis, kwargs in ((1, {"base_acceleration_y": pulse}), (0, {"base_acceleration": pulse})):
        h = model.simulate(0.5, **kwargs)
        assert (h.status, h.dimension) == ("completed", 3) and "dimension=3" in repr(h)
        k = len(h.times)
        assert h.displacements.shape == h.velocities.shape == (k, 2, 6)
        assert h.ground_acceleration.shape == (k, 2) and h.ground_acceleration_y.shape == h.base_shear_y.shape == (k,)
        u = h.displacements[-1, 0]
        assert u[axis] == pytest.approx(-slid, rel=0.02) and abs(u[1 - axis]) < 1e-9
        assert np.allclose(h.velocities[-1, 0], 0.0, atol=1e-6)  # at rest again
        mid = np.searchsorted(h.times, 0.1)
        shear = (h.base_shear, h.base_shear_y)
        ground = (h.ground_acceleration[:, 0], h.ground_acceleration_y)
        assert ground[axis][mid] == a and ground[1 - axis][mid] == 0.0
        assert shear[axis][mid] == pytest.approx(-mu * weight, rel=1e-6) and shear[1 - axis][mid] == 0.0
    # the curve's file and the figures of a time history are the plane's in this version: refused by name, not
    # failing inside; its VTK series is written (tests/python/test_space_polyhedra.py)
    for output in (lambda: md.write_curve_csv(h, tmp_path / "h.csv", model=model),
                   lambda: md.plot.report_figure(model, h)):
        with pytest.raises(md.InputError, match="a 3D wall's time history .* is not drawn or written as a curve"):
            output()
    assert not list(tmp_path.iterdir())
    # the plane's time history has no y components
    plane = md.Model([[0.0, 0.0, 1.0, 0.2]], joints={"default": law}).simulate(0.01)
    assert plane.dimension == 2 and plane.displacements.shape[2] == 3 and plane.base_shear_y.shape == (0,)


def test_the_explicit_solver_in_3d_refuses_what_it_does_not_model() -> None:
    box = [[0.0, 0.0, 0.0, 0.3, 0.2, 0.9]]
    model = md.Model3D(box, joints=SOFT_DRY, direction=90)
    with pytest.raises(md.InputError, match=r'load-controlled \(analysis.control = "load"\)'):
        model.solve_dynamic(control="displacement")
    with pytest.raises(md.InputError, match="applies to displacement control only"):
        model.solve_dynamic(max_displacement=0.01)
    softening = md.Model3D(box, joints={"default": {"cohesion": 1e5, "fracture_energy_tension": 10.0, "fracture_energy_shear": 10.0}})
    for run in (softening.solve_dynamic, lambda: softening.simulate(0.01)):
        with pytest.raises(md.InputError, match="the explicit solver in 3D takes brittle joints"):
            run()
    with pytest.raises(md.InputError, match="stiffness-proportional damping is the plane's only"):
        model.simulate(0.01, rayleigh=(1.0, 1e-4))
    with pytest.raises(md.InputError, match=r"initial_displacements\[0\]: expected 6 numbers \(ux, uy, uz, rx, ry, rz\)"):
        model.simulate(0.01, initial_displacements=[[0.0, 0.0, 0.0]] * 2)
    with pytest.raises(md.InputError, match="Model3D.simulate"):
        model.simulate("long")
    with pytest.raises(md.InputError, match="no support"):
        md.Model3D(box + [[0.0, 0.0, 0.9, 0.3, 0.2, 1.2]], base=False).solve_dynamic()


# --------------------------------------------------------------------------------------------------
# Case files
# --------------------------------------------------------------------------------------------------

JOINTS = '[joints]\nfriction = 0.7\ndilatancy = 0.7\n'
LEAF_TABLE = """[geometry.leaf]
length = 2.0
height = "1050 mm"
thickness = 0.1
block_length = 0.4
block_height = 0.175
"""


def case(text: str, name: str = "w.toml"):
    return md.parse_case("format = 1\n" + text, source=name)


def test_the_leaf_table() -> None:
    c = case(LEAF_TABLE + JOINTS + "[loads]\ndirection = 90\n")
    assert c.dimension == 3 and c.method == "limit"
    assert c.model_kwargs["boxes"].shape == (33, 6)
    assert c.model_kwargs["density"] == 2000.0 and c.model_kwargs["direction"] == 90.0  # the core's default, given
    r = c.run()
    assert r.dimension == 3 and r.collapse_multiplier == pytest.approx(0.1 / 1.05, abs=1e-6)
    full = case(LEAF_TABLE + 'first_course = "full"\n').model.boxes
    offset = case(LEAF_TABLE + 'first_course = "0 mm"\n').model.boxes
    assert np.array_equal(full, offset) and not np.array_equal(full, case(LEAF_TABLE).model.boxes)
    opened = case(LEAF_TABLE + "openings = [[0.4, 0.35, 1.2, 0.7]]\n").model.boxes
    removed = 2.0 * 1.05 * 0.1 - float(np.prod(opened[:, 3:] - opened[:, :3], axis=1).sum())
    assert removed == pytest.approx(0.8 * 0.35 * 0.1, rel=1e-9)


def test_the_u_wall_and_corner_tables() -> None:
    table = """facade = 3.0
height = 2.5
returns = 1.5
thickness = 0.25
block_length = 0.5
block_height = 0.25
"""
    u = case("[geometry.u_wall]\n" + table)
    assert u.model.boxes.shape == (115, 6)
    corner = case("[geometry.corner]\n" + table + "openings = [[1.5, 0.5, 2.5, 1.5]]\n")
    assert corner.dimension == 3 and corner.model.boxes.shape[1] == 6
    example = md.load_case(EXAMPLES / "u-wall.toml")
    assert example.model.direction == 270.0 and example.model.joints == DRY


def test_the_boxes_key_and_the_3d_keys_of_other_tables() -> None:
    c = case('[geometry]\nboxes = [[0, 0, 0, "300 mm", 0.2, 0.9]]\ndensity = 1800\n[top]\nheight = 0.1\n' + JOINTS
             + "[loads]\ndirection = 0\n[base]\nkind = \"fixed\"\n")
    assert c.model.boxes.tolist() == [[0.0, 0.0, 0.0, 0.3, 0.2, 0.9]]
    model = c.build_model()
    assert model.top_index == 2 and model.base_index == 1 and model.boxes[2, 5] == pytest.approx(1.0)


@pytest.mark.parametrize(
    "text, key, words",
    [
        (LEAF_TABLE + '[analysis]\nmethod = "static"\n', "analysis.method",
         'the 3D model takes limit analysis and the explicit solver (method "limit" or "dynamic")'),
        (LEAF_TABLE + '[analysis]\nmethod = "dynamic"\ncontrol = "displacement"\n', "analysis.control",
         "the explicit solver in 3D is load-controlled"),
        (LEAF_TABLE + '[time_history]\ndamping = "rayleigh"\ndamping_ratio = 0.05\n', "time_history.damping",
         '"rayleigh" is refused in 3D'),
        (LEAF_TABLE + '[reference]\ncollapse_multiplier = 0.1\nmethods = ["static"]\n', "reference.methods",
         "limit analysis"),
        (LEAF_TABLE + '[loads]\nlive = "top_horizontal"\n', "loads.live", "horizontal_weight"),
        (LEAF_TABLE + '[top]\nrotation = "free"\n', "top.rotation", "give its height"),
        (LEAF_TABLE + "[top]\n", "top.height", "missing key 'height' in [top]"),
        ("[geometry]\nthickness = 0.3\n" + LEAF_TABLE, "geometry.thickness", "in [geometry.leaf] thickness"),
        (LEAF_TABLE.replace("1050 mm", "1.06 m"), None, "use height = 1.05 m"),
        (LEAF_TABLE + 'first_course = "third"\n', "geometry.leaf.first_course", '"half", "full" or an offset'),
        ("[geometry]\nboxes = [[0, 0, 0, 1, 1]]\n", "geometry.boxes[0]", "expected 6 numbers"),
        ("[geometry]\nboxes = [[0, 0, 0, 1, -1, 1]]\n", "geometry.boxes[0]", "y1 > y0"),
        ("[geometry]\nboxes = []\n", "geometry.boxes", "at least one box"),
        ("[geometry]\nboxes = [[0, 0, 0, true, 1, 1]]\n", "geometry.boxes[0][3]", "expected a number"),
        ("[geometry]\nboxes = [[0, 0, 0, 1, 1, 1]]\nblocks = [[0, 0, 1, 1]]\n", None, "blocks and boxes are both given"),
        ('[geometry]\nboxes = [[0, 0, 0, 1, 1, 1], [0, 0, 1, 1, 1, 2]]\n[base]\nkind = "none"\n', None, "no support"),
        # one box without a base touches nothing because nothing holds it: the support is what is missing
        ('[geometry]\nboxes = [[0, 0, 0, 1, 1, 1]]\n[base]\nkind = "none"\n', None, "the wall has no support"),
        # openings outside the wall, or over all of it, were dropped without a word or blamed on the blocks
        (LEAF_TABLE + "openings = [[0.4, 0.35, 0.8, 0.7], [5, 0.2, 6, 0.5]]\n", "geometry.leaf.openings[1]",
         "geometry.leaf.openings[1] [x0, z0, x1, z1] = [5, 0.2, 6, 0.5] lies outside the wall (its facade spans x from "
         "0 to 2 m, z from 0 to 1.05 m)"),
        (LEAF_TABLE + "openings = [[-1, -1, 3, 3]]\n", "geometry.leaf.openings",
         "geometry.leaf.openings: the openings remove every block of the wall"),
        ("[geometry.u_wall]\nfacade = 3\nheight = 1\nreturns = 1.5\nthickness = 0.2\nblock_length = 0.4\n"
         "block_height = 0.2\nopenings = [[1, 1.2, 2, 1.5]]\n", "geometry.u_wall.openings[0]", "lies outside the wall"),
        ("[geometry.corner]\nfacade = 3\nheight = 1\nreturns = 1.5\nthickness = 0.2\nblock_length = 0.4\n"
         "block_height = 0.2\nopenings = [[-2, 0.2, -1, 0.5]]\n", "geometry.corner.openings[0]", "lies outside the wall"),
        ("[geometry.u_wall]\nfacade = 3\nheight = 2.5\nreturns = 1.5\nthickness = 0.5\nblock_length = 0.5\n"
         "block_height = 0.25\n", "geometry.u_wall.thickness", "a corner block must reach past the corner"),
        # the 2D side refuses the 3D keys by name
        ("[geometry]\nblocks = [[0, 0, 1, 1]]\n[loads]\ndirection = 90\n", "loads.direction",
         "a wall in the plane is pushed along +x"),
        ("[geometry]\nblocks = [[0, 0, 1, 1]]\n[top]\nheight = 0.2\n", "top.height", "3D wall's top beam"),
    ],
)
def test_refusals_name_the_key(text: str, key, words: str) -> None:
    with pytest.raises(md.InputError) as info:
        case(text).run()
    message = str(info.value)
    assert message.startswith("w.toml: ") and "\n" not in message and words in message, message
    if key is not None:
        assert info.value.key == key, message


@pytest.mark.parametrize(
    "boxes, volume, centroid_z, hinge, words",
    [
        # a box 0.4 x 0.6 x 1 m under a beam 1000 m high: they turn as one about the base's edge y = 0.6 m
        ([[0.0, 0.0, 0.0, 0.4, 0.6, 1.0]], 0.24, 0.5, "y = 0.60, z = 0.00 m",
         "1 of 1 block and the top beam move as one part, {hinge}; the crack runs through 1 contact: 1 rock (1 base)"),
        # the leaf 2 x 1.05 x 0.1 m of 33 blocks under a beam 1000 m high: about the base's edge y = 0.1 m
        (md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), 0.21, 0.525, "y = 0.10, z = 0.00 m",
         "33 of 33 blocks and the top beam move as one part, {hinge}; the crack runs through 6 contacts: 6 rock (6 base)"),
    ],
)
def test_the_mechanism_under_a_very_tall_beam_is_the_hand_calculation(boxes, volume, centroid_z, hinge, words) -> None:
    """A beam 1000 m high on the wall, pushed out of the wall's plane (+y): wall and beam overturn as one rigid body
    about the leeward edge of the base (a hinge at z = 0), at lambda = (W_w + W_b) (t / 2) / (W_w z_w + W_b z_b), the
    weights in proportion to the volumes (the wall's; the beam's, 1000 m over the wall's plan, its centroid at the
    wall's height plus 500 m). The description said "only the top beam moves" with no crack: the beam's top corners,
    a kilometre up, made the wall's motion and its rocking base look like rest."""
    b = np.asarray(boxes)
    t, height, plan = b[:, 4].max(), b[:, 5].max(), (b[:, 3].max() - b[:, 0].min()) * b[:, 4].max()
    beam = 1000.0
    w_wall, w_beam = volume, plan * beam
    expected = (w_wall + w_beam) * (t / 2) / (w_wall * centroid_z + w_beam * (height + beam / 2))
    model = md.Model3D(boxes, joints=DRY, direction=90.0, top=beam)
    r = model.solve_limit()
    # within the interior point's duality gap (some 3e-10 here, a relative 3e-6 of a multiplier of 1e-4)
    assert r.status == "collapse" and r.collapse_multiplier == pytest.approx(expected, rel=0, abs=r.certificate["duality_gap"])
    from masonry_dem.space.report import describe_mechanism

    assert describe_mechanism(model, r) == words.format(hinge=f"turning about an axis along x through {hinge}")


def test_a_2d_case_keeps_its_meaning() -> None:
    c = case('[geometry]\nblocks = [[0, 0, 0.2, 0.6]]\n[loads]\ndirection = 0\n' + JOINTS)
    assert c.dimension == 2 and c.method == "static" and "direction" not in c.model_kwargs
    with pytest.raises(md.InputError, match="3D model takes limit analysis"):
        case(LEAF_TABLE).run("static")
    with pytest.raises(md.InputError, match=r"no \[ground_motion\] table"):
        case(LEAF_TABLE).simulate_kwargs()


# --------------------------------------------------------------------------------------------------
# The command line
# --------------------------------------------------------------------------------------------------


def test_run_the_leaf_example(tmp_path: Path) -> None:
    """`masonry-dem run` on the 3D example: the multiplier printed, the result file, the plot and the VTK files."""
    out = tmp_path / "out"
    args = ["run", str(LEAF), "--json", str(out / "leaf.json"), "--plot", str(out / "leaf.png"), "--vtk",
            str(out / "leaf")]
    proc = subprocess.run([sys.executable, "-m", "masonry_dem", *args], cwd=tmp_path, capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    text = proc.stdout
    assert text.startswith("Leaf pushed out of plane (2 x 1.05 x 0.1 m)\n")
    assert "collapse multiplier: 0.0952\n" in text and "status:              collapse" in text
    assert "towards +y (90°)" in text and "turning about an axis along x through y = 0.10, z = 0.00 m" in text
    data = json.loads((out / "leaf.json").read_text())
    assert data["dimension"] == 3 and data["method"] == "limit" and data["blocks"] == 33
    assert data["collapse_multiplier"] == pytest.approx(0.0952381, rel=1e-6)
    assert (out / "leaf.png").read_bytes()[:8] == PNG and (out / "leaf.png").stat().st_size > 50_000
    meshio = pytest.importorskip("meshio")
    blocks = meshio.read(out / "leaf-blocks.vtu")
    assert len(blocks.cells_dict["hexahedron"]) == 34  # the wall and the base
    assert blocks.point_data["mechanism"].shape == (8 * 34, 3)
    # the leaf turns out of plane (+y) about the leeward edge of its base (y = 0.1, z = 0): the top course's centroid
    # (y = 0.05, z = 0.9625 m) moves the most, 1, and the top edge (z = 1.05 m) towards +y by 1.05 / hypot(0.05,
    # 0.9625); the base not at all
    assert np.linalg.norm(blocks.cell_data["mechanism"][0], axis=1).max() == pytest.approx(1.0, rel=1e-6)
    assert blocks.point_data["mechanism"][:, 1].max() == pytest.approx(1.05 / np.hypot(0.05, 0.9625), rel=1e-6)
    assert np.allclose(blocks.cell_data["mechanism"][0][33], 0.0)
    faces = meshio.read(out / "leaf-interfaces.vtu")
    assert len(faces.cells_dict["quad"]) == 83 and "normal_force" in faces.cell_data


def test_run_a_3d_case_with_the_explicit_solver(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    """`masonry-dem run` of a 3D case with method = "dynamic" (two boxes stacked, pushed out of plane): the multiplier
    of the stack overturning whole, b / h = 0.2 / 0.9, the result file (dimension 3, method "dynamic", the curve),
    the CSV of the curve, the plot and the VTK files."""
    path = tmp_path / "stack.toml"
    path.write_text('format = 1\ntitle = "stack"\n[geometry]\nboxes = [[0, 0, 0, 0.3, 0.2, 0.45], [0, 0, 0.45, 0.3, 0.2, 0.9]]\n'
                    "[joints]\nfriction = 0.7\ndilatancy = 0.7\nnormal_stiffness = 1e8\nshear_stiffness = 1e8\n"
                    '[loads]\ndirection = 90\n[analysis]\nmethod = "dynamic"\nsteps = 50\n')
    c = md.load_case(path)
    assert (c.dimension, c.method, c.analysis_kwargs["steps"]) == (3, "dynamic", 50)
    out = tmp_path / "out"
    args = ["run", str(path), "--json", str(out / "s.json"), "--csv", str(out / "s.csv"), "--plot", str(out / "s.png"),
            "--vtk", str(out / "s")]
    assert cli.main(args) == 0
    text = capsys.readouterr().out
    assert "method:              dynamic" in text and "status:              collapse" in text and "bracket:" in text
    assert "checked against:     limit analysis, 0.2222 (exact for these associative dry joints" in text
    data = json.loads((out / "s.json").read_text())
    assert (data["dimension"], data["method"], data["status"], data["blocks"]) == (3, "dynamic", "collapse", 2)
    assert data["collapse_multiplier"] == pytest.approx(0.2 / 0.9, rel=3e-3)
    assert len(data["curve"]["multiplier"]) > 5 and data["curve"]["displacement"][-1] > 0  # along +y
    rows = (out / "s.csv").read_text().splitlines()
    assert rows[0] == "multiplier,displacement_m" and len(rows) == len(data["curve"]["multiplier"]) + 1
    assert (out / "s.png").read_bytes()[:8] == PNG
    meshio = pytest.importorskip("meshio")
    blocks = meshio.read(out / "s-blocks.vtu")
    assert len(blocks.cells_dict["hexahedron"]) == 3 and blocks.point_data["displacement"][:, 1].max() > 0


def test_refusals_on_the_command_line(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    static = tmp_path / "static.toml"
    static.write_text(LEAF.read_text().replace('method = "limit"', 'method = "static"'))
    plane = tmp_path / "plane.toml"
    plane.write_text('format = 1\n[geometry]\nblocks = [[0, 0, 1, 1]]\n[loads]\ndirection = 45\n')
    # a limit analysis's case keeps its load-path keys (checked, then ignored): the explicit solver refuses this one
    displacement = tmp_path / "displacement.toml"
    displacement.write_text(LEAF.read_text().replace('method = "limit"', 'method = "limit"\ncontrol = "displacement"'))
    for args, words in [
        (["run", str(LEAF), "--method", "static"], "the 3D model takes limit analysis and the explicit solver"),
        (["run", str(displacement), "--method", "dynamic"], 'analysis.control = "displacement": the explicit solver in 3D'),
        (["run", str(static)], 'analysis.method = "static": the 3D model takes limit analysis'),
        (["simulate", str(LEAF)], "no [ground_motion] table"),
        (["run", str(plane)], "loads.direction: got 45"),
    ]:
        assert cli.main(args) == 2
        captured = capsys.readouterr()
        lines = captured.err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("masonry-dem: error: ") and words in lines[0], captured.err
        assert "Traceback" not in captured.err


def test_compare_a_3d_case(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    assert cli.main(["compare", str(LEAF), "--json", str(tmp_path / "c.json")]) == 0
    text = capsys.readouterr().out
    assert "collapse multiplier: 0.0952" in text and "static, dynamic:     not run" in text
    data = json.loads((tmp_path / "c.json").read_text())
    assert data["dimension"] == 3 and set(data) == {"format", "title", "dimension", "limit", "note"}


def test_the_plot_of_a_mechanism(tmp_path: Path) -> None:
    from masonry_dem.space.plot import mechanism_figure

    model, r = limit(md.corner_wall(1.5, 1.0, 1.0, 0.25, 0.5, 0.25), direction=270)
    fig = mechanism_figure(model, r, title="L", path=tmp_path / "corner")
    assert (tmp_path / "corner.png").read_bytes()[:8] == PNG
    heading = fig._suptitle.get_text()
    assert heading.startswith("L — limit, collapse, λu = ") and heading.endswith("towards -y (270°)")
    assert f"λu = {r.collapse_multiplier:.4f}" in heading
    assert len([ax for ax in fig.axes if ax.name == "3d"]) == 2
    # no collapse (a box overhanging the one under it by more than half its length: the dead loads alone
    # find no equilibrium): the wall drawn at rest, said in the title
    held = md.Model3D([[0.0, 0.0, 0.0, 1.0, 1.0, 0.2], [0.6, 0.0, 0.2, 1.6, 1.0, 0.4]])
    r = held.solve_limit()
    assert r.status == "no_equilibrium"
    fig = md.plot.report_figure(held, r, title="held", path=tmp_path / "held.png")
    assert "no mechanism drawn" in fig._suptitle.get_text()


def test_the_report_page_of_a_3d_case(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    # run --plot of a 3D case: the mechanism's two views, the contacts by state and the load curve
    out = tmp_path / "leaf.png"
    assert cli.main(["run", str(LEAF), "--plot", str(out), "--quiet"]) == 0
    assert out.read_bytes()[:8] == PNG
    model, r = limit(md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), direction=90)
    fig = md.plot.report_figure(model, r, title="leaf", path=tmp_path / "limit.png")
    assert len([ax for ax in fig.axes if ax.name == "3d"]) == 3
    curve = [ax for ax in fig.axes if ax.name != "3d" and ax.get_ylabel().startswith("load multiplier")]
    assert len(curve) == 1 and "along y" in curve[0].get_xlabel()
    assert fig._suptitle.get_text().startswith("leaf — limit, collapse")
    # the explicit pushover's curve: its points drawn (a box tipping about its long edge at b / h)
    box = md.Model3D([[0.0, 0.0, 0.0, 0.4, 0.6, 1.0]], joints=DRY, direction=90.0)
    res = box.solve_dynamic()
    fig = md.plot.report_figure(box, res, title="box", path=tmp_path / "dynamic.png")
    curve = [ax for ax in fig.axes if ax.name != "3d" and ax.get_ylabel().startswith("load multiplier")][0]
    drawn = [line for line in curve.get_lines() if len(line.get_xdata()) == len(res.curve_multiplier) > 1]
    assert drawn and np.allclose(drawn[0].get_ydata(), res.curve_multiplier)
    legend = [ax for ax in fig.axes if ax.name == "3d" and ax.get_legend() is not None][0].get_legend()
    assert any(t.get_text().startswith("rocking (") for t in legend.get_texts())


def test_import_stays_light() -> None:
    code = ("import sys, masonry_dem as md; md.Model3D; md.running_bond_3d; "
            "print(sorted(m for m in ('matplotlib', 'meshio', 'mpl_toolkits') if m in sys.modules))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0 and proc.stdout.strip() == "[]", proc.stderr


def test_a_study_of_a_3d_case_is_refused(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    pytest.importorskip("dask")
    study = tmp_path / "study.toml"
    study.write_text(f"format = 1\ncase = {json.dumps(str(LEAF))}\n")
    assert cli.main(["study", str(study), "--out", str(tmp_path / "rows.parquet")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("masonry-dem: error: ") and "case: is a 3D wall: a study runs walls in the plane" in err


def test_the_script_example_in_3d(tmp_path: Path) -> None:
    # examples/u_wall_3d.py: four directions in plan, the free leaf against t / H, the figure and the VTK files
    png = tmp_path / "u.png"
    proc = subprocess.run([sys.executable, str(EXAMPLES / "u_wall_3d.py"), str(png)], cwd=tmp_path,
                          capture_output=True, text=True, timeout=120, env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, (proc.stdout, proc.stderr)
    lam = {float(d): float(v) for d, v in re.findall(r"direction\s+([0-9.]+) deg: collapse, lambda = ([0-9.]+)", proc.stdout)}
    assert sorted(lam) == [0.0, 90.0, 180.0, 270.0]
    # the whole U sliding on its base (associative, friction 0.7) bounds every direction's multiplier
    assert all(0.0 < v <= 0.7 for v in lam.values()), lam
    # pushed away from its returns the facade has the least help: the weakest direction
    assert min(lam, key=lam.get) == 270.0
    leaf = re.search(r"free leaf: lambda = ([0-9.]+), t / H = ([0-9.]+)", proc.stdout)
    assert leaf and abs(float(leaf.group(1)) - 0.1) <= 1e-6
    assert png.stat().st_size > 0 and (tmp_path / "u-blocks.vtu").exists()


def test_a_3d_case_with_mortar_joints_reaches_the_core(tmp_path: Path) -> None:
    """Cohesion and tensile strength in a 3D case file are the Model3D's joints: the same multiplier as the model built
    from Python with those joints, to 1e-12 (the physics: tests/space_mortar.rs)."""
    text = 'format = 1\ntitle = "mortar leaf"\n' + LEAF_TABLE + "[joints]\nfriction = 0.6\ndilatancy = 0.6\ncohesion = 500\ntensile_strength = 200\n"
    path = tmp_path / "mortar.toml"
    path.write_text(text)
    case = md.load_case(path)
    res = case.run()
    law = {"default": {"friction": 0.6, "dilatancy": 0.6, "cohesion": 500.0, "tensile_strength": 200.0}}
    direct = md.Model3D(md.running_bond_3d(2.0, 1.05, 0.1, 0.4, 0.175), joints=law).solve_limit()
    assert res.status == "collapse" and direct.status == "collapse"
    assert abs(res.collapse_multiplier - direct.collapse_multiplier) <= 1e-12 * direct.collapse_multiplier
