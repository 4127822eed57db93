"""No input freezes or crashes the analysis: hostile lines, deep and long expressions, huge
files, arithmetic past the control's range.

Time is checked as growth where it can be (twice the input may cost at most about three times
as much: a backtracking regex grows four times or more per word), with generous wall-clock
bounds only as a backstop.
"""

from __future__ import annotations

import dataclasses
import json
import re
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from fanuc_macro import cli
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.evaluator import compiler
from fanuc_macro.evaluator.compiler import compile_cond, compile_expr, constant_of
from fanuc_macro.syntax.lines import ReadLimits, cut_comments
from fanuc_macro.syntax.parser import BlockParser, fast_parse, parse_text
from fanuc_macro.syntax.tree import Binary, Call, Compare, Cond, Expr, Logic, Num, Span, Var
from fanuc_macro.syntax.walk import bracket_depth, cond_exprs, subexpressions
from fanuc_macro.workspace import Workspace

ROOT = Path(__file__).resolve().parents[1]

GRAMMAR = BlockParser(use_fast_path=False)

# Lines that froze the fast path's old regex (it backtracked exponentially on them), and lines
# built to make a regex or a scanner retry: long runs that fail at their very end.
HOSTILE_LINES = {
    "integer words then a bracket": "G65P9010A1000B1000C1000D1000E1000F1000H1000I1000J1000K1000"
    "X#[#1+1]",
    "repeated words then '['": "X11" * 22 + "[",
    "digits then a letter": "X" + "1" * 3000 + "a",
    "spaces then a bad character": "X" + " " * 3000 + "!",
    "block delete then spaces": "/" + " " * 3000 + "!",
    "letters": "A" * 3000,
    "semicolons": ";" * 3000,
    "words then a comma": "X1.0" * 700 + ",",
    "decimal points": "X1." * 1000 + ".",
    "signs": "X-" * 1000 + "1",
}


def _seconds(fn: Callable[[], object], repeat: int = 5) -> float:
    """The best of a few runs: the least disturbed by the other processes of the machine."""
    best = float("inf")
    for _ in range(repeat):
        started = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - started)
    return best


def _growth(make: Callable[[int], str], parse: Callable[[str], object], n: int) -> float:
    """How much longer the input of size 4n takes than the one of size n."""
    small, large = make(n), make(4 * n)
    return _seconds(lambda: parse(large)) / max(_seconds(lambda: parse(small)), 1e-6)


# ---- the scanner: linear on every line -------------------------------------------------------

FAMILIES: dict[str, Callable[[int], str]] = {
    "integer words then '['": lambda n: "G65P9010" + "A1000" * n + "X#[#1+1]",
    "words then '['": lambda n: "X11" * n + "[",
    "words then a comma": lambda n: "X1.0" * n + ",",
    "a digit run then a letter": lambda n: "X" + "1" * (4 * n) + "a",
    "a space run then '!'": lambda n: "X" + " " * (4 * n) + "!",
    "block delete, spaces": lambda n: "/" + " " * (4 * n) + "!",
    "signed words then '#'": lambda n: "X-1.5 Y+2." * n + "#",
}


@pytest.mark.parametrize("name", FAMILIES)
def test_fast_path_time_grows_linearly(name: str) -> None:
    make = FAMILIES[name]
    growth = _growth(make, fast_parse, 400)
    # Linear is 4; the old regex was 4**400 on the first family. 12 leaves room for noise.
    assert growth < 12, f"{name}: 4x the input took {growth:.1f}x the time"


@pytest.mark.parametrize("name", FAMILIES)
def test_whole_line_parse_time_grows_linearly(name: str) -> None:
    """Fast path, grammar and the description of the syntax error together."""
    make = FAMILIES[name]
    growth = _growth(make, lambda text: BlockParser().parse_line(text), 200)
    assert growth < 12, f"{name}: 4x the input took {growth:.1f}x the time"


@pytest.mark.parametrize("name", HOSTILE_LINES)
def test_hostile_line_is_read_quickly_and_as_the_grammar_reads_it(name: str) -> None:
    text = HOSTILE_LINES[name]
    fast = BlockParser()
    started = time.perf_counter()
    parsed = fast.parse_line(text)
    assert time.perf_counter() - started < 1.0  # a backstop: these take milliseconds
    assert parsed == GRAMMAR.parse_line(text)


@pytest.mark.parametrize(
    "make",
    [lambda n: ";" * (4 * n), lambda n: "(()" * n, lambda n: "(" * n + ")" * n],
    ids=["end-of-block marks", "nested comments", "a deep comment"],
)
def test_cut_comments_is_linear(make: Callable[[int], str]) -> None:
    growth = _growth(make, cut_comments, 2000)
    assert growth < 12


# ---- expressions of any length and depth: compiled, folded and walked without recursion -------


def _sum_of_ones(terms: int) -> Expr:
    """1+1+...+1 as the grammar builds it: a left-leaning chain ``terms`` levels deep."""
    expr: Expr = Num(1.0, "1", Span(0, 1))
    for _ in range(terms - 1):
        expr = Binary("+", expr, Num(1.0, "1", Span(0, 1)), Span(0, 1))
    return expr


def _nested_sines(levels: int, inner: Expr) -> Expr:
    expr = inner
    for _ in range(levels):
        expr = Call("SIN", (expr,), Span(0, 1), Span(0, 1))
    return expr


def test_a_sum_of_20000_terms_folds_to_its_value() -> None:
    assert constant_of(_sum_of_ones(20_000)) == 20_000.0
    assert compile_expr(_sum_of_ones(20_000))(None) == 20_000.0  # type: ignore[arg-type]


def test_functions_nested_20000_deep_fold_and_walk() -> None:
    assert constant_of(_nested_sines(20_000, Num(0.0, "0", Span(0, 1)))) == 0.0
    variable = _nested_sines(20_000, Var(1.0, None, Span(0, 1)))
    assert constant_of(variable) is None
    compile_expr(variable)  # compiling is iterative; running it is bounded by the parser
    assert bracket_depth(variable) == 20_000
    assert sum(1 for _ in subexpressions(variable)) == 20_001


def test_constant_folding_compiles_each_node_once(monkeypatch: pytest.MonkeyPatch) -> None:
    """Folding at every level walked the subtree again: quadratic in the length."""
    calls = 0
    compile_node = compiler._compile_node

    def counted(*args: Any) -> Any:
        nonlocal calls
        calls += 1
        return compile_node(*args)

    monkeypatch.setattr(compiler, "_compile_node", counted)
    compile_expr(_sum_of_ones(5000))
    assert calls == 4999  # one per operator


def test_conditions_nested_deep_compile_and_walk() -> None:
    compare = Compare("EQ", Var(1.0, None, Span(0, 1)), Num(1.0, "1", Span(0, 1)), Span(0, 1))
    cond: Cond = compare
    for _ in range(20_000):
        cond = Logic(cond, (("OR", compare),), Span(0, 1))
    assert sum(1 for _ in cond_exprs(cond)) == 2 * 20_001
    compile_cond(cond)


# ---- arithmetic past the largest value: the control's overflow alarm, with the operands ------

TWELVE_NINES = "999999999999"
HUGE = "*".join([TWELVE_NINES] * 22)  # about 1e264: no exponent on FANUC, so a product


@pytest.mark.parametrize(
    ("block", "shown"),
    [
        (f"#1=BCD[{HUGE}]", "BCD[1e+264] overflows"),
        (f"#1={HUGE}*{HUGE}", "1e+300 * 999999999999. overflows"),
        (f"G01 X[{HUGE}*{HUGE}] F1.", "1e+300 * 999999999999. overflows"),
        ("#1=POW[10,400]", "POW[10.,400.] overflows"),
        (f"#2={TWELVE_NINES}.*{TWELVE_NINES}.\n#3=#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2"
         f"*#2*#2*#2*#2*#2*#2*#2*#2*#2*#2", "* 1e+24 overflows"),
    ],
)  # fmt: skip
@pytest.mark.parametrize("controller", ["0i-TF", "30i"])
def test_overflow_is_alarm_ps0111_with_its_operands(
    block: str, shown: str, controller: str
) -> None:
    found = analyse(f"O1\n{block}\nM30\n", "o.nc", config=Config(controller=controller))
    codes = [d.code for d in found.diagnostics]
    assert "MB000" not in codes
    messages = [d.message for d in found.diagnostics if d.code == "MB501"]
    assert any(shown in m and "PS0111" in m and "OVERFLOW" in m for m in messages), messages


# ---- what the analysis reads: limits with a verdict, never silence ---------------------------


def _codes(text: str, config: Config | None = None) -> list[str]:
    return [d.code for d in analyse(text, "t.nc", config=config).diagnostics]


def test_a_1_mb_line_is_not_analysed_and_says_so() -> None:
    line = "X1.5Y2.5" * 131_072
    started = time.perf_counter()
    found = analyse(f"O1\n{line}\nM30\n", "one-line.nc")
    assert time.perf_counter() - started < 3.0  # was 7.5 s and 459 MB
    (verdict,) = [d for d in found.diagnostics if d.code == "MB011"]
    assert verdict.line == 1 and str(len(line)) in verdict.message and "1024" in verdict.message
    assert "MB013" not in _codes(f"O1\n{line}\nM30\n")  # the line counts for what is read


def test_a_too_long_line_keeps_its_label() -> None:
    text = f"O1\nGOTO20\nN20 {'X1.' * 400}\nM30\n"
    assert "MB011" in _codes(text) and "MB101" not in _codes(text)


def test_a_lower_line_limit_applies_to_lines_parsed_before() -> None:
    parser = BlockParser()
    line = "G01 X10. Z-5. F0.2"
    assert parser.parse_line(line).statement is not None  # cached under the default limit
    (parsed,) = parser.parse_lines([line], max_line_length=10)
    assert parsed.statement is None and parsed.notes[0].kind == "too-long"


def test_a_10_mb_program_is_analysed_whole_by_default() -> None:
    block = "G01 X{0}.5 Z-{1}. F0.2"
    lines = ["%", "O1000"] + [block.format(i % 97, i % 89) for i in range(500_000)] + ["M30", "%"]
    text = "\n".join(lines) + "\n"
    assert len(text) > 10_000_000
    started = time.perf_counter()
    found = analyse(text, "ten.nc")
    # 5-10 s on a 2-core EPYC VM: what bounds the work is the step budget, not the clock.
    assert time.perf_counter() - started < 60.0
    assert found.doc.unread_from is None and len(found.doc.blocks) == len(lines)
    assert found.facts is not None and found.facts.stopped is None
    assert found.diagnostics == []  # 500,000 blocks run once each: no endless loop (MB703)


def test_a_program_longer_than_the_step_budget_runs_to_its_end() -> None:
    rows = "".join(f"G01 X{i % 50}.5 Z-{i % 7}. F0.2\n" for i in range(3_000))
    config = Config(step_budget=1_000)
    found = analyse(f"O1000\n{rows}M30\n", "long.nc", config=config)
    assert found.facts is not None and found.facts.stopped is None
    assert "MB703" not in {d.code for d in found.diagnostics}
    # A loop still meets the budget: every block once, and half the setting again.
    looping = f"O1000\n#1=0\n{rows}WHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n"
    found = analyse(looping, "loop.nc", config=config)
    (verdict,) = [d for d in found.diagnostics if d.code == "MB703"]
    assert "(3,506 blocks)" in verdict.message  # 3,006 blocks and 500


def test_the_limits_still_read_a_big_file_in_part() -> None:
    block = "G01 X{0}.5 Z-{1}. F0.2"
    lines = ["%", "O1000"] + [block.format(i % 97, i % 89) for i in range(60_000)] + ["M30", "%"]
    config = Config(max_blocks=25_000)
    found = analyse("\n".join(lines) + "\n", "big.nc", config=config)
    (verdict,) = [d for d in found.diagnostics if d.code == "MB013"]
    read = found.doc.unread_from
    assert read is not None and verdict.line == read == 25_000
    assert f"analysed the first {read} blocks of {len(lines)}" in verdict.message
    assert "setting fanuc-macro.analysis.max" in verdict.message


def test_the_block_limit_and_its_setting() -> None:
    config = Config.from_settings({"analysis": {"maxBlocks": 3}})
    assert config.max_blocks == 3
    found = analyse("O1\nG00 X1.\nG00 X2.\nGOTO 9\nM30\n", "t.nc", config=config)
    (verdict,) = [d for d in found.diagnostics if d.code == "MB013"]
    assert verdict.line == 3 and "first 3 blocks of 5" in verdict.message
    assert "maxBlocks" in verdict.message
    assert "MB101" not in {d.code for d in found.diagnostics}  # GOTO 9 is not read


def manifest_settings() -> dict[str, Any]:
    """Every setting of package.json, whatever category of the Settings UI it is in."""
    manifest = json.loads((ROOT / "package.json").read_text("utf-8"))
    configuration = manifest["contributes"]["configuration"]
    categories = configuration if isinstance(configuration, list) else [configuration]
    return {name: spec for c in categories for name, spec in c["properties"].items()}


def test_settings_and_their_defaults_in_package_json() -> None:
    properties = manifest_settings()
    default = Config()
    for setting, value in (
        ("maxLineLength", default.max_line_length),
        ("maxBlocks", default.max_blocks),
        ("maxFileSize", default.max_file_size),
    ):
        assert properties[f"fanuc-macro.analysis.{setting}"]["default"] == value
        changed = Config.from_settings({"analysis": {setting: 7}})
        assert dataclasses.astuple(changed.read_limits).count(7) == 1


def test_an_edit_of_a_cut_document_equals_a_fresh_parse() -> None:
    limits = ReadLimits(max_line_length=40, max_blocks=6)
    lines = [f"G01 X{i}. Z-{i}." for i in range(12)]
    parser = BlockParser()
    before = parse_text("\n".join(lines), "t", parser, limits=limits)
    lines[2] = "N5 " + "X1." * 30  # now too long
    lines[9] = "G00 X0."  # past the limit
    text = "\n".join(lines)
    edited = parse_text(text, "t", parser, previous=before, limits=limits)
    assert edited == parse_text(text, "t", BlockParser(), limits=limits)
    assert edited.blocks[0] is before.blocks[0]


def test_workspace_reads_documents_again_when_a_limit_changes() -> None:
    ws = Workspace()
    ws.add_text("a.nc", "O1\n" + "G00 X1.\n" * 10 + "M30\n")
    assert ws.document("a.nc").unread_from is None  # type: ignore[union-attr]
    assert ws.set_config(Config(max_blocks=4)) == ["a.nc"]
    assert ws.document("a.nc").unread_from == 4  # type: ignore[union-attr]
    assert "MB013" in {d.code for d in ws.analyse("a.nc").diagnostics}
    assert ws.set_config(Config(max_blocks=4, controller="30i")) == []  # same limits


# ---- the inputs of the fuzz campaign that froze or crashed the analysis ----------------------

FOUND_BY_FUZZING: dict[str, tuple[str, str]] = {
    # name: (program, the code of its verdict)
    "G65 with ten integer words then X#[...]": (
        "O1\nG65P9010A1000B1000C1000D1000E1000F1000H1000I1000J1000K1000X#[#1+1]\nM30\n",
        "MB410",  # the block reads (fast), and calls a resident program that is not there
    ),
    "X11 22 times then '['": ("O1\n" + "X11" * 22 + "[\nM30\n", "MB001"),
    "a sum of 248 terms": ("O1\n#1=" + "+".join(["1"] * 248) + "\nM30\n", "MB012"),
    "120 nested SIN[": ("O1\n#1=" + "SIN[" * 120 + "1" + "]" * 120 + "\nM30\n", "MB012"),
    "250 nested SIN[": ("O1\n#1=" + "SIN[" * 250 + "1" + "]" * 250 + "\nM30\n", "MB011"),
    "BCD of a value over 1e256": (f"O1\n#1=BCD[{HUGE}]\nM30\n", "MB501"),
    "a sum of 10,000 terms": ("O1\n#1=" + "+".join(["1"] * 10_000) + "\nM30\n", "MB011"),
    "a sum of 100,000 terms": ("O1\n#1=" + "+".join(["1"] * 100_000) + "\nM30\n", "MB011"),
    "a 1 MB line": ("O1\n" + "X1.5Y2.5" * 131_072 + "\nM30\n", "MB011"),
    "a 10 MB file": (
        "O1\n" + "".join(f"G01 X{i % 97}.{i % 7} Z-{i % 89}. F0.2\n" for i in range(420_000)),
        "MB013",
    ),
}
# Found under the read limits of their day: the verdict is for those limits (read whole by
# default, the 10 MB file is test_a_10_mb_program_is_analysed_whole_by_default's).
FOUND_UNDER_LIMITS: dict[str, tuple[int, int]] = {"a 10 MB file": (25_000, 600_000)}


@pytest.mark.parametrize("name", FOUND_BY_FUZZING)
def test_each_input_that_froze_or_crashed_gets_a_clear_verdict(name: str) -> None:
    text, code = FOUND_BY_FUZZING[name]
    blocks, characters = FOUND_UNDER_LIMITS.get(name, (None, None))
    config = Config() if blocks is None else Config(max_blocks=blocks, max_file_size=characters)
    started = time.perf_counter()
    found = analyse(text, "f.nc", config=config)
    seconds = time.perf_counter() - started
    codes = {d.code for d in found.diagnostics}
    assert "MB000" not in codes
    assert code in codes, sorted(codes)
    assert seconds < 6.0, f"{seconds:.1f} s (the aim is 3 s: about 2 s at most on this VM)"


@pytest.mark.parametrize("name", FOUND_BY_FUZZING)
def test_trace_answers_json_on_each_of_them(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "f.nc"
    path.write_text(FOUND_BY_FUZZING[name][0], "utf-8")
    blocks, characters = FOUND_UNDER_LIMITS.get(name, (None, None))
    limits = (
        [] if blocks is None else ["--max-blocks", str(blocks), "--max-file-size", str(characters)]
    )
    assert cli.main(["trace", "--format", "json", *limits, str(path)]) in (0, 1)
    out, err = capsys.readouterr()
    assert "motions" in json.loads(out)
    assert "Traceback" not in err


@pytest.mark.parametrize(
    ("text", "levels"),
    [
        ("#1=" + "SIN[" * 20_000 + "1" + "]" * 20_000, 20_001),  # the LALR stack, the AST
        ("#1=" + "-" * 20_000 + "1", 20_001),
        ("IF[" + "[" * 20_000 + "#1" + "]" * 20_000 + "EQ1]GOTO1", 20_002),
        ("#1=" + "SIN[" * 20_000 + "1", None),  # rejected: the error's description
    ],
    ids=["functions", "signs", "conditions", "unclosed"],
)
def test_the_grammar_path_takes_20000_levels_without_recursion(
    text: str, levels: int | None
) -> None:
    """The LALR driver keeps its own stack and the AST builder makes one node per reduction;
    past the depth limit the block is measured (with a stack) and refused."""
    parsed = BlockParser().parse_line(text, max_line_length=10**6)
    assert parsed.statement is None
    if levels is None:
        assert parsed.problem is not None and "not closed" in parsed.problem.message
    else:
        (note,) = parsed.notes
        assert note.kind == "too-deep" and f"nests {levels} levels deep" in note.message


def test_a_program_cut_by_the_read_limit_is_not_taken_for_ended_or_fully_run() -> None:
    """A big CAM file read in part (MB013): the M30, the G67, the END, the label N10 and the
    called program may be in the unread part, so no MB101 / MB201 / MB403 / MB406 / MB407, and
    the run stops there unfinished (no verdict that needs a whole run)."""
    rows = [f"G01 X{i}. Z-{i % 7}. F0.2" for i in range(60)]
    text = "\n".join(
        [
            "%",
            "O1234 (CAM)",
            "#1=1",
            "G66 P9010 A1.",
            "IF[#1EQ2]GOTO10",
            "WHILE[#1LT3]DO1",
            *rows,
            "#1=#1+1",
            "END1",
            "N10 G67",
            "M30",
        ]
    )
    config = Config(max_blocks=30)
    result = analyse(text, "cam.nc", config)
    codes = {d.code for d in result.diagnostics}
    assert "MB013" in codes
    assert codes == {"MB013"}
    assert result.facts is not None
    doc_facts = result.facts.document("cam.nc")
    assert doc_facts.incomplete_programs


def test_the_language_server_settings_defaults_in_package_json() -> None:
    from fanuc_macro.lsp.engine import DEFAULT_DEBOUNCE_MS, DEFAULT_PROGRESS_DELAY_MS

    properties = manifest_settings()
    assert properties["fanuc-macro.analysis.debounceMs"]["default"] == DEFAULT_DEBOUNCE_MS
    delay = properties["fanuc-macro.analysis.progressDelayMs"]["default"]
    assert delay == DEFAULT_PROGRESS_DELAY_MS
    default = Config()
    assert properties["fanuc-macro.analysis.stepBudget"]["default"] == default.step_budget
    assert properties["fanuc-macro.analysis.timeLimit"]["default"] == default.time_limit


def test_the_editor_settings_in_package_json_are_the_servers() -> None:
    from fanuc_macro.config import SPACING, FormatSettings
    from fanuc_macro.ide.messages import LOCALES

    properties = manifest_settings()
    assert properties["fanuc-macro.hover.fullPrecision"]["default"] is Config().hover_full_precision
    language = properties["fanuc-macro.language"]
    assert language["default"] == "auto" and language["enum"] == ["auto", *LOCALES]
    fmt = FormatSettings()
    assert properties["fanuc-macro.format.upperCase"]["default"] is fmt.upper_case
    assert properties["fanuc-macro.format.renumberStep"]["default"] == fmt.renumber_step
    for name, default in (
        ("spaceBetweenWords", fmt.space_between_words),
        ("spacesAroundAssignment", fmt.spaces_around_assignment),
    ):
        spec = properties[f"fanuc-macro.format.{name}"]
        assert spec["default"] == default and tuple(spec["enum"]) == SPACING


def test_the_manifests_language_is_the_one_the_extension_starts_on() -> None:
    manifest = json.loads((ROOT / "package.json").read_text("utf-8"))
    source = (ROOT / "client" / "src" / "extension.ts").read_text("utf-8")
    match = re.search(r"const LANGUAGE_ID = '([^']+)'", source)
    assert match is not None
    language = match.group(1)
    languages = [entry["id"] for entry in manifest["contributes"]["languages"]]
    assert language in languages
    assert f"onLanguage:{language}" in manifest["activationEvents"]
    assert {g["language"] for g in manifest["contributes"]["grammars"]} <= set(languages)


def test_a_g76_whose_p_has_too_many_digits_makes_a_bounded_number_of_passes() -> None:
    """``G76 P857855151995.`` reads m (finishing passes) as 85,785,515: the passes were made
    one by one (2 minutes, gigabytes). The control's m has two digits; the passes are bounded
    like the roughing ones (found by the fuzz campaign, input 81415 of seed 35)."""
    from fanuc_macro.evaluator.cycles import MAX_PASSES, g76_depths

    assert len(g76_depths(1.0, 0.3, 0.05, 0.02, 85_785_515)) <= 2 * MAX_PASSES
    assert len(g76_depths(0.0, 0.3, 0.05, 0.02, 85_785_515)) == MAX_PASSES
    text = "O1000\nT0101\nG00 X30. Z5.\nG76 P857855151995. Q17. R0.1\n"
    text += "G76 X18. Z-20. P1000 Q200 F1.5\nM30\n"
    analysis = analyse(text, "g76.nc")
    assert analysis.facts is not None and len(analysis.facts.motions) <= 2 * MAX_PASSES + 10
