"""Calls through codes the control's parameters set up (``--custom-call``), programs kept on
the control (``--on-control``) and the vendors' known cycles, through the command line as a
user runs it (a subprocess)."""

from __future__ import annotations

from pathlib import Path

from cli_runner import run

# M165 calls O9022 on the machine it was written for (parameter 6080-6089): D is the bore's
# diameter, an argument, not the D of tool radius compensation.
PROBE = """O1000 (PROBE THROUGH AN M CODE)
M165 P9814 D1.415 S1.
M30
O9022 (M165: THE CALL RECEIVES D AS #7)
#3=1/[#7-1.415]
M99
"""

G_CODE_CALL = """O1000 (A G CODE CALLS O9010)
G100 A2. B3.
M30
O9010 (G100)
#3=1/[#1+#2-5.]
M99
"""

T_CODE_CALL = """O1000 (EVERY T WORD CALLS O9000)
T5
M30
O9000 (T: THE T VALUE IN #149)
#3=1/[#149-5.]
M99
"""

CYCLES = """O1000 (BORE CHECK)
G65 P9814 D50. Z-10. S1.
M98 P2000
M30
"""


def _write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_an_m_code_set_up_as_a_call_runs_its_macro_with_the_words_as_arguments(
    tmp_path: Path,
) -> None:
    _write(tmp_path, "probe.nc", PROBE)
    plain = run(tmp_path, "check", "probe.nc")
    assert "probe.nc:2:1: MB409 hint M165 with P and argument words" in plain.stdout
    # Set up or not, the block's words are the macro's arguments: D1.415 is a diameter.
    assert "MB601" not in plain.stdout
    assert "MB502" not in plain.stdout  # O9022 runs alone: #7 is not known

    called = run(tmp_path, "check", "--custom-call", "M165=9022", "probe.nc")
    assert "MB409" not in called.stdout
    assert "MB601" not in called.stdout  # D is an argument of the call
    # O9022 ran from the call with D1.415 in #7.
    assert "probe.nc:5:4: MB502 error division of 1. by zero" in called.stdout
    assert "with #7=1.415" in called.stdout


def test_a_g_code_and_a_t_code_set_up_as_calls(tmp_path: Path) -> None:
    _write(tmp_path, "g.nc", G_CODE_CALL)
    _write(tmp_path, "t.nc", T_CODE_CALL)
    assert "MB502" not in run(tmp_path, "check", "g.nc").stdout
    done = run(tmp_path, "check", "--custom-call", "G100=9010", "g.nc")
    assert "g.nc:5:4: MB502" in done.stdout
    assert "MB502" not in run(tmp_path, "check", "t.nc").stdout
    done = run(tmp_path, "check", "--custom-call", "T=9000", "t.nc")
    assert "t.nc:5:4: MB502" in done.stdout and "#149=5" in done.stdout


def test_a_custom_call_outside_the_manuals_ranges_is_named_and_left_out(
    tmp_path: Path,
) -> None:
    _write(tmp_path, "probe.nc", PROBE)
    done = run(tmp_path, "check", "--custom-call", "M165=9010", "probe.nc")
    assert (
        "fanuc-macro: machine.customCalls: 'M165' calls O9010: an M code can call only "
        "O9020-O9029 (parameters 6080-6089) or O9001-O9009 (parameters 6071-6079)"
    ) in done.stderr
    assert "Traceback" not in done.stderr
    assert "MB409" in done.stdout  # the code is not set up


def test_calls_of_programs_on_the_control_are_not_reported_missing(tmp_path: Path) -> None:
    _write(tmp_path, "cycles.nc", CYCLES)
    plain = run(tmp_path, "check", "cycles.nc")
    assert "cycles.nc:3:5: MB403 warning M98 calls O2000" in plain.stdout
    # A known cycle is named, as a hint, not reported missing.
    assert (
        "cycles.nc:2:5: MB408 hint G65 calls O9814, Renishaw Inspection Plus: bore or boss "
        "measurement"
    ) in plain.stdout
    assert "MB403 warning G65 calls O9814" not in plain.stdout
    on_control = run(tmp_path, "check", "--on-control", "O2000-O2999,O9814", "cycles.nc")
    assert "MB403" not in on_control.stdout and "MB408" not in on_control.stdout
    again = run(tmp_path, "check", "--on-control", "2000", "--on-control", "O9814", "cycles.nc")
    assert "MB403" not in again.stdout
    wrong = run(tmp_path, "check", "--on-control", "O20x", "cycles.nc")
    assert wrong.returncode == 2
    assert "'O20x' is not a program number or a range like O9000-O9999" in wrong.stderr


def test_hover_names_a_known_cycle_and_its_arguments(tmp_path: Path) -> None:
    _write(tmp_path, "cycles.nc", CYCLES)
    program = run(tmp_path, "hover", "cycles.nc", "2", "6").stdout
    assert "**O9814** — Renishaw Inspection Plus: bore or boss measurement" in program
    assert "**D** the nominal diameter" in program
    assert "H-2000-6031" in program
    argument = run(tmp_path, "hover", "cycles.nc", "2", "12").stdout
    assert "G65 argument **D** → **#7** in O9814: the nominal diameter" in argument


def test_hover_and_definition_of_a_custom_code(tmp_path: Path) -> None:
    _write(tmp_path, "probe.nc", PROBE)
    hover = run(tmp_path, "hover", "--custom-call", "M165=9022", "probe.nc", "2", "2").stdout
    assert "**M165** — calls O9022 as a macro, like G65" in hover
    assert "**O9022** — M165: THE CALL RECEIVES D AS #7" in hover
    argument = run(tmp_path, "hover", "--custom-call", "M165=9022", "probe.nc", "2", "13")
    assert "M165 argument **D** → **#7** in O9022" in argument.stdout
    found = run(tmp_path, "definition", "--custom-call", "M165=9022", "probe.nc", "2", "2")
    assert found.stdout.strip().endswith("probe.nc:4:1")
    assert run(tmp_path, "definition", "probe.nc", "2", "2").stdout.strip() == ""
    header = run(tmp_path, "hover", "--custom-call", "M165=9022", "probe.nc", "4", "2").stdout
    assert "Called by every M165 block (setting machine.customCalls)." in header


def test_another_m_code_of_the_block_is_an_argument_of_the_call(tmp_path: Path) -> None:
    text = "O1000\nM08 M165 D2.\nM30\nO9022\n#3=1/[#13-8.]\nM99\n"
    _write(tmp_path, "m.nc", text)
    done = run(tmp_path, "check", "--custom-call", "M165=9022", "m.nc")
    assert "m.nc:5:4: MB502" in done.stdout and "with #13=8." in done.stdout


def test_a_computed_call_of_a_program_on_the_control_is_not_reported(tmp_path: Path) -> None:
    _write(tmp_path, "comp.nc", "O1000\n#1=9814\nG65 P#1 D50.\n#2=2000\nM98 P#2\nM30\n")
    plain = run(tmp_path, "check", "comp.nc").stdout
    assert "comp.nc:5:1: MB706 warning M98 calls O2000" in plain
    assert "O9814" not in plain  # a known cycle: on the control
    assert "MB706" not in run(tmp_path, "check", "--on-control", "2000", "comp.nc").stdout


def test_each_address_calls_only_its_range(tmp_path: Path) -> None:
    _write(tmp_path, "g.nc", G_CODE_CALL)
    done = run(tmp_path, "check", "--custom-call", "G100=9020", "--custom-call", "B=9028", "g.nc")
    assert done.stderr.count("machine.customCalls") == 1
    assert (
        "machine.customCalls: 'G100' calls O9020: a G code can call only O9010-O9019 "
        "(parameters 6050-6059)"
    ) in done.stderr
    done = run(tmp_path, "check", "--custom-call", "G65=9010", "--custom-call", "T5=9000", "g.nc")
    assert "'G65' already calls or returns" in done.stderr
    assert "'T5': a G or M code takes its number (G100, M165); T, S and B stand alone" in (
        done.stderr
    )


def test_a_custom_call_runs_its_program_from_another_file(tmp_path: Path) -> None:
    """The called program's file is handed to the analysis of the caller though no index holds
    the call: the value the macro sets reaches the caller's next block."""
    _write(tmp_path, "main.nc", "O1000\nT1 M06\nM165 P9814 D1.415 S1.\n#101=#100\nM30\n")
    _write(tmp_path, "O9022.nc", "O9022\n#100=#7*2\nM99\n")
    hovered = run(
        tmp_path, "hover", "--custom-call", "M165=9022", "--with", "O9022.nc", "main.nc", "4", "7"
    )
    assert "**#100** here: **2.83**" in hovered.stdout
    plain = run(tmp_path, "hover", "--with", "O9022.nc", "main.nc", "4", "7")
    assert "**#100** here: **depends on #100**" in plain.stdout
