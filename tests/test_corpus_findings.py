"""Every warning and note the checker gives on ../shared/corpus, judged by hand.

The corpus (about a hundred real programs by other authors, read from ../shared and never
copied here) is analysed as one workspace, every file knowing the others' programs, the way
``fanuc-macro check`` or an editor's workspace sees a folder. Each warning, information and
hint it gives is in ``FINDINGS`` with a verdict, true or false, and why; the test fails on a
finding the table does not hold and on an entry the checker no longer gives, so a change of
the output is judged again. Among warnings at most 5 % may be false, among notes 10 %.
Errors are judged elsewhere: the syntax and dialect errors in test_corpus.py's table, the NC
Code Checker samples' mistakes in test_ncvc_samples.py.

``python3 tests/corpus_findings.py`` prints what the checker finds now as rows to judge.
"""

from __future__ import annotations

from collections import Counter

import pytest

from corpus_findings import CORPUS, Finding, corpus_findings
from fanuc_macro.diagnostics import Severity

if not CORPUS.is_dir():
    pytest.skip(f"the shared corpus is not there ({CORPUS})", allow_module_level=True)

# Reasons that repeat.
MISSING = "the called program is in no file of the corpus: the control must have it (PS0076)"
SCALED = "FANUC reads an argument without a decimal point in its address's least increment"
NO_O = "the file's first program has no O number, and its name gives none"
NO_END = "the program has no M30, M02 or M99 before its end"
RESIDENT = "O8000-O9999, the control's resident programs: in no file of the corpus, on the control"
VENDOR = "a Renishaw cycle (program/vendor_cycles.py), kept on the control: named, not missing"
FOREIGN = "the file is that control's program, by the mark named: said once, as information"

# file -> (1-based line, code, true?, why)
FINDINGS: dict[str, list[tuple[int, str, bool, str]]] = {
    "DavidJennings1__CNC_Macros__G65  HOLE BORE MACRO.mc12": [
        (2, "MB010", True, NO_O),
        (30, "MB003", True, "'(... (G0 - G1) ...)': FANUC ends the comment at the first ')'"),
        (58, "MB003", True, "a second '(' inside the comment; its last ')' is program text"),
    ],
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O8000": [
        (1, "MB002", True, FOREIGN),
        (8, "MB408", True, VENDOR),
        (9, "MB408", True, VENDOR),
    ],
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9811": [
        (1, "MB002", True, FOREIGN),
        (221, "MB410", True, RESIDENT),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__1_grammar_errors__sampleNC(percent-not-alone).ncd": [
        (1, "MB009", True, "'%O100': the sample's mistake; the control skips the rest of the line"),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(multiple-O-codes).ncd": [
        (14, "MB407", True, NO_END),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(no-O-code).ncd": [
        (4, "MB010", True, NO_O),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(subprogram-not-found).ncd": [
        (17, "MB403", True, MISSING),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__2_syntax_errors__sampleNC(subprogram-without-M99).ncd": [
        (29, "MB407", True, NO_END),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__3_procedure_errors__sampleNC(compound-error).ncd": [
        (15, "MB603", True, "G01Z10.0 is the first feed move and no F comes before it"),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(DO-without-END).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(G66-without-G67).ncd": [
        (17, "MB406", True, "the sample's mistake: G66 P1001 and no G67 before M30"),
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(WHILE-DO-infinite-loop).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(bracket-not-closed).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(comparison-operator-is-equals-sign).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(grammar-error-inside-macro).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-grammar-error-collection).ncd": [
        (
            28,
            "MB904",
            True,
            "G00X#1 in the main program: #1 is set nowhere, vacant from cycle start",
        ),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-no-warning).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(macro-syntax-error).ncd": [
        (17, "MB404", True, SCALED),
    ],
    "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__4_macro_errors__sampleNC(procedure-error-after-expansion).ncd": [
        (17, "MB404", True, SCALED),
        (27, "MB603", True, "the G01 of the expanded macro comes before any F of the program"),
    ],
    "NCVC-CAM__Scripts__transpose_macro_set__macro_sample.ncd": [
        (2, "MB010", True, NO_O),
        (3, "MB404", True, SCALED),
        (3, "MB404", True, SCALED),
        # NCVC's macro expansion reads on past the '%'; a FANUC control stops there, and O10,
        # which no '%' closes, is never loaded: the G65 on line 3 finds no program.
        (9, "MB014", True, "O10 after the closing '%': a control does not load it"),
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__O00030.nc": [
        (13, "MB408", True, VENDOR),
        (15, "MB410", True, RESIDENT),
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__DOLLARP-TOOLR.nc": [
        (3, "MB407", True, NO_END),
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00044.nc": [
        (3, "MB407", True, NO_END),
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00094.nc": [
        (4, "MB407", True, NO_END),
    ],
    "SimsesLab__Macro-routines__Small_routines.NC": [
        (5, "MB010", True, NO_O),
    ],
    # A Haas program (5 blocks in Haas's forms): the run's verdicts past its first Haas block
    # (line 41) are not given, FANUC stopping there.
    "appliedengdesign__vscode-gcode-syntax__samplenc__sample-colors.nc": [
        (2, "MB002", True, FOREIGN),
        (90, "MB303", True, "#234 and #452 exist only with the extended common variable option"),
        (122, "MB403", True, MISSING),
    ],
    "dennisselyaev__gcode__2.nc": [
        (
            10,
            "MB701",
            True,
            "#2=1. and #3=-11. just above, never changed: IF[#2LE#3] never loops back",
        ),
        (20, "MB404", True, SCALED),
        (21, "MB404", True, SCALED),
        # O3002 (3002.nc) reads Y's #25 for X too (G0X#25Y#25) and never T's #20
        (20, "MB411", True, "X0. fills #24, which O3002 never names: lost (it moves X to #25)"),
        (20, "MB411", True, "T200 fills #20, which O3002 never names: the value is lost"),
        (21, "MB411", True, "X0. fills #24, which O3002 never names: lost (it moves X to #25)"),
        (21, "MB411", True, "T200 fills #20, which O3002 never names: the value is lost"),
    ],
    "dennisselyaev__gcode__3001.nc": [
        (61, "MB006", True, "'G1X#611f#9': a lowercase address in a FANUC 0i-MD program"),
    ],
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__fndzero-autosquare-final.nc": [
        (7, "MB010", True, NO_O),
        (12, "MB403", True, MISSING),
        (37, "MB403", True, MISSING),
    ],
    "henkikobo-cloud__nc-macro-visualizer__samples__06_long_jump_connector.nc": [
        (4, "MB701", True, "N10 #100 = 1 just before: IF [#100 EQ 1] GOTO 90 always jumps"),
        (5, "MB702", True, "N30-N50 lie between the always-taken jump and its target N90"),
        (8, "MB709", True, "N60-N80 follow GOTO 100 and no jump leads to them"),
        (11, "MB403", True, MISSING),
    ],
    "jpaullee__renishaw_macros__09000__O09023_RENISHAW_Storm.nc": [
        (2, "MB002", True, FOREIGN),
        (49, "MB408", True, VENDOR),
        (99, "MB408", True, VENDOR),
        (142, "MB410", True, RESIDENT),
        (161, "MB410", True, RESIDENT),
        (164, "MB408", True, VENDOR),
        (175, "MB408", True, VENDOR),
        (176, "MB408", True, VENDOR),
        (182, "MB410", True, RESIDENT),
        (189, "MB410", True, RESIDENT),
        (195, "MB408", True, VENDOR),
        (201, "MB408", True, VENDOR),
        (217, "MB408", True, VENDOR),
        (267, "MB408", True, VENDOR),
        (356, "MB408", True, VENDOR),
        (381, "MB408", True, VENDOR),
        (469, "MB408", True, VENDOR),
        (472, "MB408", True, VENDOR),
    ],
    "jpaullee__renishaw_macros__09000__O09724_RENISHAW_Storm.nc": [
        (2, "MB002", True, FOREIGN),
        (6, "MB410", True, RESIDENT),
    ],
    "jpaullee__renishaw_macros__09000__O09810_RENISHAW_Storm.nc": [
        (8, "MB410", True, RESIDENT),
    ],
    "jpaullee__renishaw_macros__09000__O09811_RENISHAW_Storm.nc": [
        (8, "MB410", True, RESIDENT),
        (128, "MB410", True, RESIDENT),
    ],
    "jpaullee__renishaw_macros__09000__O09814_RENISHAW_Storm.nc": [
        (8, "MB410", True, RESIDENT),
        (28, "MB410", True, RESIDENT),
        (31, "MB410", True, RESIDENT),
        (74, "MB410", True, RESIDENT),
    ],
    "khill-fbmc__fanuc-macro-b__src____tests____macros.test.ts.extracted.nc": [
        (1, "MB010", True, NO_O),
    ],
    "versabuilt__Gcode__VSC Gcode__focas__9003.nc": [
        (26, "MB404", True, SCALED),
    ],
    "versabuilt__Gcode__VSC Gcode__focas__9123.nc": [
        (54, "MB407", True, NO_END),
    ],
    "versabuilt__Gcode__VSC Gcode__haas__legacy__O09123.nc": [
        (55, "MB407", True, NO_END),
    ],
    "versabuilt__Gcode__r2c__generic__Macros Enabled__01000.nc": [
        (8, "MB010", True, NO_O),
        (29, "MB403", True, MISSING),
    ],
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9726": [
        (1, "MB002", True, FOREIGN),
    ],
    "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__O9810": [
        (1, "MB002", True, FOREIGN),
    ],
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__MS140.SPF": [
        (1, "MB002", True, FOREIGN),
    ],
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__SH150.SPF": [
        (1, "MB002", True, FOREIGN),
    ],
    "NadjImre__NC-Programi-za-FB422__CMA.DIR___PROBE_MEASURING.SPF": [
        (1, "MB002", True, FOREIGN),
    ],
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__Table_leveling.nc": [
        (1, "MB002", True, FOREIGN),
    ],
    "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__macro_Thread_milling.nc": [
        (1, "MB002", True, FOREIGN),
    ],
    "footpetaljones__PP-Probing-Macros__probe_circular_bore.nc": [
        (1, "MB002", True, FOREIGN),
    ],
    "footpetaljones__PP-Probing-Macros__probe_xy_corner.nc": [
        (1, "MB002", True, FOREIGN),
    ],
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros___psng_probe.ngc": [
        (1, "MB002", True, FOREIGN),
    ],
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros__psng_manual_change.ngc": [
        (1, "MB002", True, FOREIGN),
    ],
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen-linter.cnc": [
        (1, "MB002", True, FOREIGN),
    ],
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen.cnc": [
        (1, "MB002", True, FOREIGN),
    ],
    "ozturkf__AluFDM__G__Rohr.nc": [
        (2, "MB002", True, FOREIGN),
    ],
    "versabuilt__Gcode__VSC Gcode__haas__ngc__9002.nc": [
        (2, "MB002", True, FOREIGN),
    ],
}


@pytest.fixture(scope="module")
def found() -> list[Finding]:
    return corpus_findings()


def test_every_finding_is_judged(found: list[Finding]) -> None:
    got = Counter((f.file, f.line, f.code) for f in found)
    judged = Counter(
        (name, line, code) for name, rows in FINDINGS.items() for line, code, _t, _w in rows
    )
    new = sorted((got - judged).elements())
    gone = sorted((judged - got).elements())
    messages = {(f.file, f.line, f.code): f.message for f in found}
    assert not new, "not judged yet: " + "; ".join(f"{k}: {messages[k]}" for k in new)
    assert not gone, f"judged, no longer found: {gone}"


def test_every_verdict_has_a_reason() -> None:
    for rows in FINDINGS.values():
        for line, code, _true, why in rows:
            assert why.strip(), (line, code)


def _false_share(found: list[Finding], severities: tuple[Severity, ...]) -> tuple[int, int]:
    verdict = {
        (name, line, code): true
        for name, rows in FINDINGS.items()
        for line, code, true, _why in rows
    }
    chosen = [f for f in found if f.severity in severities]
    false = sum(1 for f in chosen if not verdict.get((f.file, f.line, f.code), True))
    return false, len(chosen)


def test_few_false_warnings(found: list[Finding]) -> None:
    false, total = _false_share(found, (Severity.WARNING,))
    print(f"corpus warnings: {total}, false: {false}")
    assert total and false <= 0.05 * total


def test_few_false_notes(found: list[Finding]) -> None:
    false, total = _false_share(found, (Severity.INFORMATION, Severity.HINT))
    print(f"corpus notes: {total}, false: {false}")
    assert total and false <= 0.10 * total
