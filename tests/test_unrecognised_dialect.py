"""A file of another control whose dialect has no mark known here: one MB002 on its first
line when most of its blocks are rejected and it has no FANUC program number; a FANUC program
with many mistakes keeps one diagnostic a block."""

from __future__ import annotations

from pathlib import Path

from cli_runner import run
from fanuc_macro.analysis import analyse

# A conversational program (Heidenhain's plain language), written for this test.
CONVERSATIONAL = """BEGIN PGM 12 MM
BLK FORM 0.1 Z X+0 Y+0 Z-20
BLK FORM 0.2 X+100 Y+100 Z+0
TOOL CALL 3 Z S2500
L Z+50 R0 FMAX M3
L X-10 Y-10 R0 FMAX
L Z-5 R0 F500
L X+110 RL F300
L Y+110
L X-10
L Z+50 R0 FMAX M30
END PGM 12 MM
"""


def test_a_file_most_of_whose_blocks_fanuc_rejects_is_one_mb002() -> None:
    found = analyse(CONVERSATIONAL, "part.h").diagnostics
    errors = [d for d in found if d.severity.value == "error"]
    assert [(d.code, d.line) for d in errors] == [("MB002", 0)]
    message = errors[0].message
    assert message.startswith("not a FANUC program: ")
    assert "of its 12 blocks are in forms FANUC rejects (lines 1, 2, 3" in message
    assert len(errors[0].related) >= 6  # each rejected block, with what FANUC rejects in it


def test_a_fanuc_program_with_many_mistakes_keeps_one_diagnostic_a_block() -> None:
    # 9 rejected blocks of 16: another control's file without a program number; with one, a
    # program meant for FANUC, each mistake its own.
    blocks = CONVERSATIONAL.splitlines(True)[1:10]
    plain = ["G00 X0 Y0\n", "G01 X10. F100.\n", "G01 Y10.\n", "G01 X0\n", "G01 Y0\n", "M30\n"]
    text = "".join(plain[:3] + blocks + plain[3:])
    alone = [d for d in analyse(text, "part.nc").diagnostics if d.severity.value == "error"]
    assert [d.message[:20] for d in alone] == ["not a FANUC program:"]
    numbered = "O1200 (PLATE)\n" + text
    found = [d for d in analyse(numbered, "part.nc").diagnostics if d.severity.value == "error"]
    assert len(found) == 9
    assert all(not d.message.startswith("not a FANUC program") for d in found)


def test_a_numbered_file_nearly_all_of_whose_blocks_fanuc_rejects_is_one_mb002() -> None:
    numbered = "O1200 (PLATE)\n" + CONVERSATIONAL  # 12 rejected blocks of 13
    found = [d for d in analyse(numbered, "part.nc").diagnostics if d.severity.value == "error"]
    assert [(d.code, d.line) for d in found] == [("MB002", 0)]
    assert found[0].message.startswith("not a FANUC program: 12 of its 13 blocks")


def test_a_few_rejected_blocks_are_reported_one_by_one() -> None:
    # Four blocks FANUC rejects among plain ones, and no O number: too few to say the file is
    # another control's.
    text = "G00 X0 Y0\nG01 X10. F100.\n" + "".join(CONVERSATIONAL.splitlines(True)[4:8])
    text += "G01 X20.\nG01 Y20.\nG01 X0\nG01 Y0\nM30\n"
    found = [d for d in analyse(text, "part.nc").diagnostics if d.severity.value == "error"]
    assert len(found) == 4
    assert all(not d.message.startswith("not a FANUC program") for d in found)


HAAS_FORMS = [
    "M97 P100",
    "G103 P1",
    "G154 P12",
    "IF [ #1 EQ #2 ] S#20 F#30",
    "#162 = #30001.116",
]


def _haas_file(forms: list[str]) -> str:
    plain = ["G00 X0 Y0", "G01 X10. F100.", "G01 Y10.", "G01 X0", "G01 Y0"]
    return "%\nO1000 (PLATE)\n" + "\n".join([*plain, *forms, "M30", "N100 M99", "%", ""])


def test_five_blocks_in_one_controls_forms_make_the_file_that_controls() -> None:
    found = [d for d in analyse(_haas_file(HAAS_FORMS), "p.nc").diagnostics if d.code == "MB002"]
    assert [d.line for d in found] == [1]
    assert found[0].message.startswith(
        "a program written for Haas (5 blocks in its forms, the first on line 8)"
    )
    # Each block keeps what its form is, as a related place.
    assert [r.message.split(":")[0] for r in found[0].related] == [
        "Haas",
        "Haas",
        "Haas",
        "Haas",
        "Haas NGC",
    ]


def test_a_fanuc_program_with_a_few_foreign_forms_keeps_one_mb002_a_block() -> None:
    found = [d for d in analyse(_haas_file(HAAS_FORMS[:4]), "p.nc").diagnostics]
    lines = [d.line for d in found if d.code == "MB002"]
    assert lines == [7, 8, 9, 10]


def test_in_another_controls_file_the_run_stops_at_its_first_rejected_block() -> None:
    """The F of a block FANUC drops is not lost to a warning: FANUC stops at that block."""
    okuma = "%\nO1234 (LATHE)\nVC1=0\nG00 X20. Z2.\nNSTART G01 X10. F0.2\nG01 Z-5.\nM30\n%\n"
    codes = [(d.code, d.line) for d in analyse(okuma, "p.nc").diagnostics]
    assert [c for c, _ in codes] == ["MB002"]  # no MB603 at G01 Z-5.: the run is of no control
    # A FANUC program with a block FANUC rejects: the run goes on past it, as the checker reads
    # it, to find the next mistakes.
    fanuc = "%\nO1234 (LATHE)\nX10.Y\nG00 X20. Z2.\nG01 X10.\nG01 Z-5.\nM30\n%\n"
    found = [(d.code, d.line) for d in analyse(fanuc, "p.nc").diagnostics]
    assert ("MB001", 2) in found and ("MB603", 4) in found


def test_the_command_line_says_it_once(tmp_path: Path) -> None:
    (tmp_path / "part.h").write_text(CONVERSATIONAL, encoding="ascii")
    (tmp_path / "lathe.nc").write_text(
        "%\nO1234 (LATHE)\nVC1=0\nG00 X20. Z2.\nNSTART G01 X10. F0.2\nG01 Z-5.\nM30\n%\n",
        encoding="ascii",
    )
    done = run(tmp_path, "check", "part.h", "lathe.nc")
    lines = done.stdout.splitlines()
    assert [line.split(": ")[0] for line in lines] == ["part.h:1:1", "lathe.nc:2:1"]
    assert "MB002 error not a FANUC program: 12 of its 12 blocks" in lines[0]
    assert "MB002 information a program written for Okuma OSP" in lines[1]
