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
