"""Coverage-guided fuzzing (atheris) of the case-file reader and of model building.

Each input is either read as the text of a case file (raw mode: the fuzzer mutates bytes, starting from
the examples) or, when its first byte is 0, turned into a structured case (every key of docs/case-format.md, each given a value drawn
from a list of troublemakers: NaN, infinities, zero, negative and huge numbers, 400-digit integers,
strings, booleans, arrays, tables). The case is loaded with :func:`masonry_dem.parse_case`; if it loads,
its model is built and, for a wall of at most MAX_SOLVE_BLOCKS blocks, a one-step static analysis is run (a 3D
wall of boxes: its limit analysis).

The only acceptable outcomes are success and a :class:`masonry_dem.MasonryError` (InputError and the
solvers' errors) whose message is one non-empty line starting with the case's name. Anything else is a
finding: another exception, a Rust panic (the bindings turn it into "internal error (please report
it)"), a crash, a time-out or running out of memory (libFuzzer's -timeout and -rss_limit_mb).

    python tests/fuzz/fuzz_case.py CORPUS_DIR [SEED_DIR ...] -max_total_time=600

writes new inputs into CORPUS_DIR and any finding as crash-*/timeout-*/oom-* in the current folder; `make
fuzz` runs it for 10 minutes, `make fuzz-short` (part of `make test`) for 20 seconds.
"""

from __future__ import annotations

import math
import sys
from typing import Any, Dict, List

import atheris

with atheris.instrument_imports():
    import tomllib

    import masonry_dem
    from masonry_dem import case as case_module

SOURCE = "fuzz.toml"
#: An input starting with this byte is a structured case; any other is the text of a case file.
STRUCTURED = b"\x00"
#: Walls with more blocks are built but not solved (building is linear in the blocks; solving is not).
MAX_SOLVE_BLOCKS = 40
#: Walls with a block more slender than this are built but not solved (see ordinary_blocks).
MAX_ASPECT = 1e3
#: Geometries that would generate more blocks than this are not fuzzed (the size limit of the core, 20
#: million blocks, is tested in tests/python/test_bad_inputs.py; building such walls takes seconds).
MAX_BUILD_BLOCKS = 20_000

FLOATS = [0.0, -0.0, 1.0, -1.0, 0.5, 0.65, 0.175, 0.4, 2.0, 9.81, 1e10, 1e-12, 1e-170, 1e-310, 1e300, 1e308,
          -1e308, math.inf, -math.inf, math.nan, 29700.0, 1000.0]
STRINGS = ["", "half", "full", "fixed", "none", "free", "static", "dynamic", "load", "displacement", "top",
           "horizontal_weight", "top_horizontal", "local", "viscous", "\u00e9", "1.0", "nan"]
KEYS: Dict[str, List[str]] = {
    "": ["format", "title", "geometry", "base", "top", "joints", "loads", "analysis", "reference", "extra"],
    "geometry": ["thickness", "density", "running_bond", "pattern", "blocks", "polygons", "supports", "boxes", "leaf",
                 "u_wall"],
    "geometry.running_bond": ["block_length", "block_height", "courses", "height", "length", "first_course", "openings"],
    "geometry.pattern": ["block_length", "block_height", "rows"],
    "geometry.leaf": ["length", "height", "thickness", "block_length", "block_height", "first_course", "openings"],
    "geometry.u_wall": ["facade", "height", "returns", "thickness", "block_length", "block_height", "openings"],
    "base": ["kind"],
    "top": ["rotation", "force", "height"],
    "joints": list(case_module.LAW_KEYS) + list(case_module.FAMILIES),
    "loads": ["gravity", "live", "direction"],
    "analysis": list(case_module.ANALYSIS_KEYS + case_module.DYNAMIC_KEYS),
    "reference": list(case_module.REFERENCE_KEYS),
}
SUBTABLES = {"geometry": ["running_bond", "pattern", "leaf", "u_wall"], "joints": list(case_module.FAMILIES)}


def toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def draw_scalar(fdp: "atheris.FuzzedDataProvider") -> Any:
    kind = fdp.ConsumeIntInRange(0, 9)
    if kind <= 3:
        return fdp.PickValueInList(FLOATS)
    if kind == 4:
        return fdp.ConsumeFloat()
    if kind == 5:
        return fdp.PickValueInList([0, 1, 2, 3, 6, -1, 200, 10**6, 2**31, 10**12, 10**400])
    if kind == 6:
        return fdp.PickValueInList(STRINGS)
    if kind == 7:
        return fdp.ConsumeBool()
    if kind == 8:
        return fdp.ConsumeIntInRange(-5, 50)
    return fdp.ConsumeUnicodeNoSurrogates(8)


def draw_value(fdp: "atheris.FuzzedDataProvider", depth: int = 0) -> Any:
    kind = fdp.ConsumeIntInRange(0, 7)
    if kind <= 4 or depth >= 3:
        return draw_scalar(fdp)
    if kind <= 6:  # arrays: rectangles, rows, forces
        return [draw_value(fdp, depth + 1) for _ in range(fdp.ConsumeIntInRange(0, 5))]
    return {"friction": draw_scalar(fdp)}


def structured_case(fdp: "atheris.FuzzedDataProvider") -> str:
    """A case file whose keys are (mostly) the real ones, with fuzzed values."""
    tables: Dict[str, Dict[str, Any]] = {
        "": {"format": 1},
        "geometry": {},
        "geometry.running_bond": {"block_length": 0.4, "block_height": 0.2, "courses": 2, "length": 0.8},
    }
    if fdp.ConsumeBool():  # a pattern or explicit blocks instead
        del tables["geometry.running_bond"]
        if fdp.ConsumeBool():
            rows = [[fdp.PickValueInList([1, 0.5, -1, 2, 1e-9, 0.25])
                     for _ in range(fdp.ConsumeIntInRange(1, 4))] for _ in range(fdp.ConsumeIntInRange(1, 4))]
            tables["geometry.pattern"] = {"block_length": 0.3, "block_height": 0.5, "rows": rows}
        else:
            blocks = []
            for _ in range(fdp.ConsumeIntInRange(1, 6)):
                x0 = fdp.PickValueInList([0.0, 0.5, 1.0, -1.0, 0.25, 1e-9, 1e9])
                y0 = fdp.PickValueInList([0.0, 0.5, 1.0, 2.0, -0.5])
                w = fdp.PickValueInList([1.0, 0.5, 0.25, 1e-9, 1e9, 2.0])
                h = fdp.PickValueInList([1.0, 0.5, 0.25, 1e-9, 1e6])
                blocks.append([x0, y0, x0 + w, y0 + h])
            tables["geometry"]["blocks"] = blocks
            if fdp.ConsumeBool():  # polygons too: a gable on some blocks, or a wedge beside them
                rise = fdp.PickValueInList([1.0, 0.5, 1e-9, 1e6, -0.5, 0.0])
                on = blocks[: fdp.ConsumeIntInRange(1, 3)]
                tables["geometry"]["polygons"] = [
                    [[x0, y1], [x1, y1], [(x0 + x1) / 2, y1 + rise]] if fdp.ConsumeBool()
                    else [[x1, y0], [x1 + rise, y0], [x1, y1]] for x0, y0, x1, y1 in on
                ]
    for _ in range(fdp.ConsumeIntInRange(0, 8)):
        path = fdp.PickValueInList(sorted(KEYS))
        if path == "joints" and fdp.ConsumeBool():
            path = "joints." + fdp.PickValueInList(list(case_module.FAMILIES))
            key = fdp.PickValueInList(list(case_module.LAW_KEYS))
        else:
            key = fdp.PickValueInList(KEYS[path])
        if key in SUBTABLES.get(path, []) or (path == "" and key not in ("format", "title", "extra")):
            tables.setdefault(f"{path}.{key}" if path else key, {})
            continue
        tables.setdefault(path, {})[key] = draw_value(fdp)
    lines: List[str] = []
    for path, items in tables.items():
        if path:
            lines.append(f"[{path}]")
        lines.extend(f"{k} = {toml_value(v)}" for k, v in items.items())
    return "\n".join(lines) + "\n"


def estimated_blocks(text: str) -> float:
    """A rough count of the blocks a case would generate (0 when it does not parse)."""
    try:
        data = tomllib.loads(text)
        geo = data["geometry"]
        if "running_bond" in geo:
            rb = geo["running_bond"]
            return float(rb["length"]) / float(rb["block_length"]) * float(rb["courses"])
        if "pattern" in geo:
            return float(sum(len(r) for r in geo["pattern"]["rows"]))
        if "leaf" in geo:  # a 3D leaf
            leaf = geo["leaf"]
            return (float(leaf["length"]) / float(leaf["block_length"]) + 2) * float(leaf["height"]) / float(leaf["block_height"])
        for name in ("u_wall", "corner"):  # a 3D facade with its returns
            if name in geo:
                w = geo[name]
                run = float(w["facade"]) + 2 * float(w["returns"])
                return (run / float(w["block_length"]) + 6) * float(w["height"]) / float(w["block_height"])
        if "boxes" in geo:
            return float(len(geo["boxes"]))
        return float(len(geo["blocks"]))
    except Exception:  # not a case the loader would accept anyway: let the loader say so
        return 0.0


def ordinary_blocks(model: "masonry_dem.Model") -> bool:
    """Whether every block is at most MAX_ASPECT times longer than high (or the reverse).

    Slivers (1e-9 x 0.5 m) are legal, but the static solver may spend half a minute on the dead-load
    state of such a wall before it reports "failed": the fuzzer would count that as a time-out."""
    r = model.rects
    w, h = r[:, 2] - r[:, 0], r[:, 3] - r[:, 1]
    return bool(((w <= MAX_ASPECT * h) & (h <= MAX_ASPECT * w)).all())


def check_error(exc: BaseException) -> None:
    """A MasonryError must be one non-empty line naming the case, and never a caught panic."""
    message = str(exc)
    if "internal error" in message:
        raise AssertionError(f"a panic in the core: {message}") from exc
    if not message.startswith(f"{SOURCE}: ") or "\n" in message or len(message) <= len(SOURCE) + 2:
        raise AssertionError(f"a message that does not name the case or is not one line: {message!r}") from exc


def test_one_input(data: bytes) -> None:
    if data[:1] == STRUCTURED:
        text = structured_case(atheris.FuzzedDataProvider(data[1:]))
    else:
        text = data.decode("utf-8", errors="replace")  # load_case refuses other bytes before parsing
    blocks = estimated_blocks(text)
    if not (blocks <= MAX_BUILD_BLOCKS):  # NaN too
        return
    try:
        case = case_module.parse_case(text, source=SOURCE)
        model = case.build_model()
        if case.dimension == 3:  # a 3D wall: limit analysis (the explicit solver's slivers take too many steps)
            if model.n_blocks <= MAX_SOLVE_BLOCKS:
                case.solve(model, "limit")
        elif model.n_blocks <= MAX_SOLVE_BLOCKS and ordinary_blocks(model):
            case.analysis_kwargs["steps"] = 1
            case.solve(model, "static")
    except masonry_dem.MasonryError as exc:
        check_error(exc)


def main() -> None:
    atheris.Setup(sys.argv, test_one_input)
    atheris.Fuzz()


if __name__ == "__main__":
    main()
