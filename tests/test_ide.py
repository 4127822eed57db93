"""The ide layer alone: the editor features as plain data, without a protocol or a client.
Positions are 0-based lines and columns in code points."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.ide.actions import code_actions
from fanuc_macro.ide.completion import completion
from fanuc_macro.ide.data import (
    ActionKind,
    CompletionKind,
    DocumentEdit,
    Location,
    Position,
    Problem,
    Range,
    SymbolKind,
    TextEdit,
)
from fanuc_macro.ide.hover import hover
from fanuc_macro.ide.inlay import inlay_hints
from fanuc_macro.ide.navigation import definition, document_symbols, references
from fanuc_macro.ide.view import View
from fanuc_macro.workspace import Workspace

ROOT = Path(__file__).resolve().parents[1]

# A character outside the Basic Multilingual Plane before the variable: two UTF-16 code units,
# one code point here.
MAIN = "O1000 (😀 MAIN)\n#1=2.5 (DIA)\nG01 (😀) X#1 F0.2\nM98 P2000\nIF[#1GT0]GOTO20\nN20 M30\n"
SUB = "O2000 (SUB)\n#100=1.\nM99\n"


def view_of(text: str, key: str = "main.nc", config: Config | None = None) -> View:
    config = config or Config()
    return View(key, analyse(text, key, config), config)


def test_hover_is_markdown_and_a_range_in_code_points() -> None:
    view = view_of(MAIN)
    column = MAIN.splitlines()[2].index("#1")
    found = hover(view, 2, column + 1)
    assert found is not None
    assert found.range == Range(Position(2, column), Position(2, column + 2))
    assert found.markdown.startswith("**#1** here: **2.5**\n\n*DIA*")
    assert "Set at line 2: `#1=2.5`" in found.markdown
    assert found.markdown.endswith("---\n\nLocal variable of the current macro level.")
    assert hover(view, 2, 0) is not None  # G01
    assert hover(view, 99, 0) is None


def test_definition_is_locations_by_document_key() -> None:
    workspace = Workspace(Config())
    workspace.add_text("main.nc", MAIN)
    workspace.add_text("sub.nc", SUB)
    documents = {}
    for key in workspace.uris():
        doc = workspace.document(key)
        assert doc is not None
        documents[key] = (doc, workspace.index(key))
    view = View("main.nc", workspace.analyse("main.nc"), Config(), documents)
    call = MAIN.splitlines()[3].index("P2000") + 1
    assert definition(view, 3, call) == [Location("sub.nc", Range.of(0, 0, 0, len("O2000 (SUB)")))]
    jump = MAIN.splitlines()[4].index("GOTO")
    assert definition(view, 4, jump) == [Location("main.nc", Range.of(5, 0, 5, 3))]
    variable = MAIN.splitlines()[2].index("#1")
    assert definition(view, 2, variable) == [Location("main.nc", Range.of(1, 0, 1, 2))]
    assert definition(view, 0, 100) == []
    reads = references(view, 2, variable, include_declaration=False)
    assert reads == [
        Location("main.nc", Range.of(2, variable, 2, variable + 2)),
        Location("main.nc", Range.of(4, 3, 4, 5)),
    ]


def test_completion_items_replace_what_is_typed() -> None:
    view = view_of(MAIN)
    text = "#2=SQ"
    found = completion(text, 1, len(text), Config(), view, snippets_supported=True)
    sqrt = next(item for item in found.items if item.label == "SQRT")
    assert sqrt.kind is CompletionKind.FUNCTION
    assert sqrt.snippet and sqrt.insert_text == "SQRT[$1]"
    assert sqrt.replace == Range.of(1, 3, 1, 5)
    assert sqrt.documentation.startswith("**SQRT")
    plain = completion(text, 1, len(text), Config(), view)
    assert next(item for item in plain.items if item.label == "SQRT").insert_text == "SQRT[]"
    variables = completion("X#", 2, 2, Config(), view)
    first = variables.items[0]
    assert (first.label, first.kind, first.detail) == ("#1", CompletionKind.VARIABLE, "DIA")
    assert first.replace == Range.of(2, 1, 2, 2)
    assert not completion("(#", 0, 2, Config(), view).items  # inside a comment


def test_code_action_closes_the_loop_and_names_its_problem() -> None:
    text = "O1000\n#1=0\nWHILE[#1LT3]DO1\n#1=#1+1\nM30\n"
    view = view_of(text)
    problem = Problem("MB201", 2, 0)
    fix, suppress = code_actions(view, [problem], "\n")
    assert fix.title == "Insert END1 to close DO1"
    assert fix.kind is ActionKind.QUICK_FIX and fix.preferred
    assert fix.fixes == (problem,) and fix.fixes[0] is problem
    assert fix.edits == (DocumentEdit("main.nc", (TextEdit(Range.of(4, 0, 4, 0), "END1\n"),)),)
    assert suppress.title == "Suppress MB201 on this line" and not suppress.preferred
    end = len(text.splitlines()[2])
    assert suppress.edits == (
        DocumentEdit(
            "main.nc", (TextEdit(Range.of(2, end, 2, end), " (fanuc-macro: ignore MB201)"),)
        ),
    )


def test_inlay_hints_and_symbols_are_plain_data() -> None:
    text = MAIN.replace("#1=2.5", "#1=5./2.")
    view = view_of(text)
    (hint,) = inlay_hints(view, 0, 10)
    assert hint.position == Position(1, len("#1=5./2."))
    assert hint.label == "= 2.5" and hint.tooltip.startswith("#1 = ")
    view = view_of(MAIN)
    (program,) = document_symbols(view)
    assert program.kind is SymbolKind.MAIN_PROGRAM and program.name == "O1000"
    assert [child.name for child in program.children] == ["N20"]
    assert program.children[0].kind is SymbolKind.LABEL


def test_no_inlay_hint_repeats_a_number_the_line_shows() -> None:
    text = (
        "O1000\n#1=2.5\n#2=-2.5\n#3=[10]\n#4=-#1\n#5=#1*2\n"
        "IF[#1GT0] THEN #6=7.\nIF[#1GT0] THEN #7=#6+1\nM30\n"
    )
    hints = {h.position.line: h.label for h in inlay_hints(view_of(text), 0, 20)}
    assert hints == {4: "= -2.5", 5: "= 5.", 7: "= 8."}


def test_the_ide_layer_loads_without_the_protocol() -> None:
    code = (
        "import sys\n"
        "import fanuc_macro.ide.actions, fanuc_macro.ide.completion, fanuc_macro.ide.hover\n"
        "import fanuc_macro.ide.inlay, fanuc_macro.ide.navigation, fanuc_macro.cli\n"
        "bad = sorted(m for m in sys.modules if m.split('.')[0] in ('lsprotocol', 'pygls'))\n"
        "assert not bad, bad\n"
    )
    env = {"PYTHONPATH": str(ROOT / "server"), "PATH": ""}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_hover_names_the_nearest_assignment_before_else_the_first_after() -> None:
    text = "O1000\nG01 X#5\n#5=1.\n#5=2.\nG01 X#5\n#5=3.\nM30\nO2000\n#5=9.\nM99\n"
    view = view_of(text)
    for line, where in ((1, "Set at line 3: `#5=1.`"), (4, "Set at line 4: `#5=2.`")):
        found = hover(view, line, text.splitlines()[line].index("#5"))
        assert found is not None and where in found.markdown, (line, found)
    own = hover(view, 5, 0)
    assert own is not None and own.markdown.startswith("**#5** = **3.**")
    assert "Set at" not in own.markdown  # the line shows it
