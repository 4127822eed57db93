"""What the hover says about the evaluator's runs, read from the features without a client."""

from __future__ import annotations

import re
import unicodedata
from pathlib import Path

from lsprotocol import types

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.lsp.convert import Codec, Lines
from fanuc_macro.lsp.features import View, hover
from fanuc_macro.program.papers import DENG_MOLYBDENUM, PU_DRUM_GROOVE, REN_ARC_THREAD


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
    assert " = **1.235**" in hover_text(view_of(metric), 2, 1)
    shown = hover_text(view_of(metric), 3, 1)
    assert " = **2.469**" in shown and "```\n= 1.235*2\n```" in shown
    inch = metric.replace("G21", "G20")
    assert " = **1.2346**" in hover_text(view_of(inch), 2, 1)
    # G21 after G20 is millimetres again; a G20 in a comment or #120 is no unit code.
    back = "O1000\nG20\nG21 (NOT G20)\n#120=1\n#1=1.23456789\nM30\n"
    assert " = **1.235**" in hover_text(view_of(back), 4, 1)
    tiny = "O1000\n#1=0.00042\nM30\n"
    assert " = **0.00042**" in hover_text(view_of(tiny), 1, 1)
    full = hover_text(view_of(metric, Config(hover_full_precision=True)), 2, 1)
    assert " = **1.2345679**" in full


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


SEEDS = Path(__file__).resolve().parent / "fixtures" / "seeds"
HOVER_COLUMNS = 70  # about what a hover holds in a line at the editor's font


def rendered_lines(markdown: str) -> float:
    """The lines a hover takes: each line of text wrapped at HOVER_COLUMNS (a Chinese
    character is two columns, a link its text), a rule one line, a paragraph gap half."""
    lines = 0.0
    for line in markdown.splitlines():
        if line.startswith("```"):
            continue
        if not line.strip():
            lines += 0.5
            continue
        shown = re.sub(r"\]\([^)]*\)", "]", line)
        width = sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in shown)
        lines += -(-width // HOVER_COLUMNS)
    return lines


def test_the_seed_modules_variables_hover_in_twelve_lines_value_first() -> None:
    measured = 0
    for path in sorted(SEEDS.glob("*.nc")):
        text = path.read_text("utf-8")
        view = view_of(text, uri=path.name)
        for line, block in enumerate(text.splitlines()):
            for found in re.finditer(r"#\d+", block):
                answer = hover(view, types.Position(line=line, character=found.start() + 1))
                if answer is None:  # in a comment
                    continue
                assert isinstance(answer.contents, types.MarkupContent)
                shown = answer.contents.value
                assert rendered_lines(shown) <= 12, (path.name, line + 1, shown)
                head = shown.split("\n\n", 1)[0]
                assert head.startswith(f"**{found.group()}**"), head
                measured += 1
    assert measured > 300
    # A variable of the module's table: the value, its name and comment, the formula with
    # the values read; then the table's formula, the kind of variable and the paper's link.
    seed = (SEEDS / "o4009_external_m50x3.nc").read_text("utf-8")
    shown = hover_text(view_of(seed), 21, 1)  # #4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.
    lead, more = shown.split("\n\n---\n\n")
    assert lead.split("\n\n")[:2] == [
        "**#4** = **1.907**",
        "h, thread height, radius — *计算外螺纹牙高*",
    ]
    assert "local variable" not in lead.lower() and "Deng" not in lead
    assert more.startswith("*7H/8 − r + es/2 + Td2/4")
    assert more.count("Local variable of the current macro level") == 1
    assert f"[Deng Ronggang, table 3]({DENG_MOLYBDENUM.link})" in more


def test_every_paper_s_link_leads_to_its_full_citation() -> None:
    page = (SEEDS.parents[2] / "docs" / "papers.md").read_text("utf-8")
    anchors = {
        re.sub(r"[^a-z0-9 -]", "", h.lower()).replace(" ", "-")
        for h in re.findall(r"^## (.+)$", page, re.MULTILINE)
    }
    for paper in (DENG_MOLYBDENUM, REN_ARC_THREAD, PU_DRUM_GROOVE):
        assert paper.anchor in anchors, paper
        assert paper.link.endswith(f"docs/papers.md#{paper.anchor}")
        heading = next(
            h for h in page.split("\n## ")[1:] if h.startswith(paper.authors_short.split(" et")[0])
        )
        assert paper.title in heading and (paper.journal or "") in heading


def test_a_code_s_hover_gives_only_the_analysed_machine_s_meaning() -> None:
    seed = (SEEDS / "o4009_external_m50x3.nc").read_text("utf-8")
    shown = hover_text(view_of(seed), 31, 1)  # G92 in O3331: a lathe's threading pass
    lead, more = shown.split("\n\n---\n\n")
    assert lead.startswith("**G92** — Threading cycle *(modal, group 01)*\n\n**Thread M50x3-5g6g**")
    assert more.startswith("`G92 X(U).. Z(W)..")
    assert "mill" not in shown.lower() and "coordinate system" not in shown.lower()
    mill = hover_text(view_of("O1\nG90 G54 G00 X0 Y0\nG92 X10. Y5.\nM30\n"), 2, 1)
    assert mill.startswith("**G92** — Workpiece coordinate system setting")
    assert "lathe" not in mill.lower() and "Threading" not in mill
    # Neither machine shows: the document is read both ways, and both meanings are given.
    both = hover_text(view_of("O1\nG92 X10. Z5.\nM30\n"), 1, 1)
    assert "Threading cycle" in both and "On a mill: Workpiece coordinate system" in both
