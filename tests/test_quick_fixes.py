"""The quick fixes the rules work out with their diagnostics (MB003, MB004, MB101, MB404,
MB601): the fix data itself, the code actions the ide layer makes of it, and that each fix,
applied to the text, gives a program without that diagnostic and without a new one."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.diagnostics import Diagnostic, Fix, FixEdit, Severity
from fanuc_macro.ide.actions import code_actions
from fanuc_macro.ide.data import ActionKind, DocumentEdit, Problem, Range, TextEdit
from fanuc_macro.ide.view import View
from fanuc_macro.syntax.lines import split_lines

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures" / "rules"
FIXED_CODES = ("MB003", "MB004", "MB101", "MB404", "MB601")
SERIOUS = (Severity.ERROR, Severity.WARNING)


def diagnostics(text: str, code: str | None = None) -> list[Diagnostic]:
    found = analyse(text, "file:///fixes.nc").diagnostics
    return [d for d in found if code is None or d.code == code]


def only(text: str, code: str) -> Diagnostic:
    (found,) = diagnostics(text, code)
    return found


def apply(text: str, fix: Fix) -> str:
    """The text with the fix's edits made, the last place first so the others keep theirs."""
    lines = text.split("\n")
    for e in sorted(fix.edits, key=lambda e: (e.line, e.column), reverse=True):
        assert e.line == e.end_line  # these rules' fixes stay on one line
        line = lines[e.line]
        lines[e.line] = line[: e.column] + e.text + line[e.end_column :]
    return "\n".join(lines)


# ---- the fix data ----------------------------------------------------------------------------


def test_mb601_replaces_the_variable_by_the_suggested_one() -> None:
    text = "O6001 (SPINDLE)\n#13=3 (M CODE)\n#1=3.5\nM#1\nM30\n"
    found = only(text, "MB601")
    assert "did you mean M#13?" in found.message
    assert found.fixes == (
        Fix("Use M#13 (#13 is set to 3 at line 2)", (FixEdit(3, 1, 3, 3, "#13"),), True),
    )
    assert apply(text, found.fixes[0]).split("\n")[3] == "M#13"


def test_mb601_offers_no_fix_when_the_suggested_value_is_not_a_whole_constant() -> None:
    # #13 gets a fraction, or a value computed at run time: the suggestion stays a question.
    for value in ("3.5", "#5+1"):
        text = f"O6001 (SPINDLE)\n#13={value} (M CODE)\n#1=3.5\nM#1\nM30\n"
        found = [d for d in diagnostics(text, "MB601") if d.line == 3]
        assert found and "did you mean M#13?" in found[0].message
        assert found[0].fixes == ()


def test_mb101_retargets_to_the_nearest_label_of_its_own_program() -> None:
    text = "O3003\nN10 #1=#1+1\nN20 G00 X1.\nIF[#1LT#2]GOTO18\nM99\nO3004\nN17 M99\n"
    found = only(text, "MB101")
    assert found.fixes == (
        Fix(
            "Change GOTO 18 to GOTO 20 (the nearest label, N20 at line 3)",
            (FixEdit(3, 14, 3, 16, "20"),),
        ),
    )
    assert not found.fixes[0].preferred  # nearest in number is a guess at the intent


def test_mb101_takes_the_lower_of_two_labels_as_near_and_skips_loops_and_copies() -> None:
    # N4 and N6 are both 1 from 5: the lower wins.
    text = "O1\nN4 G00 X1.\nN6 G00 X2.\nGOTO5\nM99\n"
    assert only(text, "MB101").fixes[0].edits == (FixEdit(3, 4, 3, 5, "4"),)
    # N6 stands twice and N7 is inside a loop the jump is outside of: N1 is what is left.
    text = "O1\nN1 #1=0\nN6 G00 X1.\nN6 G00 X2.\nWHILE[#1LT2]DO1\nN7 #1=#1+1\nEND1\nGOTO5\nM99\n"
    fix = only(text, "MB101").fixes[0]
    assert fix.edits == (FixEdit(7, 4, 7, 5, "1"),) and "N1 at line 2" in fix.title


def test_mb101_has_no_fix_in_a_program_without_labels() -> None:
    text = "O1\nG00 X1.\nGOTO5\nM99\n"
    assert only(text, "MB101").fixes == ()


def test_mb404_inserts_the_decimal_point_after_the_digits() -> None:
    text = "O1\nG65 P9001 A10 Z-10 B2.5\nM30\nO9001\nM99\n"
    a10, z10 = diagnostics(text, "MB404")
    assert a10.fixes == (Fix("Add the decimal point: A10.", (FixEdit.insert(1, 13, "."),), True),)
    assert z10.fixes == (Fix("Add the decimal point: Z-10.", (FixEdit.insert(1, 18, "."),), True),)


def test_mb004_closes_the_comment_before_the_trailing_blanks() -> None:
    text = "O2000\nG00 X100. (RETRACT  \t\nM30\n"
    found = only(text, "MB004")
    assert found.fixes == (
        Fix(
            "Close the comment with ')' at the end of the line",
            (FixEdit.insert(1, 18, ")"),),
            preferred=True,
            safe=True,  # check --fix applies it: the control reads the comment to the end
        ),
    )
    assert apply(text, found.fixes[0]).split("\n")[1] == "G00 X100. (RETRACT)  \t"


def test_mb003_takes_the_nested_parentheses_out_of_the_comment() -> None:
    text = "O9123\nG00 X1. (TOOL (T0101) BORING BAR) (NEXT)\nM99\n"
    found = only(text, "MB003")
    assert found.fixes == (
        Fix(
            "Remove the parentheses nested in the comment",
            (FixEdit(1, 8, 1, 33, "(TOOL T0101 BORING BAR)"),),
            preferred=True,
            safe=True,
        ),
    )


def test_the_fixes_stand_on_the_line_of_a_repeated_line_rule_finding() -> None:
    # A line rule's findings are worked out once per line text: each block gets its own line.
    text = "O1\nG00 X1. (A\nG00 X1. (A\nM30\n"
    lines = [d.fixes[0].edits[0].line for d in diagnostics(text, "MB004")]
    assert lines == [1, 2]


# ---- every fix of the rules' fixtures cures its diagnostic ------------------------------------


def _fixture_text(path: Path) -> str:
    return "\n".join(split_lines(path.read_text(encoding="utf-8")))


def _fixed_cases() -> list[tuple[str, str, int]]:
    cases = []
    for path in sorted(FIXTURES.glob("MB*.nc")):
        code = path.name.split("_")[0]
        if code not in FIXED_CODES:
            continue
        for i, d in enumerate(diagnostics(_fixture_text(path), code)):
            for k in range(len(d.fixes)):
                cases.append((path.name, f"{d.line + 1}:{d.column + 1}#{i}", k))
    return cases


def test_every_fixed_rule_has_a_fix_in_its_fixture() -> None:
    codes = {name.split("_")[0] for name, _, _ in _fixed_cases()}
    assert codes == set(FIXED_CODES)


@pytest.mark.parametrize(("name", "where", "k"), _fixed_cases())
def test_a_fix_removes_its_diagnostic_and_adds_none(name: str, where: str, k: int) -> None:
    text = _fixture_text(FIXTURES / name)
    code = name.split("_")[0]
    before = diagnostics(text)
    target = [d for d in before if d.code == code][int(where.split("#")[1])]
    fixed = apply(text, target.fixes[k])
    assert fixed != text
    after = diagnostics(fixed)
    # The same kind of diagnostic no longer stands there...
    assert not any(
        d.code == code and d.line == target.line and d.column == target.column for d in after
    )

    # ...and no other error or warning appears: each line's are some of those it had, less
    # this one. (Information may: a GOTO retargeted past a block leaves it unreached, MB702.)
    def serious(found: list[Diagnostic]) -> Counter[tuple[str, int]]:
        return Counter((d.code, d.line) for d in found if d.severity in SERIOUS)

    left = serious(before)
    left[(code, target.line)] = max(0, left[(code, target.line)] - 1)
    assert not serious(after) - left


# ---- the ide layer's code actions -------------------------------------------------------------


def test_code_actions_offer_the_rule_fix_before_the_suppression() -> None:
    text = "O1\nG65 P9001 A10\nM30\nO9001\nM99\n"
    analysis = analyse(text, "main.nc")
    view = View("main.nc", analysis, Config())
    problem = Problem("MB404", 1, 10)
    fix, suppress = code_actions(view, [problem], "\n")
    assert fix.title == "Add the decimal point: A10." and fix.preferred
    assert fix.kind is ActionKind.QUICK_FIX and fix.fixes[0] is problem
    assert fix.edits == (DocumentEdit("main.nc", (TextEdit(Range.of(1, 13, 1, 13), "."),)),)
    assert suppress.title == "Suppress MB404 on this line"
    # Another place, or another code at that place, is not this diagnostic: no fix of its.
    assert [a.title for a in code_actions(view, [Problem("MB404", 1, 11)], "\n")] == [
        "Suppress MB404 on this line"
    ]
    assert [a.title for a in code_actions(view, [Problem("MB601", 1, 10)], "\n")] == [
        "Suppress MB601 on this line"
    ]
