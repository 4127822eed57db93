"""Real programs written by others (``shared/corpus``): every file is analysed without an internal
error, and the blocks rejected as syntax errors (MB001), unknown functions (MB008) or other
controls' dialects (MB002) are exactly those listed in ``REJECTED``.

Each entry of the table was read by hand: a FANUC control rejects that block too, or the block
is another control's dialect. A block that a FANUC control accepts must not be in the table, so
a parser that rejects it fails here. README.md and MANIFEST.tsv describe the corpus and are not
programs.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import pytest

from fanuc_macro.analysis import Analysis, analyse
from fanuc_macro.diagnostics import Severity
from fanuc_macro.syntax.lines import decode_bytes
from fanuc_macro.syntax.parser import parse_bytes

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"
if not CORPUS.is_dir():
    pytest.skip(f"the shared corpus is not there ({CORPUS})", allow_module_level=True)

FILES = sorted(p for p in CORPUS.iterdir() if p.is_file() and p.suffix not in (".md", ".tsv"))
REJECTION_CODES = ("MB001", "MB002", "MB008")

# Reasons that repeat, named in the entries below:
#   HAAS_M97: Haas 'M97 P': a local subroutine at an N number; FANUC calls no subroutine with M97.
#   HAAS_G103: Haas 'G103 P1' / 'G103': block look-ahead limit; FANUC has no G103 (PS0010).
#   HAAS_SETTING: Haas NGC '#20040': a Haas setting read as a variable (#20000-#29999).
#   DECIMAL_VAR: Haas NGC '#30001.116'-style variable (a number with a decimal part): PS0115.
#   UNBRACKETED: Citizen/Mitsubishi expression after an address without [ ]: format error.
#   SPINDLE_SELECT: Citizen/Mitsubishi 'S1=500' spindle selection: '=' after an NC word.
#   PATH_SELECT: Citizen/Mitsubishi '$n' path selection: '$' is no FANUC address.
#   PATH_WAIT: Citizen/Mitsubishi '!L1' path wait: '!' is no FANUC address.
#   NO_ADDRESS: a variable where the address letter belongs ('X' missing): FANUC reads an
#     assignment without '=' (format error).
#   UNBRACKETED_NUMBER: an expression after an address that starts with a number ('X10.0*#1'):
#     FANUC takes only a number, #n, -#n or [expression] after an address (format error).
#   NCVC_DO_END: NCVC's macro samples copy one O1001 whose 'G01X10.0*#1' is UNBRACKETED_NUMBER.
#
# Whole files of other controls (the block reader names the dialect for the whole file once it
# sees a mark only that control's programs carry; every block FANUC rejects is that dialect's):
#   SYNTEC_HEADER: the '%@MACRO' header of a Syntec/LNC macro file.
#   SYNTEC_IF: Syntec 'IF(...)THEN' / 'ELSE' / 'END_IF', 'WHILE(...)DO' / 'END_WHILE'.
#   SYNTEC_CALL: Syntec function statements 'WAIT();', 'ALARM(n);'.
#   SYNTEC_ASSIGN: Syntec ':=' assignment.
#   SYNTEC_GLOBAL: Syntec '@n' / '@[...]' global variable ('F@119', '@149=0').
#   SYNTEC_COMMENT: Syntec '//' comment after the ';' ('GOTO6;//(**P*O)', ';//(...)').
#   SYNTEC_PARENS: '( )' grouping in a Syntec expression; FANUC reads '(' as a comment.
#   SIEMENS_DECL: Siemens Sinumerik 'PROC name(...)', 'DEF REAL x'.
#   SIEMENS_COMMENT: Siemens ';' comment; FANUC ends the block at ';' and reads the rest.
#   SIEMENS_CONTROL: Siemens IF/ELSE/ENDIF, FOR/ENDFOR, GOTOF/GOTOB, 'LABEL:', STOPRE, DIAMON,
#     TRANS, a subprogram called by name ('ms140').
#   SIEMENS_ASSIGN: Siemens named variables, 'X=expr' words, arrays, '$P_UIFR[...]='.
#   SIEMENS_CALL: Siemens functions and '( )' expressions: MSG(), C=ACP(), SETAL(), GETT().
#   SIEMENS_R: old Sinumerik (810/820) 'R20=20', 'R101=R101+1', 'Q1=12', '@136 R101 K50 K300',
#     '@100 K-220'.
#   LINUXCNC_OWORD: LinuxCNC O-words 'o<name> sub/call/endsub', 'O1 if/else/endif/return'.
#   LINUXCNC_NAMED: LinuxCNC named parameter '#<name>'.
#   LINUXCNC_COMMENT: LinuxCNC ';' comment.
#   DDCS_COMMENT: DDCS '//', ';;' and ';' comments.
#   DDCS_IF: DDCS 'IF #1>0 GOTO1', 'WHILE #91 <= 25 DO1' (no brackets, C comparison).
#   DDCS_CMP: DDCS conditions joined by '+' / '*' ('IF [#50<0]+[#50>1] GOTO').
#   DDCS_EXPR: DDCS 'G0Z-1*[...]' (no brackets), '#1505=-5000(prompt).' dialog.


def each(code: str, lines: str) -> list[tuple[int, str]]:
    """The same code on several lines that share one reason ("3 5 8": lines 3, 5 and 8)."""
    return [(int(line), code) for line in lines.split()]


NCVC_ERRORS = "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__"
DDCS_EXAMPLES = "fchabot-dxf__DDCS-Expert-skill__ddcs-expert__references__example-macros__"
SYNTEC_DOCS = "Just-Jools__LNC-Probe-macros__Documentation__Syntec documentation__OP510 Probe Macros 07-07-2023__"  # noqa: E501

# file name -> sorted (1-based line, code) of every error-severity MB001/MB002/MB008; in a file
# written for another control, the blocks its one MB002 lists.
REJECTED: dict[str, list[tuple[int, str]]] = {
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__7 GRAVER__O00003.nc": [
        (31, "MB002"),  # '/ M97 P5': HAAS_M97
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00044.nc": [
        (3, "MB002"),  # 'IF [...] THEN M31': Haas; FANUC's THEN takes one macro statement (PS0125)
    ],
    "RomanBoreyko__r_cod2__cnc__(SHABLON 3)__RAZNOE__shabloNi__0000__O00094.nc": [
        (4, "MB002"),  # 'IF [ #1 EQ #2 ] S#20 F#30': Haas; IF without GOTO/THEN is PS0125
    ],
    # Files with 5 or more blocks in one control's forms are that control's: their rejected
    # blocks are the related places of one MB002 (listed here as MB002, one per block).
    "appliedengdesign__vscode-gcode-syntax__samplenc__sample-colors.nc": [
        (41, "MB002"),  # 'G154 P25': Haas additional work offset; FANUC writes G54.1 P25
        (82, "MB002"),  # 'WHILE[ABS[#5+7.]]LT0.1]D02': unbalanced ']', 'D02' for 'DO2' (PS0125)
        (89, "MB002"),  # 'E.#234': '.' then '#' is no number (format error)
        (102, "MB002"),  # 'IF [...] THEN' alone: Haas NGC block IF, not FANUC 0i/16i/30i
        (104, "MB002"),  # 'ELSE': Haas NGC block IF
        (106, "MB002"),  # 'ENDIF': Haas NGC block IF
        (132, "MB002"),  # 'M97 P1000': HAAS_M97
    ],
    "dennisselyaev__gcode__2.nc": [
        (15, "MB001"),  # '#1=#1-#11:': ':' typed for ';' (':' is the O address: format error)
    ],
    "henkikobo-cloud__nc-macro-visualizer__samples__04_variables.nc": [
        (4, "MB002"),  # '#<RESULT> = #500': LinuxCNC named parameter
        (5, "MB002"),  # 'IF [#<RESULT> GT 0] THEN ...': LinuxCNC named parameter
    ],
    "jpaullee__renishaw_macros__09000__O09023_RENISHAW_Storm.nc": sorted(
        [
            (152, "MB002"),  # 'IF [ #30057.21 ] GOTO22': Haas NGC bare value, DECIMAL_VAR
            (198, "MB002"),  # 'G31 Z [ ... #30003.036 ... ]': DECIMAL_VAR
            (210, "MB002"),  # 'IF [ #20040 EQ 1 ] GOTO51': HAAS_SETTING
            (241, "MB002"),  # same block again: DECIMAL_VAR
            (309, "MB002"),  # same block again: DECIMAL_VAR
            # 'G103 P1' before each probe move, 'G103' at the end: HAAS_G103
            *each(
                "MB002",
                "18 50 84 92 100 106 114 120 130 139 147 165 169 196 239 245 253 265 268 274 "
                "282 307 313 357 382 391 398 404 420 428 438 450 456 461 474",
            ),
        ]
    ),
    "jpaullee__renishaw_macros__09000__O09724_RENISHAW_Storm.nc": [
        (3, "MB002"),  # 'G103 P1': HAAS_G103
        (6, "MB002"),  # 'IF[#598 NE 1.]G65 P9725': Haas IF without GOTO/THEN (PS0125)
        (9, "MB002"),  # 'IF [ #20040 EQ 1 ] GOTO90': HAAS_SETTING
        (18, "MB002"),  # '#162 = #30001.116': DECIMAL_VAR
        (25, "MB002"),  # '#30001.037 * #30001.035': DECIMAL_VAR (twice in the block)
        (28, "MB002"),  # same two variables: DECIMAL_VAR
        (38, "MB002"),  # same two variables: DECIMAL_VAR
        (41, "MB002"),  # same two variables: DECIMAL_VAR
    ],
    "jpaullee__renishaw_macros__09000__O09726_RENISHAW_Storm.nc": [(3, "MB002")],  # HAAS_G103
    "jpaullee__renishaw_macros__09000__O09730_RENISHAW_Storm.nc": [(4, "MB002")],  # HAAS_G103
    "jpaullee__renishaw_macros__09000__O09810_RENISHAW_Storm.nc": each("MB002", "3 35"),  # G103
    "jpaullee__renishaw_macros__09000__O09811_RENISHAW_Storm.nc": each("MB002", "3 151"),  # G103
    "jpaullee__renishaw_macros__09000__O09814_RENISHAW_Storm.nc": each("MB002", "3 98"),  # G103
    # Haas NGC's copy of the FOCAS dispatcher: 'G103 P1' / 'G103 P0' around each wait: HAAS_G103
    "versabuilt__Gcode__VSC Gcode__haas__ngc__9002.nc": each(
        "MB002", "24 70 79 88 97 106 115 124 133"
    ),
    # Synthetic negative tests for a Citizen linter; line 17, a bare 'M97', is NOT listed: with
    # no P it is a plain M code that a FANUC control accepts (the default code that disables
    # the interrupt-type custom macro), not Haas's local subroutine call.
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen-linter.cnc": [
        (1, "MB002"),  # '$1': PATH_SELECT
        (22, "MB002"),  # 'G0 Z-.05 M3 S1=500': SPINDLE_SELECT
        (27, "MB002"),  # 'IF[#814GT1] (MISSING GOTO)': IF without GOTO/THEN (PS0125)
        (29, "MB002"),  # 'IF[#814GT1]': IF without GOTO/THEN (PS0125)
        (31, "MB002"),  # 'IF[#814MM1] GOTO333': 'MM' is no comparison (PS0114)
        (50, "MB002"),  # 'WHILE[#500MM1]DO1': 'MM' is no comparison (PS0114)
        (61, "MB002"),  # 'WHILE[#500LT1]': WHILE without DO (PS0125)
        (75, "MB002"),  # 'WHILE[#500LT1]DO': DO without its number (PS0125)
        (80, "MB002"),  # 'G0 X#814+.1 Z0 T2': UNBRACKETED
        (81, "MB002"),  # 'G97 S1=700 M3': SPINDLE_SELECT
        (89, "MB002"),  # 'G1 #814': NO_ADDRESS
        (90, "MB002"),  # 'G2 #814 R.123': NO_ADDRESS
        (91, "MB002"),  # 'G3 #814 R.123': NO_ADDRESS
        (92, "MB002"),  # 'G32 #814 F.123': NO_ADDRESS
        (93, "MB002"),  # 'G83 #814 F.123': NO_ADDRESS
        (94, "MB002"),  # 'G87 #814 F.123': NO_ADDRESS
        (96, "MB002"),  # 'G1 X#814-.04': UNBRACKETED
        (101, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (104, "MB002"),  # 'TO': letter O typed for zero; T has no value (format error)
        (109, "MB002"),  # 'G0 X#814+.1 Z0 T19': UNBRACKETED
        (110, "MB002"),  # 'G97 S1=700 M3': SPINDLE_SELECT
        (119, "MB002"),  # 'G0 X#814+.1 Z#501': UNBRACKETED
        (124, "MB002"),  # '#501 + 1': an expression that is no statement (no '=')
        (131, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (132, "MB002"),  # 'S2=500 M24': SPINDLE_SELECT
        (135, "MB002"),  # 'G97 S1=1500 M3': SPINDLE_SELECT
        (138, "MB002"),  # '!L1': PATH_WAIT
        (141, "MB002"),  # 'GOTO (MISSING NUMBER AFTER GOTO)': GOTO without target (PS0125)
        (142, "MB002"),  # 'G0 X#814+.1': UNBRACKETED
        (166, "MB002"),  # '$2': PATH_SELECT
        (175, "MB002"),  # '!L1': PATH_WAIT
        (180, "MB002"),  # 'M98 H1': Citizen call to a sequence number (FANUC needs P)
        (199, "MB002"),  # '$0': PATH_SELECT (Citizen variable-dump section follows)
        (200, "MB002"),  # 'A': header of the Citizen $0 dump, an address without a value
    ],
    # Citizen Swiss lathe program; line 17, a bare 'M97', is not listed (see above).
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen.cnc": [
        (1, "MB002"),  # '$1': PATH_SELECT
        (22, "MB002"),  # 'G0 Z-.05 M3 S1=500': SPINDLE_SELECT
        (26, "MB002"),  # 'G0 X#814+.1 Z0 T2': UNBRACKETED
        (27, "MB002"),  # 'G97 S1=700 M3': SPINDLE_SELECT
        (34, "MB002"),  # 'G1 X#814-.04': UNBRACKETED
        (37, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (43, "MB002"),  # 'G0 X#814+.1 Z#501 T1': UNBRACKETED
        (46, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (47, "MB002"),  # 'S2=500 M24': SPINDLE_SELECT
        (50, "MB002"),  # 'G97 S1=1500 M3': SPINDLE_SELECT
        (53, "MB002"),  # '!L1': PATH_WAIT
        (56, "MB002"),  # 'G0 X#814+.1': UNBRACKETED
        (78, "MB002"),  # '$2': PATH_SELECT
        (87, "MB002"),  # '!L1': PATH_WAIT
        (92, "MB002"),  # 'M98 H1': Citizen call to a sequence number (FANUC needs P)
        (111, "MB002"),  # '$0': PATH_SELECT (Citizen variable-dump section follows)
        (112, "MB002"),  # 'A': header of the Citizen $0 dump, an address without a value
    ],
    # NCVC's "NC Code Checker 1.4" error samples (each written to hold one mistake; see
    # tests/test_ncvc_samples.py for every diagnostic they must give).
    NCVC_ERRORS + "1_grammar_errors__sampleNC(O-number-typed-as-digit-zero).ncd": [
        (2, "MB001"),  # '00001(ISHII)': digit 0 typed for the letter O, a number without address
    ],
    NCVC_ERRORS + "1_grammar_errors__sampleNC(decimal-comma).ncd": [
        (15, "MB001"),  # 'G01Z-5,0F100': ',' is no decimal point (format error)
    ],
    NCVC_ERRORS + "1_grammar_errors__sampleNC(full-width-address).ncd": [
        (3, "MB001"),  # 'Ｇ91Ｇ28Z0': full-width 'Ｇ' is no ASCII address
    ],
    NCVC_ERRORS + "1_grammar_errors__sampleNC(full-width-comment-parens).ncd": [
        (2, "MB001"),  # 'O0301（ishii）': full-width '（' opens no comment
    ],
    NCVC_ERRORS + "1_grammar_errors__sampleNC(multiple-decimal-points).ncd": [
        (17, "MB001"),  # 'G01X10.0.0': a second decimal point (format error)
        (18, "MB001"),  # 'G01Y-30..0': a second decimal point (format error)
    ],
    # Line 18, 'G01Z- 10.0F50', is NOT listed: FANUC ignores spaces outside comments.
    NCVC_ERRORS + "1_grammar_errors__sampleNC(number-without-address).ncd": [
        (20, "MB001"),  # 'G01X-50.0 30.0': '30.0' has no address
        (21, "MB001"),  # '01X50.Y-50.': '01' has no address (G01 meant)
    ],
    NCVC_ERRORS + "2_syntax_errors__sampleNC(error-inside-subprogram).ncd": [
        (26, "MB001"),  # 'G01XY0': address X without a value
        (28, "MB001"),  # 'G01Y-10.０': full-width digit '０'
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(DO-without-END).ncd": [
        (29, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(G66-without-G67).ncd": [
        (32, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(IF-malformed).ncd": [
        (17, "MB002"),  # 'IF[#100EQ0]G00X100.0': Haas; IF without GOTO/THEN is PS0125
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(WHILE-DO-infinite-loop).ncd": [
        (29, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(WHILE-malformed).ncd": [
        (18, "MB001"),  # 'WHILE[#5GT0]': WHILE without DO (PS0125)
        (20, "MB001"),  # 'X10*#1': UNBRACKETED_NUMBER
        (21, "MB001"),  # 'END': END without its number (PS0125)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(bracket-not-closed).ncd": [
        (29, "MB001"),  # 'WHILE[[#1LE10]DO1': '[' not closed (PS0114)
        (30, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(comparison-operator-is-equals-sign).ncd": [
        (28, "MB001"),  # 'WHILE[[#1=10]AND[#2<>5.0]]DO1': '=' and '<>' are no comparisons
        (29, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(function-arg-not-in-brackets).ncd": [
        (17, "MB001"),  # 'G00XCOS[45]Y10*SIN45': a function after an address without [ ]
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(macro-grammar-error-collection).ncd": [
        (17, "MB001"),  # '5.0': a number without address
        (18, "MB001"),  # '.10': a number without address
        (19, "MB001"),  # 'SIN[10]': a function without address or assignment
        (20, "MB002"),  # 'X#10+1': UNBRACKETED
        (22, "MB001"),  # '#10': a variable alone, no '=' (format error)
        (30, "MB001"),  # 'G00X-10.0-10.0Y100.0': UNBRACKETED_NUMBER
        (33, "MB001"),  # 'G00X- 100.0 -100.0': UNBRACKETED_NUMBER (the spaces do not matter)
        (34, "MB001"),  # 'G00X-100.0 -100.0': UNBRACKETED_NUMBER
        (35, "MB001"),  # 'G00X-100.0 100.0': '100.0' has no address
        (36, "MB001"),  # 'G00X-100.0 COS[#10]Y100.0SIN[180]': COS[...] has no address
        (37, "MB001"),  # 'G00X[-100.0-100.0]COS[180]#10': COS[...] has no address
        (38, "MB001"),  # 'G00X-100.0+10.0': UNBRACKETED_NUMBER
        (40, "MB001"),  # 'G00X[COS[180]]]': ']' closes no '['
    ],
    # NCVC calls these two correct ("no warning"), but NCVC's own macro language takes an
    # expression after an address without brackets; FANUC does not.
    NCVC_ERRORS + "4_macro_errors__sampleNC(macro-no-warning).ncd": [
        (27, "MB001"),  # 'G01X50*COS[#8]Y-50.*SIN[#8]': UNBRACKETED_NUMBER
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(macro-no-warning-2).ncd": [
        (9, "MB001"),  # 'G01X10.*#1Y-10.*#1*-1*FUP[...]F400': UNBRACKETED_NUMBER
        (10, "MB001"),  # 'X30.0*COS[90*#1]': UNBRACKETED_NUMBER
    ],
    NCVC_ERRORS + "4_macro_errors__sampleNC(macro-syntax-error).ncd": [
        (28, "MB001"),  # 'WHIL[#1LE10]DO1': WHIL is no keyword (WHILE misspelt)
        (29, "MB001"),  # 'G01X10.0*#1': UNBRACKETED_NUMBER (NCVC_DO_END)
    ],
    "NCVC-CAM__Scripts__transpose_macro_set__macro_sample.ncd": [
        (14, "MB002"),  # 'IF[ROUND[#13] EQ 1] THEN M8': Haas; FANUC's THEN takes a macro statement
        (23, "MB002"),  # 'IF[ROUND[#13] EQ 1]THEN M9': same
    ],
    SYNTEC_DOCS + "O8000": sorted(
        [
            (1, "MB002"),  # '%@MACRO': SYNTEC_HEADER
        ]
    ),
    SYNTEC_DOCS + "O9726": sorted(
        [
            (1, "MB002"),  # '%@MACRO': SYNTEC_HEADER
            *each("MB002", "2 66 112 177"),  # 'WAIT();' / 'ALARM(n);': SYNTEC_CALL
            # 'IF(...)THEN' / 'ELSE' / 'END_IF' / 'WHILE(...)DO': SYNTEC_IF
            *each(
                "MB002",
                "3 5 8 10 11 13 16 18 21 23 32 34 38 40 44 46 54 56 68 73 75 81 83 88 "
                "93 95 101 103 108 116 121 123 129 131 136 138 139 144 146 152 154 159 "
                "161 162",
            ),
            # 'F@119' / 'S@[@111]' / '@149=0': SYNTEC_GLOBAL
            *each("MB002", "6 30 65 109 111 114 175"),
            # '#24:=...' / '@[@111+5]:=...': SYNTEC_ASSIGN
            *each(
                "MB002",
                "15 19 25 26 27 29 31 35 37 41 43 47 50 51 52 53 57 58 59 61 62 63 64 "
                "69 70 71 77 78 79 80 85 86 87 89 90 91 97 98 99 100 105 106 107 113 "
                "117 118 119 120 125 126 127 128 132 133 134 135 140 141 142 143 148 "
                "149 150 151 155 156 157 158 164 165 166 167 170 171 172 173",
            ),
            # ';//(**P.OPEN)' / 'GOTO6;//(...)': SYNTEC_COMMENT
            *each(
                "MB002", "24 49 55 60 67 74 76 82 84 94 96 102 104 110 115 122 124 130 145 147 153"
            ),
            *each("MB002", "72 92"),  # '#29=SQRT((#4*#4)+...)': SYNTEC_PARENS
        ]
    ),
    SYNTEC_DOCS + "O9810": sorted(
        [
            (1, "MB002"),  # '%@MACRO': SYNTEC_HEADER
            *each("MB002", "2 13 21 49 52"),  # 'WAIT();' / 'ALARM(n);': SYNTEC_CALL
            # 'IF(...)THEN' / 'ELSE' / 'END_IF' / 'WHILE(...)DO': SYNTEC_IF
            *each("MB002", "3 5 7 9 10 12 22 24 25 27 29 31 32 34 36 38 39 41 46 48"),
            *each("MB002", "15 17 18 45"),  # '#24:=...' / '@[@111+5]:=...': SYNTEC_ASSIGN
        ]
    ),
    SYNTEC_DOCS + "O9811": sorted(
        [
            (1, "MB002"),  # '%@MACRO': SYNTEC_HEADER
            # 'WAIT();' / 'ALARM(n);': SYNTEC_CALL
            *each("MB002", "2 13 22 30 40 77 184 185 202 203 228 229 232 233 236 237 244 245 249"),
            # 'IF(...)THEN' / 'ELSE' / 'END_IF' / 'WHILE(...)DO': SYNTEC_IF
            *each(
                "MB002",
                "3 5 7 9 10 12 15 17 18 20 24 26 27 29 33 36 41 42 44 45 47 48 49 51 52 "
                "54 55 57 59 60 62 64 66 68 70 74 76 82 84 93 95 96 98 101 103 108 110 "
                "114 116 125 127 130 132 137 139 143 145 154 156 159 161 162 164 165 "
                "167 169 171 172 174 177 179 180 182 187 189 190 192 195 197 198 200 "
                "205 207 208 210 211 213 218 220 224 226 240 242",
            ),
            # '#24:=...' / '@[@111+5]:=...': SYNTEC_ASSIGN
            *each(
                "MB002",
                "32 34 35 37 38 56 71 78 79 80 81 85 87 88 89 90 99 104 105 111 112 113 "
                "117 119 120 121 122 128 133 134 140 141 142 146 148 149 150 151 153 "
                "175 193 214 239",
            ),
            *each("MB002", "39 107 136 216"),  # 'F@119' / 'S@[@111]' / '@149=0': SYNTEC_GLOBAL
            # ';//(**P.OPEN)' / 'GOTO6;//(...)': SYNTEC_COMMENT
            *each("MB002", "63 67 92 100 124 129"),
        ]
    ),
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__MS140.SPF": sorted(
        [
            *each("MB002", "1 7 8 9 10 11 12 13"),  # 'PROC ...' / 'DEF REAL ...': SIEMENS_DECL
            # ';...' comment lines and 'M81 ; ...': SIEMENS_COMMENT
            *each(
                "MB002",
                "2 3 4 5 15 18 20 22 25 27 29 31 33 36 39 41 43 45 48 50 53 55 57 59 62 "
                "64 66 68 70 72 75 77 79 81 85 90 94 108",
            ),
            # 'name=...', 'G0 X=expr', 'OSP1[Z]=...', '$P_UIFR[...]=': SIEMENS_ASSIGN
            *each("MB002", "16 19 21 23 28 37 49 65 69 76 83 87 91 92 93 98 101 103 111"),
            # IF/ELSE/ENDIF, FOR/ENDFOR, GOTOF/GOTOB, 'LABEL:', STOPRE: SIEMENS_CONTROL
            *each(
                "MB002",
                "24 30 35 38 40 42 46 47 51 52 54 56 60 61 63 67 78 80 82 84 86 88 95 "
                "96 97 99 100 102 104 105 110 112 116",
            ),
            # 'MSG(...)', 'C=ACP(...)', 'SETAL(n)', '( )' in expressions: SIEMENS_CALL
            *each("MB002", "26 34 44 58 71 73 74 106 107 118"),
        ]
    ),
    "NadjImre__NC-Programi-za-FB422__CMA.DIR__SH150.SPF": sorted(
        [
            # 'PROC ...' / 'DEF REAL ...': SIEMENS_DECL
            *each("MB002", "1 3 4 5 6 7 8 9 10 11 12 13 14 15 16"),
            # ';...' comment lines and 'M81 ; ...': SIEMENS_COMMENT
            *each(
                "MB002",
                "2 17 18 21 23 34 36 39 41 43 45 47 49 51 56 58 60 62 65 67 69 74 76 78 "
                "80 86 89 93 95 99 101 103 105 108 111 113 115 120 122 124 126 128 131 "
                "133 135 137 157 164 165 167",
            ),
            # 'MSG(...)', 'C=ACP(...)', 'SETAL(n)', '( )' in expressions: SIEMENS_CALL
            *each("MB002", "19 32 48 57 71 90 91 92 97 117 136 146 149 156 160 162"),
            # 'name=...', 'G0 X=expr', 'OSP1[Z]=...', '$P_UIFR[...]=': SIEMENS_ASSIGN
            *each(
                "MB002",
                "20 22 24 26 28 29 31 35 42 44 46 53 54 59 61 64 68 72 75 82 84 87 88 "
                "100 102 106 109 112 114 121 123 127 129 142 144 155 159 166 168",
            ),
            # IF/ELSE/ENDIF, FOR/ENDFOR, GOTOF/GOTOB, 'LABEL:', STOPRE: SIEMENS_CONTROL
            *each(
                "MB002",
                "25 27 30 33 37 38 40 55 63 66 70 73 77 79 81 83 85 94 96 98 104 107 "
                "110 116 118 119 125 130 132 134 138 139 141 143 145 147 150 154 161 "
                "169",
            ),
        ]
    ),
    "NadjImre__NC-Programi-za-FB422__CMA.DIR___PROBE_MEASURING.SPF": sorted(
        [
            *each("MB002", "1 3"),  # 'PROC ...' / 'DEF REAL ...': SIEMENS_DECL
            # 'name=...', 'G0 X=expr', 'OSP1[Z]=...', '$P_UIFR[...]=': SIEMENS_ASSIGN
            *each("MB002", "5 9 11 12 13 14 15 16 17 18 19 20 21 22 23 47 57 81 91"),
            # IF/ELSE/ENDIF, FOR/ENDFOR, GOTOF/GOTOB, 'LABEL:', STOPRE: SIEMENS_CONTROL
            *each(
                "MB002",
                "7 29 30 31 32 33 37 38 39 40 45 46 49 50 55 56 58 59 64 65 66 67 71 72 "
                "73 74 79 80 83 84 89 90 92 93 98 99 100 102 106",
            ),
            # 'MSG(...)', 'C=ACP(...)', 'SETAL(n)', '( )' in expressions: SIEMENS_CALL
            *each("MB002", "10 24 25 26 27 48 82 108"),
            # ';...' comment lines and 'M81 ; ...': SIEMENS_COMMENT
            *each("MB002", "35 36 42 43 44 52 53 54 61 62 63 69 70 76 77 78 86 87 88 95 96 97"),
        ]
    ),
    DDCS_EXAMPLES + "Table_leveling.nc": sorted(
        [
            # '#20=1 //...', ';;...' and ';...' comments: DDCS_COMMENT
            *each(
                "MB002",
                "1 2 3 4 5 6 7 8 9 10 11 12 13 15 19 25 29 31 37 44 49 50 51 53 55 56 "
                "63 65 66 69 70 72 73 83 84 85 93 104 106 107 108 109 111 121 122 123 "
                "124 132 143 144 146 147 148 149 150 151 152 153 154",
            ),
            *each("MB002", "33 39 74 112"),  # 'IF #1>0 GOTO1', 'WHILE #91 <= 25 DO1': DDCS_IF
        ]
    ),
    DDCS_EXAMPLES + "macro_Thread_milling.nc": sorted(
        [
            # '#20=1 //...', ';;...' and ';...' comments: DDCS_COMMENT
            *each(
                "MB002",
                "1 2 4 5 6 7 8 9 10 11 12 13 14 16 17 18 19 20 21 23 24 25 26 27 28 29 "
                "30 31 32 33 34 35 36 37 39 41 49 56 61 63 66 67 69 70 72 74 75 76 78 "
                "79 80 81 84 88 89 95 116 124 126 127 128 129 132 134 135 136 138 139 "
                "140 141 142 145 150 152 153 155 158 163 165 167 168 170 171 172 174 "
                "175 179 182 186 187 188 190 191 193 196 197 198 199 200 201 202 205 "
                "206 207 208 211 215 216 217 219 220 221 224 225 226 227 230 233 237 "
                "238 240 248 250 251 252 256 257 258 259 261 262 263 264 265 272 274",
            ),
            *each("MB002", "42 104 162 212"),  # 'IF [#50<0]+[#50>1] GOTO': DDCS_CMP
            # 'IF #1>0 GOTO1', 'WHILE #91 <= 25 DO1': DDCS_IF
            *each("MB002", "51 57 62 77 90 96 100 111 161 173 183 192 204 223 234 245 275"),
            *each("MB002", "108 244"),  # 'G0Z-1*[...]', '#1505=-5000(prompt).': DDCS_EXPR
        ]
    ),
    "footpetaljones__PP-Probing-Macros__probe_circular_bore.nc": sorted(
        [
            # 'o<name> sub/call/endsub', 'O1 if/else/endif/return': LINUXCNC_OWORD
            *each("MB002", "1 154"),
            # '#<name>' in words and assignments: LINUXCNC_NAMED
            *each(
                "MB002",
                "22 23 28 33 34 37 42 47 52 53 58 63 64 67 72 78 80 81 82 89 90 95 100 "
                "101 104 109 115 119 120 125 130 131 134 139 145 147 148 149",
            ),
        ]
    ),
    "footpetaljones__PP-Probing-Macros__probe_xy_corner.nc": sorted(
        [
            # 'o<name> sub/call/endsub', 'O1 if/else/endif/return': LINUXCNC_OWORD
            *each("MB002", "1 34 36 38 49 51 53 60 62 64 86 88 90 101 103 105 112 114 116 121"),
            # '#<name>' in words and assignments: LINUXCNC_NAMED
            *each(
                "MB002", "17 27 28 33 43 44 47 50 52 59 70 71 72 74 79 80 85 95 96 99 102 104 111"
            ),
        ]
    ),
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros___psng_probe.ngc": sorted(
        [
            # '; ...' comment lines and 'M72 ; ...': LINUXCNC_COMMENT
            *each(
                "MB002",
                "1 2 6 9 13 15 18 23 35 38 41 44 49 51 54 57 61 66 68 71 74 78 81 84 87 "
                "92 94 97 100 104 109 112 114 117 120 124",
            ),
            # 'o<name> sub/call/endsub', 'O1 if/else/endif/return': LINUXCNC_OWORD
            *each(
                "MB002",
                "4 14 17 20 22 24 25 27 28 29 31 32 33 45 46 47 50 53 56 59 62 63 64 67 "
                "70 73 76 88 89 90 93 96 99 102 105 106 107 113 116 119 122 127",
            ),
            # '#<name>' in words and assignments: LINUXCNC_NAMED
            *each("MB002", "10 11 16 19 39 52 55 58 69 72 75 82 95 98 101 110 115 118 121"),
        ]
    ),
    "linuxcnc-probe-screen__probe-screen-ng__psng__macros__psng_manual_change.ngc": sorted(
        [
            # '; ...' comment lines and 'M72 ; ...': LINUXCNC_COMMENT
            *each("MB002", "1 5 6 9 14 18 19 20 23 27 30 35 38 42 47 52 55 58 62 72 73 75 77"),
            # 'o<name> sub/call/endsub', 'O1 if/else/endif/return': LINUXCNC_OWORD
            *each("MB002", "3 7 8 21 24 25 41 43 44 45 53 54 56 57 59 60 74 78"),
            # '#<name>' in words and assignments: LINUXCNC_NAMED
            *each("MB002", "15 16 31 32 33 48 49 50 63 65 66 67 69"),
        ]
    ),
    "ozturkf__AluFDM__G__Rohr.nc": sorted(
        [
            # 'R20=20', 'R101=R101+1', 'Q1=12', '@136 R101 K50 K300', '@100 K-220': SIEMENS_R
            *each("MB002", "2 3 4 5 6 7 8 9 18 21 22 23 24 25"),
        ]
    ),
}


@cache
def analysis_of(path: Path) -> Analysis:
    data = path.read_bytes()
    return analyse(decode_bytes(data).text, path.name, doc=parse_bytes(data, path.name))


def test_corpus_has_programs() -> None:
    assert len(FILES) >= 30


def test_table_names_existing_files() -> None:
    names = {p.name for p in FILES}
    assert set(REJECTED) <= names, sorted(set(REJECTED) - names)
    for rows in REJECTED.values():
        assert rows == sorted(rows)


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_analysed_without_internal_error(path: Path) -> None:
    analysis = analysis_of(path)
    internal = [d for d in analysis.diagnostics if d.code == "MB000"]
    assert internal == []
    assert len(analysis.doc.blocks) > 0


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_rejected_blocks_are_the_listed_ones(path: Path) -> None:
    analysis = analysis_of(path)
    # A file written for another control: one MB002 on its first line (information: a
    # statement about the file) lists the blocks FANUC rejects as related places, and nothing
    # else is said of them.
    rejections = [
        d
        for d in analysis.diagnostics
        if d.code in REJECTION_CODES
        and (d.severity is Severity.ERROR or "not reported one by one" in d.message)
    ]
    whole_file = [d for d in rejections if "not reported one by one" in d.message]
    # Information for a control named by its marks; an error for a dialect not recognised.
    assert all(
        (d.severity is Severity.ERROR) == d.message.startswith("not a FANUC program")
        for d in whole_file
    )
    found = sorted(
        [(d.line + 1, d.code) for d in rejections if d not in whole_file]
        + [(r.line + 1, "MB002") for d in whole_file for r in d.related]
    )
    if whole_file:
        assert len(whole_file) == 1
        assert len(rejections) == 1, "the blocks of a foreign file are not reported one by one"
    expected = REJECTED.get(path.name, [])
    if found != expected:
        lines = analysis.doc.blocks
        extra = [(ln, c, lines[ln - 1].text) for ln, c in found if (ln, c) not in expected]
        missing = [(ln, c, lines[ln - 1].text) for ln, c in expected if (ln, c) not in found]
        pytest.fail(f"not in the table: {extra}; in the table, not found: {missing}")
