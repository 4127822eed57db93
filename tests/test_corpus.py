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
from fanuc_macro.blocks import decode_bytes
from fanuc_macro.diagnostics import Severity
from fanuc_macro.parser import parse_bytes

CORPUS = Path(__file__).resolve().parents[2] / "shared" / "corpus"
if not CORPUS.is_dir():
    pytest.skip(f"the shared corpus is not there ({CORPUS})", allow_module_level=True)

FILES = sorted(p for p in CORPUS.iterdir() if p.is_file() and p.suffix not in (".md", ".tsv"))
REJECTION_CODES = ("MB001", "MB002", "MB008")

# Reasons that repeat, named in the entries below:
#   HAAS_M97: Haas 'M97 P': a local subroutine at an N number; FANUC calls no subroutine with M97.
#   DECIMAL_VAR: Haas NGC '#30001.116'-style variable (a number with a decimal part): PS0115.
#   UNBRACKETED: Citizen/Mitsubishi expression after an address without [ ]: format error.
#   SPINDLE_SELECT: Citizen/Mitsubishi 'S1=500' spindle selection: '=' after an NC word.
#   PATH_SELECT: Citizen/Mitsubishi '$n' path selection: '$' is no FANUC address.
#   PATH_WAIT: Citizen/Mitsubishi '!L1' path wait: '!' is no FANUC address.
#   NO_ADDRESS: a variable where the address letter belongs ('X' missing): FANUC reads an
#     assignment without '=' (format error).

# file name -> sorted (1-based line, code) of every error-severity MB001/MB002/MB008.
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
    "appliedengdesign__vscode-gcode-syntax__samplenc__sample-colors.nc": [
        (82, "MB001"),  # 'WHILE[ABS[#5+7.]]LT0.1]D02': unbalanced ']', 'D02' for 'DO2' (PS0125)
        (89, "MB001"),  # 'E.#234': '.' then '#' is no number (format error)
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
    "jpaullee__renishaw_macros__09000__O09023_RENISHAW_Storm.nc": [
        (152, "MB002"),  # 'IF [ #30057.21 ] GOTO22': Haas NGC bare value as a condition (PS0114)
        (152, "MB002"),  # ... and DECIMAL_VAR
        (198, "MB002"),  # 'G31 Z [ ... #30003.036 ... ]': DECIMAL_VAR
        (241, "MB002"),  # same block again: DECIMAL_VAR
        (309, "MB002"),  # same block again: DECIMAL_VAR
    ],
    "jpaullee__renishaw_macros__09000__O09724_RENISHAW_Storm.nc": [
        (6, "MB002"),  # 'IF[#598 NE 1.]G65 P9725': Haas IF without GOTO/THEN (PS0125)
        (18, "MB002"),  # '#162 = #30001.116': DECIMAL_VAR
        (25, "MB002"),  # '#30001.037 * #30001.035': DECIMAL_VAR, twice in the block
        (25, "MB002"),
        (28, "MB002"),  # same two variables: DECIMAL_VAR
        (28, "MB002"),
        (38, "MB002"),  # same two variables: DECIMAL_VAR
        (38, "MB002"),
        (41, "MB002"),  # same two variables: DECIMAL_VAR
        (41, "MB002"),
    ],
    # Synthetic negative tests for a Citizen linter; line 17, a bare 'M97', is NOT listed: with
    # no P it is a plain M code that a FANUC control accepts (the default code that disables
    # the interrupt-type custom macro), not Haas's local subroutine call.
    "madsenmj__vscode-gcode-syntax-citizen__samplenc__sample-citizen-linter.cnc": [
        (1, "MB002"),  # '$1': PATH_SELECT
        (22, "MB002"),  # 'G0 Z-.05 M3 S1=500': SPINDLE_SELECT
        (27, "MB001"),  # 'IF[#814GT1] (MISSING GOTO)': IF without GOTO/THEN (PS0125)
        (29, "MB001"),  # 'IF[#814GT1]': IF without GOTO/THEN (PS0125)
        (31, "MB001"),  # 'IF[#814MM1] GOTO333': 'MM' is no comparison (PS0114)
        (50, "MB001"),  # 'WHILE[#500MM1]DO1': 'MM' is no comparison (PS0114)
        (61, "MB001"),  # 'WHILE[#500LT1]': WHILE without DO (PS0125)
        (75, "MB001"),  # 'WHILE[#500LT1]DO': DO without its number (PS0125)
        (80, "MB002"),  # 'G0 X#814+.1 Z0 T2': UNBRACKETED
        (81, "MB002"),  # 'G97 S1=700 M3': SPINDLE_SELECT
        (89, "MB001"),  # 'G1 #814': NO_ADDRESS
        (90, "MB001"),  # 'G2 #814 R.123': NO_ADDRESS
        (91, "MB001"),  # 'G3 #814 R.123': NO_ADDRESS
        (92, "MB001"),  # 'G32 #814 F.123': NO_ADDRESS
        (93, "MB001"),  # 'G83 #814 F.123': NO_ADDRESS
        (94, "MB001"),  # 'G87 #814 F.123': NO_ADDRESS
        (96, "MB002"),  # 'G1 X#814-.04': UNBRACKETED
        (101, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (104, "MB001"),  # 'TO': letter O typed for zero; T has no value (format error)
        (109, "MB002"),  # 'G0 X#814+.1 Z0 T19': UNBRACKETED
        (110, "MB002"),  # 'G97 S1=700 M3': SPINDLE_SELECT
        (119, "MB002"),  # 'G0 X#814+.1 Z#501': UNBRACKETED
        (124, "MB001"),  # '#501 + 1': an expression that is no statement (no '=')
        (131, "MB002"),  # 'G97 S1=500 M3': SPINDLE_SELECT
        (132, "MB002"),  # 'S2=500 M24': SPINDLE_SELECT
        (135, "MB002"),  # 'G97 S1=1500 M3': SPINDLE_SELECT
        (138, "MB002"),  # '!L1': PATH_WAIT
        (141, "MB001"),  # 'GOTO (MISSING NUMBER AFTER GOTO)': GOTO without target (PS0125)
        (142, "MB002"),  # 'G0 X#814+.1': UNBRACKETED
        (166, "MB002"),  # '$2': PATH_SELECT
        (175, "MB002"),  # '!L1': PATH_WAIT
        (180, "MB002"),  # 'M98 H1': Citizen call to a sequence number (FANUC needs P)
        (199, "MB002"),  # '$0': PATH_SELECT (Citizen variable-dump section follows)
        (200, "MB001"),  # 'A': header of the Citizen $0 dump, an address without a value
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
        (112, "MB001"),  # 'A': header of the Citizen $0 dump, an address without a value
    ],
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
    found = sorted(
        (d.line + 1, d.code)
        for d in analysis.diagnostics
        if d.code in REJECTION_CODES and d.severity is Severity.ERROR
    )
    expected = REJECTED.get(path.name, [])
    if found != expected:
        lines = analysis.doc.blocks
        extra = [(ln, c, lines[ln - 1].text) for ln, c in found if (ln, c) not in expected]
        missing = [(ln, c, lines[ln - 1].text) for ln, c in expected if (ln, c) not in found]
        pytest.fail(f"not in the table: {extra}; in the table, not found: {missing}")
