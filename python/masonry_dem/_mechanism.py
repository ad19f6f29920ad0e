"""What the descriptions of a mechanism in the two dimensions share (:mod:`masonry_dem.report` in the plane,
:mod:`masonry_dem.space.report` in 3D): when a block moves and when an interface is cracked, the parts the moving
blocks form, and the plural of a count for the sentences that say it. Below both reports; no matplotlib, no core.
"""

from __future__ import annotations

from collections import Counter
from typing import Callable, Dict, List, Sequence, Tuple

import numpy as np

#: A block moves in the mechanism when its largest corner motion exceeds this fraction of the largest of all.
MOVING_FRACTION = 1e-2
#: An interface is cracked in the mechanism when the jump across it (slip, or the gap at one end) exceeds this
#: fraction of the largest corner motion of a block.
CRACK_TOLERANCE = 5e-2


def connected_parts(moving: Sequence[int], pairs: np.ndarray, cracked: Sequence[bool]) -> List[List[int]]:
    """Group the moving blocks into parts: blocks joined by an interface that the crack does not cross."""
    parent = {i: i for i in moving}

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for (a, b), crack in zip(pairs, cracked):
        if not crack and int(a) in parent and int(b) in parent:
            parent[root(int(a))] = root(int(b))
    groups: Dict[int, List[int]] = {}
    for i in moving:
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def plural(n: int, word: str) -> str:
    """``n`` and ``word``, with an s unless ``n`` is 1: "1 block", "3 blocks"."""
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def part_name(part: Sequence[int], n_wall: int) -> str:
    """'3 blocks', '2 blocks and the top beam', 'the top beam' (indices >= n_wall are the top beam)."""
    blocks = sum(1 for i in part if i < n_wall)
    if blocks == len(part):
        return plural(blocks, "block")
    return f"{plural(blocks, 'block')} and the top beam" if blocks else "the top beam"


def family_counts(indices: Sequence[int], families: Sequence[str]) -> str:
    """'3 bed, 1 head': the families of the interfaces ``indices``, most frequent first."""
    counts = Counter(families[k] for k in indices)
    return ", ".join(f"{n} {fam}" for fam, n in counts.most_common())


def mechanism_text(
    n_moving: int,
    n_wall: int,
    beam: str,
    parts: List[List[int]],
    describe: Callable[[Sequence[int]], str],
    crack: Sequence[Tuple[List[int], str]],
    families: Sequence[str],
    noun: str,
) -> str:
    """The line on a mechanism, in either dimension: how many of the ``n_wall`` wall blocks move (``beam``: " and the
    top beam" when it moves too), the ``parts`` they form (largest first), the first two described by ``describe``,
    and the crack: each group of interfaces (``noun``) with its word, counted by family."""
    if n_moving == 0:
        head = "only the top beam moves"
    else:
        verb = "s" if n_moving == 1 and not beam else ""
        head = f"{n_moving} of {n_wall} block{'s' if n_wall > 1 else ''}{beam} move{verb}"
    if len(parts) == 1:
        text = f"{head} as one part, {describe(parts[0])}"
    else:
        shown = "; ".join(f"{part_name(p, n_wall)} {describe(p)}" for p in parts[:2])
        more = f"; {len(parts) - 2} more" if len(parts) > 2 else ""
        text = f"{head} in {len(parts)} parts: {shown}{more}"
    cracked = {k for ks, _ in crack for k in ks}
    if cracked:
        pieces = [f"{len(ks)} {what} ({family_counts(ks, families)})" for ks, what in crack if ks]
        text += f"; the crack runs through {plural(len(cracked), noun)}: " + ", ".join(pieces)
    return text
