"""A rule stands alone: what an editor shows of its diagnostics (tags, fixes) comes with the
diagnostic the rule makes, and the front ends only convert it (no rule code in ide/ or lsp/).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

from lsprotocol import types

import fanuc_macro
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.diagnostics import Diagnostic, Fix, FixEdit, Severity, Tag
from fanuc_macro.ide.actions import code_actions
from fanuc_macro.ide.data import Problem, Range, TextEdit
from fanuc_macro.ide.view import View
from fanuc_macro.lsp.convert import Codec, Lines, to_lsp_diagnostic
from fanuc_macro.rules.context import LineFinding
from fanuc_macro.rules.dialect import in_foreign_file
from fanuc_macro.syntax import dialects
from fanuc_macro.syntax.parser import default_parser

DEAD = "O1000\nGOTO 10\nG00 X1\nN10 M30\nG00 X2\n"


def test_dead_code_diagnostics_carry_the_unnecessary_tag() -> None:
    diags = analyse(DEAD).diagnostics
    tagged = {d.code for d in diags if Tag.UNNECESSARY in d.tags}
    untagged = {d.code for d in diags if not d.tags}
    assert "MB702" in tagged
    assert "MB701" not in tagged and "MB709" not in tagged
    assert untagged.isdisjoint({"MB702", "MB710"})


def test_the_language_server_maps_any_rules_tags() -> None:
    diag = Diagnostic("MB101", Severity.ERROR, "m", 0, 0, 0, 1, tags=frozenset({Tag.DEPRECATED}))
    lines = Lines(("GOTO 1",), Codec())
    converted = to_lsp_diagnostic(diag, "a.nc", "file:///a.nc", lines)
    assert converted.tags == [types.DiagnosticTag.Deprecated]
    plain = to_lsp_diagnostic(Diagnostic("MB702", Severity.HINT, "m", 0, 0, 0, 1), "a", "a", lines)
    assert plain.tags is None  # the tag is the diagnostic's, not the code's


def test_mb201_carries_its_fix_and_the_action_writes_the_documents_line_end() -> None:

    text = "O1000\r\n#1=0\r\nWHILE[#1LT3]DO1\r\n#1=#1+1\r\nM30\r\n"
    (diag,) = [d for d in analyse(text).diagnostics if d.code == "MB201"]
    assert diag.fixes == (
        Fix("Insert END1 to close DO1", (FixEdit.insert(4, 0, "END1\n"),), preferred=True),
    )
    view = View("main.nc", analyse(text, "main.nc"), Config())
    fix = code_actions(view, [Problem("MB201", diag.line, diag.column)], "\r\n")[0]
    assert fix.edits[0].edits == (TextEdit(Range.of(4, 0, 4, 0), "END1\r\n"),)


def test_mb305_carries_its_fixes_on_its_line() -> None:
    text = "O1\n#1=1\nIF [#1 AND #2 LT 0] GOTO 5\nN5 M30\n"
    (diag,) = [d for d in analyse(text).diagnostics if d.code == "MB305"]
    titles = [(fix.title, fix.preferred) for fix in diag.fixes]
    assert titles == [
        (
            "Bracket the condition: [#1 LT 0] AND [#2 LT 0] "
            "(compare each operand on its own, joined by AND)",
            True,
        ),
        ("Bracket the condition: [#1 AND #2] LT 0 (bracket it as the control reads it)", False),
    ]
    assert {(e.line, e.column, e.end_column) for fix in diag.fixes for e in fix.edits} == {
        (2, diag.column, diag.end_column)
    }


def test_a_file_of_another_dialect_folds_its_rejected_blocks_in_the_dialect_rule() -> None:

    parsed = default_parser().parse_line("IF [#1 EQ #2] S#20 F#30")
    foreign = dialects.FileDialect("Haas", "M97", 3)
    findings = (
        LineFinding("MB006", "lower case", 0, 1),
        LineFinding("MB001", "syntax", 2, 5),
        LineFinding("MB302", "kept", 6, 7),
        LineFinding("MB003", "comment", 8, 9),
    )
    folded = in_foreign_file(findings, parsed, foreign)
    assert [(f.code, f.start, f.end) for f in folded] == [("MB302", 6, 7), ("MB002", 2, 5)]
    assert folded[1].message.startswith("Haas")


SCANNED = ("ide", "lsp", "cli", "dap", "analysis.py", "workspace.py")


def test_no_rule_code_outside_the_rules() -> None:
    """The front ends, ide/ and the analysis name no rule's code: what a rule does for the
    editor (fixes, tags, folding) is the rule's. MB000 is the analysis's own failure."""

    package = Path(fanuc_macro.__file__).parent
    code = re.compile(r"MB\d{3}")
    found: list[str] = []
    for part in SCANNED:
        root = package / part
        for path in sorted(root.rglob("*.py")) if root.is_dir() else [root]:
            for node in ast.walk(ast.parse(path.read_text("utf-8"))):
                if (
                    isinstance(node, ast.Constant)
                    and isinstance(node.value, str)
                    and code.fullmatch(node.value)
                    and node.value != "MB000"
                ):
                    found.append(f"{path.relative_to(package)}:{node.lineno} {node.value}")
    assert not found, found
