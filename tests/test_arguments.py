"""The locals a called program names, and MB411 across files: an argument the macro never
uses, reported at the call, with the letter the macro reads."""

from __future__ import annotations

from pathlib import Path

from cli_runner import run
from fanuc_macro.program.arguments import argument_numbers, locals_named
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import BlockParser, parse_text

BOLT_CIRCLE = """\
O9010 (BOLT CIRCLE: R RADIUS (#18), H HOLES (#11), NOT #4)
#1=0
WHILE[#1LT#11]DO1
G81 X[#18*COS[#1*360/#11]] Y[#18*SIN[#1*360/#11]] Z#26 R2. F#9
#1=#1+1
END1
G80
M99
"""


def named(text: str) -> object:
    doc = parse_text(text, "untitled:t.nc", BlockParser())
    return locals_named(doc, build_index(doc).programs[0])


def test_the_locals_a_program_names_and_reads_first() -> None:
    use = named(BOLT_CIRCLE)
    assert use is not None
    assert use.named == frozenset({1, 9, 11, 18, 26})  # the comment's #18 and #4 are no names
    assert use.read_first == (11, 18, 26, 9)  # #1 is set before it is read
    counter = named("O9020\n#1=#1+1\nG00 X#1\nM99\n")
    assert counter is not None and counter.read_first == (1,)  # '#1=#1+1' reads #1 first


def test_a_program_whose_locals_the_text_cannot_say_gives_none() -> None:
    assert named("O9020\n#30=4\nG00 X#[#30]\nM99\n") is None
    assert named("O9020\nM98 P9021\nM99\n") is None


def test_argument_specification_two_fills_sets_of_three() -> None:
    assert argument_numbers(["I", "J", "K", "I", "J", "K"]) == [4, 5, 6, 7, 8, 9]
    assert argument_numbers(["A", "I", "I", "R"]) == [1, 4, 7, 18]


def test_an_argument_the_macro_in_another_file_never_uses(tmp_path: Path) -> None:
    (tmp_path / "main.nc").write_text(
        "O1000\nG90 G17 G54\nT3 M06\nG43 H3 Z50.\nS1200 M03\n"
        "G65 P9010 I50. H6. Z-10. F150.\nG65 P9010 R50. H6. Z-10. F150.\nM30\n"
    )
    (tmp_path / "O9010.nc").write_text(BOLT_CIRCLE)
    result = run(tmp_path, "check", "main.nc", "O9010.nc")
    rows = [line for line in result.stdout.splitlines() if " MB411 " in line]
    assert rows == [
        "main.nc:6:11: MB411 warning I50. gives #4 to O9010, which never uses #4: the value "
        "is lost; it reads #18 (R), which this call does not pass"
    ]
    alone = run(tmp_path, "check", "main.nc")  # the macro not checked with it: nothing said
    assert "MB411" not in alone.stdout


def test_m98_words_the_subprogram_in_another_file_reads_as_arguments(tmp_path: Path) -> None:
    main = "O1000\nG90 G17 G54\nT3 M06\nG43 H3 Z50.\nS1200 M03\n{call}\nG00 Z50.\nM30\n"
    (tmp_path / "O9010.nc").write_text(BOLT_CIRCLE)
    (tmp_path / "main.nc").write_text(main.format(call="M98 P9010 R50. H6. Z-10. F150."))
    result = run(tmp_path, "check", "main.nc", "O9010.nc")
    rows = [line for line in result.stdout.splitlines() if " MB412 " in line]
    assert rows == [
        "main.nc:6:11: MB412 warning R50. H6. Z-10. F150. are no arguments: M98 passes none, "
        "and O9010 reads #18 (R), #11 (H), #26 (Z), #9 (F) before setting them, vacant here; "
        "G65 P9010 passes them"
    ]
    (tmp_path / "main.nc").write_text(main.format(call="G65 P9010 R50. H6. Z-10. F150."))
    twin = run(tmp_path, "check", "main.nc", "O9010.nc")
    assert "MB412" not in twin.stdout and "MB411" not in twin.stdout


def test_a_local_always_set_before_it_is_read_takes_nothing_from_the_call() -> None:
    # #4 is set on each pass before the loop reads it; #5 is set in the loop and read after
    # it (the loop may run no time); #6 is set in a THEN, which may not happen.
    text = (
        "O9030\n#1=0\nWHILE[#1LT#11]DO1\n#4=#18*2\nG00 X#4\n#5=1\n#1=#1+1\nEND1\n"
        "G00 Y#5\nIF[#1GT1]THEN#6=2\nG00 Z#6\nM99\n"
    )
    use = named(text)
    assert use is not None
    assert use.used == frozenset({5, 6, 11, 18})
    # A GOTO may skip any set: every named local may take the call's value.
    jumping = named("O9031\nIF[#18GT0]GOTO10\n#4=1\nN10 G00 X#4\nM99\n")
    assert jumping is not None and jumping.used == jumping.named == frozenset({4, 18})
