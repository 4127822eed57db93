"""The document-wide rules' scans kept from one analysis to the next, and the line rules' fast
way through blocks of plain NC words: the same results as reading every line, for work that
follows the edit, not the document (counted, not timed)."""

from __future__ import annotations

import dataclasses
import random
from collections.abc import Callable
from typing import Any

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.line_maps import LineMap
from fanuc_macro.program.index import build_index
from fanuc_macro.rules import expressions, flow, variable_use
from fanuc_macro.rules.context import RuleContext
from fanuc_macro.syntax.parser import default_parser, parse_text, statements_of
from fanuc_macro.syntax.tree import Bracket, Call, Document, NcStatement, ParsedLine, Var
from fanuc_macro.syntax.walk import (
    _variables,
    bracket_depth,
    plain_variables,
    subexpressions,
    top_expressions,
    variables,
)

LINES = [
    "G01 X1. Y2.",
    "#201=#1+1",
    "(COMMENT)",
    "",
    "G00 X-#250 Z#3",
    "IF[#1GT2]GOTO10",
    "N10 #5=#300*2",
    "G01 X[#1+2.] Y-#2",
    "WHILE[#1 LT 3] DO1",
    "X@@ GOTO 5",
    "END1",
    "M30",
]


def _text(rng: random.Random, n: int) -> list[str]:
    return [rng.choice(LINES) for _ in range(n)]


def _piece(parsed: ParsedLine) -> tuple[str, ...]:
    """A line's variables as written: empty for most lines."""
    return tuple(parsed.text[v.span.start : v.span.end] for v in _all_variables(parsed))


def _all_variables(parsed: ParsedLine) -> list[object]:
    return [v for st in statements_of(parsed.statement) for v in variables(st)]


class Counter:
    """A piece function that counts its calls."""

    def __init__(self, piece: Callable[[ParsedLine], Any] = _piece) -> None:
        self.piece = piece
        self.calls = 0

    def __call__(self, parsed: ParsedLine) -> Any:
        self.calls += 1
        return self.piece(parsed)


def _fresh(doc: Document) -> tuple[list[int], list[tuple[str, ...]]]:
    found = [(b.line, _piece(b.parsed)) for b in doc.blocks]
    return [ln for ln, p in found if p], [p for _, p in found if p]


def test_a_scan_after_edits_equals_a_fresh_one_and_reads_only_the_edited_lines() -> None:
    rng = random.Random(7)
    parser = default_parser()
    counted = Counter()
    scan = LineMap(counted)
    lines = _text(rng, 3000)
    doc = parse_text("\n".join(lines), "file:///a.nc", parser)
    scan(doc)
    for _ in range(60):
        kind = rng.choice(["change", "insert", "delete", "paste"])
        at = rng.randrange(len(lines))
        if kind == "change":
            lines[at] = rng.choice(LINES)
            edited = 1
        elif kind == "insert":
            lines[at:at] = _text(rng, rng.randint(1, 3))
            edited = at
        elif kind == "delete":
            del lines[at : at + rng.randint(1, 3)]
            edited = 0
        else:
            lines[at:at] = _text(rng, rng.randint(20, 40))
            edited = 40
        new = parse_text("\n".join(lines), "file:///a.nc", parser, previous=doc)
        before = counted.calls
        scanned = scan(new)
        assert (scanned.lines, scanned.values) == _fresh(new)
        if kind in ("change", "paste"):
            assert counted.calls - before <= edited
        else:  # a line kept is the same parse wherever it stands now
            assert counted.calls - before <= 3
        doc = new


def test_a_scan_of_another_document_under_the_same_name_is_not_stale() -> None:
    parser = default_parser()
    scan = LineMap(_piece)
    a = parse_text("#201=1\nG01 X1.\n#5=#300", "file:///a.nc", parser)
    b = parse_text("G01 X2.\n#202=1\nG01 X3.\n#7=1", "file:///a.nc", parser)
    assert scan(a).lines == [0, 2]
    scanned = scan(b)
    assert (scanned.lines, scanned.values) == ([1, 3], [("#202",), ("#7",)])
    assert scan(a).values == [("#201",), ("#5", "#300")]


def _dead_stretches_by_every_line(
    ctx: RuleContext, first: int, end: int, runs: dict[int, int]
) -> list[tuple[int, int]]:
    """The stretches as a walk over every line finds them."""
    found: list[tuple[int, int]] = []
    start: int | None = None
    last = first
    for line in range(first, end + 1):
        block = ctx.doc.blocks[line] if line < end else None
        live = block is None or block.statement is None or line in runs
        if block is not None and block.statement is None and start is not None:
            continue
        if not live:
            if start is None:
                start = line
            last = line
        elif start is not None:
            found.append((start, last))
            start = None
    return found


def test_dead_stretches_from_the_gaps_of_the_lines_run_equal_a_walk_over_every_line() -> None:
    rng = random.Random(3)
    text = "\n".join(["O1000", *_text(rng, 400), "M30"])
    doc = parse_text(text, "file:///d.nc", default_parser())
    n = len(doc.blocks)
    for trial in range(300):
        density = rng.choice([0.0, 0.3, 0.9, 0.99, 1.0])
        runs = {ln: 1 for ln in range(n + 5) if rng.random() < density}
        ctx = RuleContext(doc, build_index(doc))
        first = rng.randrange(n)
        end = rng.randrange(first, n + 1) if trial % 3 else n
        walked = _dead_stretches_by_every_line(ctx, first, end, runs)
        assert flow._dead_stretches(ctx, first, end, runs) == walked
        assert flow._stretches_between(ctx, runs, first, end) == walked  # an edit's window


def test_plain_words_give_the_variables_and_depths_of_the_walks() -> None:
    texts = [*LINES, "G01 X#1 Y-#2 Z+#3 F#[#4]", "G01 X- # 5 Y.5 Z-.5", "M98 P#1 H#2"]
    for text in texts:
        parsed = default_parser().parse_lines([text], 1000)[0]
        for statement in statements_of(parsed.statement):
            assert list(variables(statement)) == list(_variables(statement))
            for expr in top_expressions(statement):
                assert bracket_depth(expr) == _depth_by_walk(expr)
                assert next(iter(subexpressions(expr))) is expr
            if isinstance(statement, NcStatement) and "[" not in text:
                assert plain_variables(statement) == list(_variables(statement))


def _depth_by_walk(expr: object) -> int:
    if isinstance(expr, Bracket):
        return 1 + _depth_by_walk(expr.inner)
    if isinstance(expr, Call):
        return 1 + max((_depth_by_walk(a) for a in expr.args), default=0)
    if isinstance(expr, Var):
        return 0 if expr.index is None else 1 + _depth_by_walk(expr.index)
    children = [getattr(expr, name) for name in ("left", "right", "operand") if hasattr(expr, name)]
    return max((_depth_by_walk(c) for c in children), default=0)


def test_a_one_number_edit_of_a_long_program_scans_one_line_per_rule() -> None:
    """After an edit, MB303's, MB901's and the flow rules' scans read the edited line, not the
    document: their pieces are computed once."""
    cfg = dataclasses.replace(Config(), max_blocks=10**7, max_file_size=10**9)
    body = [
        f"#{1 + i % 30}=#101*{i % 7 + 1}. (C {i})\nG01 X[#100+{i % 5}.] Z{i}." for i in range(3000)
    ]
    text = "\n".join(["O1000", "#100=1.", "#101=2.", *body, "#250=1", "M30"])
    uri = "file:///long.nc"
    first = analyse(text, uri, cfg)
    edited = text.replace("#101*3.", "#101*13.", 1)
    doc = parse_text(edited, uri, default_parser(), previous=first.doc)
    scans: list[LineMap[Any]] = [
        expressions._extended_lines,
        variable_use._local_reads,
        flow._unreadable_lines,
    ]
    originals = [scan._look for scan in scans]
    counters = [Counter(piece) for piece in originals]
    for scan, counter in zip(scans, counters, strict=True):
        scan._look = counter
    try:
        second = analyse(edited, uri, cfg, doc=doc, previous_facts=first.facts)
    finally:
        for scan, piece in zip(scans, originals, strict=True):
            scan._look = piece
    assert [c.calls for c in counters] == [1, 1, 1]
    fresh = analyse(edited, uri, cfg)
    assert second.diagnostics == fresh.diagnostics
    assert any(d.code == "MB303" for d in fresh.diagnostics)


def test_the_line_rules_check_blocks_of_plain_words_without_walking_them(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A CAM file's blocks (G01 X Y Z with numbers, #n or -#n) need no expression walk: the
    line rules give their findings from the words themselves."""
    from fanuc_macro.rules import LINE_CHECKS, dialect
    from fanuc_macro.syntax import walk

    cam = [  # as bench/bench_lsp.py's cam_program writes them
        f"G01 X{i / 1000:.3f} Y{(i * 7919) % 100_003 / 1000:.3f} Z-{i % 977 / 100:.2f}"
        for i in range(500)
    ]
    text = "\n".join(["O1234", *cam, "G01 X#1 Y-#2 Z#34", "M98 H5", "G103 P1", "X#20001", "M30"])
    parsed = [b.parsed for b in parse_text(text, "file:///cam.nc", default_parser()).blocks]
    plain = [
        p
        for p in parsed
        if isinstance(p.statement, NcStatement) and plain_variables(p.statement) is not None
    ]
    assert len(plain) > 500
    expected = [[list(check(p)) for check in LINE_CHECKS] for p in plain]
    assert sum(len(f) for found in expected for f in found) == 4  # MB302, three MB002
    for p in plain:  # the same as the way through every statement
        assert list(dialect.check_line(p)) == list(dialect._check_line(p))
        assert list(expressions.check_line(p)) == list(expressions._check_line(p))
    walked = [0]

    def counted(expr: object) -> object:
        walked[0] += 1
        raise AssertionError("walked")

    monkeypatch.setattr(walk, "subexpressions", counted)
    monkeypatch.setattr(walk, "top_expressions", counted)
    assert [[list(check(p)) for check in LINE_CHECKS] for p in plain] == expected
    assert walked[0] == 0


def test_the_plain_words_way_gives_the_general_way_s_findings_on_every_corpus_line() -> None:
    """The line rules' way for blocks of plain words (dialect and expressions) against the way
    through every statement, on each line of the seeds and of the corpus of real programs."""
    from pathlib import Path

    from fanuc_macro.rules import dialect
    from fanuc_macro.syntax.lines import decode_bytes, split_lines

    root = Path(__file__).resolve().parents[1]
    corpus = root.parent / "shared" / "corpus"
    if not corpus.is_dir():
        pytest.skip("the corpus of real programs (../shared/corpus) is not beside the checkout")
    files = sorted((root / "tests" / "fixtures" / "seeds").glob("*.nc"))
    files += sorted(p for p in corpus.iterdir() if p.suffix not in (".md", ".tsv"))
    parser = default_parser()
    plain = 0
    # Haas numbers and codes, variables no control has and read-only targets in assignments and
    # bracketed words, which take a way of their own.
    extra = ["#20001=#1", "#5=#1.5+#20002", "G01 X[#30001.5+1.] M97 P1", "G103 X[#1] M98 H2"]
    extra += ["#0=[#1]", "#3000=1", "#5021=#50+1.", "#50=[#1+#60]", "G01 X[#40+1] Z[#5001]"]
    for lines in [extra, *(split_lines(decode_bytes(f.read_bytes()).text) for f in files)]:
        for line in lines:
            p = parser.parse_line(line)
            if isinstance(p.statement, NcStatement) and plain_variables(p.statement) is not None:
                plain += 1
            assert list(dialect.check_line(p)) == list(dialect._check_line(p)), line
            assert list(expressions.check_line(p)) == list(expressions._check_line(p)), line
    assert plain > 1000  # the corpus is mostly blocks of plain words


def test_vacant_reads_kept_from_the_last_analysis_equal_a_fresh_look() -> None:
    """MB901's reads of a vacant local, kept where neither the line nor its facts changed:
    after edits of a call's arguments, of the macro it calls and of lines that move it, the
    diagnostics are those of a fresh analysis."""
    from fanuc_macro.workspace import Workspace

    cfg = dataclasses.replace(Config(), max_blocks=10**7, max_file_size=10**9)
    lines = ["%", "O1000 (MAIN)", *(f"#{v}=0" for v in range(1, 9))]
    for i in range(3000):
        call = f"G65 P9000 A{i % 5}." if i % 3 else f"G65 P9000 A1. C{i % 4}."
        lines += [f"#{1 + i % 8}=#{1 + i % 8}+1", call]
    lines += ["G65 P9100 A1.", "M30", "O9000 (MACRO)", "#10=#1+#2", "#11=#3*2", "M99"]
    lines += ["O9100 (CALLED LAST)", "#10=#1*#2", "M99", "%"]  # its run is kept
    middle = lines.index("G65 P9000 A1. C0.", len(lines) // 2)
    macro = lines.index("O9000 (MACRO)")
    uri = "file:///vacant.nc"
    workspace = Workspace(cfg)
    workspace.add_text(uri, "\n".join(lines))
    workspace.analyse(uri)
    edits = [
        (middle, "G65 P9000 A1. B2."),  # #2 passed once: not vacant every time
        (middle, "G65 P9000 A1. C0."),
        (macro + 3, "#12=#4+1"),  # a new read of a local nobody passes
        (middle - 1, "#4=#4+7"),
        (middle, None),  # a line put in: the macro's lines move
    ]
    found: list[int] = []
    for at, text in edits:
        if text is None:
            lines.insert(at, "(NOTE)")
        else:
            lines[at] = text
        edited = "\n".join(lines)
        workspace.add_text(uri, edited)
        diagnostics = workspace.analyse(uri).diagnostics
        assert diagnostics == analyse(edited, "file:///fresh.nc", cfg).diagnostics
        found.append(sum(d.code == "MB901" for d in diagnostics))
    assert found == [1, 2, 3, 3, 3]
