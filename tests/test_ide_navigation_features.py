"""Rename, document highlight, folding and selection ranges, workspace symbols and the call
hierarchy in the ide layer: plain answers, positions in 0-based lines and code points."""

from __future__ import annotations

import itertools
from pathlib import Path

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.ide.calls import incoming_calls, outgoing_calls, prepare_call_hierarchy
from fanuc_macro.ide.data import DocumentEdit, Position, Range, SymbolKind, TextEdit
from fanuc_macro.ide.highlight import HighlightKind, highlights
from fanuc_macro.ide.ranges import Fold, FoldKind, folding_ranges, selection_ranges
from fanuc_macro.ide.rename import Refusal, RenameTarget, prepare_rename, rename
from fanuc_macro.ide.view import Indexed, View
from fanuc_macro.ide.workspace_symbols import workspace_symbols
from fanuc_macro.workspace import Workspace

SEEDS = Path(__file__).resolve().parent / "fixtures" / "seeds"
SEED = (SEEDS / "o4009_external_m50x3.nc").read_text("utf-8")

LOOPS = (
    "(FIRST COMMENT)\n"  # 0
    "(SECOND COMMENT)\n"  # 1
    "O1 (LOOPS)\n"  # 2
    "#1=0\n"  # 3
    "WHILE[#1LT3]DO1\n"  # 4
    "N5 #1=#1+1\n"  # 5
    "#2=[#1+[2*#1]]\n"  # 6
    "IF[#1EQ2]GOTO5\n"  # 7
    "END1\n"  # 8
    "M98 P2\n"  # 9
    "M30\n"  # 10
    "%\n"  # 11
    "O2 (SUB)\n"  # 12
    "#100=#100+1\n"  # 13
    "M99\n"  # 14
)


def view_of(text: str, key: str = "main.nc", config: Config | None = None) -> View:
    config = config or Config()
    return View(key, analyse(text, key, config), config)


def column(text: str, line: int, what: str) -> int:
    return text.splitlines()[line].index(what)


def workspace_view(texts: dict[str, str], key: str) -> tuple[View, dict[str, Indexed]]:
    workspace = Workspace(Config())
    for name, text in texts.items():
        workspace.add_text(name, text)
    documents: dict[str, Indexed] = {}
    for name in workspace.uris():
        doc = workspace.document(name)
        assert doc is not None
        documents[name] = (doc, workspace.index(name))
    return View(key, workspace.analyse(key), Config(), documents), documents


def applied(text: str, edit: DocumentEdit) -> str:
    lines = text.split("\n")
    for change in sorted(edit.edits, key=lambda e: e.range.start, reverse=True):
        start, end = change.range.start, change.range.end
        assert start.line == end.line
        line = lines[start.line]
        lines[start.line] = line[: start.column] + change.new_text + line[end.column :]
    return "\n".join(lines)


# ---- rename ----------------------------------------------------------------------------------


def test_rename_of_a_label_changes_its_gotos() -> None:
    view = view_of(SEED)
    goto = column(SEED, 40, "GOTO10") + 4
    target = prepare_rename(view, 40, goto)
    assert target == RenameTarget("label", 10, Range.of(40, goto, 40, goto + 2), "10")
    [edit] = rename(view, 40, goto, "N15")
    assert edit == DocumentEdit(
        "main.nc",
        (TextEdit(Range.of(30, 1, 30, 3), "15"), TextEdit(Range.of(40, goto, 40, goto + 2), "15")),
    )
    text = applied(SEED, edit)
    assert text.splitlines()[30].startswith("N15 G01")
    assert "GOTO15" in text.splitlines()[40]
    # From the label itself, the same edits.
    assert rename(view, 30, 1, "15") == (edit,)


def test_rename_of_a_program_keeps_the_repeat_count_of_m98() -> None:
    view = view_of(SEED)
    call = column(SEED, 10, "P0013331")
    target = prepare_rename(view, 10, call + 1)
    assert isinstance(target, RenameTarget) and target.placeholder == "3331"
    [edit] = rename(view, 10, call, "O5000")
    text = applied(SEED, edit).splitlines()
    assert text[10].startswith("M98 P0015000") and text[17].startswith("O5000 ")
    # The program after the repeat count stays four digits: P0010012, not P00112.
    [edit] = rename(view, 10, call, "12")
    text = applied(SEED, edit).splitlines()
    assert text[10].startswith("M98 P0010012") and text[17].startswith("O12 ")


def test_rename_follows_m99_p_and_the_lathe_profile() -> None:
    text = (
        "O1\nG71 U1. R0.5\nG71 P10 Q20 U0.2 W0.1 F0.2\nN10 G00 X20.\nN20 G01 Z-10.\n"
        "G70 P10 Q20\nM99 P10\n"
    )
    lathe = view_of(text, config=Config(controller="0i-TF"))
    [edit] = rename(lathe, 3, 1, "30")
    assert [e.range.start.line for e in edit.edits] == [2, 3, 5, 6]
    after = applied(text, edit).splitlines()
    assert after[2].startswith("G71 P30 Q20") and after[5] == "G70 P30 Q20"
    assert after[6] == "M99 P30"


def test_rename_refuses_what_it_cannot_follow() -> None:
    computed = "O1\nN10 #1=1\nGOTO#1\nGOTO10\nM30\n"
    view = view_of(computed)
    refusal = prepare_rename(view, 2, 1)
    assert isinstance(refusal, Refusal) and "computed GOTO" in refusal.message
    refusal = prepare_rename(view, 1, 1)  # N10: the GOTO#1 may reach it
    assert isinstance(refusal, Refusal) and "line 3" in refusal.message
    variable = prepare_rename(view, 1, 4)
    assert isinstance(variable, Refusal) and "#1 is a variable number" in variable.message
    plain = view_of("O1\nN10 G00 X0\nN20 G00 X1\nGOTO10\nM30\n")
    taken = rename(plain, 3, 4, "20")
    assert isinstance(taken, Refusal) and "N20 is already a label" in taken.message
    for bad in ("0", "100000", "O10", "1.5", "ten"):
        assert isinstance(rename(plain, 3, 4, bad), Refusal), bad
    twice = view_of("O1\nN10 G00 X0\nN10 G00 X1\nGOTO10\nM30\n")
    assert isinstance(prepare_rename(twice, 1, 1), Refusal)
    assert prepare_rename(plain, 1, 5) is None  # G00: nothing with a name


def test_rename_of_a_program_across_the_workspace() -> None:
    texts = {
        "main.nc": "O1000\nM98 P1234\nG65 P1234 A1.\nM30\n",
        "other.nc": "O1001\nG66 P1234 A2.\nM30\n",
        "sub.nc": "%\nO1234 (SUB)\n#100=#1\nM99\n%\n",
    }
    view, _ = workspace_view(texts, "sub.nc")
    edits = rename(view, 1, 2, "2000")
    assert isinstance(edits, tuple)
    by_key = {e.key: applied(texts[e.key], e) for e in edits}
    assert by_key["main.nc"] == "O1000\nM98 P2000\nG65 P2000 A1.\nM30\n"
    assert by_key["other.nc"] == "O1001\nG66 P2000 A2.\nM30\n"
    assert by_key["sub.nc"].splitlines()[1] == "O2000 (SUB)"
    taken = rename(view, 1, 2, "O1001")
    assert isinstance(taken, Refusal) and "already a program" in taken.message
    # From a call in another document, the same rename.
    caller, _ = workspace_view(texts, "main.nc")
    assert rename(caller, 1, 5, "2000") == edits
    # A number two documents define: which one a call runs depends on the document.
    texts["copy.nc"] = "O1234 (COPY)\nM99\n"
    twice, _ = workspace_view(texts, "sub.nc")
    refusal = prepare_rename(twice, 1, 2)
    assert isinstance(refusal, Refusal) and "defined 2 times" in refusal.message


def test_rename_refuses_a_label_a_subprogram_returns_to() -> None:
    texts = {
        "main.nc": "O1000\nM98 P2000\nN50 G00 X0\nM30\n",
        "sub.nc": "O2000\nG00 X1\nM99 P50\n",
    }
    view, _ = workspace_view(texts, "main.nc")
    refusal = prepare_rename(view, 2, 1)
    assert isinstance(refusal, Refusal)
    assert "O2000, called at line 2, returns to N50" in refusal.message
    # In the called program, its M99 P names the caller's label, not one of its own.
    texts["sub.nc"] = "O2000\nN50 G00 X1\nM99 P50\n"
    sub, _ = workspace_view(texts, "sub.nc")
    refusal = prepare_rename(sub, 1, 1)
    assert isinstance(refusal, Refusal) and "called as a subprogram" in refusal.message
    # A main program's M99 P jumps to its own label: renamed with it.
    alone = view_of("O1\nN50 G00 X1\nM99 P50\n")
    [edit] = rename(alone, 1, 1, "60")
    assert applied("O1\nN50 G00 X1\nM99 P50\n", edit) == "O1\nN60 G00 X1\nM99 P60\n"


def test_rename_refuses_a_program_numbered_by_its_file() -> None:
    texts = {"main.nc": "O1000\nM98 P8501\nM30\n", "O8501.NC": "G00 X1\nM99\n"}
    view, _ = workspace_view(texts, "main.nc")
    refusal = prepare_rename(view, 1, 5)
    assert isinstance(refusal, Refusal) and "file name 'O8501.NC'" in refusal.message
    computed = view_of("O1\nM98 P#1\nM30\n")
    refusal = prepare_rename(computed, 1, 1)  # on the M98
    assert isinstance(refusal, Refusal) and "computed program number" in refusal.message
    nowhere = prepare_rename(view_of("O1\nM98 P7777\nM30\n"), 1, 5)
    assert isinstance(nowhere, Refusal) and "no program O7777" in nowhere.message


# ---- document highlight ----------------------------------------------------------------------


def test_highlight_reads_and_writes_of_a_variable() -> None:
    view = view_of(LOOPS)
    found = highlights(view, 5, 4)  # the #1 of #1=#1+1
    kinds = [(h.range.start.line, h.range.start.column, h.kind) for h in found]
    assert kinds == [
        (3, 0, HighlightKind.WRITE),
        (4, 6, HighlightKind.READ),
        (5, 3, HighlightKind.WRITE),
        (5, 6, HighlightKind.READ),
        (6, 4, HighlightKind.READ),
        (6, 10, HighlightKind.READ),
        (7, 3, HighlightKind.READ),
    ]
    # A common variable: every program of the document.
    commons = view_of("O1\n#100=1\nM30\nO2\n#101=#100\nM99\n")
    assert [h.range.start.line for h in highlights(commons, 4, 7)] == [1, 4]


def test_highlight_of_a_label_and_of_a_program() -> None:
    view = view_of(LOOPS)
    label = highlights(view, 7, column(LOOPS, 7, "GOTO"))
    assert [(h.range, h.kind) for h in label] == [
        (Range.of(5, 1, 5, 2), HighlightKind.TEXT),
        (Range.of(7, 13, 7, 14), HighlightKind.TEXT),
    ]
    program = highlights(view, 12, 1)
    assert [h.range for h in program] == [Range.of(9, 5, 9, 6), Range.of(12, 1, 12, 2)]
    assert highlights(view, 10, 1) == []  # M30


# ---- folding and selection -------------------------------------------------------------------


def test_folding_ranges_of_programs_loops_and_comments() -> None:
    assert folding_ranges(view_of(LOOPS)) == [
        Fold(0, 1, FoldKind.COMMENT),
        Fold(2, 10, FoldKind.REGION),  # O1 .. M30
        Fold(4, 7, FoldKind.REGION),  # WHILE .. the line before END1
        Fold(12, 14, FoldKind.REGION),  # O2 .. M99
    ]
    haas = view_of("O1\nIF [#1 GT 0] THEN\nG00 X1\nG00 X2\nELSE\nG00 X3\nG00 X4\nENDIF\nM30\n")
    assert Fold(1, 3, FoldKind.REGION) in folding_ranges(haas)
    assert Fold(4, 6, FoldKind.REGION) in folding_ranges(haas)
    seed_folds = folding_ranges(view_of(SEED))
    assert Fold(1, 15, FoldKind.REGION) in seed_folds  # O4009 .. M30
    assert Fold(17, 46, FoldKind.REGION) in seed_folds  # O3331 .. M99


def test_selection_ranges_grow_from_the_expression_to_the_program() -> None:
    view = view_of(LOOPS)
    [chain] = selection_ranges(view, [Position(6, 10)])  # the last #1 of #2=[#1+[2*#1]]
    assert chain == [
        Range.of(6, 10, 6, 12),  # #1
        Range.of(6, 8, 6, 12),  # 2*#1
        Range.of(6, 7, 6, 13),  # [2*#1]
        Range.of(6, 4, 6, 13),  # #1+[2*#1]
        Range.of(6, 3, 6, 14),  # [#1+[2*#1]]
        Range.of(6, 0, 6, 14),  # the block
        Range.of(5, 0, 7, 14),  # the loop's body
        Range.of(4, 0, 8, 4),  # the loop
        Range.of(2, 0, 10, 3),  # the program
    ]
    for inner, outer in itertools.pairwise(chain):
        assert outer.start <= inner.start and inner.end <= outer.end and inner != outer
    [word] = selection_ranges(view, [Position(9, 5)])
    assert word[:3] == [Range.of(9, 5, 9, 6), Range.of(9, 4, 9, 6), Range.of(9, 0, 9, 6)]


# ---- workspace symbols -----------------------------------------------------------------------


def test_workspace_symbols_of_every_document() -> None:
    _, documents = workspace_view(
        {"b.nc": LOOPS, "a.nc": "O3000 (FIRST)\nN100 G00 X0\nM30\n"}, "a.nc"
    )
    found = workspace_symbols(documents, "")
    assert [(s.name, s.location.key) for s in found] == [
        ("O3000", "a.nc"),
        ("O0001", "b.nc"),
        ("O0002", "b.nc"),
        ("N100", "a.nc"),
        ("N5", "b.nc"),
    ]
    assert found[0].detail == "FIRST" and found[0].kind is SymbolKind.MAIN_PROGRAM
    assert found[2].kind is SymbolKind.SUBPROGRAM and found[4].container == "O0001"
    assert [s.name for s in workspace_symbols(documents, "o00")] == ["O0001", "O0002"]
    assert [s.name for s in workspace_symbols(documents, "n1")] == ["N100"]
    assert workspace_symbols(documents, "zzz") == []


# ---- call hierarchy --------------------------------------------------------------------------


def test_call_hierarchy_across_documents() -> None:
    texts = {
        "main.nc": "O1000 (MAIN)\nM98 P1234\nG65 P1234 A1.\nM98 P2000\nM30\n",
        "sub.nc": "O1234 (SUB)\nM98 P2000\nM99\n%\nO2000 (LEAF)\nM99\n",
    }
    view, documents = workspace_view(texts, "main.nc")
    [called] = prepare_call_hierarchy(view, 1, 5)
    assert (called.key, called.first_line, called.name, called.detail) == (
        "sub.nc",
        0,
        "O1234",
        "SUB",
    )
    [main] = prepare_call_hierarchy(view, 4, 1)  # the M30: its program
    assert (main.key, main.name) == ("main.nc", "O1000")
    [incoming] = incoming_calls(documents, "sub.nc", 0)
    assert incoming.item.name == "O1000"
    assert incoming.ranges == (Range.of(1, 0, 1, 9), Range.of(2, 0, 2, 9))
    leaf = incoming_calls(documents, "sub.nc", 4)
    assert [(e.item.key, e.item.name, e.ranges) for e in leaf] == [
        ("main.nc", "O1000", (Range.of(3, 0, 3, 9),)),
        ("sub.nc", "O1234", (Range.of(1, 0, 1, 9),)),
    ]
    outgoing = outgoing_calls(documents, "main.nc", 0)
    assert [(e.item.name, len(e.ranges)) for e in outgoing] == [("O1234", 2), ("O2000", 1)]
    assert outgoing_calls(documents, "sub.nc", 4) == []
