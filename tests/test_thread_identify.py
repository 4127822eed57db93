"""What thread a program cuts: designations in comments, module shapes, the cuts' side and
lead, and the sentence a hover gives when the thread cannot be identified."""

from __future__ import annotations

import pytest

from fanuc_macro.analysis import analyse
from fanuc_macro.syntax.parser import parse_text
from fanuc_macro.threads.identify import LineThreadWords, Thread, describe, thread_words


def words(comment: str) -> tuple[tuple[str, ...], tuple[str, ...], int | None]:
    parsed = parse_text(f"G00 X1. ({comment})\n").blocks[0].parsed
    found = thread_words(parsed)
    return tuple(form for _t, form in found.designations), found.other_forms, found.starts


@pytest.mark.parametrize(
    ("comment", "forms"),
    [
        ("M50X3-5G6G", ("M50X3-5G6G",)),
        ("外螺纹 M50×3-5g6g", ("M50x3-5g6g",)),
        ("THREAD M10-6G", ("M10-6G",)),
        ("M20X1.5LH", ("M20X1.5LH",)),
        ("M20X1.5-6G-LH", ("M20X1.5LH-6G",)),
        ("M16xPh3P1.5-6H", ("M16xPh3P1.5-6H",)),
        ("M50X6(P3", ("M50XPH6P3",)),
        ("M30 PROGRAM END", ()),
        ("M8 COOLANT ON", ()),
        ("#100=M50", ()),
    ],
)
def test_designations_in_comments(comment: str, forms: tuple[str, ...]) -> None:
    assert words(comment)[0] == forms


@pytest.mark.parametrize(
    ("comment", "starts"),
    [("M50X3 2 START", 2), ("3-STARTS", 3), ("双线螺纹", 2), ("M24X3 - START POINT", None)],
)
def test_number_of_starts(comment: str, starts: int | None) -> None:
    assert words(comment)[2] == starts


def _threads(text: str) -> list[Thread]:
    return analyse(text, "t.nc").threads


HAND = "O1 ({})\nG97 S500 M03\nG00 X{} Z5.\nG92 X{} Z-30. F{}\nX{}\nX{}\nG00 X100.\nM30\n"


def test_thread_from_the_designation_and_the_cuts() -> None:
    (t,) = _threads(HAND.format("M20X2.5", 22, 19.5, 2.5, 19.0, 18.5))
    assert t.identified and t.internal is False and t.name == "M20x2.5-6g"
    assert "the passes go deeper towards the axis" in t.job.side_reason
    assert t.pitch_class is not None and t.pitch_class.name == "6g"
    assert t.root_x() == pytest.approx(16.624, abs=5e-4)  # d3 min of M20x2.5-6g
    assert "the designation M20X2.5 at line 1" in t.known_from()


def test_all_capital_class_is_read_on_the_side_the_cuts_show() -> None:
    (t,) = _threads(HAND.format("M36X2-6H", 32, 34.2, 2, 34.6, 35.0))
    assert t.internal is True and t.name == "M36x2-6H"
    assert t.root_x() == pytest.approx(36.657, abs=5e-4)  # D2 max + H with a sharp tool


def test_no_size_known_is_said_in_the_hover() -> None:
    (t,) = _threads(HAND.format("OD THREAD", 22, 19.5, 2.5, 19.0, 18.5))
    assert not t.identified
    text = describe(t)
    # The example names a thread and its side: in the case of ISO 965-1.
    assert "not identified" in text and "(M50x3-5g6g)" in text


# One G32 cut and no move after it: the cut does not tell an external thread from an internal
# one.  At X45. it is past the root of M50x3-5g6g (X45.985).
ONE_CUT = "O1 ({})\nG97 S500 M03\nG00 X45. Z5.\nG32 Z-30. F3.\nM30\n"


@pytest.mark.parametrize("comment", ["M50X3-5G6G", "M50X3"])
def test_a_designation_of_either_kind_is_not_used_when_nothing_tells_the_side(
    comment: str,
) -> None:
    (t,) = _threads(ONE_CUT.format(comment))
    assert t.job.internal is None
    assert not t.identified and t.internal is None and t.designation is None
    text = describe(t)
    assert f"the designation {comment} at line 1 has" in text
    assert "or an internal" in text and "neither the cuts nor the program's first comments" in text
    # No verdict from a guessed side: the same pass under a designation that says external is
    # past the root.
    assert analyse(ONE_CUT.format(comment), "t.nc").diagnostics == []
    said = {d.code for d in analyse(ONE_CUT.format("M50x3-5g6g"), "t.nc").diagnostics}
    assert {"MB801", "MB802"} <= said


@pytest.mark.parametrize(
    ("comment", "internal", "name"),
    [
        ("M50x3-5g6g", False, "M50x3-5g6g"),
        ("M50x3-5G6G", True, "M50x3-5G6G"),  # the x shows the case was kept
        ("M50X3-4H5H", True, "M50x3-4H5H"),  # the seed paper's: ISO 965-1 has no external 4h5h
        ("M50X3-6E", False, "M50x3-6e"),  # E is an external position only
        ("EXTERNAL M50X3-5G6G", False, "M50x3-5g6g"),  # the program's first comment says
    ],
)
def test_a_designation_that_tells_its_side_is_used_without_the_cuts(
    comment: str, internal: bool, name: str
) -> None:
    (t,) = _threads(ONE_CUT.format(comment))
    assert t.job.internal is None
    assert t.internal is internal and t.designation is not None and t.name == name


@pytest.mark.parametrize(
    ("comment", "what"),
    [("TR40X7", "trapezoidal"), ("1/2-13 UNC", "Unified"), ("NPT 1/2", "pipe thread")],
)
def test_other_thread_forms_are_named(comment: str, what: str) -> None:
    (t,) = _threads(HAND.format(comment, 42, 39.5, 7, 39.0, 38.5))
    assert not t.identified and t.unsupported is not None and what in t.unsupported
    assert what in describe(t)


def test_taper_cut_is_not_checked_against_a_parallel_profile() -> None:
    text = "O1 (M20X2.5)\nG00 X24. Z5.\nG92 X19.5 Z-30. R-1. F2.5\nX18.\nX16.\nM30\n"
    (t,) = _threads(text)
    assert t.unsupported is not None and "taper" in t.unsupported
    assert not {d.code for d in analyse(text, "t.nc").diagnostics} & {"MB801", "MB802"}


def test_a_module_called_twice_is_two_threads_with_their_own_inputs() -> None:
    module = (
        "O3001\n#3=#101/[8*SIN[60]]\n#4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.\n#9=0.15\n"
        "N10 G92 X[#100-2.*#9] Z-30. F#101\n#9=#9+0.15\nIF[#9LT#4]GOTO10\n"
        "G92 X[#100-2.*#4] Z-30. F#101\nM99\n"
    )
    main = "O1\nG00 X32. Z5.\n#100=30.\n#101=2.\n#103=0.038\n#104=0.170\nM98 P3001\n"
    main += "G00 X26. Z5.\n#100=24.\n#101=3.\n#103=0.048\n#104=0.200\nM98 P3001\nM30\n"
    first, second = _threads(main + module)
    assert (first.major, first.pitch, second.major, second.pitch) == (30.0, 2.0, 24.0, 3.0)
    assert first.pitch_class is not None and first.pitch_class.name == "6g"
    assert second.pitch_class is not None and second.pitch_class.name == "6g"
    assert first.module is not None and first.module.height_var == 4
    assert first.nose_radius == pytest.approx(2 / (8 * 0.8660254), abs=1e-6)


def test_a_comment_without_a_latin_letter_is_passed_over_as_the_patterns_would() -> None:
    """The comments of the corpus and random ones (letters that fold to Latin ones in a
    case-blind match among them) give the same thread words when every pattern is tried."""
    import random
    import re

    from fanuc_macro.syntax.parser import BlockParser
    from fanuc_macro.threads import identify
    from test_parser import program_lines

    rng = random.Random(7)
    pieces = ["M", "m", "X", "×", "ſtart", "ſ", "K", "ı", "İ", "线", "双", "Tr", "UNC", "NPT", "R"]
    pieces += ["Rc", "G", "1/2", "3", "24", ".5", "-", " ", "螺纹", "(", "P", "H", "LH", "6g"]
    comments = [" ".join(rng.choices(pieces, k=rng.randint(1, 8))) for _ in range(3000)]
    lines = [*program_lines(), *(f"G00 X1. ({c.replace('(', '')})" for c in comments)]
    parser = BlockParser()
    parsed = [p for p in map(parser.parse_line, lines) if p.comments]
    quick = [identify._line_words(p) for p in parsed]
    texts = [c.text for p in parsed for c in p.comments]
    assert sum(1 for t in texts if not identify._MAY_NAME_A_THREAD.search(t)) > 100
    every_pattern = re.compile("")
    saved, identify._MAY_NAME_A_THREAD = identify._MAY_NAME_A_THREAD, every_pattern
    try:
        slow = [identify._line_words(p) for p in parsed]
    finally:
        identify._MAY_NAME_A_THREAD = saved
    for p, q, s in zip(parsed, quick, slow, strict=True):
        assert vars_of(q) == vars_of(s), p.text


def vars_of(words: LineThreadWords) -> tuple[object, ...]:
    return (words.designations, words.other_forms, words.starts, words.pipes)


def test_a_comment_names_a_role_as_the_word_by_word_search_finds_it() -> None:
    from fanuc_macro.program.meanings import ROLE_WORDS, role_of_comment
    from fanuc_macro.syntax.parser import BlockParser
    from test_parser import program_lines

    def word_by_word(comment: str) -> str | None:
        upper = comment.upper()
        return next((r for r, ws in ROLE_WORDS.items() for w in ws if w in upper), None)

    parser = BlockParser()
    comments = [c.text for p in map(parser.parse_line, program_lines()) for c in p.comments]
    comments += [f"#1 = {w.lower()} of the thread" for ws in ROLE_WORDS.values() for w in ws]
    named = [role_of_comment(c) for c in comments]
    assert named == [word_by_word(c) for c in comments]
    assert sum(1 for r in named if r is not None) >= sum(len(ws) for ws in ROLE_WORDS.values())
