"""The block reader and the grammar: forms without spaces, spans, comments, line ends, encodings,
large files, and the fast path that must give the same result as the Lark grammar."""

from __future__ import annotations

import dataclasses
import random
from collections.abc import Iterator
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.program.index import build_index, program_number_of_name
from fanuc_macro.syntax.lines import (
    BINARY,
    cut_comments,
    decode_bytes,
    not_text_reason,
    split_lines,
)
from fanuc_macro.syntax.parser import BlockParser, fast_parse, parse_bytes, parse_text
from fanuc_macro.syntax.tree import (
    Assign,
    Binary,
    Block,
    Bracket,
    Call,
    Compare,
    End,
    Goto,
    IfGoto,
    IfThen,
    Logic,
    Mixed,
    NcStatement,
    Num,
    ParsedLine,
    Print,
    ProgramStart,
    Span,
    Unary,
    Var,
    While,
)

ROOT = Path(__file__).resolve().parents[1]
SEEDS = ROOT / "tests" / "fixtures" / "seeds"
CORPUS = ROOT.parent / "shared" / "corpus"

GRAMMAR = BlockParser(use_fast_path=False)  # every line through Lark


def line(text: str) -> ParsedLine:
    parsed = GRAMMAR.parse_line(text)
    assert parsed.problem is None, parsed.problem
    return parsed


def stmt(text: str) -> object:
    return line(text).statement


def block(text: str) -> Block:
    doc = parse_text(text, parser=GRAMMAR)
    assert len(doc.blocks) == 1
    return doc.blocks[0]


def words(text: str) -> list[tuple[str, str]]:
    """(address, source of the value) of an NC block."""
    b = block(text)
    nc = b.statement
    assert isinstance(nc, NcStatement), nc
    return [(w.address, b.source(w.value.span)) for w in nc.words]


def nodes(obj: object) -> Iterator[object]:
    """Every AST node under ``obj`` (itself included) that has a span."""
    if isinstance(obj, tuple):
        for item in obj:
            yield from nodes(item)
        return
    if not dataclasses.is_dataclass(obj) or isinstance(obj, Span):
        return
    if hasattr(obj, "span"):
        yield obj
    for f in dataclasses.fields(obj):
        if f.name not in ("span", "name_span", "id_span"):
            yield from nodes(getattr(obj, f.name))


# ---- forms without spaces ------------------------------------------------------------------


def test_if_goto_without_spaces() -> None:
    s = stmt("IF[#1EQ#102]GOTO2010")
    assert isinstance(s, IfGoto)
    assert isinstance(s.cond, Compare)
    assert s.cond.op == "EQ"
    assert s.cond.left == Var(1.0, None, Span(3, 5))
    assert isinstance(s.cond.right, Var) and s.cond.right.number == 102
    assert isinstance(s.goto.target, Num) and s.goto.target.value == 2010


def test_g_codes_from_variables_without_spaces() -> None:
    assert words("G90G1G#8X#601") == [("G", "90"), ("G", "1"), ("G", "#8"), ("X", "#601")]
    nc = stmt("G90G1G#8X#601")
    assert isinstance(nc, NcStatement)
    assert [type(w.value) for w in nc.words] == [Num, Num, Var, Var]


def test_sequence_number_before_if() -> None:
    p = line("N45IF[#100GE#18]GOTO2")
    assert p.seq == 45
    assert isinstance(p.statement, IfGoto)
    assert isinstance(p.statement.cond, Compare) and p.statement.cond.op == "GE"
    assert isinstance(p.statement.goto.target, Num) and p.statement.goto.target.value == 2


def test_wh_with_and_of_bracketed_conditions() -> None:
    s = stmt("WH[[#1GE#2]AND[#3GE#7]]DO1")
    assert isinstance(s, While)
    assert s.loop_id == 1
    assert isinstance(s.cond, Logic)
    assert isinstance(s.cond.first, Compare) and s.cond.first.op == "GE"
    assert [op for op, _ in s.cond.rest] == ["AND"]
    second = s.cond.rest[0][1]
    assert isinstance(second, Compare) and isinstance(second.right, Var)
    assert second.right.number == 7


@pytest.mark.parametrize("text", ["WHILE[#1LT10]DO2", "WHILE [ #1 LT 10 ] DO2", "wh[#1lt10]do2"])
def test_while_spellings(text: str) -> None:
    s = stmt(text)
    assert isinstance(s, While) and s.loop_id == 2 and isinstance(s.cond, Compare)


def test_unary_minus_before_bracket_after_an_address() -> None:
    text = "G3I-[#106]Z[#5003-[#107*#17]]F#9"
    assert words(text) == [
        ("G", "3"),
        ("I", "-[#106]"),
        ("Z", "[#5003-[#107*#17]]"),
        ("F", "#9"),
    ]
    nc = stmt(text)
    assert isinstance(nc, NcStatement)
    i_value = nc.words[1].value
    assert isinstance(i_value, Unary) and i_value.op == "-"
    assert isinstance(i_value.operand, Bracket)
    z_value = nc.words[2].value
    assert isinstance(z_value, Bracket) and isinstance(z_value.inner, Binary)
    assert z_value.inner.op == "-"


def test_atan_slash_form_is_one_call_with_two_arguments() -> None:
    s = stmt("#1=ATAN[#2]/[#3]")
    assert isinstance(s, Assign)
    call = s.value
    assert isinstance(call, Call)
    assert call.name == "ATAN" and call.slash_form
    assert [a.number for a in call.args if isinstance(a, Var)] == [2, 3]


def test_atan_slash_form_then_a_division() -> None:
    s = stmt("#1=ATAN[#2]/[#3]/2")
    assert isinstance(s, Assign)
    assert isinstance(s.value, Binary) and s.value.op == "/"
    assert isinstance(s.value.left, Call) and s.value.left.slash_form
    assert isinstance(s.value.right, Num)


def test_atan_of_a_division_is_one_argument() -> None:
    s = stmt("#168= ATAN[ ABS[ #25 ] / ABS[ #24 ] ]")
    assert isinstance(s, Assign)
    assert isinstance(s.value, Call) and len(s.value.args) == 1
    assert isinstance(s.value.args[0], Binary) and s.value.args[0].op == "/"


@pytest.mark.parametrize("name", ["ATAN", "POW"])
def test_comma_functions(name: str) -> None:
    s = stmt(f"#1={name}[#2,2.]")
    assert isinstance(s, Assign)
    call = s.value
    assert isinstance(call, Call)
    assert call.name == name and not call.slash_form and len(call.args) == 2
    assert isinstance(call.args[1], Num) and call.args[1].value == 2.0


def test_indirect_assignment_of_vacant() -> None:
    s = stmt("#[#1+100]=#0")
    assert isinstance(s, Assign)
    assert s.target.number is None
    assert isinstance(s.target.index, Binary) and s.target.index.op == "+"
    assert s.value == Var(0.0, None, Span(10, 12))


def test_operators_without_spaces() -> None:
    s = stmt("#1=#2AND#3OR#4XOR#5*2MOD3")
    assert isinstance(s, Assign)
    ops = [n.op for n in nodes(s.value) if isinstance(n, Binary)]
    assert sorted(ops) == ["*", "AND", "MOD", "OR", "XOR"]


@pytest.mark.parametrize(
    "text",
    [
        "DPRNT[X#24[44]*Y#25[44]]",
        "DPRNT[***COMPONENT*NO*#171[60]***]",
        "DPRNT[UNITS*#4006[20]]",
        "DPRNT[]",
        "BPRNT[A#1[3]]",
    ],
)
def test_dprnt_formats(text: str) -> None:
    s = stmt(text)
    assert isinstance(s, Print)
    assert s.keyword == text[:5]
    assert block(text).source(s.span) == text


@pytest.mark.parametrize("text", ["POPEN", "PCLOS"])
def test_popen_pclos(text: str) -> None:
    s = stmt(text)
    assert isinstance(s, Print) and s.keyword == text


def test_m98_compressed_program_number_keeps_its_digits() -> None:
    nc = stmt("M98 P0013331")
    assert isinstance(nc, NcStatement)
    p = nc.find("P")
    assert p is not None and isinstance(p.value, Num)
    assert p.value.text == "0013331"
    index = build_index(parse_text("O1\nM98 P0013331\nM30\n", parser=GRAMMAR))
    (call,) = index.programs[0].calls
    assert (call.kind, call.program, call.repeat) == ("M98", 3331, 1)


@pytest.mark.parametrize(
    ("text", "number", "name"),
    [
        ("O9123<NAME>", 9123, "NAME"),
        ("O9123<G65  HOLE BORE MACRO>", 9123, "G65  HOLE BORE MACRO"),
        ("O<PROBE>", None, "PROBE"),
        ("O0010", 10, None),
        ("O09811 (HAAS FIVE DIGITS)", 9811, None),
        (":1234", 1234, None),
        ("o1000", 1000, None),
    ],
)
def test_program_numbers_and_names(text: str, number: int | None, name: str | None) -> None:
    s = stmt(text)
    assert isinstance(s, ProgramStart)
    assert (s.number, s.name) == (number, name)


@pytest.mark.parametrize(
    ("name", "number"),
    [
        ("O8501.NC", 8501),
        ("o8501.nc", 8501),
        ("8501.nc", 8501),
        ("O09010", 9010),
        ("O09010.nc", 9010),
        ("O8501 DESCRIPTION.nc", 8501),
        ("O8501_ROUGH.nc", 8501),
        ("8501 ROUGH.nc", 8501),
        ("01000.nc", 1000),
        ("O12345678.nc", 12345678),
        ("/shop/progs/O8501.NC", 8501),
        ("C:\\progs\\O8501.NC", 8501),
        ("file:///shop/O8501%20ROUGH.nc", 8501),
        # Names that are not program numbers.
        ("04_variables.nc", None),
        ("2024-01-05.nc", None),
        ("PART2.nc", None),
        ("SAMPLE 3.nc", None),
        ("O8501X.nc", None),
        ("O8501.bak.nc", None),
        ("12345.nc", None),
        ("0.nc", None),
        ("O0.nc", None),
        ("prog.nc", None),
        ("untitled:Untitled-1", None),
    ],
)
def test_program_number_of_a_file_name(name: str, number: int | None) -> None:
    assert program_number_of_name(name) == number


def test_a_file_without_o_line_is_the_program_its_name_numbers() -> None:
    index = build_index(parse_text("%\n(ROUGH)\nG00 X100.\nM99\n%\n", "/p/O8501.NC"))
    [program] = index.programs
    assert (program.number, program.named_by_file, program.display_name) == (
        8501,
        "O8501.NC",
        "O8501",
    )
    assert program.first_line == 2 and program.header_line is None
    # An O line in the file wins over the name; text before it stays a fragment.
    index = build_index(parse_text("G00 X0\nO1234\nM99\n", "/p/O8501.NC"))
    assert [(p.number, p.named_by_file) for p in index.programs] == [(None, None), (1234, None)]
    # No number in the name: "(main)", as before.
    [program] = build_index(parse_text("G00 X0\nM30\n", "/p/part.nc")).programs
    assert (program.number, program.display_name) == (None, "(main)")


@pytest.mark.parametrize(
    ("text", "skip", "first"),
    [
        ("/1 G01 X10.", 1, "G"),
        ("/G00X0", 0, "G"),
        ("/ G68 X [ 0. ] R [ -90. ]", 0, "G"),
        ("/9M99", 9, "M"),
        ("/2 N10 G00 X0", 2, "G"),
    ],
)
def test_block_skip(text: str, skip: int, first: str) -> None:
    p = line(text)
    assert p.skip == skip
    assert isinstance(p.statement, NcStatement)
    assert p.statement.words[0].address == first


def test_block_skip_before_a_macro_statement() -> None:
    p = line("/#1=#1+1")
    assert p.skip == 0 and isinstance(p.statement, Assign)


@pytest.mark.parametrize(
    ("text", "seq", "kind"),
    [
        ("N10", 10, type(None)),
        ("N10 G00 X0", 10, NcStatement),
        ("N 333 G1 X1.", 333, NcStatement),
        ("N49END1", 49, End),
        ("N41GOTO#22", 41, Goto),
        ("N500#3000=1(D NOT SET RIGHT)", 500, Assign),
        ("N99999 M99", 99999, NcStatement),
        ("n20 g00 x0", 20, NcStatement),
    ],
)
def test_sequence_numbers(text: str, seq: int, kind: type) -> None:
    p = line(text)
    assert p.seq == seq
    assert isinstance(p.statement, kind)
    assert p.seq_span is not None
    assert p.text[p.seq_span.start : p.seq_span.end].replace(" ", "").upper() == f"N{seq}"


def test_lowercase_is_read_and_flagged() -> None:
    p = line("n10 g01 x10. f#9")
    assert p.has_lowercase
    assert p.seq == 10
    nc = p.statement
    assert isinstance(nc, NcStatement)
    assert [w.address for w in nc.words] == ["G", "X", "F"]
    assert all(w.address_lowercase for w in nc.words)
    upper = line("N10 G01 X10. F#9")
    assert not upper.has_lowercase


def test_lowercase_keywords() -> None:
    s = stmt("if[#1gt#2]goto10")
    assert isinstance(s, IfGoto) and isinstance(s.cond, Compare) and s.cond.op == "GT"
    s = stmt("#1=sin[#2]+atan[#3]/[#4]")
    assert isinstance(s, Assign)
    names = sorted(n.name for n in nodes(s.value) if isinstance(n, Call))
    assert names == ["ATAN", "SIN"]


def test_lowercase_only_in_comments_is_not_flagged() -> None:
    assert not line("G00 X100. (retract)").has_lowercase


def test_if_then_assignment_and_alarm() -> None:
    s = stmt("IF[#24EQ#0]THEN#3000=1(X NOT GIVEN)")
    assert isinstance(s, IfThen)
    assert s.then.target.number == 3000


def test_mixed_block() -> None:
    s = stmt("G01 X#1 #1=#1-2.")
    assert isinstance(s, Mixed)
    assert isinstance(s.nc, NcStatement) and isinstance(s.macro, Assign)


@pytest.mark.parametrize(
    "text",
    [
        "#1=#1-#11:",
        "IF[#1GT#2]",
        "WHILE[#1LT#2]",
        "G01 Z[#1+#17 F#9",
        "#1=[#2+1]]",
        "GOTO",
        "G1X--1.",
        "E.#234",
    ],
)
def test_rejected_blocks(text: str) -> None:
    p = GRAMMAR.parse_line(text)
    assert p.problem is not None
    assert p.statement is None
    assert 0 <= p.problem.span.start <= p.problem.span.end <= len(text)


# ---- spans -----------------------------------------------------------------------------------


def test_spans_of_an_if_goto() -> None:
    b = block("N45IF[#100GE#18]GOTO2")
    s = b.statement
    assert isinstance(s, IfGoto) and isinstance(s.cond, Compare)
    assert b.parsed.seq_span is not None
    assert b.source(b.parsed.seq_span) == "N45"
    assert b.source(s.span) == "IF[#100GE#18]GOTO2"
    assert b.source(s.cond.span) == "#100GE#18"
    assert b.source(s.cond.left.span) == "#100"
    assert b.source(s.cond.right.span) == "#18"
    assert b.source(s.goto.span) == "GOTO2"
    assert b.source(s.goto.target.span) == "2"


def test_spans_of_words() -> None:
    b = block("  G3I-[#106]Z[#5003-[#107*#17]]F#9 (HELIX)")
    nc = b.statement
    assert isinstance(nc, NcStatement)
    assert [b.source(w.span) for w in nc.words] == [
        "G3",
        "I-[#106]",
        "Z[#5003-[#107*#17]]",
        "F#9",
    ]
    assert b.source(nc.span) == "G3I-[#106]Z[#5003-[#107*#17]]F#9"
    (comment,) = b.parsed.comments
    assert b.source(comment.span) == "(HELIX)"
    assert comment.text == "HELIX"


def test_spans_with_spaces_inside_words() -> None:
    b = block("G01 X - 1. Z [ #1 + 2. ] S #[ #161 ]")
    nc = b.statement
    assert isinstance(nc, NcStatement)
    assert [b.source(w.span) for w in nc.words] == [
        "G01",
        "X - 1.",
        "Z [ #1 + 2. ]",
        "S #[ #161 ]",
    ]
    x = nc.words[1].value
    assert isinstance(x, Num) and x.value == -1.0 and x.text == "-1."


def test_spans_of_functions() -> None:
    b = block("#1=ATAN[#2]/[#3] (ANGLE)")
    s = b.statement
    assert isinstance(s, Assign) and isinstance(s.value, Call)
    assert b.source(s.span) == "#1=ATAN[#2]/[#3]"
    assert b.source(s.value.span) == "ATAN[#2]/[#3]"
    assert b.source(s.value.name_span) == "ATAN"
    assert [b.source(a.span) for a in s.value.args] == ["#2", "#3"]


def test_spans_of_loops() -> None:
    b = block("WHILE [#1 LT 5] DO2")
    s = b.statement
    assert isinstance(s, While)
    assert b.source(s.span) == "WHILE [#1 LT 5] DO2"
    assert b.source(s.id_span) == "2"
    b = block("N49END1")
    e = b.statement
    assert isinstance(e, End)
    assert b.source(e.span) == "END1"
    assert b.source(e.id_span) == "1"


def test_spans_are_in_characters_after_chinese_text() -> None:
    b = block("(中文注释 车螺纹) G00 X#15 Z[#2-1.]")
    nc = b.statement
    assert isinstance(nc, NcStatement)
    assert [b.source(w.span) for w in nc.words] == ["G00", "X#15", "Z[#2-1.]"]
    assert b.source(b.parsed.comments[0].span) == "(中文注释 车螺纹)"


def children(obj: object) -> Iterator[object]:
    """The nodes directly under ``obj``."""
    for f in dataclasses.fields(obj):  # type: ignore[arg-type]
        if f.name in ("span", "name_span", "id_span"):
            continue
        stack = [getattr(obj, f.name)]
        while stack:
            value = stack.pop()
            if isinstance(value, tuple):
                stack.extend(value)
            elif dataclasses.is_dataclass(value) and hasattr(value, "span"):
                yield value


@pytest.mark.parametrize(
    "text",
    [
        "IF[#1EQ#102]GOTO2010",
        "N45IF[#100GE#18]GOTO2",
        "WH[[#1GE#2]AND[#3GE#7]]DO1",
        "G3I-[#106]Z[#5003-[#107*#17]]F#9",
        "#104=FUP[#103/[#17*[-1.0]]]",
        "#1=ATAN[#2,#3]+POW[#4,2]-SQRT[ABS[#5]]",
        "#[#1+100]=#0",
        "IF[#24EQ#0]THEN#3000=1(X NOT GIVEN)",
        "IF [ [ ABS[ [ #174 - #177 ] * 2 ] ] - [ #[ #161 ] * #30 * 2 ] GT #173 ] GOTO5",
        "G65 P9726 X#24 Q#17 S #[ #161 + 1 ]",
        "G01 X#1 #1=#1-2.",
        "  #100 = [#100 - .100]   (STOCK)",
        "G91 A[360.0 / #2]",
    ],
)
def test_every_node_span_is_inside_its_parent(text: str) -> None:
    p = line(text)

    def check(node: object, outer: Span) -> None:
        span: Span = node.span  # type: ignore[attr-defined]
        assert outer.start <= span.start < span.end <= outer.end, (node, outer)
        source = text[span.start : span.end]
        assert source.strip() == source, node  # no surrounding blanks
        for child in children(node):
            check(child, span)

    assert p.statement is not None
    check(p.statement, Span(0, len(text)))


# ---- comments ------------------------------------------------------------------------------


def test_chinese_comments() -> None:
    p = line("#15 = 92.82 (#15 为车各层的 X 坐标 92.82 是车第一刀的初始值)")
    assert isinstance(p.statement, Assign)
    assert p.comments[0].text == "#15 为车各层的 X 坐标 92.82 是车第一刀的初始值"
    assert not p.has_lowercase
    p = line("IF[#15GT80]GOTO5 (如果#15 大于 80 即跳转 05 行 车削继续)")
    assert isinstance(p.statement, IfGoto)
    assert p.comments[0].text.startswith("如果")


def test_first_closing_parenthesis_ends_a_comment() -> None:
    """FANUC: comments do not nest; the first ')' ends the comment."""
    p = line("(G CODE FROM GROUP 1 (G0 - G1)")
    assert [c.text for c in p.comments] == ["G CODE FROM GROUP 1 (G0 - G1"]
    assert p.notes == ()
    assert p.statement is None
    p = line("(OLD (NOTE) G01 X5.")
    assert [c.text for c in p.comments] == ["OLD (NOTE"]
    assert isinstance(p.statement, NcStatement)
    assert [w.address for w in p.statement.words] == ["G", "X"]


def test_nested_comment_is_noted_with_the_column_fanuc_stops_at() -> None:
    p = line("(TOOL (T0101) BORING BAR)")
    assert [c.text for c in p.comments] == ["TOOL (T0101) BORING BAR"]
    (note,) = p.notes
    assert note.kind == "nested-comment"
    assert "column 13" in note.message
    assert "' BORING BAR)'" in note.message
    assert p.statement is None and p.problem is None


def test_unclosed_comment() -> None:
    p = line("G00 X100. (RETRACT")
    (comment,) = p.comments
    assert not comment.closed and comment.text == "RETRACT"
    assert [n.kind for n in p.notes] == ["unclosed-comment"]
    assert isinstance(p.statement, NcStatement)


def test_special_characters_inside_comments() -> None:
    p = line("G00 X1. (A;B #1=[2] <X> *) Z2. (#[#161+9] LOAD/ATAN)")
    assert [c.text for c in p.comments] == ["A;B #1=[2] <X> *", "#[#161+9] LOAD/ATAN"]
    assert p.notes == ()
    nc = p.statement
    assert isinstance(nc, NcStatement)
    assert [w.address for w in nc.words] == ["G", "X", "Z"]


# ---- end of block, tape mark, line ends, empty files --------------------------------------------


@pytest.mark.parametrize("text", ["G01 X10. F0.2", "IF[#1GT0]GOTO5", "#1=#1+1"])
def test_eob_semicolon_is_optional(text: str) -> None:
    plain = line(text)
    for variant in (text + ";", text + " ;", text + " ; ", text + ";;"):
        p = line(variant)
        assert p.statement == plain.statement
        assert p.notes == ()


def test_bare_eob_is_an_empty_block() -> None:
    for text in (";", " ; ", ";;"):
        p = line(text)
        assert p.is_empty and p.notes == ()


def test_text_after_eob_is_noted_and_not_read() -> None:
    p = line("G00 X100.; Z100.")
    assert [n.kind for n in p.notes] == ["text-after-eob"]
    nc = p.statement
    assert isinstance(nc, NcStatement)
    assert [w.address for w in nc.words] == ["G", "X"]


@pytest.mark.parametrize("text", ["%", " % ", "%;"])
def test_tape_mark(text: str) -> None:
    p = line(text)
    assert p.tape_mark and p.is_empty


def test_tape_mark_fused_to_a_block() -> None:
    p = line("M30%")
    assert p.tape_mark
    assert isinstance(p.statement, NcStatement)
    assert p.statement.words[0].address == "M"


def test_crlf_cr_and_lf_give_the_same_blocks() -> None:
    lines = ["%", "O1000 (MAIN)", "G00 X100.", "IF[#1GT0]GOTO10", "N10 M30", "%"]
    docs = [parse_text(sep.join(lines) + sep, parser=GRAMMAR) for sep in ("\n", "\r\n", "\r")]
    for doc in docs:
        assert [b.text for b in doc.blocks] == lines
    assert [b.parsed for b in docs[0].blocks] == [b.parsed for b in docs[1].blocks]
    assert [b.parsed for b in docs[0].blocks] == [b.parsed for b in docs[2].blocks]


def test_crlf_through_bytes() -> None:
    doc = parse_bytes(b"%\r\nO1\r\nG1X1.\r\nM30\r\n%\r\n")
    assert [b.text for b in doc.blocks] == ["%", "O1", "G1X1.", "M30", "%"]
    assert doc.encoding == "utf-8"


def test_no_newline_at_the_end() -> None:
    doc = parse_text("O1\nG00 X0\n%", parser=GRAMMAR)
    assert [b.text for b in doc.blocks] == ["O1", "G00 X0", "%"]
    assert doc.blocks[-1].parsed.tape_mark


@pytest.mark.parametrize("text", ["", "\n", "   \n\n", "%\n%\n"])
def test_empty_file(text: str) -> None:
    doc = parse_text(text, parser=GRAMMAR)
    assert all(b.parsed.is_empty for b in doc.blocks)
    assert analyse(text).diagnostics == []
    assert parse_bytes(text.encode()).encoding == "utf-8"


def test_empty_bytes() -> None:
    doc = parse_bytes(b"")
    assert len(doc.blocks) <= 1
    assert all(b.parsed.is_empty for b in doc.blocks)


# ---- a large file ------------------------------------------------------------------------------


def test_100000_lines() -> None:
    rows = ["%", "O1000 (LARGE PROGRAM)"]
    body = [
        "N{n} G01 X{a}.5 Z-{b}. F0.2",
        "#{v}=#{v}+{a}.5 (STEP)",
        "IF[#{v}GT{b}]GOTO{n}",
        "G00 X#{l} Z[#{l}-{a}.]",
        "WHILE[#1LT10]DO1",
        "#1=#1+1",
        "END1",
        "G02 X{a}. Z-{b}. R{r}.",
    ]
    i = 0
    while len(rows) < 99_999:
        pattern = body[i % len(body)]
        rows.append(
            pattern.format(
                n=i % 9000 + 1, a=i % 97, b=i % 89, v=100 + i % 40, l=i % 33 + 1, r=i % 7 + 1
            )
        )
        i += 1
    rows.append("%")
    text = "\n".join(rows) + "\n"
    doc = parse_text(text, parser=BlockParser())
    assert len(doc.blocks) == 100_000
    assert not [b for b in doc.blocks if b.parsed.problem is not None]
    loops = sum(1 for k in range(i) if k % len(body) == body.index("WHILE[#1LT10]DO1"))
    assert sum(isinstance(b.statement, While) for b in doc.blocks) == loops


# ---- bytes and encodings -----------------------------------------------------------------------

CHINESE = (
    "O4009 (外螺纹 M50X3 主程序)\n#1=50. (螺纹公称直径)\nG00 X[#1+10.] Z10. (快速定位到起点)\nM30\n"
)
JAPANESE = "O1000 (ねじ切り加工プログラム)\nG00 X100. Z100. (工具を逃がす)\nM30\n"


def comment_texts(doc: object) -> list[str]:
    return [c.text for b in doc.blocks for c in b.parsed.comments]  # type: ignore[attr-defined]


def test_gb18030_comments() -> None:
    doc = parse_bytes(CHINESE.encode("gb18030"))
    assert doc.encoding == "gb18030"
    assert doc.decode_note is None  # a clean reading in a shop's encoding: nothing to say
    assert comment_texts(doc) == ["外螺纹 M50X3 主程序", "螺纹公称直径", "快速定位到起点"]
    assert not [b for b in doc.blocks if b.parsed.problem is not None]


def test_shift_jis_comments() -> None:
    doc = parse_bytes(JAPANESE.encode("shift_jis"))
    assert doc.encoding == "shift_jis"
    assert doc.decode_note is None
    assert comment_texts(doc) == ["ねじ切り加工プログラム", "工具を逃がす"]


def test_utf8_with_and_without_bom() -> None:
    for data in (CHINESE.encode(), b"\xef\xbb\xbf" + CHINESE.encode()):
        doc = parse_bytes(data)
        assert doc.encoding == "utf-8" and doc.decode_note is None
        assert doc.blocks[0].text == "O4009 (外螺纹 M50X3 主程序)"


def test_bytes_no_legacy_encoding_takes() -> None:
    decoded = decode_bytes(b"O1 (\xff\xfe\xff)\nM30\n")
    assert decoded.encoding in ("gb18030", "shift_jis", "cp1252", "latin-1")
    assert decoded.text.startswith("O1 (")
    assert decoded.note is not None and "encoding is unclear" in decoded.note


# The start of an ELF executable: NUL bytes from the fifth byte on.
ELF_START = b"\x7fELF\x02\x01\x01\x00\x00\x00\x00\x00\x00\x00\x00\x00\x02\x00>\x00"


def test_binary_bytes_are_not_read_as_a_program() -> None:
    data = ELF_START + b"O1000\nG00 X1.\nM30\n" * 40
    doc = parse_bytes(data, "a.out.nc")
    assert doc.encoding == BINARY and [b.text for b in doc.blocks] == [""]
    assert doc.decode_note is not None
    assert doc.decode_note.startswith("not a program text: it holds NUL bytes")
    assert "(the first at byte 8)" in doc.decode_note
    assert not build_index(doc).programs


def test_control_codes_make_bytes_binary_without_a_nul() -> None:
    noise = bytes(range(1, 32)) * 4  # 124 bytes, 84 of them control codes no text has
    reason = not_text_reason(noise + b"O1000\nM30\n" * 100)
    assert reason is not None and "84 of its first 1,124 bytes are control codes" in reason
    # Below the share (5%), the same controls are read as (bad) text.
    assert not_text_reason(noise + b"O1000\nM30\n" * 300) is None


@pytest.mark.parametrize(
    ("bom", "name"),
    [(b"\xff\xfe", "UTF-16"), (b"\xfe\xff", "UTF-16"), (b"\xff\xfe\x00\x00", "UTF-32")],
)
def test_utf16_and_utf32_are_not_read(bom: bytes, name: str) -> None:
    reason = not_text_reason(bom + "O1000\nM30\n".encode("utf-16-le"))
    assert reason is not None and f"it is {name} text" in reason


def test_text_controls_and_a_tape_leader_are_text() -> None:
    """Tab, line ends, form feed, the tape reader's DC1-DC4 and SUB are text; the NULs of a
    punched tape's leader and trailer (blank tape) do not make the file binary."""
    program = b"%\x12\r\nO1000\t(X)\nG00 X1.\x0c\nM30\x14\n%\n\x1a"
    assert not_text_reason(program) is None
    assert not_text_reason(b"\x00" * 200 + program + b"\x00" * 200) is None
    assert not_text_reason(b"\x00" * 200 + program + b"\x00" + program) is not None
    assert not_text_reason(b"") is None and not_text_reason(b"\x00" * 10) is None
    assert decode_bytes(b"\x00" * 20 + program).encoding == "utf-8"


def test_workspace_says_a_file_is_not_text() -> None:
    from fanuc_macro.workspace import Workspace

    workspace = Workspace()
    workspace.add_bytes("bin.nc", ELF_START + b"O1000\nM30\n")
    workspace.add_bytes("prog.nc", b"O2000\nM30\n")
    note = workspace.not_text("bin.nc")
    assert note is not None and "NUL bytes" in note
    assert workspace.not_text("prog.nc") is None and workspace.not_text("other.nc") is None
    assert sorted(workspace.program_numbers()) == [2000]
    [only] = analyse("", "bin.nc", doc=workspace.document("bin.nc")).diagnostics
    assert (only.code, only.line, only.message) == ("MB007", 0, note)


def test_random_bytes_never_raise() -> None:
    rng = random.Random(20240611)
    nc_bytes = b"GXZNO#[]()=;%/-+. 0123456789IFGOTOWHILEDOEND\n\r\t"
    for i in range(300):
        size = rng.randrange(0, 400)
        if i % 3 == 0:
            data = bytes(rng.randrange(256) for _ in range(size))
        elif i % 3 == 1:
            data = bytes(rng.choice(nc_bytes) for _ in range(size))
        else:  # a program with legacy-encoded comment bytes and random noise
            data = CHINESE.encode("gb18030")[: size % 80] + bytes(
                rng.randrange(256) for _ in range(size % 50)
            )
        doc = parse_bytes(data, f"random{i}.nc")
        assert doc.encoding in ("utf-8", "gb18030", "shift_jis", "cp1252", "latin-1", BINARY)
        assert len(doc.blocks) == doc.line_count
        for b in doc.blocks:
            assert (b.parsed.problem is None) or (b.parsed.statement is None)


@pytest.mark.parametrize(
    "text",
    ["N" + "9" * 400, "/" + "9" * 400 + " X1.", "O" + "9" * 400, "G01 X" + "9" * 400],
    ids=["N", "block-skip", "O", "X"],
)
def test_numbers_too_large_for_a_float_never_raise(text: str) -> None:
    """A corrupt file may hold any digits: the reader reports, it does not crash."""
    doc = parse_bytes(text.encode("ascii"))
    assert len(doc.blocks) == 1
    assert GRAMMAR.parse_line(text).text == text


@pytest.mark.parametrize(
    "text",
    ["C-99999999999999", "X+1.555555555555 Y1", "X - 99999999999999", "X[1] Y-9999999999999"],
)
def test_a_number_too_long_is_named_without_its_sign_as_the_grammar_names_it(text: str) -> None:
    got = BlockParser().parse_line(text).problem
    assert got is not None and got == GRAMMAR.parse_line(text).problem
    assert "the number 9" in got.message or "the number 1" in got.message


# ---- the fast path gives what the grammar gives -----------------------------------------------


def program_lines() -> list[str]:
    files = sorted(SEEDS.glob("*.nc"))
    if CORPUS.is_dir():
        files += sorted(p for p in CORPUS.iterdir() if p.suffix not in (".md", ".tsv"))
    assert files
    out: list[str] = []
    for path in files:
        out.extend(split_lines(decode_bytes(path.read_bytes()).text))
    return out


def random_nc_lines(count: int, seed: int) -> list[str]:
    rng = random.Random(seed)
    addresses = "ABCDEFGHIJKLMPQRSTUVWXYZ"

    def space() -> str:
        return rng.choice(["", "", "", " ", "  ", "\t"])

    def number() -> str:
        digits = "".join(rng.choice("0123456789") for _ in range(rng.randint(1, 6)))
        return rng.choice(
            [digits, digits + ".", "." + digits, digits[:2] + "." + digits[2:], "00" + digits]
        )

    def value() -> str:
        k = rng.randrange(12)
        if k < 6:
            return rng.choice(["", "", "-", "+", "- "]) + space() + number()
        if k < 8:
            return "#" + space() + str(rng.randint(0, 9999))
        if k < 9:
            return "-" + space() + "#" + str(rng.randint(1, 999))
        if k < 10:
            return "+#" + str(rng.randint(1, 99))
        if k < 11:
            return "[#" + str(rng.randint(1, 33)) + "+1.]"
        return rng.choice(["", ".", "-", "--1", "#", "1.2.3"])  # rejected by both

    out: list[str] = []
    for _ in range(count):
        parts: list[str] = []
        if rng.random() < 0.1:
            parts.append("/" + rng.choice(["", "1", "9", " ", " 2"]))
        if rng.random() < 0.3:
            parts.append(rng.choice("Nn") + space() + str(rng.randint(0, 99999)))
        for _ in range(rng.randint(0, 6)):
            letter = rng.choice(addresses)
            parts.append((letter.lower() if rng.random() < 0.15 else letter) + space() + value())
        text = "".join(p + space() for p in parts)
        if rng.random() < 0.05:
            text = " " + text
        if rng.random() < 0.05:
            text += rng.choice(["(C)", ";", " ;", "%", "(NOTE"])
        out.append(text)
    return out


def test_fast_path_equals_grammar_on_program_lines() -> None:
    grammar, fast = BlockParser(use_fast_path=False), BlockParser()
    different = [t for t in program_lines() if grammar.parse_line(t) != fast.parse_line(t)]
    assert different == []


def test_fast_path_equals_grammar_on_random_lines() -> None:
    grammar, fast = BlockParser(use_fast_path=False), BlockParser()
    lines = random_nc_lines(4000, seed=1234)
    different = [t for t in lines if grammar.parse_line(t) != fast.parse_line(t)]
    assert different == []
    # The comparison means something only if both paths are exercised: many plain blocks the
    # fast path takes, and blocks that it leaves to the grammar, some of them rejected.
    taken = sum(fast_parse(cut_comments(t).code) is not None for t in lines)
    rejected = sum(grammar.parse_line(t).problem is not None for t in lines)
    assert taken > len(lines) // 3
    assert rejected > 100


def test_fast_parse_result_equals_the_grammar_fields() -> None:
    grammar = BlockParser(use_fast_path=False)
    seen = 0
    for text in random_nc_lines(1500, seed=99):
        if any(ch in text for ch in "(;%"):
            continue
        fast = fast_parse(text)
        if fast is None:
            continue
        seen += 1
        p = grammar.parse_line(text)
        assert p.problem is None, text
        assert fast == (p.skip, p.seq, p.seq_span, p.statement), text
    assert seen > 500


@pytest.mark.parametrize(
    "text",
    [
        "M98 P1000",
        "N20 m98 p2000 L3",
        "G65 P9010 A1. B2.",
        "G66 P9011",
        "G66.1 P9011",
        "M99",
        "M - 99",
        "M97 P100",
        "G 65 P#1",
        "M#98",
        "G01 M98. P10",
        "G00 X1. M30",
        "M98P1000 (SUB)",
        "M99;",
        "% M99",
    ],
)
def test_fast_path_finds_the_calls_the_index_looks_for(text: str) -> None:
    grammar, fast = BlockParser(use_fast_path=False), BlockParser()
    assert fast.parse_line(text) == grammar.parse_line(text)


@pytest.mark.parametrize(
    "text",
    ["#1=2", "IF[#1GT0]GOTO5", "GOTO5", "X[#1+1.]", "O1000", "WHILE[#1LT2]DO1", "X+#1", "G1 X1.E"],
)
def test_fast_parse_leaves_other_blocks_to_the_grammar(text: str) -> None:
    assert fast_parse(text) is None


@pytest.mark.parametrize("text", ["G01 X10. Z-5. F0.2", "N10 G00 X-#24", "/1 M05", "x1.y2."])
def test_fast_parse_takes_plain_blocks(text: str) -> None:
    assert fast_parse(text) is not None


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("G01Z-5,0F100", "FANUC's decimal point is '.'; write -5.0"),
        ("G01X10.0.0", "a second decimal point at column 9, in '10.0.0'"),
        ("G01X-50.0 30.0", "the number '30.0' at column 11 has no address letter"),
        ("00001(ISHII)", "the letter O typed as the digit 0? A program number is written O0001"),
        ("01X50.Y-50.", "(G01 meant, or the letter O typed as the digit 0?)"),
        ("\uff2791\uff2728Z0", "full-width '\uff27' (U+FF27) at column 1"),
        ("#3000=91\xa0(D INPUT MISSING)", "no-break space '\\xa0' (U+00A0) at column 9"),
        ("\u3000", "ideographic space '\\u3000' (U+3000) at column 1"),
        ("  \u3000 (A COMMENT)", "ideographic space '\\u3000' (U+3000) at column 3"),
        ("G01X10.*#1Y5.", "write X[10.*#1], not X10.*#1"),
        ("G01X50*COS[#8]Y-50.", "write X[50*COS[#8]], not X50*COS[#8]"),
        ("G00XCOS[45]", "write X[COS[...]], not XCOS[...]"),
        ("G01XY0", "address X at column 4 has no value"),
        ("WHILE[[#1LE10]DO1", "'[' at column 6 is not closed before 'DO'"),
        ("G00X[COS[180]]]", "']' at column 15 closes no '['"),
        ("WHILE[[#1=10]AND[#2<>5.0]]DO1", "'=' at column 10 is no comparison on FANUC: write EQ"),
        ("WHIL[#1LE10]DO1", "'WHIL' at column 1 is no FANUC word: WHILE?"),
        ("#10", "#10=<value> assigns it"),
    ],
)
def test_typing_mistakes_are_named(text: str, message: str) -> None:
    problem = BlockParser().parse_line(text).problem
    assert problem is not None and problem.dialect is None
    assert message in problem.message


@pytest.mark.parametrize(
    ("text", "dialect"),
    [
        ("%@MACRO;", "LNC/Syntec"),
        ("#24:=#1341+5;", "LNC/Syntec"),
        ("IF(#17<>#0)THEN", "LNC/Syntec"),
        ("END_IF;", "LNC/Syntec"),
        ("WAIT();", "LNC/Syntec"),
        ("PROC MS140", "Siemens Sinumerik"),
        ("DEF REAL START_X", "Siemens Sinumerik"),
        ("IF($AC_MEA[1]==1) GOTOF GRESKA", "Siemens Sinumerik"),
        ("N001 R20=20", "Siemens Sinumerik"),
        ("N250 @100 K-220", "Siemens Sinumerik"),
        ("o<probe> sub", "LinuxCNC"),
        ("O100 if [#<_task> EQ 0]", "LinuxCNC"),
        ("IF #1>0 GOTO1", "DDCS"),
        ("VC1=0", "Okuma OSP"),
        ("VS12=5", "Okuma OSP"),
        ("G00 X[VC1*10.] Z5.", "Okuma OSP"),
        ("NLOOP G01 X10.", "Okuma OSP"),
        ("GOTO NEND", "Okuma OSP"),
        ("IF [#1 LT 10] NLOOP", "Okuma OSP"),
        ("CALL OSUB", "Okuma OSP"),
        ("H1=0.216", "wire EDM"),
        ("H000=+00000000", "wire EDM"),
        ("E001=", "wire EDM"),
        ("G97 S1=500 M3", "Mitsubishi/Citizen"),
        ("Q1=12", "not FANUC (dialect not recognised)"),
        ("IF[#1<=#2]GOTO10", "not FANUC (dialect not recognised)"),
    ],
)
def test_dialect_forms_are_named(text: str, dialect: str) -> None:
    problem = BlockParser().parse_line(text).problem
    assert problem is not None and problem.dialect == dialect


@pytest.mark.parametrize(
    ("text", "found"),
    [
        ("VS1=5", "'VS1'"),  # not Citizen's S1= spindle selection
        ("POS1=5", "address P at column 1 has no value"),  # a typing mistake, not Citizen's
        ("H1=0.216", "'H1='"),
        ("GOTO NEND", "'GOTO NEND'"),
    ],
)
def test_dialect_messages_quote_what_they_name(text: str, found: str) -> None:
    problem = BlockParser().parse_line(text).problem
    assert problem is not None and found in problem.message
    assert "Mitsubishi" not in (problem.dialect or "")


def test_haas_only_codes_in_a_fanuc_block() -> None:
    text = "O1000\nG103 P1\nG154 P10\nM109 P501\n#1=#20001\nM109\nG154\n#2=#10001\nM30\n"
    found = {d.line: d.message for d in analyse(text).diagnostics if d.code == "MB002"}
    assert sorted(found) == [1, 2, 3, 4]
    assert found[1].startswith("Haas: G103 (block look-ahead limit)")
    assert found[2].startswith("Haas: G154 P<n>") and "G54.1 P<n>" in found[2]
    assert found[3].startswith("Haas: M109 P<n>")
    assert found[4].startswith("Haas NGC: #20001 reads Haas setting 1")


def test_an_okuma_file_is_one_diagnostic_that_lists_its_rejected_blocks() -> None:
    text = "O1234\nVC1=0\nG00 X10.\nX#1+1.\nNLOOP VC1=VC1+1\nM02\n"
    rejected = [d for d in analyse(text).diagnostics if d.code in ("MB001", "MB002")]
    assert [d.line for d in rejected] == [0]
    assert rejected[0].message.startswith(
        "a program written for Okuma OSP (VC/VS variable assignment on line 2)"
    )
    assert [r.line for r in rejected[0].related] == [1, 3, 4]
    assert all(r.message.startswith("Okuma OSP") for r in rejected[0].related)


def test_a_file_of_another_dialect_is_one_diagnostic_on_its_first_line() -> None:
    text = "PROC MS140\n;COMMENT\nG0 X10.\nif(A<>0)\nelse\nendif\nM17\n"
    diags = analyse(text).diagnostics
    rejected = [(d.line, d.code) for d in diags if d.code in ("MB001", "MB002", "MB005", "MB008")]
    assert rejected == [(0, "MB002")]
    whole = next(d for d in diags if d.code == "MB002")
    assert "Siemens" in whole.message and "5 of its blocks are" in whole.message
    assert [r.line for r in whole.related] == [0, 1, 3, 4, 5]
    assert not [d for d in diags if "Haas" in d.message]


def test_the_whole_file_diagnostic_skips_a_leading_tape_mark() -> None:
    text = "%\n\nO1234\nVC1=0\nM02\n%\n"
    whole = [d for d in analyse(text).diagnostics if d.code == "MB002"]
    assert [d.line for d in whole] == [2]
    assert "1 of its blocks is in forms FANUC rejects (line 4)" in whole[0].message


def test_a_fanuc_file_keeps_its_own_findings() -> None:
    """One C comparison does not make a FANUC program another control's."""
    text = "O1000\nIF[#1<=#2]GOTO10\n;\nN10 M30\n"
    codes = [(d.line, d.code) for d in analyse(text).diagnostics if d.code.startswith("MB00")]
    assert codes == [(1, "MB002")]


@pytest.mark.parametrize(
    ("text", "assigns", "seq"),
    [
        ("#5=#4*2:", 5, None),  # ':' typed for ';'
        ("N10 #5 = [#4*2", 5, 10),  # a '[' not closed
        ("#1=ABC[2]", 1, None),  # an unknown function
        ("IF[#1GT2]THEN#5=3:", 5, None),
        ("/N20#100=#4 +", 100, 20),
        ("N30 G01 X[1", None, 30),
        ("#1==2", None, None),  # a comparison typed where an assignment stands: not one
        ("#0=1:", None, None),  # #0 is never set
        ("G01 X10.*#1", None, None),
    ],
)
def test_a_rejected_block_keeps_what_it_plainly_says(
    text: str, assigns: int | None, seq: int | None
) -> None:
    parsed = BlockParser().parse_line(text)
    assert parsed.statement is None and parsed.problem is not None
    assert parsed.failed_assignment == assigns
    assert parsed.seq == seq


def test_no_cascade_after_a_syntax_error() -> None:
    text = "O1\nG65 P2 A1.\nM30\nO2\nGOTO10\nN10 #5=#1*2:\n#6=#5+1.\nG00 X#5 Z#6\nM99\n"
    codes = [(d.line + 1, d.code) for d in analyse(text, "typo.nc").diagnostics]
    assert codes == [(6, "MB001")]  # no MB101 for N10, no MB901 for #5


def test_a_new_version_keeps_the_blocks_of_the_lines_an_edit_did_not_touch() -> None:
    parser = BlockParser()
    lines = [f"G01 X{i}. Z-{i}." for i in range(50)]
    old = parse_text("\n".join(lines), "file:///v.nc", parser)
    edited = list(lines)
    edited[20] = "G01 X0.5"
    new = parse_text("\n".join(edited), "file:///v.nc", parser, previous=old)
    kept = zip(old.blocks, new.blocks, strict=True)
    assert all(a is b for i, (a, b) in enumerate(kept) if i != 20)
    assert new.blocks[20].text == "G01 X0.5" and new.blocks[20].line == 20
    edited[10:10] = ["M08", "M09"]  # lines added: those after them are new blocks, renumbered
    moved = parse_text("\n".join(edited), "file:///v.nc", parser, previous=new)
    assert all(a is b for a, b in zip(new.blocks[:10], moved.blocks[:10], strict=True))
    assert [b.line for b in moved.blocks] == list(range(52))
    assert [b.text for b in moved.blocks] == edited
    assert moved.blocks[30].parsed is new.blocks[28].parsed
    assert parse_text("\n".join(edited), "file:///v.nc", parser).blocks == moved.blocks


def test_a_line_of_dos_end_of_file_marks_is_an_empty_block() -> None:
    """Ctrl-Z (0x1A) after the closing % of a file saved under DOS: the sending program stops at
    it, the control never reads it."""
    parsed = BlockParser().parse_line("\x1a")
    assert parsed.is_empty and parsed.problem is None
    assert BlockParser().parse_line("G00\x1a").problem is not None  # inside a block: rejected


def test_a_line_of_one_comment_is_cut_as_the_general_scan_cuts_it() -> None:
    """The quick cut of a line with one '(' (no ';' or '%') gives what the scan of every
    comment, end of block and tape mark gives, on the corpus and on random lines."""
    from fanuc_macro.syntax.lines import _cut_comments

    rng = random.Random(11)
    pieces = ["G01", " X1.", "(", ")", "(a)", "#1", "=", "[", "]", "注释", " ", "b", "))", "(("]
    lines = [*program_lines(), *("".join(rng.choices(pieces, k=6)) for _ in range(5000))]
    quick = 0
    for line in lines:
        assert cut_comments(line) == _cut_comments(line), line
        quick += line.count("(") == 1 and ";" not in line and "%" not in line
    assert quick > 1000
