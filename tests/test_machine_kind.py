"""Which machine a program is for, read from its codes (controller 0i-F): each mark, the
margin between the two machines, a file of both machines' programs, the corpus judged by hand,
and what the command line says and does with it."""

from __future__ import annotations

from pathlib import Path

import pytest

from cli_runner import run
from fanuc_macro.analysis import analyse
from fanuc_macro.config import Config
from fanuc_macro.program.index import build_index
from fanuc_macro.program.machine_kind import LATHE, MILL, guess_machine, machine_config
from fanuc_macro.program_files import find_programs
from fanuc_macro.syntax.parser import parse_bytes, parse_text

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"


def guess(text: str) -> tuple[str | None, str]:
    found = guess_machine(parse_text(text, "t.nc"))
    return found.kind, found.reason


# One mark each: the block that shows it, the machine, a word of the reason.
MARKS = [
    ("T1 M06", MILL, "M06"),
    ("G43 H1 Z50.", MILL, "G43/G44 H"),
    ("G91 G28 Z0.", MILL, "G91"),
    ("G00 X10. Y20.", MILL, "Y axis"),
    ("G81 X0 Z-5. R2. F100.", MILL, "drilling cycle"),
    ("G73 X0 Z-20. R2. Q3. F100.", MILL, "drilling cycle"),
    ("G90 G00 X0", MILL, "G90 without"),
    ("G90", MILL, "G90 without"),
    ("G41 D2 X10.", MILL, "G41/G42 D"),
    ("G96 S180 M03", LATHE, "G96"),
    ("G50 S2500", LATHE, "G50"),
    ("G01 U-2. W-1. F0.2", LATHE, "U or W"),
    ("G77 X46. Z-30. F0.25", LATHE, "G77, G78 or G79"),
    ("G71 P10 Q20 F0.25", LATHE, "multiple repetitive"),
    ("G73 P10 Q20 F0.25", LATHE, "multiple repetitive"),
    ("G70 P10 Q20", LATHE, "multiple repetitive"),
    ("G71 U2. R0.5", LATHE, "U or W"),
    ("G76 P020060 Q100 R0.05", LATHE, "G76's first block"),
    ("G32 Z-30. F1.5", LATHE, "G32"),
    ("G92 X19.2 Z-30. F1.5", LATHE, "G92 with F"),
    ("T0101", LATHE, "four-digit T"),
]


@pytest.mark.parametrize("block,machine,why", MARKS, ids=[m[0] for m in MARKS])
def test_each_mark_tells_its_machine(block: str, machine: str, why: str) -> None:
    kind, reason = guess(f"O1000\nG00 X100. Z100.\n{block}\nM30\n")
    assert kind == machine
    assert why in reason and "on line 3" in reason


@pytest.mark.parametrize(
    "block",
    [
        "G65 P9810 X10. Y20. Z5. F3000.",  # a call's letters are its arguments
        "M98 P1000 L2",
        "G10 L2 P1 X0 Y0 Z-300.",  # data, not a move
        "G04 U1.5",  # a lathe's dwell in seconds: no axis
        "G90 X40. Z-10. F0.2",  # a lathe's turning cycle or a mill's absolute move
        "T1",  # a tool number alone
        "G00 X100. Z100.",
        "G71",  # metric input on ISO-dialect controls; the lathe's cycle has P and Q
        "G70 G40",
    ],
)
def test_blocks_of_both_machines_are_no_mark(block: str) -> None:
    assert guess(f"O1000\n{block}\nM30\n") == (
        None,
        "no code of the program is a lathe's or a mill's alone",
    )


def test_one_mark_of_the_other_machine_among_several_is_an_option_of_the_machine() -> None:
    lathe_with_y = "O1000\nG50 S2000\nT0101\nG96 S150 M03\nG00 Y0\nG01 U-2. F0.2\nM30\n"
    kind, reason = guess(lathe_with_y)
    assert kind == LATHE
    assert "a mill's mark, a Y axis word on line 5, is taken for an option" in reason
    mill_turn = "O1000\nT0101\nG96 S150\nT1 M06\nG43 H1 Z5.\nM30\n"
    kind, reason = guess(mill_turn)
    assert kind is None
    assert reason.startswith("it has marks of both: a four-digit T (tool and offset number) on")
    assert "and M06 (tool change) on line 4 (a mill's)" in reason


LATHE_CYCLE_INSIDE = "G90 X40. Z-10. F0.2\nX30.\n"  # starts at X10.: inside its passes


def test_a_file_of_a_lathe_program_and_a_mill_program_runs_each_as_its_machine() -> None:
    text = (
        "O1000\nT0101\nG00 X10. Z2.\n" + LATHE_CYCLE_INSIDE + "M30\n%\n"
        "O2000\nT1 M06\nG54 G00 X10. Y0.\nG43 H1 Z2.\n" + LATHE_CYCLE_INSIDE + "M30\n"
    )
    doc = parse_text(text, "t.nc")
    config = machine_config(Config(), doc, build_index(doc))
    assert [(line, lathe) for _, line, lathe in config.program_machines] == [
        (0, True),
        (7, False),
    ]
    found = [(d.code, d.line) for d in analyse(text, "t.nc").diagnostics]
    assert ("MB813", 2) in found  # the lathe's cycle starts inside its pass
    assert not [line for code, line in found if code == "MB813" and line > 5]  # G90: absolute


def test_an_explicit_controller_wins_over_the_codes() -> None:
    text = "O1000\nT1 M06\nG00 X10. Z2.\n" + LATHE_CYCLE_INSIDE + "M30\n"
    assert "MB813" not in {d.code for d in analyse(text, "t.nc").diagnostics}
    lathe = analyse(text, "t.nc", Config(controller="0i-TF"))
    assert "MB813" in {d.code for d in lathe.diagnostics}


def test_with_neither_machine_shown_only_what_both_readings_find_is_reported() -> None:
    text = "O1000\nG00 X10. Z2.\n" + LATHE_CYCLE_INSIDE + "#1=1/0\nM30\n"
    codes = {d.code for d in analyse(text, "t.nc").diagnostics}
    assert "MB813" not in codes  # a lathe's verdict only: a mill reads G90 otherwise
    assert "MB502" in codes  # the division by zero, on either machine
    lathe = {d.code for d in analyse(text, "t.nc", Config(controller="0i-TF")).diagnostics}
    assert {"MB813", "MB502"} <= lathe


# The corpus, judged by hand: the machine its codes show (None: neither, or both). A file
# whose codes show no machine is a macro of arithmetic, a probing or tool-setting macro
# without a Y move, or another control's file; none is read as the wrong machine.
CORPUS_MACHINES: dict[str, str | None] = {
    "DavidJennings1__CNC_Macros__G65  HOLE BORE MACRO.mc12": "mill",
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O8000": "mill",
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9726": None,
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9810": "mill",
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9811": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(O-number-typed-as-digit-zero).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(decimal-comma).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(full-width-address).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(full-width-comment-parens).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(multiple-decimal-points).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(number-without-address).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(percent-not-alone).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(M98-without-P).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(error-inside-subprogram).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(multiple-O-codes).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(no-O-code).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(subprogram-not-found).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(subprogram-without-M99).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__3_procedure_errors__sampleNC(compound-error).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__G66_multi_modal__sanpleNC(G66-multiple-modal-call-error).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(DO-without-END).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(G66-without-G67).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(GOTO-infinite-loop).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(GOTO-target-N-missing).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(IF-malformed).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(WHILE-DO-infinite-loop).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(WHILE-malformed).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(bracket-not-closed).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(comparison-operator-is-equals-sign).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(function-arg-not-in-brackets).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(grammar-error-inside-macro).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-grammar-error-collection).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-no-warning).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-no-warning-2).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-syntax-error).ncd": "mill",
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(procedure-error-after-expansion).ncd": "mill",
    "NCVC-CAM__Scripts__transpose_macro_set__macro_sample.ncd": "mill",
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__MS140.SPF": None,
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__SH150.SPF": "mill",
    "NadjImre__NC-Programi-za-FB422__CMA.DIR___PROBE_MEASURING.SPF": None,
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__7 GRAVER__O00003.nc": "mill",
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__O00030.nc": "mill",
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__DOLLARP-TOOLR.nc": None,
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00044.nc": None,
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00094.nc": None,
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00214.nc": "mill",
    "RomanBoreyko__r_cod2__cnc__SHABLON__O00026.nc": "mill",
    "RomanBoreyko__r_cod2__cnc__SHABLON__O00999.nc": "mill",
    "SimsesLab__Macro-routines__Small_routines.NC": "mill",
    "appliedengdesign__vscode-gcode-syntax__samplenc__sample-colors.nc": "mill",
    "dennisselyaev__gcode__1.nc": "mill",
    "dennisselyaev__gcode__2.nc": "mill",
    "dennisselyaev__gcode__3.nc": "mill",
    "dennisselyaev__gcode__3001.nc": "mill",
    "dennisselyaev__gcode__3002.nc": "mill",
    "dennisselyaev__gcode__3003.nc": "mill",
    "enier290188__cnc__src__lathe__240916__o20012.nc": "lathe",
    "enier290188__cnc__src__lathe__240916__o20013.nc": "lathe",
    "enier290188__cnc__src__lathe__240924__valve.nc": "lathe",
    "enier290188__cnc__src__lathe__241001__round_head_plug.nc": "lathe",
    "enier290188__cnc__src__lathe__241006__weld_pin.nc": "lathe",
    "enier290188__cnc__src__lathe___nims___nims_1002_right_part.nc": "lathe",
    "enier290188__cnc__src__lathe__lathe_hp__lathe_hp_1__lathe_hp_1.nc": "lathe",
    "enier290188__cnc__src__lathe__lathe_hp__lathe_hp_2__lathe_hp_2.nc": "lathe",
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__Table_leveling.nc": "mill",
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__fndzero-autosquare-final.nc": "mill",
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__macro_Thread_milling.nc": "mill",
    "footpetaljones__PP-Probing-Macros__probe_circular_bore.nc": "mill",
    "footpetaljones__PP-Probing-Macros__probe_xy_corner.nc": "mill",
    "henkikobo-cloud__nc-macro-visualizer__samples__04_variables.nc": None,
    "henkikobo-cloud__nc-macro-visualizer__samples__06_long_jump_connector.nc": None,
    "johnhinfinity__Steady-rest-macro-Program__Steady rest maker.nc": "lathe",
    "jpaullee__renishaw_macros__09000__O09023_RENISHAW_Storm.nc": "mill",
    "jpaullee__renishaw_macros__09000__O09220 WARMUP PROGRAM.nc": None,
    "jpaullee__renishaw_macros__09000__O09724_RENISHAW_Storm.nc": "mill",
    "jpaullee__renishaw_macros__09000__O09726_RENISHAW_Storm.nc": "mill",
    "jpaullee__renishaw_macros__09000__O09730_RENISHAW_Storm.nc": None,
    "jpaullee__renishaw_macros__09000__O09731_RENISHAW_Storm.nc": None,
    "jpaullee__renishaw_macros__09000__O09810_RENISHAW_Storm.nc": "mill",
    "jpaullee__renishaw_macros__09000__O09811_RENISHAW_Storm.nc": "mill",
    "jpaullee__renishaw_macros__09000__O09814_RENISHAW_Storm.nc": "mill",
    "khill-fbmc__fanuc-macro-b__src____tests____macros.test.ts.extracted.nc": None,
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros___psng_probe.ngc": "mill",
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros__psng_manual_change.ngc": "mill",
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen-linter.cnc": "lathe",
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen.cnc": "lathe",
    "ozturkf__AluFDM__G__Rohr.nc": "mill",
    "versabuilt__Gcode__VSC Gcode__focas__9000.nc": None,
    "versabuilt__Gcode__VSC Gcode__focas__9001.nc": None,
    "versabuilt__Gcode__VSC Gcode__focas__9002.nc": None,
    "versabuilt__Gcode__VSC Gcode__focas__9003.nc": None,
    "versabuilt__Gcode__VSC Gcode__focas__9004.nc": None,
    "versabuilt__Gcode__VSC Gcode__focas__9123.nc": None,
    "versabuilt__Gcode__VSC Gcode__haas__legacy__O09123.nc": None,
    "versabuilt__Gcode__VSC Gcode__haas__ngc__9002.nc": None,
    "versabuilt__Gcode__r2c__generic__Macros Enabled__01000.nc": None,
    "z64__cncbook__stdbc.nc": "mill",
}


@pytest.mark.skipif(not CORPUS.is_dir(), reason="the shared corpus is not there")
def test_the_corpus_programs_are_each_read_as_their_machine() -> None:
    files = sorted(find_programs([str(CORPUS)]).programs)
    assert sorted(f.name for f in files) == sorted(CORPUS_MACHINES), "judge the new files"
    wrong = {}
    for f in files:
        kind = guess_machine(parse_bytes(f.read_bytes(), f.name)).kind
        if kind != CORPUS_MACHINES[f.name]:
            wrong[f.name] = kind
    assert not wrong


def _program(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="ascii")
    return path


def test_the_command_line_says_which_machine_and_the_setting_wins(tmp_path: Path) -> None:
    mill = _program(
        tmp_path, "mill.nc", "O1000\nT1 M06\nG00 X10. Z2.\n" + LATHE_CYCLE_INSIDE + "M30\n"
    )
    checked = run(tmp_path, "check", "--verbose", "mill.nc")
    assert checked.returncode == 0, checked.stdout
    assert (
        "mill.nc: Machine: a mill (0i-F read as 0i-MF), from its codes: M06 (tool change) on "
        "line 2." in checked.stderr
    )
    as_lathe = run(tmp_path, "check", "--controller", "0i-TF", "mill.nc")
    assert "MB813" in as_lathe.stdout
    hovered = run(tmp_path, "hover", str(mill), "1", "2")
    assert "Machine: a mill (0i-F read as 0i-MF)" in hovered.stdout
    hovered = run(tmp_path, "hover", "--controller", "0i-TF", str(mill), "1", "2")
    assert "Machine: a lathe, as the controller setting 0i-TF says." in hovered.stdout


def test_a_mills_incremental_moves_add_up_in_the_trace(tmp_path: Path) -> None:
    _program(
        tmp_path,
        "face.nc",
        "O2000\nT1 M06\nG90 G54 G00 X0. Y0.\n#1=0\nWHILE [#1 LT 3] DO1\n"
        "G91 G01 Y10. F500.\nG90\n#1=#1+1\nEND1\nM30\n",
    )
    traced = run(tmp_path, "trace", "face.nc")
    moves = [line for line in traced.stdout.splitlines() if " G01 " in line and "->" in line]
    ends = [line.split("-> ")[1].rstrip("]") for line in moves]
    assert ends == ["X0. Y10.", "X0. Y20.", "X0. Y30."]
    as_lathe = run(tmp_path, "trace", "--controller", "0i-TF", "face.nc")
    assert "X0. Y30." not in as_lathe.stdout  # a lathe has no G91: Y10. each time


def test_both_readings_of_an_unknown_machine_are_kept_between_edits() -> None:
    """A document whose machine is not known is run as a lathe and as a mill; an edit that
    changes no block's run (a comment) runs neither again, and the diagnostics stay."""
    from fanuc_macro.workspace import Workspace

    text = "O1000\nG00 X10. Z2.\n" + LATHE_CYCLE_INSIDE + "#1=1/0\nM30\n"
    workspace = Workspace(Config())
    workspace.add_bytes("t.nc", text.encode())
    first = workspace.analyse("t.nc")
    assert first.mill_facts is not None and first.facts is not None
    workspace.add_bytes("t.nc", text.replace("M30", "M30 (END)").encode())
    again = workspace.analyse("t.nc")
    assert again.facts is first.facts and again.mill_facts is first.mill_facts
    assert [(d.code, d.line) for d in again.diagnostics] == [
        (d.code, d.line) for d in first.diagnostics
    ]


# A subprogram whose own blocks show no machine (arithmetic and moves in X and Z alone).
ARC_MACRO = "O9001 (ARC MOVES)\n#3=#1*2.\nG01 X#3 Z#2 F100.\nM99\n"


def test_a_subprogram_of_no_machine_of_its_own_runs_as_its_callers(tmp_path: Path) -> None:
    (tmp_path / "o9001.nc").write_text(ARC_MACRO)
    (tmp_path / "o2001.nc").write_text(
        "O2001\nT1 M06\nG90 G54 G00 X0 Y0\nG43 H1 Z50.\nG65 P9001 A5. B-2.\nM30\n"
    )
    said = run(tmp_path, "check", "--verbose", "o9001.nc", "o2001.nc")
    assert (
        "o9001.nc: Machine: a mill (0i-F read as 0i-MF), as the programs that call it show "
        "(O2001); its own codes show neither machine."
    ) in said.stderr
    # A lathe's program calls it too: the callers disagree, the machine stays not known.
    (tmp_path / "o3001.nc").write_text("O3001\nT0101\nG96 S180 M03\nG65 P9001 A5. B-2.\nM30\n")
    both = run(tmp_path, "check", "--verbose", "o9001.nc", "o2001.nc", "o3001.nc")
    assert "o9001.nc: Machine: not known" in both.stderr
    alone = run(tmp_path, "check", "--verbose", "o9001.nc")
    assert "o9001.nc: Machine: not known" in alone.stderr


def test_a_plain_block_of_no_marking_code_is_marked_as_the_whole_look_marks_it(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A block of NC words whose codes mark nothing is read by its words alone: the same marks
    as the look at its codes, letters and T words, on the corpus and random blocks."""
    import random

    from fanuc_macro.program import machine_kind
    from fanuc_macro.syntax.parser import BlockParser
    from test_parser import program_lines

    rng = random.Random(3)
    words = ["G0", "G01", "G4", "G91", "G96", "G50", "M6", "M3", "M98", "X1.", "Y2.", "U.5"]
    words += ["W-1.", "Z3.", "T0101", "T0001", "T12", "T1234", "F.2", "S500", "P1", "Q2", "H1"]
    lines = [*program_lines(), *(" ".join(rng.sample(words, 4)) for _ in range(4000))]
    parser = BlockParser()
    parsed = [parser.parse_line(line) for line in lines]
    quick = [machine_kind._line_marks(p) for p in parsed]

    class Everything:
        def isdisjoint(self, _codes: object) -> bool:
            return False

    monkeypatch.setattr(machine_kind, "_MARKING_CODES", Everything())
    assert quick == [machine_kind._line_marks(p) for p in parsed]
    assert sum(1 for q in quick if q) > 1000
