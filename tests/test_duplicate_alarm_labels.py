"""MB102 and copies of an N that run the same blocks to the same end: wherever the control
lands, the program does the same, so there is nothing to report."""

from __future__ import annotations

import pytest

from fanuc_macro.analysis import analyse

PROGRAM = """O1000
#1=1
GOTO10
N906#3000=6(TOOL NOT SET)
N10G0X10.
IF[#1EQ1]GOTO20
{second}
N20G0X20.
IF[#2EQ0]GOTO906
M30
"""


def mb102(second: str) -> list[int]:
    text = PROGRAM.format(second=second)
    return [d.line for d in analyse(text, "labels.nc").diagnostics if d.code == "MB102"]


@pytest.mark.parametrize(
    "second",
    [
        "N906#3000=6(TOOL NOT SET)",  # the same alarm block
        "N906 #3000=6(TOOL NOT SET)  ",  # blanks around it do not matter
    ],
)
def test_copies_that_raise_the_same_alarm_are_not_reported(second: str) -> None:
    assert mb102(second) == []


@pytest.mark.parametrize(
    "second",
    [
        "N906#3000=7(PROBE FAIL)",  # another alarm
        "N906#3000=6(TOOL NOT SET!)",  # another message
        "N906G0X0.",  # no end: the run goes on elsewhere
    ],
)
def test_copies_that_differ_are_reported(second: str) -> None:
    assert mb102(second) == [8]


def test_copies_that_run_the_same_blocks_to_m30_are_not_reported() -> None:
    text = (
        "O1000\n#1=1\nGOTO10\nN99G0X100.\nM30\nN10G0X10.\nIF[#1EQ1]GOTO20\n"
        "N99G0X100.\nM30\nN20G0X20.\nIF[#2EQ0]GOTO99\nM30\n"
    )
    assert [d for d in analyse(text, "m30.nc").diagnostics if d.code == "MB102"] == []
