"""NCVC's "NC Code Checker 1.4" error samples (``shared/corpus/NCVC-CAM__...``): each file was
written to hold one mistake, which its name says. The checker must report that mistake at its
line, and no other error or warning except the ones listed here, each a real FANUC mistake that
the sample's author left in by accident (NCVC's own language takes an expression after an
address without brackets, so its samples copy a 'G01X10.0*#1' that FANUC rejects).

The lines come from reading each file by hand; NCVC ships its own checker's output beside each
sample (``*_cvted.ncd``), which names the same lines where it flags the mistake.
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

PREFIX = "NCVC-CAM__Scripts__NC.Code.Checker1.4__errors__"

# The 'G01X10.0*#1' of the O1001 that the macro samples copy: an expression after an address
# without brackets, which FANUC rejects (MB001). Not the sample's mistake, but a real one.
UNBRACKETED_COPY = "MB001"

# sample (the mistake its name says) -> every (1-based line, code) it must give at error or
# warning severity, and the mistake's own diagnostic whatever its severity. The first entry is
# the mistake; the ones after it say why they are there.
EXPECTED: dict[str, list[tuple[int, str]]] = {
    "1_grammar_errors__sampleNC(O-number-typed-as-digit-zero).ncd": [(2, "MB001")],
    "1_grammar_errors__sampleNC(decimal-comma).ncd": [(15, "MB001")],
    "1_grammar_errors__sampleNC(full-width-address).ncd": [(3, "MB001")],
    "1_grammar_errors__sampleNC(full-width-comment-parens).ncd": [(2, "MB001")],
    # The sample has the mistake twice, 'X10.0.0' and 'Y-30..0'.
    "1_grammar_errors__sampleNC(multiple-decimal-points).ncd": [(17, "MB001"), (18, "MB001")],
    # Twice too: 'G01X-50.0 30.0' and '01X50.Y-50.'. Line 18, 'Z- 10.0', is no mistake:
    # FANUC ignores spaces (NCVC flags it).
    "1_grammar_errors__sampleNC(number-without-address).ncd": [(20, "MB001"), (21, "MB001")],
    "1_grammar_errors__sampleNC(percent-not-alone).ncd": [(1, "MB009")],
    "2_syntax_errors__sampleNC(M98-without-P).ncd": [(18, "MB405")],
    # Two mistakes in the subprogram: 'G01XY0' and the full-width digit of 'G01Y-10.０'.
    "2_syntax_errors__sampleNC(error-inside-subprogram).ncd": [(26, "MB001"), (28, "MB001")],
    "2_syntax_errors__sampleNC(multiple-O-codes).ncd": [(14, "MB407")],
    "2_syntax_errors__sampleNC(no-O-code).ncd": [(4, "MB010")],
    "2_syntax_errors__sampleNC(subprogram-not-found).ncd": [(17, "MB403")],
    # Reported on the last block of O2001, after which the M99 is missing.
    "2_syntax_errors__sampleNC(subprogram-without-M99).ncd": [(29, "MB407")],
    # 'G01Z10.0' with no F yet. NCVC's other findings in this file (H10 for T01, M06 with the
    # spindle on, M05 before the retract, coolant stopped by M30) are shop practice, not
    # something a FANUC control rejects or a macro mistake: not reported.
    "3_procedure_errors__sampleNC(compound-error).ncd": [(15, "MB603")],
    # FANUC's own example of multiple modal calls (the manual page ships with the sample):
    # correct, so nothing to report.
    "4_macro_errors__G66_multi_modal__sanpleNC(G66-multiple-modal-call-error).ncd": [],
    "4_macro_errors__sampleNC(DO-without-END).ncd": [
        (28, "MB201"),
        (31, "MB202"),  # the same mistake seen from its end: END2 closes no DO2
        (29, UNBRACKETED_COPY),
    ],
    "4_macro_errors__sampleNC(G66-without-G67).ncd": [
        (17, "MB406"),
        # O1001 is the DO-without-END sample's: its three mistakes come along.
        (31, "MB201"),
        (32, UNBRACKETED_COPY),
        (34, "MB202"),
    ],
    # Reported on the loop's first block, N1 (the GOTO1 that closes it is line 24).
    "4_macro_errors__sampleNC(GOTO-infinite-loop).ncd": [(17, "MB703")],
    "4_macro_errors__sampleNC(GOTO-target-N-missing).ncd": [(17, "MB101")],
    "4_macro_errors__sampleNC(IF-malformed).ncd": [(17, "MB002")],
    "4_macro_errors__sampleNC(WHILE-DO-infinite-loop).ncd": [(28, "MB703"), (29, UNBRACKETED_COPY)],
    "4_macro_errors__sampleNC(WHILE-malformed).ncd": [
        (18, "MB001"),  # WHILE without DO
        (20, "MB001"),  # 'X10*#1': the unbracketed expression again
        (21, "MB001"),  # 'END' without its number: the other end of the malformed loop
    ],
    "4_macro_errors__sampleNC(bracket-not-closed).ncd": [
        (29, "MB001"),
        (30, UNBRACKETED_COPY),
        (32, "MB202"),  # END2 would close no DO2 even with the bracket closed (DO1 ... END2)
    ],
    "4_macro_errors__sampleNC(comparison-operator-is-equals-sign).ncd": [
        (28, "MB001"),
        (29, UNBRACKETED_COPY),
    ],
    "4_macro_errors__sampleNC(function-arg-not-in-brackets).ncd": [(17, "MB001")],
    # A kanji comment (the word 全角, "full-width") in Shift-JIS, read as written
    # (test_kanji_comment_is_read_as_written): nothing to report.
    "4_macro_errors__sampleNC(grammar-error-inside-macro).ncd": [],
    "4_macro_errors__sampleNC(macro-grammar-error-collection).ncd": [
        (17, "MB001"),  # '5.0'
        (18, "MB001"),  # '.10'
        (19, "MB001"),  # 'SIN[10]'
        (20, "MB002"),  # 'X#10+1': unbracketed, the Mitsubishi/Citizen form
        (22, "MB001"),  # '#10'
        (30, "MB001"),  # 'G00X-10.0-10.0Y100.0'
        (33, "MB001"),  # 'G00X- 100.0 -100.0' (lines 31 and 32 differ only by spaces: fine)
        (34, "MB001"),  # 'G00X-100.0 -100.0'
        (35, "MB001"),  # 'G00X-100.0 100.0'
        (36, "MB001"),  # 'G00X-100.0 COS[#10]Y100.0SIN[180]'
        (37, "MB001"),  # 'G00X[-100.0-100.0]COS[180]#10'
        (38, "MB001"),  # 'G00X-100.0+10.0'
        (40, "MB001"),  # 'G00X[COS[180]]]'
        # 'G00X#1' in the main program, where #1 is never set: a real mistake. O0001 reads #1
        # before setting it, so it may be a macro called with A: the hint says both.
        (28, "MB904"),
    ],
    # NCVC calls these two correct, but their unbracketed expressions after an address
    # ('X50*COS[#8]', 'X10.*#1') are NCVC's language, not FANUC's.
    "4_macro_errors__sampleNC(macro-no-warning).ncd": [(27, "MB001")],
    "4_macro_errors__sampleNC(macro-no-warning-2).ncd": [(9, "MB001"), (10, "MB001")],
    "4_macro_errors__sampleNC(macro-syntax-error).ncd": [(28, "MB001"), (29, UNBRACKETED_COPY)],
    # O1001 runs 'G#1X#2Y#3' (G1 from A1) with no F set in O0001 before the call.
    "4_macro_errors__sampleNC(procedure-error-after-expansion).ncd": [(27, "MB603")],
}

# Notes (information, hint) these samples may give besides, and why each is true there.
TOLERATED_NOTES = {
    "MB404": "G65 arguments without a decimal point (A1, D100): their value depends on the machine",
    "MB701": "WHILE[#1LE10] with #1=1 from A1, in a loop whose END is missing: always true",
}


@cache
def analysis_of(name: str) -> Analysis:
    path = CORPUS / (PREFIX + name)
    data = path.read_bytes()
    return analyse(decode_bytes(data).text, path.name, doc=parse_bytes(data, path.name))


def test_every_sample_is_in_the_table() -> None:
    samples = {p.name[len(PREFIX) :] for p in CORPUS.glob(PREFIX + "*")}
    assert samples == set(EXPECTED)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_sample_gives_its_mistake_and_nothing_else(name: str) -> None:
    analysis = analysis_of(name)
    expected = EXPECTED[name]
    loud = {(d.line + 1, d.code) for d in analysis.diagnostics if d.severity is Severity.ERROR}
    loud |= {(d.line + 1, d.code) for d in analysis.diagnostics if d.severity is Severity.WARNING}
    mistake = {(d.line + 1, d.code) for d in analysis.diagnostics} & set(expected)
    assert loud | mistake == set(expected), sorted(loud | mistake)
    notes = {
        d.code
        for d in analysis.diagnostics
        if d.severity in (Severity.INFORMATION, Severity.HINT)
        and (d.line + 1, d.code) not in expected
    }
    assert notes <= set(TOLERATED_NOTES), sorted(notes - set(TOLERATED_NOTES))


def test_the_no_warning_samples_hold_only_the_unbracketed_expressions() -> None:
    for name in ("macro-no-warning).ncd", "macro-no-warning-2).ncd"):
        analysis = analysis_of("4_macro_errors__sampleNC(" + name)
        loud = [d for d in analysis.diagnostics if d.severity in (Severity.ERROR, Severity.WARNING)]
        assert loud and all("must be in brackets" in d.message for d in loud)


def test_kanji_comment_is_read_as_written() -> None:
    """The samples are in Shift-JIS, the encoding of a Japanese shop: read without a note."""
    analysis = analysis_of("4_macro_errors__sampleNC(grammar-error-inside-macro).ncd")
    assert analysis.doc.encoding == "shift_jis"
    assert "全角" in analysis.doc.blocks[25].text
    assert "MB007" not in {d.code for d in analysis.diagnostics}
