"""Studies (masonry_dem.study): the study file's checks, the rows against serial runs and exact values, the
mirrored wall of the -x direction, random values and textures, and the study machinery on Dask: resume,
a worker killed, a bad sample, Ctrl-C, the command line, and a scheduler with two workers started as
processes of their own.

The Dask tests share one LocalCluster of two worker processes (a module fixture). No timing is asserted.
"""

from __future__ import annotations

import math
import os
import signal
import socket
import subprocess
import sys
import time
from statistics import NormalDist
from pathlib import Path
from typing import Any, Dict, Iterator, List, Optional

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python < 3.11 only
    import tomli as tomllib

import numpy as np
import pandas as pd
import pytest

import masonry_dem as md
from masonry_dem import cli
from masonry_dem.case import case_from_dict
from masonry_dem.study import load_study, parse_study, read_results, run_study, study_from_dict
from masonry_dem.study.model import Texture, Variation, mirrored, texture_blocks

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
WALL1 = EXAMPLES / "ferris-tinloi-wall1.toml"
BLOCK = EXAMPLES / "single-block-sliding.toml"


def table(path: Path) -> Dict[str, Any]:
    return tomllib.loads(path.read_text(encoding="utf-8"))


def make(case: Any, vary: Optional[Dict[str, Any]] = None, **options: Any) -> Any:
    """A study of ``case`` (a path, a case table or a builder), its [vary] tables and its [study] keys."""
    return study_from_dict({"format": 1, "case": case, "study": options, "vary": vary or {}})


def same(a: float, b: float) -> bool:
    """Equal to the last bit, NaN equal to NaN."""
    return (math.isnan(a) and math.isnan(b)) or a == b


@pytest.fixture(scope="module")
def client() -> Iterator[Any]:
    from distributed import Client

    from masonry_dem.study.runner import local_cluster

    cluster = local_cluster(2)
    with Client(cluster) as c:
        yield c
    cluster.close()


# --------------------------------------------------------------------------------------------------
# The study file
# --------------------------------------------------------------------------------------------------

BAD_STUDIES = [
    ('[vary.friction]\ndistribution = "gauss"\nmean = 0.6\nstd = 0.1', "vary.friction.distribution", 'of "uniform"'),
    ("[vary.frcition]\nvalues = [0.5]", "vary.frcition", "did you mean 'friction'"),
    ("[vary.friction]\nvalues = [0.5, -1.0]", "vary.friction.values", "vary.friction.values[1] = -1.0"),
    ('[vary.friction]\ndistribution = "normal"\nmean = 0.6', "vary.friction.std", "missing key 'std'"),
    ('[vary.friction]\ndistribution = "uniform"\nmin = 0.7\nmax = 0.5', "vary.friction.max", "must be > min"),
    ('[vary.friction]\ndistribution = "normal"\nmean = 0.6\nstd = 0.01\nmin = 5.0', "vary.friction.min", "no probab"),
    ("[vary.friction]\nvalues = [0.5]\nstart = 0.1", "vary.friction", "exactly one of"),
    ("[vary.cohesion]\nvalues = [0.5]\nassociative = true", "vary.cohesion.associative", "only a friction"),
    ("[vary.opening_x]\nvalues = [0.5]", "vary.opening_x.opening", "no opening 0"),
    ('[vary.courses]\ndistribution = "uniform"\nmin = 1\nmax = 3', "vary.courses.distribution", "integer"),
    ('[vary.direction]\nvalues = ["+y"]', "vary.direction.values", '"+x" and "-x"'),
    ("[vary.precompression]\nvalues = [1e3]", "vary.precompression", "[top] table"),
    ('[study]\nmethods = ["static", "explicit"]', "study.methods", 'entry 1: expected one of "static"'),
    ("[study]\nsamples = 0", "study.samples", "must be >= 1"),
]


@pytest.mark.parametrize("text,key,words", BAD_STUDIES)
def test_bad_study_names_the_key(text: str, key: str, words: str) -> None:
    study = f'format = 1\ncase = "{WALL1}"\n{text}\n'
    with pytest.raises(md.InputError) as caught:
        parse_study(study, source="s.toml")
    message = str(caught.value)
    assert message.startswith("s.toml: ") and words in message, message
    assert caught.value.key == key, (caught.value.key, message)


def test_bad_base_case_and_texture() -> None:
    with pytest.raises(md.InputError, match="s.toml: case: cannot read"):
        parse_study('format = 1\ncase = "no-such-case.toml"\n', source="s.toml")
    with pytest.raises(md.InputError, match="joints.friction"):
        make({"geometry": {"blocks": [[0, 0, 1, 1]]}, "joints": {"friction": -1}})
    with pytest.raises(md.InputError, match="running_bond"):
        make(str(BLOCK), {"texture": {"length_std": 0.1}})


def test_size_and_row_order() -> None:
    study = make(
        str(BLOCK),
        {
            "friction": {"start": 0.2, "stop": 0.6, "count": 5},
            "cohesion": {"distribution": "uniform", "min": 0.0, "max": 1.0},
        },
        methods=["limit", "static"],
        samples=3,
        seed=5,
    )
    items = list(study.items())
    assert study.size == len(items) == 2 * 5 * 3
    assert [i.row for i in items] == list(range(30))
    assert [i.values["friction"] for i in items[:10:2]] == pytest.approx([0.2, 0.3, 0.4, 0.5, 0.6])
    assert study.item(17) == items[17]
    # a sample's random value is the same at every grid point and for every method
    assert len({i.values["cohesion"] for i in items if i.sample == 1}) == 1


# --------------------------------------------------------------------------------------------------
# Random values and textures (no analysis)
# --------------------------------------------------------------------------------------------------


def test_random_values_depend_on_seed_sample_and_name_only() -> None:
    friction = {"distribution": "normal", "mean": 0.6, "std": 0.05}
    cohesion = {"distribution": "uniform", "min": 0.0, "max": 1.0}
    one = make(str(BLOCK), {"friction": friction}, samples=50, seed=7)
    two = make(str(BLOCK), {"cohesion": cohesion, "friction": friction}, samples=50, seed=7)
    other = make(str(BLOCK), {"friction": friction}, samples=50, seed=8)

    def drawn(study: Any) -> List[float]:
        return [item.values["friction"] for item in study.items()]

    assert drawn(one) == drawn(two)  # another variation changes nothing
    assert drawn(one) != drawn(other)
    assert len(set(drawn(one))) == 50


@pytest.mark.parametrize(
    "variation,mean,std",
    [
        (Variation("x", distribution="uniform", low=2.0, high=4.0), 3.0, 2.0 / math.sqrt(12)),
        (Variation("x", distribution="normal", mean=0.65, std=0.05), 0.65, 0.05),
        (Variation("x", distribution="lognormal", mean=2.0, std=0.5), 2.0, 0.5),
    ],
)
def test_distributions_have_their_moments(variation: Variation, mean: float, std: float) -> None:
    rng = np.random.default_rng(3)
    x = np.array([variation.draw(rng) for _ in range(20000)])
    assert abs(x.mean() - mean) < 4 * std / math.sqrt(len(x))
    assert x.std() == pytest.approx(std, rel=0.03)


def test_truncated_draws_stay_in_their_window() -> None:
    rng = np.random.default_rng(4)
    v = Variation("x", distribution="normal", mean=0.65, std=0.05, low=0.6, high=0.62)
    x = np.array([v.draw(rng) for _ in range(2000)])
    assert x.min() >= 0.6 and x.max() <= 0.62
    # the mean of a truncated normal: mu + sigma (phi(a) - phi(b)) / (Phi(b) - Phi(a)), a = -1, b = -0.6
    n = NormalDist()
    exact = 0.65 + 0.05 * (n.pdf(-1.0) - n.pdf(-0.6)) / (n.cdf(-0.6) - n.cdf(-1.0))
    assert abs(x.mean() - exact) < 4 * x.std() / math.sqrt(len(x))
    w = Variation("x", distribution="lognormal", mean=1.0, std=0.3, high=0.9)
    assert max(w.draw(rng) for _ in range(500)) <= 0.9


def test_texture_tiles_the_wall() -> None:
    rb = dict(block_length=0.4, block_height=0.175, courses=6, length=2.0, first_course="half")
    texture = Texture(length_std=0.15, height_std=0.1, bond="random", min_fraction=0.25)
    blocks = np.array(texture_blocks(rb, texture, np.random.default_rng(11)))
    again = np.array(texture_blocks(rb, texture, np.random.default_rng(11)))
    assert np.array_equal(blocks, again)
    widths, heights = blocks[:, 2] - blocks[:, 0], blocks[:, 3] - blocks[:, 1]
    assert widths.min() >= 0.25 * 0.4 - 1e-12 and heights.min() > 0
    top = blocks[:, 3].max()
    assert np.sum(widths * heights) == pytest.approx(2.0 * top, rel=1e-12)  # no gap, no overlap
    assert blocks[:, 0].min() == 0.0 and blocks[:, 2].max() == 2.0
    plain = texture_blocks(rb, Texture(), np.random.default_rng(0))
    assert np.allclose(np.array(plain), md.running_bond(**rb))  # no perturbation: the case's own wall


def test_precompression_raises_sliding_by_its_share_of_the_weight() -> None:
    """A block under a top beam slides with it on the base: lambda W = mu (W + P), lambda = mu (1 + P / W)."""
    data = table(BLOCK)
    data["top"] = {"rotation": "fixed", "force": [0.0, 0.0]}
    study = make(data, {"precompression": {"values": [0.0, 500.0, 2000.0]}}, methods=["limit", "static"])
    weight = 1000.0 * 9.81 * 0.4 * 0.175  # [N]
    for item in study.items():
        case = study.case(item)
        assert case.model.top_force == [0.0, -item.values["precompression"]]
        expected = 0.65 * (1.0 + item.values["precompression"] / weight)
        res = case.run(item.method)
        # dilatancy 0: limit analysis gives an estimate (its value in last_equilibrium), the static solver a collapse
        assert res.status == ("estimate" if item.method == "limit" else "collapse"), res.error
        assert res.last_equilibrium == pytest.approx(expected, rel=1e-7)


def test_openings_move_and_resize_about_their_centre() -> None:
    data = table(WALL1)
    data["geometry"]["running_bond"]["openings"] = [[0.3, 0.3, 0.75, 0.75]]
    study = make(data, {"opening_x": {"values": [1.2]}, "opening_height": {"values": [0.2]}})
    case = study.case(study.item(0))
    moved = [0.975, 0.425, 1.425, 0.625]  # centre x 1.2, width 0.45 kept; centre y 0.525 kept, height 0.2
    rb = dict(data["geometry"]["running_bond"], openings=[moved])
    assert np.allclose(case.model.blocks, md.running_bond(**rb))


# --------------------------------------------------------------------------------------------------
# The -x direction: the wall mirrored
# --------------------------------------------------------------------------------------------------


def limit_of(study: Any, direction: str) -> float:
    item = next(i for i in study.items() if i.values.get("direction") == direction)
    return float(study.case(item).run("limit").collapse_multiplier)


def test_minus_x_of_a_symmetric_wall_is_its_plus_x() -> None:
    """Wall 1 is its own mirror image (courses H F F F F H and F F F F F): the same collapse both ways."""
    study = make(str(WALL1), {"direction": {"values": ["+x", "-x"]}})
    plus, minus = limit_of(study, "+x"), limit_of(study, "-x")
    assert plus == pytest.approx(0.6429, abs=1e-4)
    assert minus == pytest.approx(plus, rel=1e-9)


def test_minus_x_is_the_push_towards_minus_x() -> None:
    """An opening off the centre breaks the symmetry: the mirrored wall's limit analysis is the collapse
    of the wall itself pushed towards -x, found by driving its control point to -10 mm."""
    data = table(WALL1)
    data["geometry"]["running_bond"]["openings"] = [[0.3, 0.3, 0.75, 0.75]]
    study = make(data, {"direction": {"values": ["+x", "-x"]}})
    plus, minus = limit_of(study, "+x"), limit_of(study, "-x")
    assert abs(plus - minus) > 0.05  # not symmetric
    model = case_from_dict(data).build_model()
    pushed = model.solve_static(control="displacement", max_displacement=-0.01)
    assert -pushed.last_equilibrium == pytest.approx(minus, rel=0.01)
    parameters = case_from_dict(data).model
    assert np.allclose(mirrored(mirrored(parameters)).blocks, parameters.blocks, rtol=0, atol=1e-15)


# --------------------------------------------------------------------------------------------------
# On Dask
# --------------------------------------------------------------------------------------------------


def serial_row(method: str, friction: float, direction: str) -> Any:
    """The analysis of a wall-1 row, built here from the case file alone."""
    data = table(WALL1)
    data["joints"].update(friction=friction, dilatancy=friction)
    case = case_from_dict(data)
    if direction == "-x":
        b = np.asarray(case.model.blocks)
        flipped = np.column_stack([2.0 - b[:, 2], b[:, 1], 2.0 - b[:, 0], b[:, 3]])
        case.model = type(case.model)(**{**case.model.arguments(), "blocks": flipped})
    return case.run(method)


def test_grid_gives_the_serial_results(client: Any) -> None:
    frictions = [0.45, 0.55, 0.6, 0.65, 0.7]
    study = make(
        str(WALL1),
        {"friction": {"values": frictions, "associative": True}, "direction": {"values": ["+x", "-x"]}},
        methods=["static", "limit"],
    )
    frame = run_study(study, scheduler=client, chunk=3)
    assert len(frame) == 20 and list(frame["row"]) == list(range(20))
    for _, row in frame.iterrows():
        results = serial_row(row["method"], row["friction"], row["direction"])
        assert row["status"] == results.status
        assert same(row["collapse_multiplier"], results.collapse_multiplier), row["row"]
        assert same(row["last_equilibrium"], results.last_equilibrium)
        assert (row["iterations"], row["steps"], row["blocks"]) == (results.iterations, results.steps, 33)


def test_friction_grid_of_a_sliding_block_is_exact(client: Any) -> None:
    """A block on its base slides at lambda = friction (examples/single-block-sliding.toml, made associative:
    limit analysis of dilatancy 0 gives an estimate, not a collapse)."""
    frictions = [0.2, 0.35, 0.5, 0.65, 0.8]
    study = make(str(BLOCK), {"friction": {"values": frictions, "associative": True}}, methods=["limit", "static"])
    frame = run_study(study, scheduler=client)
    assert (frame["status"] == "collapse").all()
    for method, rel in (("limit", 1e-6), ("static", 1e-4)):
        got = frame[frame["method"] == method]["collapse_multiplier"].to_numpy()
        assert got == pytest.approx(frictions, rel=rel)


def test_a_bad_sample_gives_a_row_with_its_error(client: Any) -> None:
    study = make(
        str(BLOCK),
        {"friction": {"distribution": "uniform", "min": -0.4, "max": 0.6, "associative": True}},
        methods=["limit"],
        samples=12,
        seed=2,
    )
    frame = run_study(study, scheduler=client)
    assert list(frame["row"]) == list(range(12))
    bad = frame[frame["friction"] < 0]
    good = frame[frame["friction"] >= 0]
    assert len(bad) and len(good)
    assert (bad["status"] == "error").all() and bad["collapse_multiplier"].isna().all()
    assert bad["error"].str.contains("joints.friction: must be >= 0").all()
    assert (good["status"] == "collapse").all()
    assert good["collapse_multiplier"].to_numpy() == pytest.approx(good["friction"].to_numpy(), rel=1e-6)


def limit_study(n: int = 24) -> Any:
    return make(
        str(WALL1),
        {
            "friction": {"distribution": "normal", "mean": 0.65, "std": 0.05, "associative": True},
            "direction": {"values": ["+x", "-x"]},
        },
        methods=["limit"],
        samples=n // 2,
        seed=9,
        chunk=2,
    )


def test_a_study_of_the_spectrum_ag(client: Any) -> None:
    """[vary.ag] varies the a_g of the base case's [assessment]: each row holds the linear check's verdict and
    ratio at that a_g, the same as the check made directly (a block 0.2 x 0.6 m rocking: alpha0 = 1/3, e* = 1)."""
    case = table(EXAMPLES / "single-block-rocking.toml")
    case["joints"]["dilatancy"] = case["joints"]["friction"]  # associative: limit analysis is exact
    case["assessment"] = {"spectrum": "ec8", "ag": 1.0, "ground_type": "B"}
    ags = ["0.1 g", "0.3 g", "0.5 g"]
    frame = run_study(make(case, {"ag": {"values": ags}}, methods=["limit"]), scheduler=client)
    assert list(frame["ag"]) == pytest.approx([0.1 * 9.80665, 0.3 * 9.80665, 0.5 * 9.80665], rel=1e-15)
    for _, row in frame.iterrows():
        model = case_from_dict({**case, "assessment": {**case["assessment"], "ag": row["ag"]}}).build_model()
        parameters = md.assessment.AssessmentParameters(spectrum=md.assessment.ec8_spectrum(row["ag"], "B"))
        checked = md.assessment.assess(model, model.solve_limit(), parameters, gravity=9.81)
        check = checked.linear
        assert row["ratio"] == pytest.approx(check.ratio, rel=1e-9) and row["verdict"] == checked.verdict
        assert row["a0_star"] == pytest.approx((1 / 3) * 9.81 / 1.35, rel=1e-6)
        assert row["demand"] == pytest.approx(row["ag"] * 1.2 / 2.0, rel=1e-12)
        assert row["pga"] == pytest.approx(row["ag"] * 1.2, rel=1e-12)
    assert list(frame["ratio"] >= 1) == [True, True, False]  # a0* = 2.42 m/s2 against 0.59, 1.77, 2.94
    # the base case needs an [assessment] table
    with pytest.raises(md.InputError, match=r"vary\.ag: ag is the \[assessment\] spectrum's a_g"):
        make(str(BLOCK), {"ag": {"values": [2.0]}})


def test_dynamic_method_in_workers(client: Any) -> None:
    """The explicit solver, one thread in each worker, on the sliding block: lambda = friction to its tolerance."""
    frame = run_study(make(str(BLOCK), {"friction": {"values": [0.4, 0.6]}}, methods=["dynamic"]), scheduler=client)
    assert (frame["status"] == "collapse").all()
    assert frame["collapse_multiplier"].to_numpy() == pytest.approx([0.4, 0.6], rel=2e-3)


def test_textures_are_the_same_for_every_method_of_a_sample() -> None:
    texture = {"length_std": 0.2, "height_std": 0.1, "bond": "random"}
    study = make(str(WALL1), {"texture": texture}, samples=2, methods=["static", "limit"])
    blocks = [np.asarray(study.case(item).model.blocks) for item in study.items()]
    assert np.array_equal(blocks[0], blocks[1]) and np.array_equal(blocks[2], blocks[3])
    assert blocks[0].shape != blocks[2].shape or not np.array_equal(blocks[0], blocks[2])


def test_resumed_study_recomputes_nothing(client: Any, tmp_path: Path) -> None:
    study, out = limit_study(), tmp_path / "r.parquet"
    whole = run_study(study, scheduler=client)

    def stop_halfway(done: int, failed: int, total: int) -> None:
        if done >= total // 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt) as stopped:
        run_study(study, out, scheduler=client, progress=stop_halfway)
    first = stopped.value.results  # type: ignore[attr-defined]
    assert 12 <= len(first) < 24
    assert len(read_results(out)) == len(first)
    with pytest.raises(md.InputError, match="resume"):
        run_study(study, out, scheduler=client)
    calls: List[int] = []
    resumed = run_study(study, out, scheduler=client, resume=True, progress=lambda d, f, t: calls.append(d))
    assert calls[0] == len(first) and calls[-1] == 24  # started from the rows written
    kept = resumed.set_index("row").loc[first["row"]]
    pd.testing.assert_frame_equal(kept.reset_index(), first)  # the same rows, timings included: not run again
    timing = ["elapsed_s", "task_s"]
    pd.testing.assert_frame_equal(resumed.drop(columns=timing), whole.drop(columns=timing))
    assert not (tmp_path / "r.parquet.parts").exists()


def test_resume_refuses_another_study(client: Any, tmp_path: Path) -> None:
    out = tmp_path / "r.parquet"
    run_study(limit_study(4), out, scheduler=client)
    with pytest.raises(md.InputError, match="another study"):
        run_study(limit_study(6), out, scheduler=client, resume=True)


def test_builder_as_the_base(client: Any) -> None:
    study = make(sliding_block, {"mu": {"values": [0.3, 0.4]}}, methods=["limit"])
    frame = run_study(study, scheduler=client)
    assert frame["collapse_multiplier"].to_numpy() == pytest.approx([0.3, 0.4], rel=1e-6)


def sliding_block(mu: float) -> Any:
    return md.Model([[0.0, 0.0, 0.4, 0.175]], gravity=9.81, joints={"default": {"friction": mu, "dilatancy": mu}})


def test_command_line(client: Any, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    study_file = tmp_path / "s.toml"
    study_file.write_text(
        f'format = 1\ncase = "{BLOCK}"\n[study]\nmethods = ["limit"]\n[vary.friction]\nvalues = [0.3, 0.5]\nassociative = true\n'
        '[vary.direction]\nvalues = ["+x", "-x"]\n'
    )
    out, csv, plot = tmp_path / "s.parquet", tmp_path / "s.csv", tmp_path / "s.png"
    outputs = ["--out", str(out), "--csv", str(csv), "--plot", str(plot)]
    args = ["study", str(study_file), "--scheduler", client.scheduler.address, *outputs, "-q"]
    assert cli.main(args) == 0
    printed = capsys.readouterr().out
    assert "4 collapse" in printed and f"wrote {plot}" in printed
    assert list(pd.read_csv(csv)["collapse_multiplier"]) == pytest.approx([0.3, 0.3, 0.5, 0.5])
    assert plot.stat().st_size > 10_000
    assert cli.main(args) == 2  # the results exist: --resume, or remove them
    assert "--resume" in capsys.readouterr().err
    assert cli.main(args + ["--resume"]) == 0
    assert cli.main(["study", str(study_file), "--workers", "0"]) == 2


def test_a_killed_worker_loses_no_row(client: Any) -> None:
    """One worker is killed (SIGKILL) in the middle of the study: its tasks run again elsewhere."""
    study = make(
        str(WALL1),
        {"friction": {"distribution": "uniform", "min": 0.55, "max": 0.75, "associative": True}},
        methods=["static"],
        samples=30,
        chunk=3,
    )
    killed: List[int] = []

    def kill_one(done: int, failed: int, total: int) -> None:
        if done >= 6 and not killed:
            pid = next(iter(client.run(os.getpid).values()))
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    frame = run_study(study, scheduler=client, progress=kill_one)
    assert killed
    assert sorted(frame["row"]) == list(range(30)) and frame["row"].is_unique
    assert set(frame["status"]) <= {"collapse", "stalled"}
    client.wait_for_workers(2, timeout=60)


def crashing_block(mu: float) -> Any:
    """A builder whose worker process dies (as on a segmentation fault) for mu > 0.5."""
    if mu > 0.5:
        os._exit(1)
    return sliding_block(mu)


def test_an_analysis_that_kills_its_worker_is_lost_alone() -> None:
    """Dask gives up on a task whose worker died (here at once: allowed-failures 0); the chunk is split, the
    other analysis runs again alone, and the culprit gets its row, status "lost"."""
    import dask
    from distributed import Client

    from masonry_dem.study.runner import local_cluster

    study = make(crashing_block, {"mu": {"values": [0.3, 0.9]}}, methods=["limit"], chunk=2)
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
        cluster = local_cluster(1)
    with cluster, Client(cluster) as c:
        frame = run_study(study, scheduler=c)
    assert list(frame["status"]) == ["collapse", "lost"]
    assert frame["collapse_multiplier"][0] == pytest.approx(0.3, rel=1e-6)
    assert "worker died" in frame["error"][1]


# --------------------------------------------------------------------------------------------------
# Processes of their own: Ctrl-C, and a scheduler with two workers
# --------------------------------------------------------------------------------------------------


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def test_ctrl_c_keeps_what_is_written(tmp_path: Path) -> None:
    study_file = tmp_path / "s.toml"
    study_file.write_text(
        f'format = 1\ncase = "{WALL1}"\n[study]\nmethods = ["static"]\nsamples = 400\nchunk = 2\n'
        '[vary.friction]\ndistribution = "normal"\nmean = 0.65\nstd = 0.05\nassociative = true\n'
    )
    out = tmp_path / "s.parquet"
    command = [sys.executable, "-m", "masonry_dem", "study", str(study_file), "--out", str(out), "--workers", "1", "-q"]
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 60
    while not (tmp_path / "s.parquet.parts").is_dir() and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.1)
    os.killpg(proc.pid, signal.SIGINT)  # as a terminal does: the whole process group
    stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 130, stderr
    assert "--resume" in stderr
    written = read_results(out)
    assert 0 < len(written) < 400 and written["row"].is_unique


def test_scheduler_and_workers_of_their_own(tmp_path: Path) -> None:
    """`dask scheduler` and two `dask worker` processes, as on a cluster; the study given their address."""
    dask = str(Path(sys.executable).parent / "dask")
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    flags = dict(stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=tmp_path)
    processes = [
        subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"], **flags)
    ]
    try:
        processes += [
            subprocess.Popen([dask, "worker", address, "--nthreads", "1", "--no-dashboard", "--nworkers", "1"], **flags)
            for _ in range(2)
        ]
        from distributed import Client

        with Client(address, timeout=60) as c:
            c.wait_for_workers(2, timeout=60)
            study = make(str(BLOCK), {"friction": {"values": [0.3, 0.4, 0.5, 0.6], "associative": True}},
                         methods=["limit"])
            frame = run_study(study, scheduler=address)
            assert len(c.scheduler_info()["workers"]) == 2
        assert frame["collapse_multiplier"].to_numpy() == pytest.approx([0.3, 0.4, 0.5, 0.6], rel=1e-6)
    finally:
        for p in processes:  # the workers' nannies and the scheduler, started here
            p.kill()
            p.wait(timeout=20)


def test_inline_case() -> None:
    """The base case as a [case] table (its format left out): a block of 0.4 x 0.175 m slides at mu."""
    text = """format = 1
[case.geometry]
blocks = [[0.0, 0.0, 0.4, 0.175]]
[case.joints]
friction = 0.65
[vary.friction]
values = [0.4]
associative = true
"""
    study = parse_study(text, source="s.toml")
    assert study.case(study.item(0)).run("limit").collapse_multiplier == pytest.approx(0.4, rel=1e-6)
    with pytest.raises(md.InputError, match=r"s.toml: \[case\]: .*joints.friction"):
        parse_study(text.replace("friction = 0.65", "friction = -1.0"), source="s.toml")


def test_example_study_reads() -> None:
    study = load_study(EXAMPLES / "studies" / "wall1-fragility.toml")
    assert study.size == 1000 and study.parameters == ("friction",) and study.texture is not None
