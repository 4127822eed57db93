"""Blocks of plain words kept as their code (``PlainNc``): the nodes built on demand equal
the ones the full parse builds, what the compiler and the rules read from the code equals what
they read from the nodes, and an analysis of CAM output builds no nodes for its blocks."""

from __future__ import annotations

import dataclasses
import random
import sys
from pathlib import Path

import pytest

from fanuc_macro import analysis
from fanuc_macro.config import Config
from fanuc_macro.evaluator import machine
from fanuc_macro.line_maps import LineMap
from fanuc_macro.rules import LINE_CHECKS, statements
from fanuc_macro.syntax.lines import cut_comments
from fanuc_macro.syntax.parser import BlockParser, _fast_parse, parse_text
from fanuc_macro.syntax.tree import BARE_CODES, NcStatement, ParsedLine, PlainNc, Span
from fanuc_macro.workspace import Workspace
from test_parser import program_lines, random_nc_lines

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
from bench_lsp import cam_program


def cam_lines(count: int, seed: int) -> list[str]:
    """Blocks as CAM systems write them, and their neighbours: N numbers, block skip, lower
    case, tabs, comments, codes that end or call, numbers of 12 and 13 digits."""
    rng = random.Random(seed)

    def number() -> str:
        whole = str(rng.randint(0, 99999))
        if rng.random() < 0.03:
            return rng.choice(["123456789012", "12345678.9012", "1234567890123", "-0"])
        return rng.choice(
            [
                whole,
                whole + ".",
                f"{rng.random() * 500:.{rng.randint(0, 5)}f}",
                "." + str(rng.randint(0, 999)),
                "0" + whole,
            ]
        )

    out: list[str] = []
    for _ in range(count):
        parts: list[str] = []
        if rng.random() < 0.1:
            parts.append(rng.choice(["/", "/1", "/ 2"]))
        if rng.random() < 0.3:
            parts.append(rng.choice("Nn") + str(rng.randint(0, 99999)))
        if rng.random() < 0.7:
            parts.append(
                "G" + rng.choice(["01", "1", "00", "2", "3", "1.5", "17", "90", "67", "66", "103"])
            )
        for letter in rng.sample("XYZIJKFSTMPHDQR", rng.randint(1, 5)):
            sign = rng.choice(["", "", "-", "+"])
            parts.append(
                (letter.lower() if rng.random() < 0.05 else letter)
                + (rng.choice(["2", "30", "99", "98", "8", "3"]) if letter == "M" else "")
                + ("" if letter == "M" else sign + number())
            )
        if rng.random() < 0.2:
            parts.append(parts[-1])  # an address twice
        text = rng.choice([" ", "", "\t"]).join(parts)
        text += rng.choice(["", "", " ", "\t", " (CUT)", ";", "%"])
        out.append(text)
    return out


def every_line() -> list[str]:
    return [*program_lines(), *random_nc_lines(3000, seed=77), *cam_lines(6000, seed=5)]


def test_a_plain_block_s_nodes_equal_the_full_parse_s() -> None:
    fresh, grammar = BlockParser(), BlockParser(use_fast_path=False)
    plain = 0
    for text in every_line():
        parsed = fresh.parse_line(text)
        nc = parsed.statement
        if type(nc) is not PlainNc:
            continue
        if not nc.built():  # a line met before was built by that comparison
            plain += 1
            full = _fast_parse(cut_comments(text).code)
            assert full is not None and full[3] is not None, text
            expected = full[3]
            assert nc.codes == tuple(
                (w.address, w.value.value)  # type: ignore[union-attr]
                for w in expected.words
                if w.address in "GM"
            ), text
            assert nc.pairs() == [
                (text[w.span.start], w.value.text)  # type: ignore[union-attr]
                for w in expected.words
            ], text
            assert not nc.built(), text  # codes and pairs are read from the code
            assert nc.words == expected.words, text
            assert nc.built(), text
        slow = grammar.parse_line(text)
        assert isinstance(slow.statement, NcStatement), text
        assert nc.words == slow.statement.words and nc.span == slow.statement.span, text
        assert nc == slow.statement and slow.statement == nc, text
        assert hash(nc) == hash(slow.statement), text
        assert parsed == slow, text
    assert plain > 4000


def test_plain_blocks_compare_by_the_code_of_their_words() -> None:
    parser = BlockParser()
    a = parser.parse_line("G01 X1. Y2.(A)").statement
    b = parser.parse_line("G01 X1. Y2. (B)").statement
    c = parser.parse_line("G01 X1. Y3.").statement
    assert type(a) is PlainNc and type(b) is PlainNc and type(c) is PlainNc
    assert a == b and a != c
    assert not a.built() and not b.built() and not c.built()  # compared by their code
    assert hash(a) == hash(b) == hash(NcStatement(a.words, a.span))
    made = PlainNc("G01 X1. Y3.", Span(0, 11), (("G", 1.0),))
    assert made == c and made.words == c.words and made.codes == c.codes
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.code = "X1"  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        a.span = Span(0, 1)  # type: ignore[misc]


@pytest.mark.parametrize(
    "text",
    [
        "M98 P1000",
        "G65 P9010 A1.",
        "G66.1 P1",
        "M99",
        "G01 X 1.",
        "G01 X#1",
        "X1234567890123",
        "N1234567890123 X1",
        "G01 N10 X1",
        "O1000",
    ],
)
def test_blocks_that_are_not_plain_words_of_numbers_are_parsed_in_full(text: str) -> None:
    assert type(BlockParser().parse_line(text).statement) is not PlainNc


def _general_findings(parsed: ParsedLine) -> tuple[object, ...] | None:
    found = [f for check in LINE_CHECKS for f in check(parsed)]
    return tuple(found) or None


def test_the_line_rules_way_for_plain_blocks_gives_the_general_way_s_findings() -> None:
    """The line rules' and the programs' ends' answers from a plain block's codes, against the
    answers from its nodes (an NcStatement of the same words)."""
    parser = BlockParser()
    seen = 0
    for text in every_line():
        parsed = parser.parse_line(text)
        nc = parsed.statement
        if type(nc) is not PlainNc:
            continue
        seen += 1
        nodes = dataclasses.replace(parsed, statement=NcStatement(nc.words, nc.span))
        assert analysis._findings_of_line(parsed) == _general_findings(nodes), text
        assert statements._end_or_g67(parsed) == statements._end_or_g67(nodes), text
        assert machine._ends_program_line(parsed) == machine._ends_program_line(nodes), text
    assert seen > 5000


def test_no_line_map_finds_anything_in_a_bare_line() -> None:
    """The line maps do not look at bare lines (``ParsedLine.bare``): every map's look finds
    nothing in any, and a map of a document is the lines where a look at every line finds
    something."""
    maps: list[LineMap[object]] = [
        value
        for name, module in sorted(sys.modules.items())
        if name.startswith("fanuc_macro.")
        for value in vars(module).values()
        if isinstance(value, LineMap)
    ]
    assert len(maps) >= 13  # those of the rules, the evaluator, the analysis and the threads
    parser = BlockParser()
    texts = every_line()
    parsed = [parser.parse_line(text) for text in texts]
    bare = [p for p in parsed if p.bare]
    assert len(bare) > 1000
    for p in parsed:  # bare: plain upper case words alone, of the few G codes
        nc = p.statement
        expected = (
            type(nc) is PlainNc
            and not p.comments
            and not p.notes
            and not p.tape_mark
            and not p.has_lowercase
            and BARE_CODES.issuperset(nc.codes)
        )
        assert p.bare == expected or (expected and ";" in p.text), p.text
    for line_map in maps:
        if line_map.every_line:
            continue  # it looks at bare lines too (the machine's marks)
        for p in bare:
            assert not line_map._look(p), (line_map._look, p.text)
    doc = parse_text("\n".join(texts) + "\n", "file:///bare.nc", parser)
    for line_map in maps:
        everywhere = [b.line for b in doc.blocks if line_map._look(b.parsed)]
        assert line_map(doc).lines == everywhere, line_map._look


def test_an_analysis_of_cam_output_builds_no_nodes_for_its_blocks() -> None:
    text = cam_program(3000)
    config = dataclasses.replace(Config(), max_blocks=10**6, max_file_size=10**9)
    workspace = Workspace(config, BlockParser())  # lines no earlier test has parsed
    uri = "file:///cam.nc"
    workspace.add_text(uri, text)
    workspace.analyse(uri)
    lines = text.split("\n")
    lines[1500] = lines[1500].replace("X", "X1", 1)  # a keystroke
    workspace.add_text(uri, "\n".join(lines))
    result = workspace.analyse(uri)
    plain = [b.parsed.statement for b in result.doc.blocks if type(b.statement) is PlainNc]
    assert len(plain) > 3000
    built = [b.parsed.text for b in result.doc.blocks if isinstance(b.statement, PlainNc)]
    built = [t for t, s in zip(built, plain, strict=True) if s.built()]  # type: ignore[union-attr]
    # The header's spindle block, whose words the run checks one by one (S against the
    # machine's maximum), and the program's end, which the programs' ends rule reads in full.
    assert built == ["S3000 M03", "M30"]
