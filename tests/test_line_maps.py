"""Line maps give after an edit what a look at every line gives, looking only at the edit."""

from __future__ import annotations

import random

from fanuc_macro.analysis import analyse
from fanuc_macro.line_maps import LineMap, edit_between
from fanuc_macro.parser import default_parser, parse_text
from fanuc_macro.syntax import Document, ParsedLine

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


def _marked(parsed: ParsedLine) -> str | None:
    return parsed.text if "M" in parsed.text or parsed.problem is not None else None


def _doc(lines: list[str], uri: str = "file:///m.nc") -> Document:
    return parse_text("\n".join(lines) + "\n", uri, default_parser())


def _full(doc: Document) -> tuple[list[int], list[str]]:
    found = [(b.line, v) for b in doc.blocks if (v := _marked(b.parsed)) is not None]
    return [line for line, _ in found], [v for _, v in found]


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


def test_a_map_after_random_edits_equals_a_look_at_every_line() -> None:
    rnd = random.Random(7)
    marks: LineMap[str] = LineMap(_marked)
    for trial in range(40):
        lines = [rnd.choice(LINES) for _ in range(rnd.randint(0, 60))]
        uri = f"file:///t{trial % 3}.nc"
        for _ in range(15):
            doc = _doc(lines, uri)
            got_lines, got = marks(doc)
            assert (list(got_lines), list(got)) == _full(doc), lines
            lines = _edited(rnd, lines)


def test_an_edit_is_looked_at_alone() -> None:
    lines = [f"G01 X{i}. M{i % 7}" for i in range(2000)]
    marks: LineMap[str] = LineMap(_marked)
    marks(_doc(lines))
    assert marks.lines_computed == 2000
    lines[1000] = "G01 X0.5"
    marks(_doc(lines))
    assert marks.lines_computed == 2001
    lines[500:500] = ["M08", "M09"]  # lines added: those after them move
    got_lines, _ = marks(_doc(lines))
    assert marks.lines_computed == 2003
    assert got_lines[-1] == 2001


def test_the_edit_between_two_versions() -> None:
    old = [*_doc(["A", "B", "C", "D"]).blocks]
    new = [*_doc(["A", "X", "Y", "C", "D"]).blocks]
    edit = edit_between([b.parsed for b in old], [b.parsed for b in new])
    assert (edit.head, edit.old_end, edit.new_end, edit.shift) == (1, 2, 3, 1)
    same = [b.parsed for b in old]
    assert edit_between(same, same).head == 4
    assert edit_between([], same) == edit_between([], same)


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
