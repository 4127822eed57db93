"""A new version of a document read from the earlier one equals one read from scratch: its
blocks (the lines compared by text, only the changed stretch parsed), its program index
(kept when the edit changed only lines the index skips) and the workspace's verdict on
whether it runs the same."""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from fanuc_macro.program.index import build_index, index_after_edit
from fanuc_macro.syntax import parser as parser_module
from fanuc_macro.syntax.lines import ReadLimits
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.workspace import Workspace

FIXTURES = Path(__file__).parent / "fixtures"
PROGRAMS = sorted([*(FIXTURES / "seeds").glob("*.nc"), *(FIXTURES / "rules").glob("*.nc")])
URI = "file:///O1234.nc"


def edit(lines: list[str], rng: random.Random) -> list[str]:
    out = list(lines)
    i = rng.randrange(len(out))
    pick = rng.randrange(7)
    if pick == 0:
        out.insert(i, "")
    elif pick == 1 and len(out) > 2:
        del out[i]
    elif pick == 2:
        out[i] = out[rng.randrange(len(out))]
    elif pick == 3:
        out[i] = out[i] + " (NOTE)"
    elif pick == 4:
        out[i] = out[i].replace("1", "2", 1)
    elif pick == 5:
        j = rng.randrange(len(out))
        out[i], out[j] = out[j], out[i]
    else:
        out[i] = "G01 X1. Z2."
    return out


@pytest.mark.parametrize(
    "limits",
    [ReadLimits(), ReadLimits(max_blocks=40), ReadLimits(max_line_length=30)],
    ids=["whole", "40 blocks", "short lines"],
)
@pytest.mark.parametrize("path", PROGRAMS[::3], ids=lambda p: p.name)
def test_a_version_read_from_the_last_equals_one_read_anew(path: Path, limits: ReadLimits) -> None:
    rng = random.Random(path.name)
    lines = path.read_text("utf-8", errors="replace").splitlines()
    if not lines:
        return
    parser = BlockParser()
    doc = parse_text("\n".join(lines), URI, parser, limits=limits)
    index = build_index(doc)
    for _ in range(15):
        lines = edit(lines, rng)
        text = "\n".join(lines)
        new = parse_text(text, URI, parser, doc, limits, previous_limits=limits)
        fresh = parse_text(text, URI, BlockParser(), limits=limits)
        assert new == fresh
        index = index_after_edit(index, doc, new)
        assert index == build_index(fresh)
        doc = new


def test_the_workspace_keeps_the_index_of_an_edit_of_a_plain_block() -> None:
    ws = Workspace()
    text = "%\nO1234\nG01 X1. F0.2\nG01 X2.\nGOTO 10\nN10 M30\n%\n"
    ws.add_text(URI, text)
    index = ws.index(URI)
    ws.add_text(URI, text.replace("X2.", "X3."))
    assert ws.index(URI) is index
    ws.add_text(URI, text.replace("GOTO 10", "GOTO 20"))
    assert ws.index(URI) is not index
    assert ws.index(URI) == build_index(parse_text(text.replace("GOTO 10", "GOTO 20"), URI))


def _char_edit(text: str, rng: random.Random) -> str:
    """A keystroke or a paste anywhere: characters typed, a stretch cut (line ends included)."""
    i = rng.randrange(len(text) + 1)
    pick = rng.randrange(6)
    if pick == 0:
        return text[:i] + rng.choice(["1", " ", "\n", "X", "(", "#1=2\n", "\n\n"]) + text[i:]
    if pick == 1:
        return text[:i] + text[i + rng.randrange(1, 40) :]
    if pick == 2:
        return text[:i] + "\n" + text[i:] if rng.random() < 0.5 else text.rstrip("\n")
    if pick == 3:
        return text + "\n" if not text.endswith("\n") else text + "G00 X1."
    if pick == 4:
        return text[: rng.randrange(len(text) + 1)]
    j = rng.randrange(len(text) + 1)
    return text[: min(i, j)] + "GOTO 10\n(注释)" + text[max(i, j) :]


@pytest.mark.parametrize(
    "limits",
    [ReadLimits(), ReadLimits(max_blocks=40), ReadLimits(max_characters=900)],
    ids=["whole", "40 blocks", "900 characters"],
)
@pytest.mark.parametrize("path", PROGRAMS[1::4], ids=lambda p: p.name)
def test_a_version_read_from_the_last_text_equals_one_read_anew(
    path: Path, limits: ReadLimits, monkeypatch: pytest.MonkeyPatch
) -> None:
    # With the earlier text, a text with LF line ends is compared with it by characters and
    # only the lines of the edit are split out: never the whole text, while every line is read.
    splits: list[int] = []
    split = parser_module.split_lines
    monkeypatch.setattr(
        parser_module, "split_lines", lambda text: splits.append(len(text)) or split(text)
    )
    rng = random.Random(path.name)
    text = path.read_text("utf-8", errors="replace").replace("\r\n", "\n")
    parser = BlockParser()
    doc = parse_text(text, URI, parser, limits=limits)
    for _ in range(40):
        old, text = text, _char_edit(text, rng)
        splits.clear()
        new = parse_text(text, URI, parser, doc, limits, previous_limits=limits, previous_text=old)
        if new.unread_from is None and doc.unread_from is None:
            assert not splits
        fresh = parse_text(text, URI, BlockParser(), limits=limits)
        assert new == fresh
        assert all(
            a.parsed is b.parsed
            for a, b in zip(doc.blocks, new.blocks, strict=False)
            if a.parsed.text == b.parsed.text and a.line == b.line
        ) or len(doc.blocks) != len(new.blocks)
        doc = new


def test_a_text_with_cr_is_read_the_usual_way() -> None:
    parser = BlockParser()
    old = "%\r\nO1\r\nG00 X1.\r\nM30\r\n%\r\n"
    doc = parse_text(old, URI, parser)
    text = old.replace("X1.", "X12.")
    new = parse_text(
        text, URI, parser, doc, ReadLimits(), previous_limits=ReadLimits(), previous_text=old
    )
    assert new == parse_text(text, URI, BlockParser())
    assert new.blocks[0].parsed is doc.blocks[0].parsed
