"""What the hover says about the evaluator's runs, read from the features without a client."""

from __future__ import annotations

from lsprotocol import types

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.lsp.convert import Codec, Lines
from fanuc_macro.lsp.features import View, hover


def view_of(text: str, config: Config | None = None, uri: str = "t.nc") -> View:
    config = config or Config()
    return View(
        key=uri,
        uri=uri,
        analysis=analyse(text, uri, config),
        lines=Lines(text.splitlines(), Codec()),
        config=config,
    )


def hover_text(view: View, line: int, character: int) -> str:
    found = hover(view, types.Position(line=line, character=character))
    assert found is not None and isinstance(found.contents, types.MarkupContent)
    return found.contents.value


ENDLESS = "O1000\n#1=0\nWHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n"


def test_program_hover_says_the_safety_net_stopped_the_analysis() -> None:
    stopped = hover_text(view_of(ENDLESS, Config(time_limit=1e-9)), 0, 2)
    assert "Analysis stopped after 1e-09 s" in stopped
    assert "Analysis stopped" not in hover_text(view_of(ENDLESS), 0, 2)


def test_program_hover_says_a_main_looking_program_is_taken_for_a_macro() -> None:
    text = "O9041 (BORE)\nIF[#26EQ#0]GOTO90\nG01 Z#26 F#9\nM30\nN90 #3000=1(Z IS NEEDED)\nM30\n"
    shown = hover_text(view_of(text), 0, 2)
    assert "Analysed as a macro with unknown arguments" in shown
    assert "reads #26 (Z), #9 (F) before setting them" in shown
    value = hover_text(view_of(text), 2, 7)  # #26 in G01 Z#26
    assert "depends on #26" in value
    plain = "O9042\n#26=-5.\nG01 Z#26 F100.\nM30\n"
    assert "unknown arguments" not in hover_text(view_of(plain), 0, 2)


def test_values_are_shown_at_the_least_input_increment_of_the_unit() -> None:
    metric = "O1000\nG21\n#1=1.23456789\n#2=#1*2\nM30\n"
    assert "Value assigned: **1.235**" in hover_text(view_of(metric), 2, 1)
    shown = hover_text(view_of(metric), 3, 1)
    assert "Value assigned: **2.469**" in shown and "= 1.235*2\n= 2.469" in shown
    inch = metric.replace("G21", "G20")
    assert "Value assigned: **1.2346**" in hover_text(view_of(inch), 2, 1)
    # G21 after G20 is millimetres again; a G20 in a comment or #120 is no unit code.
    back = "O1000\nG20\nG21 (NOT G20)\n#120=1\n#1=1.23456789\nM30\n"
    assert "Value assigned: **1.235**" in hover_text(view_of(back), 4, 1)
    tiny = "O1000\n#1=0.00042\nM30\n"
    assert "Value assigned: **0.00042**" in hover_text(view_of(tiny), 1, 1)
    full = hover_text(view_of(metric, Config(hover_full_precision=True)), 2, 1)
    assert "Value assigned: **1.2345679**" in full


def test_the_argument_letter_is_shown_only_where_a_call_passes_arguments() -> None:
    sub = "O2000\n#3=#1+1.\nM99\n"
    by_g65 = view_of("O1000\nG65 P2000 A1.\nM30\n" + sub)
    assert "G65 argument **A**" in hover_text(by_g65, 4, 4)  # #1 in #3=#1+1.
    by_m98 = view_of("O1000\n#1=5.\nM98 P2000\nM30\n" + sub)
    assert "argument" not in hover_text(by_m98, 5, 4)
    alone = view_of(sub)  # a sub program no call of which is known may be a macro
    assert "G65 argument **A**" in hover_text(alone, 1, 4)
    main = view_of("O1000\n#1=5.\nM30\n")
    assert "argument" not in hover_text(main, 1, 1)


def test_a_missing_label_or_program_is_not_explained_twice() -> None:
    jump = "O1000\n#1=1\nGOTO 99\nM30\n"
    shown = hover_text(view_of(jump), 2, 1)
    assert shown.startswith("**GOTO 99**") and "PS0128" not in shown  # MB101 says it
    quiet = hover_text(view_of(jump, Config(disabled=frozenset({"MB101"}))), 2, 1)
    assert "No N99 in O1000: the jump stops with alarm PS0128" in quiet
    call = "O1000\nM98 P1234\nM30\n"
    assert "PS0076" not in hover_text(view_of(call), 1, 5)  # MB403 says it
    quiet_call = hover_text(view_of(call, Config(disabled=frozenset({"MB403"}))), 1, 5)
    assert "PS0076" in quiet_call
