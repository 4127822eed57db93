"""A comment whose text runs on over several lines without its '(' on each: one MB001 on the
first line the control reads as a block, none on the lines it never reaches."""

from __future__ import annotations

from fanuc_macro.analysis import analyse


def found(text: str) -> list[tuple[str, int]]:
    return [(d.code, d.line) for d in analyse(text, "runaway.nc").diagnostics]


def test_a_comment_that_runs_on_is_one_alarm() -> None:
    text = "O1000\n(THIS PROGRAM CUTS THE\nOUTER PROFILE OF PART 12\nWITH TOOL 3)\nG0X10.Z5.\nM30\n"
    diagnostics = analyse(text, "runaway.nc").diagnostics
    assert [(d.code, d.line) for d in diagnostics] == [("MB004", 1), ("MB001", 2)]
    message = diagnostics[1].message
    assert "comment opened on line 2" in message and "'OUTER PROFILE OF PART 12'" in message
    assert "line 4 goes on with it too" in message


def test_a_comment_never_closed_stops_at_the_first_block() -> None:
    text = "O1000\n(SETUP NOTES\nMOUNT IN VISE\nZERO ON TOP\nG0X10.Z5.\nG01Z\nM30\n"
    assert found(text) == [("MB004", 1), ("MB001", 2), ("MB001", 5)]  # G01Z: its own mistake


def test_chinese_prose_runs_on_too() -> None:
    text = "O1000\n(螺纹加工\n注意刀具\nG0X10.Z5.\nM30\n"
    assert found(text) == [("MB004", 1), ("MB001", 2)]


def test_a_broken_block_after_an_unclosed_comment_keeps_its_own_message() -> None:
    text = "O1000\n(ROUGHING\nG01 X10. Z\nM30\n"
    diagnostics = analyse(text, "runaway.nc").diagnostics
    assert [(d.code, d.line) for d in diagnostics] == [("MB004", 1), ("MB001", 2)]
    assert "goes on with the comment" not in diagnostics[1].message


def test_an_empty_line_ends_the_run() -> None:
    text = "O1000\n(NOTES\nMOUNT IN VISE\n\nZERO ON TOP\nM30\n"
    assert found(text) == [("MB004", 1), ("MB001", 2), ("MB001", 4)]


def test_without_an_unclosed_comment_every_line_is_its_own() -> None:
    text = "O1000\n(NOTES)\nMOUNT IN VISE\nZERO ON TOP\nM30\n"
    assert found(text) == [("MB001", 2), ("MB001", 3)]
