"""The evaluator runs the seed programs as a FANUC control would: thread-math.md's numbers."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.evaluator import Facts, Unknown, evaluate
from fanuc_macro.evaluator.values import f_fix, f_fup, f_round
from fanuc_macro.ide.trace import trace
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import parse_text

SEEDS = Path(__file__).parent / "fixtures" / "seeds"


def run(text: str, uri: str = "t.nc") -> tuple[Facts, object]:
    doc = parse_text(text, uri)
    index = build_index(doc)
    return evaluate([(uri, doc, index)], only_uri=uri), doc


def seed(name: str) -> tuple[Facts, str]:
    path = SEEDS / name
    facts, _ = run(path.read_text("utf-8"), str(path))
    return facts, str(path)


def written(facts: Facts, uri: str, text: str, needle: str) -> list[float | None]:
    """Values written by the first assignment line that starts with ``needle``."""
    lines = text.splitlines()
    line = next(i for i, t in enumerate(lines) if t.startswith(needle))
    write = facts.document(uri).writes[line]
    s = write[1]
    return [s.first, s.last, s.count]  # type: ignore[list-item]


@pytest.mark.parametrize(
    ("name", "h", "ap_max", "ap_min", "u1", "passes", "g92"),
    [
        ("o4009_external_m50x3.nc", 1.907, 0.0921, 0.0202, 1.0361, 88, 186),
        ("o4010_internal_m50x3.nc", 1.777, 0.0889, 0.0199, 0.9632, 83, 176),
    ],
)
def test_symmetric_module_numbers(name, h, ap_max, ap_min, u1, passes, g92) -> None:
    facts, uri = seed(name)
    text = Path(uri).read_text("utf-8")
    assert round(written(facts, uri, text, "#4=")[0], 3) == h
    assert round(written(facts, uri, text, "#5=")[0], 4) == ap_max
    assert round(written(facts, uri, text, "#6=")[0], 4) == ap_min
    assert round(written(facts, uri, text, "#10=")[0], 4) == u1
    # "#7=#7+1." runs once per rough pass; the last increment ends the loop.
    assert written(facts, uri, text, "#7=#7+1.")[2] == passes
    cuts = [m for m in facts.motions if m.code == "G92"]
    assert len(cuts) == g92
    # The modal G92: the block "X[...]" alone repeats the cycle, and is its own record.
    assert any(set(m.words) == {"X", "F"} for m in cuts)


def test_external_final_x_and_trace_words() -> None:
    facts, _ = seed("o4009_external_m50x3.nc")
    cuts = [m for m in facts.motions if m.code == "G92"]
    first = cuts[0]
    assert first.words["X"] == pytest.approx(49.816, abs=5e-4)
    assert first.words["W"] == -60.0
    assert first.words["F"] == 3.0
    assert cuts[-1].words["X"] == pytest.approx(50 - 2 * 1.906804, abs=1e-3)


def test_arc_thread_layers_and_m1_bug() -> None:
    facts, uri = seed("o2_arc_thread_roughing.nc")
    g32 = [m for m in facts.motions if m.code == "G32"]
    assert len(g32) == 14  # 7 cuts per layer, two layers (O3 and O4)
    text = Path(uri).read_text("utf-8")
    lines = text.splitlines()
    line10 = next(i for i, t in enumerate(lines) if t.startswith("N16 #10"))
    assert facts.document(uri).writes[line10][1].first == pytest.approx(45.15, abs=0.01)
    line11 = next(i for i, t in enumerate(lines) if t.startswith("N17 #11"))
    assert facts.document(uri).writes[line11][1].first == pytest.approx(7.84, abs=0.01)
    line12 = next(i for i, t in enumerate(lines) if t.startswith("N18 #12"))
    assert facts.document(uri).writes[line12][1].first == pytest.approx(13.93, abs=0.01)
    alphas = facts.document(uri).reads
    line25 = next(i for i, t in enumerate(lines) if t.startswith("N25 G00"))
    s = alphas[(line25, 16)]
    assert s.count == 7
    assert s.first == pytest.approx(51.24, abs=0.01)
    # The paper's 134.82 is 37.31 + 7 x 13.93 with its rounded angles; unrounded: 134.846.
    assert s.last == pytest.approx(134.82, abs=0.03)
    findings = [f for f in facts.document(uri).findings if f.kind == "address-non-integer"]
    assert findings and "93.82" in findings[0].message


def test_arc_thread_finishing_19_cuts() -> None:
    facts, _ = seed("o5_arc_thread_finishing.nc")
    assert sum(1 for m in facts.motions if m.code == "G32") == 19


def test_vacancy_rules() -> None:
    # #1=#0 first: a main program that read #1 before setting it would receive arguments.
    text = (
        "O1\n#1=#0\n#2=#1\n#3=#1*5\n#4=#1+#1\n#5=#0+1\n#6=-#1\nIF[#1EQ#0]THEN#7=1\n"
        "IF[#1EQ0]THEN#8=1\nM30\n"
    )
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert w[1][1].first is None
    assert w[2][1].first is None  # a plain copy keeps vacancy
    assert w[3][1].first == 0.0
    assert w[4][1].first == 0.0
    assert w[5][1].first == 1.0
    assert w[6][1].first == 0.0
    assert w[7][1].first == 1.0  # vacant EQ #0
    assert 8 not in w  # vacant is not 0 for EQ


def test_functions_in_degrees_and_rounding() -> None:
    text = (
        "O1\n#1=SIN[30]\n#2=ATAN[1]/[1]\n#3=ATAN[-1,-1]\n#4=FIX[-1.2]\n#5=FUP[-1.2]\n"
        "#6=ROUND[2.5]\n#7=27 MOD 20\n#8=[[48/#7]+[8*4]]/[3+[[4*3]/2]+3]\nM30\n"
    )
    facts, _ = run(text)
    w = {line: s[1].first for line, s in facts.document("t.nc").writes.items()}
    assert w[1] == pytest.approx(0.5)
    assert w[2] == pytest.approx(45.0)
    assert w[3] == pytest.approx(225.0)
    assert w[4] == -1.0
    assert w[5] == -2.0
    assert w[6] == 3.0
    assert w[7] == 7.0
    assert w[8] == pytest.approx((48 / 7 + 32) / 12)
    assert f_round(-2.5) == -3.0 and f_fix(2.9) == 2.0 and f_fup(2.1) == 3.0


def test_g65_arguments_spec_i_and_ii() -> None:
    text = "O1\nG65 P1000 A1.0 B2.0 I-3.0 I4.0 D5.0\nM30\nO1000\n#30=#4\n#31=#7\n#32=#1\nM99\n"
    facts, _ = run(text)
    w = {line: s[1].first for line, s in facts.document("t.nc").writes.items()}
    assert w[4] == -3.0  # #4 from the first I
    assert w[5] == 5.0  # D overrides the second I (#7)
    assert w[6] == 1.0


def test_m98_repeat_and_shared_locals() -> None:
    text = "O1\n#1=0\nM98 P0032000\n#2=#1\nM30\nO2000\n#1=#1+1\nM99\n"
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert w[3][1].first == 3.0  # O2000 ran three times on the caller's locals


def test_m99_p_returns_to_label() -> None:
    text = "O1\nM98 P2000\n#1=1\nN50 #2=2\nM30\nO2000\nM99 P50\n"
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert 2 not in w and w[3][1].first == 2.0


def test_endless_loop_is_stopped_and_named() -> None:
    text = "O1\n#1=0\nWHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n"
    result = analyse(text, "loop.nc")
    d = [x for x in result.diagnostics if x.code == "MB703"]
    assert d and d[0].line == 2 and "#1 stays 0." in d[0].message


def test_unknown_inputs_give_dependencies() -> None:
    text = "O3331\n#1=1.*#101\n#4=SQRT[#1]\nIF[#4GT1]GOTO10\n#5=1\nN10 M99\n"
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert isinstance(w[1][1].first, Unknown)
    assert w[1][1].first.describe() == "depends on #101"
    assert isinstance(w[2][1].first, Unknown)
    assert facts.document("t.nc").jumps[3].undecided == 1


def test_math_domain_message_names_values() -> None:
    text = "O3\n#1=93.82\n#4=10\n#5=125\n#10=ASIN[[[#5-#1]/2]/#4]\nM30\n"
    result = analyse(text, "asin.nc")
    d = next(x for x in result.diagnostics if x.code == "MB501")
    assert "1.559" in d.message and "#5=125." in d.message and "#4=10." in d.message


def test_zero_divide_and_runtime_goto() -> None:
    result = analyse("O1\n#1=0\n#2=5/#1\nM30\n", "z.nc")
    assert any(d.code == "MB502" for d in result.diagnostics)
    result = analyse("O1\n#1=7\nGOTO#1\nM30\n", "g.nc")
    assert any(d.code == "MB704" for d in result.diagnostics)


def test_statements_per_second_budget_is_sane() -> None:
    facts, _ = run("O1\n#1=0\nWHILE[#1LT1000]DO1\n#1=#1+1\nEND1\nM30\n")
    assert facts.stopped is None
    assert facts.document("t.nc").writes[3][1].last == 1000.0
    assert math.isclose(facts.document("t.nc").writes[3][1].count, 1000)


def _seed_codes(
    name: str, old: str, new: str, config: Config | None = None
) -> dict[str, list[str]]:
    text = (SEEDS / name).read_text("utf-8")
    assert old in text
    result = analyse(text.replace(old, new), name, config)
    found: dict[str, list[str]] = {}
    for d in result.diagnostics:
        found.setdefault(d.code, []).append(d.message)
    return found


def test_threading_rules_on_the_seed_module() -> None:
    # The paper's module as it is: no threading diagnostic.
    clean = analyse((SEEDS / "o4009_external_m50x3.nc").read_text("utf-8"), "o4009.nc")
    assert not [d for d in clean.diagnostics if d.code.startswith("MB8")]
    # The finishing pass 0.4 mm (diameter) deeper than the module's own root: past the root
    # of 5g6g that ISO 965-1 allows with the module's nose radius (d2 min 47.833 − H + 2r).
    found = _seed_codes(
        "o4009_external_m50x3.nc", "X[#100-2.*#4] (直进法精车)", "X[#100-2.*#4-0.4] (直进法精车)"
    )
    assert "at X45.786 is 0.157 mm (radius) past the root X46.101" in found["MB801"][0]
    # A nose radius far above P/(8 sin 60) for P = 3.
    found = _seed_codes(
        "o4009_external_m50x3.nc", "#3=#101/[8*SIN[60]] (刀尖半径)", "#3=0.6 (刀尖半径)"
    )
    assert "nose radius 0.6" in found["MB805"][0]
    # S x P over the machine's threading feed limit, when the limit is set; not checked when
    # nobody set it.
    limited = Config(max_threading_feed=10000.0)
    found = _seed_codes("o4009_external_m50x3.nc", "G97 S400", "G97 S4000", limited)
    assert "12000." in found["MB807"][0]
    assert "MB807" not in _seed_codes("o4009_external_m50x3.nc", "G97 S400", "G97 S4000")


def test_fitting_method_tool_radius_from_chinese_comments() -> None:
    found = _seed_codes("o2_arc_thread_roughing.nc", "N07 #18 = 1.2", "N07 #18 = 10.5")
    assert (
        "tool radius #18 = 10.5 is not smaller than the groove radius #4 = 10"
        in (found["MB806"][0])
    )
    assert "MB501" in found  # and ASIN[#18/[#4-#18]] leaves its domain


def test_g65_repeat_starts_each_call_from_its_arguments() -> None:
    # G65 L3: three calls with A1.; the macro adds to #1 and accumulates in a common.
    text = "O1\n#100=0\nG65 P2000 L3 A1.\n#101=#100\nM30\nO2000\n#1=#1+10.\n#100=#100+#1\nM99\n"
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert w[3][1].first == 33.0  # 11 + 11 + 11, not 11 + 21 + 31


def test_g66_calls_after_each_move_until_g67() -> None:
    text = (
        "O1\n#100=0\nG66 P2000 A5.\nG01 X1. F0.1\nG01 X2.\n#101=1\nG67\nG01 X3.\nM30\n"
        "O2000\n#100=#100+#1\nM99\n"
    )
    facts, _ = run(text)
    w = facts.document("t.nc").writes
    assert w[10][1].count == 2 and w[10][1].last == 10.0  # after X1. and X2., not after X3.


def test_long_loop_is_not_called_endless_and_overflow_is_an_alarm() -> None:
    nested = (
        "O1\n#1=0\nWHILE[#1LT1000]DO1\n#2=0\nWHILE[#2LT1000]DO2\n#2=#2+1\nEND2\n"
        "#1=#1+1\nEND1\nM30\n"
    )
    codes = {d.code for d in analyse(nested, "nested.nc").diagnostics}
    assert "MB708" in codes and "MB703" not in codes and "MB701" not in codes
    away = analyse("O1\n#1=5\nWHILE[#1GT0]DO1\n#1=#1+1\nEND1\nM30\n", "away.nc").diagnostics
    assert any(d.code == "MB703" and "moving away" in d.message for d in away)
    overflow = analyse("O1\n#1=10\n" + "#1=#1*10\n" * 400 + "M30\n", "big.nc").diagnostics
    assert any(d.code == "MB501" and "OVERFLOW" in d.message for d in overflow)


def test_workspace_keeps_the_facts_while_only_comments_change() -> None:
    from fanuc_macro.workspace import Workspace

    text = (SEEDS / "o4009_external_m50x3.nc").read_text("utf-8")
    ws = Workspace()
    ws.add_text("a.nc", text)
    first = ws.analyse("a.nc").facts
    ws.add_text("a.nc", text.replace("(螺纹螺距)", "(PITCH 螺距)"))
    assert ws.analyse("a.nc").facts is first  # a comment: the program runs the same
    ws.add_text("a.nc", text.replace("#101=3.", "#101=2."))
    again = ws.analyse("a.nc")
    assert again.facts is not first
    assert sum(1 for m in again.facts.motions if m.code == "G92") != 186


def test_g76_two_block_form_cuts_the_controls_passes() -> None:
    # First block: 2 finishing passes, chamfer 1.0L, 60°, Δdmin 0.1, allowance 0.05.
    # Second: root X27.4, height k 1.3, first depth Δd 0.4, lead 2 (FANUC 0i-TF manual).
    text = (
        "O1\nG97 S600 M03\nG00 X32. Z5.\nG76 P021060 Q100 R0.05\n"
        "G76 X27.4 Z-30. P1300 Q400 F2.\nG00 X100. Z100.\nM30\n"
    )
    facts, _ = run(text)
    passes = [m for m in facts.motions if m.code == "G76"]
    assert all(m.line == 4 for m in passes)  # the parameter block is never a cut
    depths = [round((27.4 + 2 * 1.3 - m.x) / 2, 4) for m in passes if m.x is not None]
    # Δd√n while each cut takes at least Δdmin, roughing to k - d, then k twice.
    assert depths == [0.4, 0.5657, 0.6928, 0.8, 0.9, 1.0, 1.1, 1.2, 1.25, 1.3, 1.3]
    assert [m.finishing for m in passes][-3:] == [False, True, True]
    assert [m.cycle_pass for m in passes] == list(range(1, 12))
    assert {m.start_x for m in passes} == {32.0} and {m.z for m in passes} == {-30.0}


def test_g76_internal_goes_outwards_from_its_start_point() -> None:
    text = "O1\nG00 X36. Z5.\nG76 P010060 Q100 R0\nG76 X40. Z-25. P1000 Q500 F2.\nM30\n"
    facts, _ = run(text)
    xs = [m.x for m in facts.motions if m.code == "G76"]
    assert xs[0] == pytest.approx(38.0 + 1.0) and xs[-1] == 40.0 and xs == sorted(xs)


def test_round_in_an_address_rounds_to_the_least_input_increment() -> None:
    # FANUC's manual: ROUND in an NC address rounds at the address's least input increment.
    text = (
        "O1\n#1=1.2345\n#2=ROUND[#1]\nG00 X[ROUND[#1]] Z[ROUND[#1]*2.]\nG20\n"
        "G00 X[ROUND[#1]]\nM30\n"
    )
    facts, _ = run(text)
    moves = [m for m in facts.motions if m.code == "G00"]
    assert moves[0].words["X"] == 1.235 and moves[0].words["Z"] == 2.47
    assert facts.document("t.nc").writes[2][1].first == 1.0  # a macro statement: whole number
    assert moves[1].x == pytest.approx(1.2345)  # inch: 0.0001


def test_atan_range_is_the_controls_parameter() -> None:
    from fanuc_macro.config import Config

    text = "O1\n#1=ATAN[-1.]/[-1.]\n#2=ATAN[-1.,1.]\nM30\n"
    default = analyse(text, "a.nc").facts
    signed = analyse(text, "a.nc", config=Config(atan_signed=True)).facts
    assert default is not None and signed is not None
    assert default.document("a.nc").writes[1][1].first == pytest.approx(225.0)
    assert signed.document("a.nc").writes[1][1].first == pytest.approx(-135.0)
    assert signed.document("a.nc").writes[2][1].first == pytest.approx(-45.0)
    assert Config.from_settings({"machine": {"atanRange": "-180-180"}}).atan_signed


def test_value_range_depends_on_the_controller() -> None:
    from fanuc_macro.config import Config

    # No exponent on FANUC: 10^11, then 10^55.
    text = "O1\n#1=100000000000.\n#2=#1*#1*#1*#1*#1\nM30\n"
    small = analyse(text, "r.nc").diagnostics
    assert any(
        d.code == "MB501" and "OVERFLOW" in d.message and "±1e+47" in d.message for d in small
    )
    big = analyse(text, "r.nc", config=Config(controller="30i")).diagnostics
    assert not any(d.code == "MB501" for d in big)
    tiny = analyse("O1\n#1=0.0000000001\n#2=#1*#1*#1\nM30\n", "u.nc").facts
    assert tiny is not None and tiny.document("u.nc").writes[2][1].first == 0.0


def test_fix_of_a_value_a_hair_under_a_whole_number_is_noted() -> None:
    text = "O1\n#1=0\n#2=0\nWHILE[#2LT8]DO1\n#1=#1+0.1\n#2=#2+1\nEND1\n#3=FIX[#1*10.]\nM30\n"
    facts, _ = run(text)
    seen = facts.document("t.nc").roundings[7]
    assert (seen.function, seen.result) == ("FIX", 7.0) and seen.argument < 8.0


def test_multiple_modal_calls_run_in_the_manual_order() -> None:
    """The example of FANUC's "multiple modal call": a move in a G66 macro calls the macro
    specified before it, never itself, and G67 cancels the last one first."""
    text = (
        "O1\nG91 G00\nG66 P9100\nX10.\nG66 P9200\nX15.\nG67\nG67\nX-25.\nM30\n"
        "O9100\nZ50.\nM99\n"
        "O9200\nX60.\nY70.\nM99\n"
    )
    facts, _ = run(text)
    moves = [m.line for m in facts.motions]
    # (1-1) (2-1) (1-2) (3-1) (2-1) (3-2) (2-1) (1-3), as the manual's figure shows.
    assert moves == [3, 11, 5, 14, 11, 15, 11, 8]
    assert not [f for f in facts.document("t.nc").findings if f.kind.startswith("nesting")]


def test_g76_on_a_mill_is_fine_boring_not_a_thread() -> None:
    from fanuc_macro.config import Config

    text = "O1\nG00 X0. Y0. Z5.\nG76 X10. Y10. Z-20. R2. Q0.5 P1000 F100.\nG80\nM30\n"
    mill = analyse(text, "m.nc", config=Config(controller="0i-MF"))
    assert mill.facts is not None
    # The block is a hole of the boring cycle, recorded as such: no threading pass.
    [boring] = [m for m in mill.facts.motions if m.code == "G76"]
    assert boring.drilling and boring.line == 2 and boring.words["Q"] == 0.5
    assert not mill.threads


# ---- budgets: blocks, never seconds ------------------------------------------------------------

ENDLESS = "O1\n#1=0\nWHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n"


def test_step_budget_stops_at_the_same_block_every_time() -> None:
    config = Config(step_budget=10_000)
    doc = parse_text(ENDLESS, "t.nc")
    runs = [evaluate([("t.nc", doc, build_index(doc))], config) for _ in range(2)]
    assert [f.steps for f in runs] == [10_000, 10_000]  # the budget's blocks, not a multiple
    assert runs[0].stopped == "budget" and runs[0].stop_message() is None
    messages = [[f.message for f in r.document("t.nc").findings] for r in runs]
    assert messages[0] == messages[1]
    assert "the step budget (10,000 blocks)" in messages[0][0]


def test_safety_net_stop_gives_no_verdict_that_needs_a_whole_run() -> None:
    # O1 never ends; O2, called by nothing, runs whole in a few blocks.
    text = ENDLESS + "O2\n#1=1\nIF[#1EQ1]GOTO9\nG00 X1.\nN9 M30\n"
    config = Config(time_limit=1e-9)  # spent before the first look at the clock
    result = analyse(text, "slow.nc", config)
    assert result.facts is not None and result.facts.stopped == "time"
    message = result.facts.stop_message()
    assert message is not None and message.startswith("analysis stopped after 1e-09 s")
    found = {(d.line, d.code) for d in result.diagnostics}
    assert not {code for _, code in found} & {"MB703", "MB707", "MB708"}, found
    assert {(8, "MB701"), (9, "MB702")} <= found  # O2's run was whole
    # With the default limit the step budget ends O1's run: the endless loop is named.
    found = {(d.line, d.code) for d in analyse(text, "slow.nc").diagnostics}
    assert {(2, "MB703"), (8, "MB701"), (9, "MB702")} <= found


def test_trace_says_why_the_run_stopped() -> None:
    doc = parse_text(ENDLESS, "t.nc")
    summary = trace("t.nc", doc, build_index(doc), config=Config(time_limit=1e-9))["summary"]
    assert summary["stopped"] == "time"
    assert summary["stop_message"].startswith("analysis stopped after")


# ---- calls the analysis cannot follow ----------------------------------------------------------


def _written_values(text: str) -> dict[int, object]:
    """line -> the first value its assignment wrote."""
    facts, _ = run(text)
    return {line: s[1].first for line, s in facts.document("t.nc").writes.items()}


def test_commons_and_offsets_are_unknown_after_a_call_outside_the_workspace() -> None:
    text = (
        "O1\n#100=0\n#2001=0.5\n#5221=-100.\n#1=7.\n"
        "G65 P9814 Z-5. F3000.\n"  # a probe vendor's macro: not in the analysed files
        "#2=#100\n#3=#2001\n#4=#5221\n#5=#1\n"
        "IF[#100EQ0]GOTO10\nN10 M30\n"
    )
    facts, _ = run(text)
    doc = facts.document("t.nc")
    after = {line: doc.writes[line][1].first for line in (6, 7, 8, 9)}
    assert isinstance(after[6], Unknown) and after[6].describe() == "depends on #100"
    assert isinstance(after[7], Unknown) and isinstance(after[8], Unknown)
    assert after[9] == 7.0  # G65 opens a local level of its own: the caller's #1 stays
    assert doc.jumps[10].undecided == 1 and not doc.jumps[10].taken
    codes = {d.code for d in analyse(text, "probe.nc").diagnostics}
    assert "MB701" not in codes


def test_m98_outside_the_workspace_may_change_the_callers_locals() -> None:
    w = _written_values("O1\n#1=7.\n#100=1.\nM98 P9001\n#2=#1\n#3=#100\nM30\n")
    assert isinstance(w[4], Unknown) and w[4].describe() == "depends on #1"
    assert isinstance(w[5], Unknown)


def test_a_call_with_an_unknown_program_number_is_a_call_into_the_unknown() -> None:
    # #500 is set by another program: G65 P#500 could call anything.
    w = _written_values("O1\n#100=1.\n#1=2.\nG65 P#500\n#2=#100\n#3=#1\nM99\n")
    assert isinstance(w[4], Unknown)
    assert w[5] == 2.0
    # A call the analysis follows changes only what the callee writes.
    w = _written_values(
        "O1\n#100=1.\n#101=2.\nG65 P2000\n#2=#100\n#3=#101\nM30\nO2000\n#100=5.\nM99\n"
    )
    assert w[4] == 5.0 and w[5] == 2.0


def test_g66_of_an_unknown_macro_runs_it_after_each_move() -> None:
    text = (
        "O1\n#100=1.\nG66 P9999 A1.\n#2=#100\nG01 X1. F0.1\n#3=#100\nG67\n#100=2.\n"
        "G01 X2.\n#4=#100\nM30\n"
    )
    w = _written_values(text)
    assert w[3] == 1.0  # G66 itself calls nothing
    assert isinstance(w[5], Unknown)  # the move called O9999
    assert w[9] == 2.0  # after G67 a move calls nothing


def test_feed_left_by_an_unknown_callee_is_not_a_missing_feed() -> None:
    text = "O1\nG65 P9810 Z-5. F3000.\nG01 X10.\nM30\n"
    assert "MB603" not in {d.code for d in analyse(text, "feed.nc").diagnostics}
    assert "MB603" in {d.code for d in analyse("O1\nG01 X10.\nM30\n", "feed.nc").diagnostics}


# ---- programs that receive arguments ------------------------------------------------------------


def test_main_looking_program_that_reads_its_locals_first_gets_unknown_arguments() -> None:
    text = (
        "O9041 (BORE)\nIF[#26EQ#0]GOTO90\nIF[#7LE0]GOTO90\nG01 Z#26 F#9\nM30\n"
        "N90 #3000=1(Z AND D ARE NEEDED)\nM30\n"
    )
    facts, _ = run(text)
    doc = facts.document("t.nc")
    assert doc.jumps[1].undecided == 1 and doc.jumps[2].undecided == 1
    assert doc.assumed_arguments == {0: ((26, 1), (7, 2), (9, 3))}
    result = analyse(text, "bore.nc")
    codes = [d.code for d in result.diagnostics]
    assert "MB503" not in codes and "MB701" not in codes and "MB603" not in codes
    hint = next(d for d in result.diagnostics if d.code == "MB904")
    assert hint.line == 1 and "#26 (Z), #7 (D), #9 (F)" in hint.message
    # Set before they are read: a main program, its locals vacant at cycle start.
    facts, _ = run("O1\n#26=#0\nIF[#26EQ#0]GOTO90\nM30\nN90 #3000=1(Z IS NEEDED)\nM30\n")
    assert facts.document("t.nc").jumps[2].taken == 1
    assert not facts.document("t.nc").assumed_arguments


def test_alarm_inside_a_while_on_an_unknown_is_not_reached() -> None:
    text = "O1\nWHILE[#500LT3]DO1\n#3000=2(PROBE NOT READY)\nEND1\nM30\n"
    assert "MB503" not in {d.code for d in analyse(text, "wait.nc").diagnostics}
    # The same alarm in a loop whose test is decided is reached.
    text = "O1\n#1=0\nWHILE[#1LT3]DO1\n#3000=2(PROBE NOT READY)\nEND1\nM30\n"
    assert "MB503" in {d.code for d in analyse(text, "wait.nc").diagnostics}


def test_a_rejected_assignment_sets_its_variable_to_an_unknown_value() -> None:
    facts, _ = run("O1\n#5=#4*2:\n#6=#5\nM30\n")
    doc = facts.document("t.nc")
    assert isinstance(doc.writes[1][1].first, Unknown)
    assert isinstance(doc.writes[2][1].first, Unknown)  # not vacant: set, to what is not known
    assert not doc.assumed_arguments  # a block that does not parse reads nothing known


def test_motions_that_go_alike_share_their_words() -> None:
    """The words a run makes for a motion (computed by macro, or an F added) are shared by the
    motions with the same words in the same order: one dict each, not one per motion. A zero
    and a negative zero are different words (they print differently), and the order counts."""
    text = (
        "O1\nG99 G01 F0.2\n#1=1.\n#2=0.\n#3=-0.0001\n"  # X#3: X-0. to 0.001 mm
        + "G01 X#1 Z-2.\n" * 5
        + "G01 X#1 Z-2. F0.2\n"  # the F written: its dict is the same as the F added
        + "G01 X#3 Z-2.\nG01 X#2 Z-2.\nG01 X#3 Z-2.\nG01 Z-2. X#1\nM30\n"
    )
    facts, _ = run(text)
    motions = facts.motions
    assert len(motions) == 10
    words = [m.words for m in motions]
    assert all(w is words[0] for w in words[:6])
    assert words[0] == {"X": 1.0, "Z": -2.0, "F": 0.2}
    assert words[6] is words[8] and words[7] is not words[6]
    assert [math.copysign(1.0, w["X"]) for w in words[6:9]] == [-1.0, 1.0, -1.0]
    assert words[9] is not words[0] and list(words[9]) == ["Z", "X", "F"]


class _Frame:
    """What a compiled expression reads: locals #1-#33, no globals."""

    signed_atan = False
    length_increment = 0.001

    def __init__(self, values: dict[int, object]) -> None:
        self.locals: list[object] = [None] * 34
        for n, v in values.items():
            self.locals[n] = v
        self.store: dict[int, object] = {}

    def read_global(self, number: int) -> object:
        return None

    def note_rounding(self, name: str, argument: float, result: float) -> None:
        pass


def _outcome(expression: str, frame: _Frame) -> object:
    from fanuc_macro.evaluator.compiler import compile_expr
    from fanuc_macro.evaluator.values import MacroAlarm
    from fanuc_macro.syntax.parser import BlockParser
    from fanuc_macro.syntax.tree import Assign

    statement = BlockParser().parse_line(f"#30={expression}").statement
    assert isinstance(statement, Assign)
    try:
        return compile_expr(statement.value)(frame)  # type: ignore[arg-type]
    except MacroAlarm as alarm:
        return ("alarm", alarm.alarm, alarm.message, alarm.node is not None)


@pytest.mark.parametrize("op", ["+", "-", "*", "/", "MOD", "AND", "OR"])
def test_an_operation_with_a_number_on_the_right_gives_what_the_general_one_gives(
    op: str,
) -> None:
    """``#1+2.`` is compiled with the number held in the operation's closure: the same value,
    vacancy, unknown or alarm as ``#1+#2`` with #2 = 2."""
    lefts: list[object] = [None, 0.0, 5.5, -3.0, 1.5e308, Unknown(frozenset({7}))]
    for number in ("2.", "0", "0.5", "8."):
        right = float(number)
        for left in lefts:
            frame = _Frame({1: left, 2: right})
            general = _outcome(f"#1{op}#2", frame)
            special = _outcome(f"#1{op}{number}", frame)
            if isinstance(general, float) and math.isnan(general):
                assert isinstance(special, float) and math.isnan(special)
            else:
                assert special == general, (left, op, number)
