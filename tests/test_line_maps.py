"""Line maps: the diff of two versions of a document, and the analysis's maps (line rules,
dialect marks, programs' ends, suppressions) after edits. The maps' work after random edits is
counted in tests/test_rule_scans.py."""

from __future__ import annotations

import random

from fanuc_macro.analysis import analyse
from fanuc_macro.line_maps import Diff, LineMap, line_diff
from fanuc_macro.syntax.parser import default_parser, parse_text
from fanuc_macro.syntax.tree import Document

LINES = [
    "G01 X1. Z-2. F0.2",
    "#1=#1+1",
    "(COMMENT)",
    "",
    "M30",
    "N10 G00 X5.",
    "IF[#1GT3]GOTO10",
    "G67",
    "M99",
    "#2=[#1",  # rejected: a problem
]


def _doc(lines: list[str], uri: str = "file:///m.nc") -> Document:
    return parse_text("\n".join(lines) + "\n", uri, default_parser())


def _edited(rnd: random.Random, lines: list[str]) -> list[str]:
    out = list(lines)
    kind = rnd.randrange(5)
    at = rnd.randrange(len(out) + 1)
    if kind == 0 and out:  # a line replaced
        out[min(at, len(out) - 1)] = rnd.choice(LINES)
    elif kind == 1:  # lines added
        out[at:at] = [rnd.choice(LINES) for _ in range(rnd.randint(1, 4))]
    elif kind == 2 and out:  # lines removed
        del out[at : at + rnd.randint(1, 4)]
    elif kind == 3 and len(out) > 1:  # two lines swapped
        i, j = rnd.randrange(len(out)), rnd.randrange(len(out))
        out[i], out[j] = out[j], out[i]
    else:  # a stretch pasted again further on
        out[at:at] = out[: rnd.randint(0, 6)]
    return out


def test_the_diff_between_two_versions() -> None:
    old = _doc(["A", "B", "C", "D"])
    new = _doc(["A", "X", "Y", "C", "D"])
    diff = line_diff(old, new)
    assert (diff.start, diff.old_end, diff.end, diff.shift) == (1, 2, 3, 1)
    assert line_diff(old, new) is diff  # once per pair of versions
    same = line_diff(old, _doc(["A", "B", "C", "D"]))
    assert (same.start, same.end, same.old_end) == (4, 4, 4)
    motions = [object() for _ in range(5)]
    moved = Diff(motions, [*motions[:2], object(), *motions[3:]], identical=True)
    assert (moved.start, moved.end, moved.old_end, moved.shift) == (2, 3, 3, 0)


def test_what_a_map_finds_between_lines() -> None:
    marks: LineMap[str] = LineMap(lambda p: p.text if "M" in p.text else None)
    found = marks(_doc(["M3", "G0", "M5", "M30", "G1"]))
    assert list(found) == [(0, "M3"), (2, "M5"), (3, "M30")]
    assert found.between(1, 4) == range(1, 3)
    assert found.within(1, 4) == [(2, "M5"), (3, "M30")]
    assert len(found) == 3


def test_analyses_of_edits_equal_fresh_ones() -> None:
    """The line rules, the programs' ends (MB406, MB407) and the suppressions read line maps:
    an analysis of an edited document gives what one of the same text in a new document gives."""
    rnd = random.Random(11)
    lines = [
        "O1000",
        "G66 P9000 A1.",
        "#1=SQRT[-1]",
        "G01 X1. Y2.",
        "(MAIN)",
        "R1=5",
        "M30",
        "O2000",
        "G00 X0",
        "#5=[#1",
        "M99",
        "O3000",
        "G01 x1.",
        "GOTO5",
    ]
    for _ in range(60):
        edited = analyse("\n".join(lines) + "\n", "file:///edits.nc")
        fresh = analyse("\n".join(lines) + "\n", f"file:///fresh{rnd.random()}.nc")
        assert [(d.code, d.line, d.message) for d in edited.diagnostics] == [
            (d.code, d.line, d.message) for d in fresh.diagnostics
        ]
        lines = _edited(rnd, lines)
        if rnd.random() < 0.3:
            lines.insert(
                rnd.randrange(len(lines) + 1),
                rnd.choice(
                    [
                        "M30",
                        "G67",
                        "M99",
                        "O4000",
                        "R2=1",
                        "%@MACRO",
                        "#2=SQRT[-2] (fanuc-macro: ignore MB501)",
                        "GOTO7 (fanuc-macro: ignore)",
                    ]
                ),
            )
