"""The ide layer's semantic tokens, signature help and code lenses, as plain data (lines 0-based,
columns in code points)."""

from __future__ import annotations

import itertools
from pathlib import Path

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.ide.lenses import code_lenses
from fanuc_macro.ide.locate import locals_read_before_set
from fanuc_macro.ide.semantic import SemanticToken, semantic_tokens
from fanuc_macro.ide.signature import function_signature, signature_help
from fanuc_macro.ide.token_legend import TOKEN_MODIFIERS, TOKEN_TYPES, TokenModifier, TokenType
from fanuc_macro.ide.view import View
from fanuc_macro.program.arguments import argument_numbers
from fanuc_macro.program.variables import ARGUMENT_VARIABLES
from fanuc_macro.workspace import Workspace

SEEDS = Path(__file__).resolve().parent / "fixtures" / "seeds"

MAIN = (
    "O1000 (MAIN)\n"
    "N10 G65 P9010 A1. X2.\n"
    "#1=SIN[30]+ATAN[1]/[2] MOD #[#5+1]\n"
    "IF[#1 EQ 2]GOTO10\n"
    "WHILE[#101LT3]DO1\n"
    "#500=#4001+#5001 (#2 IN A COMMENT)\n"
    "IF[#1GT0]THEN G01X#101\n"
    "END1\n"
    "M30\n"
    "O9010 (BORE A HOLE)\n"
    "#100=#24 (START X)\n"
    "#101=#1+#26+#30\n"
    "#2=1 (B IS SET, NOT GIVEN)\n"
    "#102=#2\n"
    "M99\n"
)

D = frozenset({TokenModifier.DECLARATION})
W = frozenset({TokenModifier.MODIFICATION})
LIB = frozenset({TokenModifier.DEFAULT_LIBRARY})
SYSTEM_RO = frozenset({TokenModifier.SYSTEM, TokenModifier.DEFAULT_LIBRARY, TokenModifier.READONLY})
COMMON = frozenset({TokenModifier.COMMON})


def view_of(text: str, key: str = "main.nc") -> View:
    return View(key, analyse(text, key, Config()), Config())


def shown(view: View, text: str, first: int = 0, last: int | None = None) -> list[tuple]:
    lines = text.splitlines()
    return [
        (t.line, lines[t.line][t.start : t.end], t.type, t.modifiers)
        for t in semantic_tokens(view, first, last)
    ]


def test_the_legend_is_the_protocols_standard_types_and_the_controls_modifiers() -> None:
    assert TOKEN_TYPES == (
        "namespace", "label", "variable", "parameter", "function", "keyword", "operator"
    )  # fmt: skip
    assert TOKEN_MODIFIERS[:4] == ("declaration", "readonly", "defaultLibrary", "modification")
    assert {"common", "system"} <= set(TOKEN_MODIFIERS)


def test_tokens_of_programs_labels_variables_functions_and_keywords() -> None:
    view = view_of(MAIN)
    tokens = shown(view, MAIN)
    assert tokens[:4] == [
        (0, "O1000", TokenType.NAMESPACE, D),
        (1, "N10", TokenType.LABEL, D),
        (1, "P9010", TokenType.NAMESPACE, frozenset()),
        (2, "#1", TokenType.VARIABLE, W),  # O1000 is no macro: #1 is a plain local
    ]
    line = {n: [t[1:] for t in tokens if t[0] == n] for n in range(15)}
    assert line[2][1:] == [
        ("SIN", TokenType.FUNCTION, LIB),
        ("ATAN", TokenType.FUNCTION, LIB),
        ("MOD", TokenType.OPERATOR, frozenset()),
        # the evaluator assumed O1000 is given #5 (read before it is set): an argument
        ("#5", TokenType.PARAMETER, frozenset()),
    ]
    assert [t[:2] for t in line[3]] == [
        ("IF", TokenType.KEYWORD),
        ("#1", TokenType.VARIABLE),
        ("EQ", TokenType.OPERATOR),
        ("GOTO", TokenType.KEYWORD),
        ("10", TokenType.LABEL),
    ]
    assert [t[:2] for t in line[4]] == [
        ("WHILE", TokenType.KEYWORD),
        ("#101", TokenType.VARIABLE),
        ("LT", TokenType.OPERATOR),
        ("DO", TokenType.KEYWORD),
    ]
    assert line[5] == [  # nothing in the comment
        ("#500", TokenType.VARIABLE, COMMON | W),
        ("#4001", TokenType.VARIABLE, SYSTEM_RO),
        ("#5001", TokenType.VARIABLE, SYSTEM_RO),
    ]
    # The NC words of IF ... THEN are the grammar's; G01 is no keyword, X#101's #101 a token.
    assert [t[0] for t in line[6]] == ["IF", "#1", "GT", "THEN", "#101"]
    assert line[7] == [("END", TokenType.KEYWORD, frozenset())]
    assert line[8] == []
    # O9010 is called by G65: the locals it reads before it sets them are its arguments (#30:
    # K of the ninth set of specification II); #2, set first, is not one.
    assert line[10] == [
        ("#100", TokenType.VARIABLE, COMMON | W),
        ("#24", TokenType.PARAMETER, frozenset()),
    ]
    assert [t[:2] for t in line[11]] == [
        ("#101", TokenType.VARIABLE),
        ("#1", TokenType.PARAMETER),
        ("#26", TokenType.PARAMETER),
        ("#30", TokenType.PARAMETER),
    ]
    assert [t[:2] for t in line[12]] == [("#2", TokenType.VARIABLE)]
    assert [t[:2] for t in line[13]] == [
        ("#102", TokenType.VARIABLE),
        ("#2", TokenType.VARIABLE),
    ]


def test_tokens_are_in_order_without_overlaps_and_a_range_is_a_slice_of_the_full() -> None:
    view = view_of(MAIN)
    full = semantic_tokens(view)
    for before, after in itertools.pairwise(full):
        assert (before.line, before.end) <= (after.line, after.start)
    assert semantic_tokens(view, 3, 5) == [t for t in full if 3 <= t.line <= 5]
    assert semantic_tokens(view, 40, 50) == []


def test_a_written_system_variable_that_may_be_written_is_not_readonly() -> None:
    text = "O1\n#3000=1 (STOP)\n#2001=0.1\n"
    tokens = semantic_tokens(view_of(text))
    written = frozenset({TokenModifier.SYSTEM, TokenModifier.DEFAULT_LIBRARY}) | W
    assert SemanticToken(1, 0, 5, TokenType.VARIABLE, written) in tokens
    assert all(TokenModifier.READONLY not in t.modifiers for t in tokens)


def test_a_program_a_macro_call_of_another_file_calls_takes_arguments() -> None:
    workspace = Workspace(Config())
    workspace.add_text("main.nc", "O1\nG65 P8000 X1.\nM30\n")
    workspace.add_text("sub.nc", "O8000\n#100=#24\nM99\n")
    documents = {}
    for key in workspace.uris():
        doc = workspace.document(key)
        assert doc is not None
        documents[key] = (doc, workspace.index(key))
    sub = View("sub.nc", workspace.analyse("sub.nc"), Config(), documents)
    assert [t.type for t in semantic_tokens(sub, 1, 1)] == [TokenType.VARIABLE, TokenType.PARAMETER]
    # Uncalled, it returns with M99: a macro whose caller is elsewhere.
    alone = view_of("O8000\n#100=#24\nM99\n", "sub.nc")
    assert [t.type for t in semantic_tokens(alone, 1, 1)] == [
        TokenType.VARIABLE,
        TokenType.PARAMETER,
    ]
    # Called by M98, it reads its caller's locals: no arguments.
    shared = view_of("O1\n#24=1\nM98 P8000\nM30\nO8000\n#100=#24\nM99\n")
    assert [t.type for t in semantic_tokens(shared, 5, 5)] == [TokenType.VARIABLE] * 2


# ---- signature help --------------------------------------------------------------------------


def test_argument_numbers_follow_the_specifications() -> None:
    assert argument_numbers(["A", "X", "Z", "H"]) == [1, 24, 26, 11]
    assert argument_numbers(["I", "J", "K", "I", "K"]) == [4, 5, 6, 7, 9]
    assert argument_numbers(["J", "I"]) == [5, 7]  # out of order: the next set
    # The reference's example, G65 A1.0 B2.0 I-3.0 I4.0 D5.0: D fills #7 after the second I.
    assert argument_numbers(["A", "B", "I", "I", "D"]) == [1, 2, 4, 7, 7]
    assert argument_numbers(["G", "L"]) == [None, None]
    assert all(
        argument_numbers([letter]) == [n]
        for letter, n in ARGUMENT_VARIABLES.items()
        if letter not in "IJK"
    )


def test_call_signature_names_the_locals_the_callee_reads_and_the_letter_at_the_cursor() -> None:
    view = view_of(MAIN)
    line = "G65 P9010 A1. X2."
    found = signature_help(line, len(line), view)
    assert found is not None
    assert found.label == "G65 P9010 A=#1 X=#24 Z=#26"
    labels = [found.label[p.start : p.end] for p in found.parameters]
    assert labels == ["A=#1", "X=#24", "Z=#26"]
    assert found.active == 1  # X, being typed
    assert found.documentation == "**O9010** — BORE A HOLE"
    x = found.parameters[1].documentation
    assert x.startswith("**X** → **#24** — read by O9010 at line 11") and "(START X)" in x
    at_a = signature_help(line, line.index("A1.") + 2, view)
    assert at_a is not None and at_a.active == 0
    after = signature_help("G65 P9010 A1. ", 14, view)
    assert after is not None and after.active is None  # between words
    # A letter the callee does not read is shown, and said to be unread.
    b = signature_help("G65 P9010 B", 11, view)
    assert b is not None and b.label == "G65 P9010 A=#1 B=#2 X=#24 Z=#26" and b.active == 1
    # O9010 sets #2 before it reads it: B would be lost.
    assert b.parameters[1].documentation == (
        "**B** → **#2** — unused: O9010 does not read #2 before it sets it"
    )
    assert signature_help("G01 X1.", 7, view) is None
    assert signature_help("G65 P9010 (A COMMENT", 14, view) is None  # typing a comment
    assert signature_help("G65 P9010 (A) X", 15, view) is not None  # after one
    assert signature_help("G65", 1, view) is None  # in the G word itself


def test_call_signature_of_a_program_not_in_the_workspace() -> None:
    found = signature_help("G66 P7777 Z1", 12, view_of(MAIN))
    assert found is not None and found.label == "G66 P7777 Z=#26" and found.active == 0
    assert found.documentation == "O7777 is not in the workspace."
    no_view = signature_help("G65 P1 (A COMMENT) R", 20, None)
    assert no_view is not None and no_view.label == "G65 P1 R=#18"


def test_function_signature_and_its_active_parameter() -> None:
    atan = function_signature("#1=ATAN[#2]/[#3", 15)
    assert atan is not None and atan.label == "ATAN[a]/[b]" and atan.active == 1
    assert [atan.label[p.start : p.end] for p in atan.parameters] == ["a", "b"]
    first = function_signature("#1=ATAN[#2", 10)
    assert first is not None and first.active == 0
    power = function_signature("#1=POW[2,", 9)
    assert power is not None and power.label == "POW[a,b]" and power.active == 1
    inner = function_signature("G01 X[SIN[#1+[2", 15)  # an expression's bracket inside SIN
    assert inner is not None and inner.label == "SIN[a]" and inner.active == 0
    assert "degrees" in inner.parameters[0].documentation
    assert function_signature("#1=[#2+", 7) is None
    assert function_signature("#1=SIN[30]+", 11) is None  # closed
    assert function_signature("(SIN[", 5) is None  # a comment
    # In a G65 line the function's brackets win.
    found = signature_help("G65 P9010 X[ROUND[", 18, view_of(MAIN))
    assert found is not None and found.label == "ROUND[x]"


# ---- code lenses -----------------------------------------------------------------------------


def test_code_lenses_count_the_callers_and_the_runs() -> None:
    view = view_of(MAIN)
    lenses = [(lens.range.start.line, lens.title) for lens in code_lenses(view)]
    assert lenses == [
        (0, "entered once"),
        (9, "called from O1000 · 1×"),
        (9, "entered once"),
    ]
    called = code_lenses(view)[1]
    assert [r.range.start.line for r in called.references] == [1]
    assert called.tooltip == "O1000, line 2"
    assert code_lenses(view)[2].tooltip == "What the analysed runs did"
    assert called.range.start.column == 0 and called.range.end.column == len("O9010")


def test_a_subprogram_nobody_calls_says_so() -> None:
    lenses = code_lenses(view_of("O8000\n#1=1\nM99\n"))
    assert lenses[0].title == "no caller in the workspace"


def seed_views() -> dict[str, View]:
    workspace = Workspace(Config())
    for path in sorted(SEEDS.glob("*.nc")):
        workspace.add_text(path.name, path.read_text("utf-8"))
    documents = {}
    for key in workspace.uris():
        doc = workspace.document(key)
        assert doc is not None
        documents[key] = (doc, workspace.index(key))
    return {key: View(key, workspace.analyse(key), Config(), documents) for key in documents}


def test_the_thread_subprogram_lens_counts_its_cuts_and_depths() -> None:
    view = seed_views()["o4009_external_m50x3.nc"]
    lenses = code_lenses(view)
    titles = [lens.title for lens in lenses]
    assert titles[0] == "entered once"
    # The main program's cycle time (tests/test_cycle_time.py works it out by hand).
    assert titles[1] == "cycle time 10 min 1.3 s"
    assert titles[2] == "called from O4009 · 1×"
    thread = titles[3]
    assert thread.startswith("entered once · M50x3-5g6g: ")
    (job,) = [t.job for t in view.analysis.threads]
    cuts, depths = len(job.passes), len(set(job.xs))
    assert cuts > depths > 1  # two cuts per depth (shifted flanks), spring passes
    assert thread.endswith(f": {cuts} cuts at {depths} depths (G92 F3)")
    assert lenses[3].tooltip.endswith("a cut is one threading motion, a depth an X the cuts reach")
    # The subprogram, called only: the time of its own blocks (all but O4009's two rapids'
    # and one tool change's).
    assert titles[4] == "9 min 59.0 s in its own blocks"


def test_callers_in_other_files_are_named_with_their_file() -> None:
    views = seed_views()
    workspace = {key: (v.doc, v.index) for key, v in views.items()}
    other = view_of("O7\nM98 P3331\nM98 P3331\nM30\n", "other.nc")
    workspace["other.nc"] = (other.doc, other.index)
    key = "o4009_external_m50x3.nc"
    view = View(key, views[key].analysis, Config(), workspace)
    lens = code_lenses(view)[2]
    assert lens.title == "called from O0007 · 2×, O4009 · 1×"  # the most calls first
    # The calls by document: this one's without its name.
    assert lens.tooltip == "O4009, line 11\nO0007, line 2 (other.nc)\nO0007, line 3 (other.nc)"


def test_locals_read_before_set_follow_the_lines_and_read_a_value_before_its_target() -> None:
    text = "O9000\n#1=#1+1\n#2=5\n#3=#2+#4+#100\nIF[#5EQ#0]THEN#5=#6\n#7=[#7]\nM99\n"
    doc = view_of(text).doc
    assert locals_read_before_set(doc.blocks, 0, len(doc.blocks)) == {1: 1, 4: 3, 5: 4, 6: 4, 7: 5}
    assert locals_read_before_set(doc.blocks, 3, 4) == {2: 3, 4: 3}


def test_the_tokens_kept_from_an_earlier_request_are_those_of_the_line_now() -> None:
    from fanuc_macro import database
    from fanuc_macro.ide import semantic

    text = "O1000\n#1=SIN[30]\nG65 P9010 A1.\nM30\nO9010\n#3=#1+#24\n#3=#1+#24\nM99\n"
    config = Config()
    view = View("t.nc", analyse(text, "t.nc", config), config)
    worked_out = database.current().table(semantic.LINE_TOKENS)
    worked_out.clear()

    def fresh(v: View) -> list[SemanticToken]:
        out: list[SemanticToken] = []
        for block in v.doc.blocks:
            program = v.index.program_at(block.line)
            called = semantic.CalledPrograms.of(v)
            arguments = semantic._arguments_of(v, program, called)
            targets = semantic._targets_by_line(program) if program is not None else {}
            out.extend(semantic.block_tokens(block, arguments, targets.get(block.line, ())))
        return out

    first = semantic_tokens(view)
    assert first == fresh(view)
    assert worked_out  # kept for the next request
    # Two lines moved down by one: their tokens come from the cache, on their new lines; the
    # sub-program is no longer called with G65, so its locals are no longer arguments.
    edited = text.replace("G65 P9010 A1.\n", "(NO CALL)\nM98 P9010\n")
    view = View("t.nc", analyse(edited, "t.nc", config), config)
    again = semantic_tokens(view)
    assert again == fresh(view)
    assert {t.line for t in again if t.type == TokenType.PARAMETER} == set()
    assert {t.line for t in first if t.type == TokenType.PARAMETER} == {5, 6}
