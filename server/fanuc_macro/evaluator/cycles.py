"""FANUC's multiple threading cycle G76 as the control runs it: the depth of every pass.

FANUC 0i-TF / 30i-B Operator's Manual, "Multiple threading cycle (G76)": the n-th cut reaches
the depth Δd·√n from the crest (radius), one edge along the flank; when a cut would take less
than Δdmin the cut is Δdmin; roughing stops at k − d (d the finishing allowance) and the
finishing cut to k is made m times. How the control clamps the last roughing cut that would
pass k − d is not spelt out in the manual: here it stops at k − d (unverified).
"""

from __future__ import annotations

import math

MAX_PASSES = 2000  # a G76 with more passes than this is cut short (its Δd is a typo)


def g76_depths(
    height: float,
    first_depth: float,
    min_depth: float,
    allowance: float,
    finishing_passes: int,
) -> list[tuple[float, bool]]:
    """(depth from the crest, finishing) of every pass of a G76 (radius values, mm).

    ``height`` is k, ``first_depth`` Δd, ``min_depth`` Δdmin, ``allowance`` d and
    ``finishing_passes`` m.
    """
    # m has two digits on the control (P mmrraa); a P of more digits gives a bigger number
    # here, bounded like the roughing passes.
    finishing = max(1, min(finishing_passes, MAX_PASSES))
    if height <= 0.0:
        return [(0.0, True)] * finishing
    rough_end = max(0.0, height - max(0.0, allowance))
    passes: list[tuple[float, bool]] = []
    done = 0.0
    n = 1
    step = first_depth if first_depth > 0.0 else height
    while done < rough_end - 1e-9 and len(passes) < MAX_PASSES:
        depth = step * math.sqrt(n)
        if depth - done < min_depth:
            depth = done + min_depth
        if depth >= rough_end - 1e-9:
            depth = rough_end
        passes.append((depth, False))
        done = depth
        n += 1
    passes.extend([(height, True)] * finishing)
    return passes
