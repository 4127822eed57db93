"""Work bounds of big programs, counted in operations, not seconds: no rule or index question
that is quadratic in blocks, loops, labels or jumps, and caches that keep what is in use."""

from __future__ import annotations

import random
from collections.abc import Iterator
from typing import Any

import pytest

from fanuc_macro.per_line import PerLine
from fanuc_macro.program import index as index_module
from fanuc_macro.program.index import Loop, Program, build_index
from fanuc_macro.rules import jumps
from fanuc_macro.rules.context import RuleContext
from fanuc_macro.syntax.parser import BlockParser, parse_text
from fanuc_macro.syntax.tree import ParsedLine


class CountedList(list[Any]):
    """A list that counts how many of its items are read, and fails past a budget."""

    def __init__(self, items: list[Any], budget: int) -> None:
        super().__init__(items)
        self.reads = 0
        self.budget = budget

    def _read(self, n: int) -> None:
        self.reads += n
        if self.reads > self.budget:
            raise AssertionError(f"more than {self.budget} reads of a list of {len(self)}")

    def __iter__(self) -> Iterator[Any]:
        for item in super().__iter__():
            self._read(1)
            yield item

    def __getitem__(self, i: Any) -> Any:
        item = super().__getitem__(i)
        self._read(len(item) if isinstance(i, slice) else 1)
        return item


def dense_program(groups: int) -> str:
    """Each group: a label, a loop with a GOTO out of it and one inside, a label after it."""
    out = ["O2000"]
    for g in range(groups):
        label = 2 * g + 1
        out += [
            f"N{label} #1=#1+1",
            "WHILE[#1LT3]DO1",
            "WHILE[#2LT2]DO2",
            f"IF[#2GT9]GOTO{label + 1}",
            "#2=#2+1",
            "END2",
            "END1",
            f"IF[#1LT0]GOTO{label}",
            f"N{label + 1} #3=#1",
        ]
    return "\n".join([*out, "M30"]) + "\n"


def brute_enclosing(program: Program, line: int) -> list[Loop]:
    return [
        lp for lp in program.loops if lp.end_line is not None and lp.do_line < line <= lp.end_line
    ]


def test_enclosing_loops_are_the_loops_whose_body_holds_the_line() -> None:
    rnd = random.Random(7)
    for trial in range(40):
        lines = ["O1"]
        for _ in range(rnd.randint(1, 60)):
            k = rnd.random()
            loop_id = rnd.randint(1, 3)
            if k < 0.3:
                lines.append(f"WHILE[#1LT{loop_id}]DO{loop_id}")
            elif k < 0.55:
                lines.append(f"END{loop_id}")  # unmatched and crossed ENDs too
            else:
                lines.append("#1=#1+1")
        lines.append("M30")
        doc = parse_text("\n".join(lines) + "\n", f"t{trial}")
        for program in build_index(doc).programs:
            for line in range(-1, len(doc.blocks) + 2):
                expected = brute_enclosing(program, line)
                assert program.enclosing_loops(line) == expected, (trial, line)


def test_label_line_and_program_at_match_a_scan() -> None:
    text = "O1\nN5\nGOTO5\nN5\nN7\nGOTO5\nN5\nM99\nO2\nN5\nGOTO5\nM99\n"
    doc = parse_text(text, "t")
    index = build_index(doc)
    for program in index.programs:
        for seq, lines in program.labels.items():
            for at in range(-1, len(doc.blocks) + 1):
                expected = next((ln for ln in lines if ln > at), lines[0])
                assert program.label_line(seq, at) == expected
    for line in range(-2, len(doc.blocks) + 2):
        expected = next((p for p in index.programs if p.contains(line)), None)
        assert index.program_at(line) is expected


def test_the_jumps_rule_reads_each_loop_a_bounded_number_of_times() -> None:
    """4,000 loops and 2,000 GOTOs in one program: a scan of every loop for each GOTO would read
    the loop list 16 million times; the rule reads it once to build the map of what holds each
    line."""
    doc = parse_text(dense_program(2000), "dense")
    index = build_index(doc)
    (program,) = index.programs
    assert len(program.loops) == 4000 and len(program.jumps) == 4000
    program.loops = counted = CountedList(program.loops, budget=3 * 4000)
    diagnostics = list(jumps.check(RuleContext(doc, index)))
    assert not [d for d in diagnostics if d.code == "MB103"]
    assert 0 < counted.reads <= 3 * 4000


def test_the_loop_map_is_built_once_per_program(monkeypatch: pytest.MonkeyPatch) -> None:
    built: list[int] = []
    real = index_module._loop_stretches

    def spy(loops: list[Loop]) -> Any:
        built.append(len(loops))
        return real(loops)

    monkeypatch.setattr(index_module, "_loop_stretches", spy)
    doc = parse_text(dense_program(500), "dense")
    index = build_index(doc)
    list(jumps.check(RuleContext(doc, index)))
    list(jumps.check(RuleContext(doc, index)))
    assert built == [1000]


def test_a_label_written_thousands_of_times_is_found_by_bisection() -> None:
    """3,000 copies of N1, each followed by a GOTO1: finding where each jump lands by a scan of
    the copies would read 9 million list items."""
    text = "O1\n" + "N1 #1=#1+1\nGOTO1\n" * 3000 + "M30\n"
    doc = parse_text(text, "dups")
    index = build_index(doc)
    (program,) = index.programs
    budget = 60 * 3000
    program.labels[1] = counted = CountedList(program.labels[1], budget)
    list(jumps.check(RuleContext(doc, index)))
    assert counted.reads <= budget


def test_an_edit_the_index_skips_keeps_the_jumps_rule_s_diagnostics(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A keystroke in an assignment keeps the program index, and with it what the jumps rule
    found: its 4,000 jumps are not looked at again. An edit of a label is."""
    from fanuc_macro.workspace import Workspace

    looked: list[int] = []
    real = jumps._check

    def spy(ctx: RuleContext, found: list[Any]) -> bool:
        looked.append(sum(len(p.jumps) for p in ctx.index.programs))
        return real(ctx, found)

    monkeypatch.setattr(jumps, "_check", spy)
    lines = [*dense_program(2000).splitlines()[:-1], "N5000 GOTO4001", "M30"]
    workspace = Workspace()
    uri = "file:///dense.nc"
    workspace.add_text(uri, "\n".join(lines))
    first = [d for d in workspace.analyse(uri).diagnostics if d.code.startswith("MB10")]
    assert [d.code for d in first] == ["MB101"]
    assert looked == [4001]
    lines[5] = lines[5].replace("#2=#2+1", "#2=#2+2")
    workspace.add_text(uri, "\n".join(lines))
    kept = [d for d in workspace.analyse(uri).diagnostics if d.code.startswith("MB10")]
    assert kept == first and looked == [4001]
    lines.insert(len(lines) - 1, "N4001")  # the label the last jump wanted
    workspace.add_text(uri, "\n".join(lines))
    assert not [d for d in workspace.analyse(uri).diagnostics if d.code.startswith("MB10")]
    assert looked == [4001, 4001]


# ---- caches ----------------------------------------------------------------------------------


def distinct_lines(n: int, start: int = 0) -> list[ParsedLine]:
    parser = BlockParser(cache_size=10 * n + 10)
    return [parser.parse_line(f"#1={i}") for i in range(start, start + n)]


def test_a_per_line_cache_at_its_bound_keeps_what_is_used_and_drops_the_oldest() -> None:
    computed: list[str] = []

    def compute(parsed: ParsedLine) -> str:
        computed.append(parsed.text)
        return parsed.text

    cache = PerLine(compute, limit=8)
    first = distinct_lines(8)
    for parsed in first:
        cache(parsed)
    for parsed in distinct_lines(40, start=100):
        cache(first[0])  # used all along
        cache(first[1])
        cache(parsed)
        assert len(cache) <= 8
    assert first[0] in cache and first[1] in cache
    assert not any(parsed in cache for parsed in first[2:])  # the oldest, unused, went
    assert computed.count(first[0].text) == 1 and computed.count(first[1].text) == 1


def test_a_document_larger_than_the_cache_recomputes_only_what_is_not_kept() -> None:
    computed = 0

    def compute(parsed: ParsedLine) -> int:
        nonlocal computed
        computed += 1
        return len(parsed.text)

    cache = PerLine(compute, limit=1000)
    document = distinct_lines(1500)
    for parsed in document:  # the first analysis computes every line
        cache(parsed)
    assert computed == 1500
    for _ in range(3):  # each analysis after it: only the lines the cache could not keep
        computed = 0
        for parsed in document:
            cache(parsed)
        assert computed == 1500 - len(cache) == 500


def test_the_parse_cache_keeps_the_lines_of_a_document_larger_than_its_bound(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    parser = BlockParser(cache_size=100)
    parsed_texts: list[str] = []
    real = parser._parse_uncached

    def counting(text: str) -> ParsedLine:
        parsed_texts.append(text)
        return real(text)

    monkeypatch.setattr(parser, "_parse_uncached", counting)
    lines = [f"#1={i}" for i in range(300)]
    document = parser.parse_lines(lines)  # a document holds its lines
    assert len(parsed_texts) == 300
    again = parser.parse_lines(lines)
    assert len(parsed_texts) == 300  # an edit of the document parses no line again
    assert [a is b for a, b in zip(document, again, strict=True)] == [True] * 300
    del document, again
    for i in range(1000):  # lines nobody keeps: the cache holds about its bound of them
        parser.parse_line(f"#2={i}")
    own = parser._cache
    assert len(own) <= 100
    assert "#2=999" in own and "#1=0" not in own
