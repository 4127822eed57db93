"""A rule stands alone: what an editor shows of its diagnostics (tags, fixes) comes with the
diagnostic the rule makes, and the front ends only convert it (no rule code in ide/ or lsp/).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path
from types import MappingProxyType, ModuleType

import pytest
from lsprotocol import types

import fanuc_macro
from fanuc_macro.analysis import RULE_DOCS, RULES, analyse
from fanuc_macro.config import Config
from fanuc_macro.diagnostics import Diagnostic, Fix, FixEdit, RuleDoc, RuleInfo, Severity, Tag
from fanuc_macro.ide.actions import code_actions
from fanuc_macro.ide.data import Problem, Range, TextEdit
from fanuc_macro.ide.view import View
from fanuc_macro.lsp.convert import Codec, Lines, to_lsp_diagnostic
from fanuc_macro.rules import FAMILIES, declared
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
        LineFinding("MB301", "kept", 6, 7),
        LineFinding("MB302", "FANUC's variable numbers: not applied", 10, 11),
        LineFinding("MB003", "comment", 8, 9),
    )
    folded = in_foreign_file(findings, parsed, foreign)
    assert [(f.code, f.start, f.end) for f in folded] == [("MB301", 6, 7), ("MB002", 2, 5)]
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


# ---- the registry and the layout of a rule family -------------------------------------------


def test_the_registry_is_read_only_and_built_from_the_declarations() -> None:
    assert isinstance(RULES, MappingProxyType) and isinstance(RULE_DOCS, MappingProxyType)
    assert list(RULES) == sorted(RULES) and list(RULE_DOCS) == list(RULES)
    for module in FAMILIES:
        for name, value in vars(module).items():
            if isinstance(value, RuleInfo):
                assert name == value.code and RULES[name] is value
            if isinstance(value, RuleDoc):
                assert name == f"{value.code}_DOC" and RULE_DOCS[value.code] is value
    with pytest.raises(TypeError):
        RULES["MB999"] = RULES["MB101"]  # type: ignore[index]


def test_a_code_declared_twice_is_an_error() -> None:
    other = RuleInfo("MB101", "other", Severity.ERROR, "another rule", "jumps")
    with pytest.raises(ValueError, match="MB101 declared twice"):
        declared(RuleInfo, FAMILIES, other)


@pytest.mark.parametrize("module", FAMILIES, ids=lambda m: m.__name__.rsplit(".", 1)[-1])
def test_each_rules_documentation_is_beside_the_function_that_finds_it(module: ModuleType) -> None:
    """Each ``MBxxx_DOC`` is followed (after the other docs of that place) by the first
    top-level function that names its rule: ``MBxxx`` given to ``make`` or ``"MBxxx"`` in a
    line finding."""
    assert module.__file__ is not None
    tree = ast.parse(Path(module.__file__).read_text("utf-8"))
    codes = sorted(n for n, v in vars(module).items() if isinstance(v, RuleInfo))
    assert codes
    placed: dict[str, str] = {}
    pending: list[str] = []
    for node in tree.body:
        target = node.targets[0] if isinstance(node, ast.Assign) else None
        if isinstance(target, ast.Name) and target.id.endswith("_DOC"):
            pending.append(target.id.removesuffix("_DOC"))
        elif isinstance(node, ast.FunctionDef | ast.ClassDef) and pending:
            for code in pending:
                placed[code] = node.name
                # the code itself, or a module table naming it (math_domain's alarms)
                names = {code} | _tables_naming(tree, code)
                assert any(_names(n, names) for n in ast.walk(node)), (
                    f"{code}_DOC is above {node.name}, which does not find it"
                )
            pending = []
    assert sorted(placed) == codes, f"documented beside a function: {sorted(placed)}"


def _names(node: ast.AST, names: set[str]) -> bool:
    return (isinstance(node, ast.Name) and node.id in names) or (
        isinstance(node, ast.Constant) and node.value in names
    )


def _tables_naming(tree: ast.Module, code: str) -> set[str]:
    """The module-level names whose value names ``code``."""
    return {
        target.id
        for node in tree.body
        if isinstance(node, ast.Assign) and any(_names(n, {code}) for n in ast.walk(node.value))
        for target in node.targets
        if isinstance(target, ast.Name) and not target.id.startswith("MB")
    }
