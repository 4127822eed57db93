"""The thread module completed into the user's program: the call at the cursor, the sub-program
after the program, the user's #100-#104 used and not repeated, a free O number."""

from __future__ import annotations

from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.ide.completion import completion
from fanuc_macro.ide.data import CompletionItem, TextEdit
from fanuc_macro.ide.view import View
from fanuc_macro.syntax.parser import default_parser, parse_text

# A main program of the paper's shape with all five values, no call yet; the cursor goes on
# the empty line 9.
MAIN = (
    "O1234 (M50X3-5G6G)\nT0101\nG00 X55. Z0.\nG97 S400 M03\n#100=50.\n#101=3.\n#102=50.\n"
    "#103=0.048\n#104=0.170\n\nG00 X100. Z100.\nM30\n%\n"
)
CURSOR_LINE = 9


def view_of(text: str, workspace_texts: dict[str, str] | None = None) -> View:
    config = Config()
    workspace = {}
    for key, other in (workspace_texts or {}).items():
        analysis = analyse(other, key, config)
        workspace[key] = (analysis.doc, analysis.index)
    return View("t.nc", analyse(text, "t.nc", config), config, workspace)


def thread_items(view: View, line_text: str, line: int = CURSOR_LINE) -> list[CompletionItem]:
    found = completion(line_text, line, len(line_text), Config(), view, snippets_supported=True)
    return [i for i in found.items if i.label.startswith("thread module")]


def apply(text: str, line: int, typed: str, item: CompletionItem) -> str:
    """The text after accepting ``item`` with ``typed`` typed at the start of ``line``."""
    lines = text.split("\n")
    lines[line] = typed
    edits: list[TextEdit] = list(item.additional_edits)
    assert item.replace is not None
    edits.append(TextEdit(item.replace, item.insert_text))
    for edit in sorted(edits, key=lambda e: e.range.start, reverse=True):
        start, end = edit.range.start, edit.range.end
        joined = "\n".join(lines)
        offset = sum(len(x) + 1 for x in lines[: start.line]) + start.column
        stop = sum(len(x) + 1 for x in lines[: end.line]) + end.column
        lines = (joined[:offset] + edit.new_text + joined[stop:]).split("\n")
    return "\n".join(lines)


def test_the_call_goes_at_the_cursor_and_the_sub_program_after_the_program() -> None:
    view = view_of(MAIN)
    (item,) = thread_items(view, "thread")
    assert item.filter_text == "thread"
    assert item.insert_text.startswith("M98 P0013331 (CALL O3331:")
    assert "#100=" not in item.insert_text  # the user's values, not entered twice
    (sub,) = item.additional_edits
    # After M30, before the tape's closing %.
    assert (sub.range.start.line, sub.range.start.column) == (12, 0)
    assert sub.new_text.startswith("O3331 (EXTERNAL THREAD SUB")
    assert sub.new_text.rstrip("\n").endswith("M99 (BACK TO THE MAIN PROGRAM)")
    assert "O1234" not in sub.new_text and "#100=" not in sub.new_text
    assert "88 passes, 186 G92 cuts, final X46.186" in item.label

    done = apply(MAIN, CURSOR_LINE, "thread", item)
    lines = done.split("\n")
    assert lines[CURSOR_LINE].startswith("M98 P0013331")
    assert (
        lines[-2] == "%"
        and lines.count("O3331 (EXTERNAL THREAD SUB - SYMMETRIC LEFT-RIGHT CUTTING, G92)") == 1
    )
    result = analyse(done, "t.nc", Config())
    errors = [d for d in result.diagnostics if d.severity.value == "error"]
    assert errors == []
    (thread,) = result.threads
    assert thread.name.upper().startswith("M50X3")
    # Nothing more to complete: the program calls the module it has.
    assert thread_items(view_of(done), "thread", CURSOR_LINE + 1) == []


def test_values_left_to_a_designation_are_entered_with_the_call() -> None:
    partial = MAIN.replace("#103=0.048\n#104=0.170\n", "")
    item = thread_items(view_of(partial), "thread", CURSOR_LINE - 2)[0]
    lines = item.insert_text.split("\n")
    assert lines[0].startswith("#103=0.048") and lines[1].startswith("#104=0.17")
    assert lines[2].startswith("M98 P0013331")
    assert not any(line.startswith(("#100", "#101", "#102")) for line in lines)


def test_a_free_program_number_and_a_call_that_is_already_there() -> None:
    taken = {"lib.nc": "O3331 (SOMETHING ELSE)\nM99\n%\nO3332\nM99\n"}
    (item,) = thread_items(view_of(MAIN, taken), "thread")
    assert item.insert_text.startswith("M98 P0013333")
    assert item.additional_edits[0].new_text.startswith("O3333 ")
    # A call to a program that is nowhere gets that program; no second call is written.
    called = MAIN.replace("\n\nG00 X100.", "\nM98 P0015555\n\nG00 X100.")
    (item,) = thread_items(view_of(called), "thread", CURSOR_LINE + 1)
    assert item.insert_text == ""
    assert item.additional_edits[0].new_text.startswith("O5555 ")


def test_found_by_thread_m98_and_the_chinese_word() -> None:
    view = view_of(MAIN)
    assert thread_items(view, "th")[0].filter_text == "thread"
    m98 = thread_items(view, "M9")
    assert m98 and m98[0].filter_text == "M98"
    chinese = thread_items(view, "螺")
    assert chinese and chinese[0].filter_text == "螺纹"
    assert chinese[0].replace is not None and chinese[0].replace.start.column == 0
    assert thread_items(view, "G9") == [] and thread_items(view, "X") == []


def test_internal_thread_and_a_program_at_the_end_of_the_file() -> None:
    internal = "O2000 (M50X3-6H INTERNAL)\n#100=50.\n#101=3.\n#102=40.\n#103=0.\n#104=0.265\n\nM30"
    (item,) = thread_items(view_of(internal), "thread", 6)
    assert item.insert_text.startswith("M98 P0013330")
    (sub,) = item.additional_edits
    assert (sub.range.start.line, sub.range.start.column) == (7, 3)  # after M30, no %
    assert sub.new_text.startswith("\nO3330 (INTERNAL THREAD SUB")
    done = apply(internal, 6, "thread", item)
    assert done.endswith("M99 (BACK TO THE MAIN PROGRAM)")
    assert parse_text(done, "t.nc", default_parser()).blocks[8].text.startswith("O3330")


def test_no_item_outside_the_program_that_enters_the_thread() -> None:
    two = MAIN + "O5000\n#1=1\n\nM30\n%\n"
    assert thread_items(view_of(two), "thread", 16) == []
    assert thread_items(view_of("O1\nG00 X1.\n\nM30\n"), "thread", 2) == []
