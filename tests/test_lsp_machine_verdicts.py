"""The call and machine-state verdicts in the editor: a real server process over stdio
(pytest-lsp) publishes them for a program as it is typed, and withdraws them when it is right."""

from __future__ import annotations

from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import client, codes, diagnostics, open_text, start

__all__ = ["client"]  # the fixture, imported for the tests here

HOLES = """O1000 (SIX HOLES)
G90 G17 G21 G54
T3 M06
G43 H3 Z50.
M98 P9010 R50. H6.
G00 Z2.
G01 Z-1. F100.
M30
O9010 (BOLT CIRCLE)
#1=0
WHILE[#1LT#11]DO1
G81 X[#18*COS[#1*360/#11]] Y[#18*SIN[#1*360/#11]] Z-10. R2. F150.
#1=#1+1
END1
G80
M99
"""


async def test_an_m98_with_arguments_and_a_feed_without_the_spindle(client: LanguageClient) -> None:
    await start(client, None)
    uri = "untitled:holes.nc"
    open_text(client, uri, HOLES)
    found = await diagnostics(client, uri, lambda d: {"MB412", "MB611"} <= codes(d))
    m98 = next(d for d in found if d.code == "MB412")
    assert m98.range.start.line == 4 and "M98 passes none" in m98.message
    spindle = next(d for d in found if d.code == "MB611")
    assert spindle.range.start.line == 6 and "M06 on line 3 stopped it" in spindle.message
    assert spindle.severity == types.DiagnosticSeverity.Warning
    fixed = HOLES.replace("M98 P9010", "G65 P9010").replace("G43 H3 Z50.", "G43 H3 Z50.\nS1200 M03")
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=fixed)],
        )
    )
    await diagnostics(client, uri, lambda d: not {"MB412", "MB611", "MB411"} & codes(d))


CONTOUR = """O5000 (BOSS)
G90 G17 G21 G40 G54
T1 M06
G43 H1 Z50.
S1000 M03
G00 X-40. Y0.
Z2.
G01 Z-2. F150.
G41 D1
G03 X-20. Y20. R20.
G02 X20. Y20. I10. J-20.
G01 Y-10.
G40 G00 X-40.
G00 Z50.
M30
"""


async def test_arc_and_compensation_verdicts_follow_the_edits(client: LanguageClient) -> None:
    """A compensation started on an arc and an arc whose centre puts the end off the circle;
    then a line typed above them and the centre put right: the arc's verdict goes, the other
    moves down with its line and names the G41's new line."""
    await start(client, None)
    uri = "untitled:boss.nc"
    open_text(client, uri, CONTOUR)
    found = await diagnostics(client, uri, lambda d: {"MB631", "MB622"} <= codes(d))
    start_up = next(d for d in found if d.code == "MB631")
    assert start_up.range.start.line == 9 and "G41 from line 9" in start_up.message
    arc = next(d for d in found if d.code == "MB622")
    assert arc.range.start.line == 10 and "PS0020" in arc.message
    assert arc.severity == types.DiagnosticSeverity.Error
    fixed = CONTOUR.replace("O5000 (BOSS)\n", "O5000 (BOSS)\n(OP10)\n").replace(
        "I10. J-20.", "I20. J-20."
    )
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=uri, version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=fixed)],
        )
    )
    found = await diagnostics(client, uri, lambda d: "MB622" not in codes(d))
    [start_up] = [d for d in found if d.code == "MB631"]
    assert start_up.range.start.line == 10 and "G41 from line 10" in start_up.message
