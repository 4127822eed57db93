"""Rule fixtures, the rule documentation, suppression comments and rule settings.

Each fixture ``tests/fixtures/rules/MBxxx_<name>[_<variant>].nc`` is a small program in which
every line that must produce a diagnostic carries ``(expect: MBxxx)`` (several codes:
``(expect: MB101 MB103)``). The codes a fixture is about are the one in its file name and those
of its expect comments; for those codes, the diagnostics must stand exactly on the expected
lines, and nowhere else in the file. A rule that needs a setting (a machine limit) is tested with
a comment ``(settings: {"machine": {"maxSpindleSpeed": 4000}})``: the editor's settings object
under ``fanuc-macro``, in JSON.

The lists of codes are read from ``fanuc_macro.analysis.RULES`` when the tests are
collected, so a rule declared later (the evaluator's MB5xx-MB9xx) is covered as soon as it is
declared: it needs a section in docs/rules.md and a fixture. The sections are generated from
the RuleDoc beside each rule's function (scripts/rules_doc.py; tests/test_rules_doc.py checks
the file is not stale), and these tests read the generated file as a user would.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from functools import cache
from pathlib import Path

import pytest

from fanuc_macro.analysis import RULES, Analysis, analyse
from fanuc_macro.config import NOT_SET, Config
from fanuc_macro.diagnostics import Diagnostic, Severity
from fanuc_macro.rules.context import RuleContext
from fanuc_macro.syntax.lines import decode_bytes, split_lines
from fanuc_macro.syntax.parser import parse_bytes

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures" / "rules"
DOCS = ROOT / "docs" / "rules.md"

EXPECT = re.compile(r"\(expect:([^)]*)\)")
SETTINGS = re.compile(r"\(settings:([^)]*)\)")
CODE = re.compile(r"MB\d{3}")
HEADING = re.compile(r"^## (MB\d{3}) (\S+)\s*$", re.M)
FENCE = re.compile(r"^```nc\n(.*?)^```", re.M | re.S)

ALL_CODES = sorted(RULES)
FIXTURE_FILES = sorted(FIXTURES.glob("MB*.nc"))


# ---- helpers ---------------------------------------------------------------------------------


def fixture_code(path: Path) -> str:
    return path.name.split("_")[0]


@cache
def fixture_analysis(path: Path) -> tuple[Analysis, dict[int, set[str]]]:
    """The analysis of a fixture, read from bytes as the CLI does, and its expect comments."""
    data = path.read_bytes()
    text = decode_bytes(data).text
    config = fixture_config(path)
    doc = parse_bytes(data, str(path), limits=(config or Config()).read_limits)
    expected: dict[int, set[str]] = {}
    for line, line_text in enumerate(split_lines(text)):  # those the analysis reads or not
        for m in EXPECT.finditer(line_text):
            expected.setdefault(line, set()).update(CODE.findall(m.group(1)))
    return analyse(text, str(path), config, doc=doc), expected


def fixture_settings(path: Path) -> dict[str, object]:
    """The settings of a fixture's ``(settings: {...})`` comments: read from its lines before
    it is parsed, since some (the limits of what the analysis reads) change the parse."""
    settings: dict[str, object] = {}
    for line_text in split_lines(decode_bytes(path.read_bytes()).text):
        for m in SETTINGS.finditer(line_text):
            settings.update(json.loads(m.group(1)))
    return settings


def fixture_config(path: Path) -> Config | None:
    settings = fixture_settings(path)
    return Config.from_settings(settings) if settings else None


@cache
def doc_sections() -> dict[str, tuple[str, str]]:
    """code -> (name in the heading, text of the section up to the next heading)."""
    text = DOCS.read_text("utf-8")
    heads = list(HEADING.finditer(text))
    sections: dict[str, tuple[str, str]] = {}
    for i, m in enumerate(heads):
        end = heads[i + 1].start() if i + 1 < len(heads) else len(text)
        code = m.group(1)
        assert code not in sections, f"docs/rules.md has two sections for {code}"
        sections[code] = (m.group(2), text[m.end() : end])
    return sections


def pairs(diags: list[Diagnostic], *codes: str) -> set[tuple[int, str]]:
    return {(d.line, d.code) for d in diags if d.code in codes}


def codes_of(text: str, config: Config | None = None) -> set[str]:
    return {d.code for d in analyse(text, config=config).diagnostics}


# ---- fixtures ----------------------------------------------------------------------------------


def test_there_are_fixtures() -> None:
    assert len(FIXTURE_FILES) >= len([c for c in ALL_CODES if c < "MB500"])


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: p.name)
def test_fixture_name(path: Path) -> None:
    code, name, *_variant = path.stem.split("_")
    assert code in RULES, f"{path.name}: {code} is not a registered rule"
    assert name == RULES[code].name, f"{path.name}: the rule {code} is named {RULES[code].name}"


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: p.name)
def test_fixture_diagnostics(path: Path) -> None:
    analysis, expected = fixture_analysis(path)
    about = {fixture_code(path)} | {c for codes in expected.values() for c in codes}
    want = {(line, code) for line, codes in expected.items() for code in codes}
    got = pairs(analysis.diagnostics, *about)
    shown = {(line + 1, code) for line, code in got}  # 1-based in the messages, as in editors
    assert got == want, (
        f"missing (1-based line, code): {sorted((ln + 1, c) for ln, c in want - got)}; "
        f"unexpected: {sorted((ln + 1, c) for ln, c in got - want)}; all: {sorted(shown)}"
    )


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: p.name)
def test_fixture_has_a_negative_part(path: Path) -> None:
    """Blocks without an expect comment: correct code that must not trigger the rule."""
    analysis, expected = fixture_analysis(path)
    quiet = [
        b
        for b in analysis.doc.blocks
        if b.parsed.statement is not None and fixture_code(path) not in expected.get(b.line, ())
    ]
    assert len(quiet) >= 2


@pytest.mark.parametrize("path", FIXTURE_FILES, ids=lambda p: p.name)
def test_fixture_never_fails_internally(path: Path) -> None:
    analysis, _ = fixture_analysis(path)
    assert not [d for d in analysis.diagnostics if d.code == "MB000"]


# ---- every registered rule: documented, with a fixture ---------------------------------------


@pytest.mark.parametrize("code", ALL_CODES)
def test_rule_has_doc_section_and_fixture(code: str) -> None:
    info = RULES[code]
    sections = doc_sections()
    assert code in sections, f"docs/rules.md has no section '## {code} {info.name}'"
    name, body = sections[code]
    assert name == info.name, f"docs/rules.md names {code} '{name}', the rule is '{info.name}'"
    assert info.severity.value in body, f"the section of {code} does not give its severity"
    fixtures = [p for p in FIXTURE_FILES if fixture_code(p) == code]
    assert fixtures, f"no fixture tests/fixtures/rules/{code}_{info.name}.nc"


@pytest.mark.parametrize("code", ALL_CODES)
def test_rule_doc_says_what_it_does_not_report(code: str) -> None:
    _name, body = doc_sections()[code]
    assert "**What it does not report.**" in body, f"the section of {code} has no such paragraph"


def test_doc_sections_are_registered_rules() -> None:
    stale = {code for code in doc_sections() if code not in RULES}
    assert not stale, f"docs/rules.md documents codes that are not registered: {sorted(stale)}"


def test_doc_sections_in_code_order() -> None:
    codes = list(doc_sections())
    assert codes == sorted(codes)


def _example(code: str) -> str:
    m = FENCE.search(doc_sections()[code][1])
    assert m is not None, f"the section of {code} has no ```nc example"
    return m.group(1)


# "The example assumes `"fanuc-macro.machine.maxSpindleSpeed": 4000`": a setting the example
# needs, as the section states it.
EXAMPLE_SETTING = re.compile(r'`"fanuc-macro\.([\w.]+)":\s*([^`]+)`')


def _example_config(code: str) -> Config | None:
    settings: dict[str, object] = {}
    for key, value in EXAMPLE_SETTING.findall(doc_sections()[code][1]):
        *groups, name = key.split(".")
        node = settings
        for group in groups:
            child = node.setdefault(group, {})
            assert isinstance(child, dict)
            node = child
        node[name] = json.loads(value)
    return Config.from_settings(settings) if settings else None


@pytest.mark.parametrize("code", [c for c in ALL_CODES if c != "MB000"])
def test_doc_example_triggers_its_rule(code: str) -> None:
    """The example of each section produces the diagnostic it illustrates.

    MB000 has none: no correct program makes the analyser fail.
    """
    text = _example(code)
    if code == "MB007":  # the example is a file saved in GB18030, its third line in UTF-8
        lines = text.splitlines(keepends=True)
        data = b"".join(
            line.encode("utf-8" if n == 2 else "gb18030") for n, line in enumerate(lines)
        )
        analysis = analyse(text, "example.nc", doc=parse_bytes(data, "example.nc"))
    else:
        analysis = analyse(text, "example.nc", _example_config(code))
    assert code in {d.code for d in analysis.diagnostics}, text


# ---- MB000: a failing rule is reported, the others still run -----------------------------------


def test_failing_rule_gives_mb000_and_others_still_report() -> None:
    def broken(ctx: RuleContext) -> Iterator[Diagnostic]:
        raise RuntimeError("rule bug")
        yield  # pragma: no cover

    analysis = analyse("O1000\nGOTO 5\nM30\n", extra_checks=[broken])
    internal = [d for d in analysis.diagnostics if d.code == "MB000"]
    assert len(internal) == 1
    assert internal[0].severity is Severity.ERROR
    assert "rule bug" in internal[0].message
    assert "MB101" in {d.code for d in analysis.diagnostics}


# ---- suppression comments ----------------------------------------------------------------------

DEEP = "#1=SIN[[[[[[#2]]]]]]"  # six levels: MB301


def test_deep_brackets_trigger_without_a_comment() -> None:
    assert "MB301" in codes_of(f"O1000\n{DEEP}\nM30\n")


@pytest.mark.parametrize(
    "comment",
    [
        "(fanuc-macro: ignore MB301)",
        "(FANUC-MACRO: IGNORE mb301)",
        "(fanuc-macro:ignore MB301 - checked by hand)",
        "(fanuc-macro: ignore MB101 MB301)",
        "(fanuc-macro: ignore MB101, MB301)",
        "(fanuc-macro: ignore)",
    ],
)
def test_suppression_comment_hides_the_code(comment: str) -> None:
    assert "MB301" not in codes_of(f"O1000\n{DEEP} {comment}\nM30\n")


def test_suppression_names_only_some_codes() -> None:
    text = "O1000\nG00 X#50 Z#200 (fanuc-macro: ignore MB302)\nM30\n"
    found = codes_of(text)
    assert "MB302" not in found
    assert "MB303" in found


def test_suppression_of_several_codes() -> None:
    text = "O1000\nG00 X#50 Z#200 (fanuc-macro: ignore MB302 MB303)\nM30\n"
    assert not codes_of(text) & {"MB302", "MB303"}


def test_suppression_without_code_hides_everything_on_its_line_only() -> None:
    text = "O1000\nGOTO 5 (fanuc-macro: ignore)\nGOTO 6\nM30\n"
    diags = analyse(text).diagnostics
    assert pairs(diags, "MB101") == {(2, "MB101")}
    assert not [d for d in diags if d.line == 1]


def test_suppression_comment_before_the_code_of_the_line() -> None:
    text = f"O1000\n(fanuc-macro: ignore MB301) {DEEP}\nM30\n"
    assert "MB301" not in codes_of(text)


def test_ignore_file_hides_the_codes_it_names_in_the_whole_file() -> None:
    text = "O1000 (fanuc-macro: ignore-file MB101)\nGOTO 5\nGOTO 6\nM99 P7\nM30\n"
    found = analyse(text).diagnostics
    assert not pairs(found, "MB101")
    everything = "O1000\nGOTO 5\n(fanuc-macro: ignore-file)\nGOTO 6\nM30\n"
    assert analyse(everything).diagnostics == []
    # "ignore-file MB301" is not an "ignore" of every code of its line
    assert "MB101" in codes_of("O1000\nGOTO 5 (fanuc-macro: ignore-file MB301)\nM30\n")


def test_ignore_start_and_end_hide_the_lines_between_them() -> None:
    text = (
        "O1000\nGOTO 5\n(fanuc-macro: ignore-start MB101)\nGOTO 6\nGOTO 7\n"
        "(fanuc-macro: ignore-end MB101)\nGOTO 8\nM30\n"
    )
    assert {line for line, _code in pairs(analyse(text).diagnostics, "MB101")} == {1, 6}
    unclosed = "O1000\nGOTO 5\n(fanuc-macro: ignore-start)\nGOTO 6\nGOTO 7\nM30\n"
    assert {line for line, _code in pairs(analyse(unclosed).diagnostics, "MB101")} == {1}


def test_a_suppression_is_not_judged_when_a_rule_failed() -> None:
    # The failed rule may have been the one whose finding the comment hides.
    text = "O1000\n#1=SIN[30.] (fanuc-macro: ignore MB301)\nM30\n"
    assert "MB015" in {d.code for d in analyse(text).diagnostics}

    def broken(_ctx: object) -> list[Diagnostic]:
        raise RuntimeError("a rule's bug")

    found = {d.code for d in analyse(text, extra_checks=[broken]).diagnostics}
    assert "MB000" in found and "MB015" not in found


def test_other_comment_does_not_suppress() -> None:
    text = f"O1000\n{DEEP} (IGNORE MB301)\nM30\n"
    assert "MB301" in codes_of(text)


def test_suppression_of_a_file_diagnostic_on_the_first_line() -> None:
    def mb007(first_comment: str) -> set[str]:
        text = f"O1000 ({first_comment})\n(中文注释 螺纹)\nM30\n"
        data = text.encode("gb18030") + "(粘贴的 UTF-8 注释)\n".encode()  # two encodings
        return {d.code for d in analyse(text, doc=parse_bytes(data)).diagnostics}

    assert "MB007" in mb007("MAIN")
    assert "MB007" not in mb007("fanuc-macro: ignore MB007")


# ---- Config: disabled rules and severities ------------------------------------------------------

ERRORS = "O1000\nGOTO 5\nG00 X#50\nM98 P2000\nM30\n"  # MB101, MB302, MB403


def test_default_config_reports_the_errors() -> None:
    assert {"MB101", "MB302", "MB403"} <= codes_of(ERRORS)


def test_config_disabled() -> None:
    found = codes_of(ERRORS, Config(disabled=frozenset({"MB101", "MB403"})))
    assert "MB101" not in found
    assert "MB403" not in found
    assert "MB302" in found


@pytest.mark.parametrize("code", ALL_CODES)
def test_config_disables_each_rule(code: str) -> None:
    """A disabled code never appears, whatever the program (here: its fixtures)."""
    for path in FIXTURE_FILES:
        if fixture_code(path) != code:
            continue
        config = Config.from_settings({**fixture_settings(path), "rules": {"disabled": [code]}})
        analysis, _ = fixture_analysis(path)
        if code == "MB007":
            again = analyse("", str(path), config=config, doc=analysis.doc)
        else:
            again = analyse(decode_bytes(path.read_bytes()).text, str(path), config=config)
        assert code not in {d.code for d in again.diagnostics}


def test_config_severities() -> None:
    default = {d.code: d for d in analyse(ERRORS).diagnostics}
    config = Config(severities={"MB101": Severity.WARNING, "MB403": Severity.ERROR})
    changed = {d.code: d for d in analyse(ERRORS, config=config).diagnostics}
    assert default["MB101"].severity is Severity.ERROR
    assert changed["MB101"].severity is Severity.WARNING
    assert default["MB403"].severity is Severity.WARNING
    assert changed["MB403"].severity is Severity.ERROR
    assert changed["MB302"].severity is default["MB302"].severity
    assert changed["MB101"].message == default["MB101"].message
    assert (changed["MB101"].line, changed["MB101"].column) == (
        default["MB101"].line,
        default["MB101"].column,
    )


def test_config_from_editor_settings() -> None:
    config = Config.from_settings(
        {"rules": {"disabled": ["mb403"], "severity": {"MB101": "Warning", "MB302": "nonsense"}}}
    )
    assert config.disabled == frozenset({"MB403"})
    assert config.severities == {"MB101": Severity.WARNING}
    diags = {d.code: d for d in analyse(ERRORS, config=config).diagnostics}
    assert "MB403" not in diags
    assert diags["MB101"].severity is Severity.WARNING
    assert diags["MB302"].severity is Severity.ERROR


@pytest.mark.parametrize(
    ("text", "fixes"),
    [
        ("IF [#1 AND #2 LT 0] GOTO 5", ["[#1 LT 0] AND [#2 LT 0]", "[#1 AND #2] LT 0"]),
        ("IF [#3 EQ #1 OR #2] GOTO 5", ["[#3 EQ #1] OR [#3 EQ #2]", "#3 EQ [#1 OR #2]"]),
        (
            "WHILE [#1 XOR #2 XOR #3 NE 0] DO1",
            ["[#1 NE 0] XOR [#2 NE 0] XOR [#3 NE 0]", "[#1 XOR #2 XOR #3] NE 0"],
        ),
        # Mixed operators or the logic inside arithmetic: only the control's reading.
        ("IF [#1 OR #2 AND #3 EQ 1] GOTO 5", ["[#1 OR #2 AND #3] EQ 1"]),
        ("IF [#1+#2 AND #3 LT 0] GOTO 5", ["#1+[#2 AND #3] LT 0"]),
    ],
)
def test_logic_operand_fixes(text: str, fixes: list[str]) -> None:
    from fanuc_macro.rules.expressions import logic_fixes, logic_operands
    from fanuc_macro.syntax.parser import default_parser

    parsed = default_parser().parse_line(text)
    assert parsed.statement is not None
    [found] = logic_operands(parsed.statement)
    assert [rewritten for _, rewritten in logic_fixes(text, found)] == fixes


def test_logic_operand_fix_must_keep_within_five_brackets() -> None:
    from fanuc_macro.rules.expressions import acceptable_fix

    assert acceptable_fix("IF [[#1 LT 0] AND [#2 LT 0]] GOTO 5 (OK [[[[[ ]]]]])", 1)
    assert acceptable_fix("IF [[ABS[[[#1]]] LT 0] AND [#2 LT 0]] GOTO 5", 1)  # five deep
    assert not acceptable_fix("IF [[ABS[[[[#1]]]] LT 0] AND [#2 LT 0]] GOTO 5", 1)  # six
    assert not acceptable_fix("IF [[#1 LT 0] AND [#2 LT 0] GOTO 5", 1)  # not closed


def test_duplicate_label_dead_copy_needs_the_evaluator() -> None:
    text = "O2004\n#1=1.\nN30 G00 X10.\nIF[#1EQ2.]GOTO30\nG00 X20.\nM30\nN30 G00 X30.\nM30\n"
    assert pairs(analyse(text).diagnostics, "MB102") == {(3, "MB102")}
    assert not pairs(analyse(text, run_evaluator=False).diagnostics, "MB102")
    # A common variable the analysis does not know leaves the branch undecided: nothing is dead.
    undecided = text.replace("#1=1.\n", "").replace("#1EQ", "#100EQ")
    assert not pairs(analyse(undecided).diagnostics, "MB102")


def test_extended_commons_once_per_file_with_the_count_and_range() -> None:
    lines = ["O9040", "#1=1."] + [f"#{200 + i % 300}=#5061" for i in range(167)] + ["M99"]
    diags = [d for d in analyse("\n".join(lines) + "\n").diagnostics if d.code == "MB303"]
    [mb303] = diags
    assert mb303.line == 2 and (mb303.column, mb303.end_column) == (0, 4)
    first = "#200 is the first of 167 uses of #200-#499 in this file, lines 3-169"
    assert first in mb303.message
    assert "#200, #201, #202, #203, #204, #205, ..." in mb303.message
    assert [r.line for r in mb303.related] == [168]
    one = analyse("O9040\n#1=#450\nM99\n").diagnostics
    assert [d.message.split(":")[0] for d in one if d.code == "MB303"] == [
        "#450 is its only use in this file"
    ]


def test_extended_commons_setting_says_the_option_is_there() -> None:
    text = "O9040\n#200=#5061\nG00 X#350\nM99\n"
    assert "MB303" in codes_of(text)
    config = Config.from_settings({"machine": {"extendedCommons": True}})
    assert config.extended_commons
    assert "MB303" not in codes_of(text, config)
    assert not Config.from_settings({"machine": {"extendedCommons": "yes"}}).extended_commons


def test_machine_limits_are_checked_only_when_set() -> None:
    """No default machine limit: a spindle speed is too high only against one the user set."""
    assert Config().max_spindle_speed == NOT_SET == Config().max_threading_feed
    unset = Config.from_settings({"machine": {"maxSpindleSpeed": None, "maxThreadingFeed": 0}})
    assert unset.max_spindle_speed == NOT_SET == unset.max_threading_feed
    limited = Config.from_settings({"machine": {"maxSpindleSpeed": 6000}})
    assert limited.max_spindle_speed == 6000.0
    text = "O1000\n#19=6500.\nS#19 M03\n#19=5000.\nS#19 M03\nM30\n"
    assert "MB602" not in codes_of(text)
    assert pairs(analyse(text, config=limited).diagnostics, "MB602") == {(2, "MB602")}


def test_docs_name_every_word_the_threading_rules_know() -> None:
    from fanuc_macro.program.meanings import KNOWN_MODULES, ROLE_WORDS

    text = (ROOT / "docs" / "rules.md").read_text("utf-8")
    for words in ROLE_WORDS.values():
        for word in words:
            assert f"`{word}`" in text, word
    for number in KNOWN_MODULES:
        assert f"| O{number:04d} |" in text


@pytest.mark.parametrize(
    ("comment", "role"),
    [
        ("#18 为刀尖圆弧半径", "nose_radius"),
        ("#4 为粗车第一层圆弧槽的半径", "groove_radius"),
        ("刀尖半径", "nose_radius"),
        ("计算外螺纹牙高", "thread_height"),
        ("THREAD HEIGHT H=1.907", "thread_height"),
        ("螺纹公称直径", "nominal_diameter"),
        ("FEED", None),
    ],
)
def test_role_of_comment(comment: str, role: str | None) -> None:
    from fanuc_macro.program.meanings import role_of_comment

    assert role_of_comment(comment) == role
