"""What the descriptions of a mechanism in the two dimensions share (:mod:`masonry_dem.report` in the plane,
:mod:`masonry_dem.space.report` in 3D): when a block moves and when an interface is cracked, the parts the moving
blocks form, and the plural of a count for the sentences that say it. Below both reports; no matplotlib, no core.
"""

from __future__ import annotations

from typing import Dict, List, Sequence

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
