"""The settings machine.customCalls and machine.programsOnControl from the editor, and the
hover of a vendor's known cycle, end to end: a real server process over stdio (pytest-lsp)."""

from __future__ import annotations

from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import client, codes, diagnostics, hover, open_text, start

__all__ = ["client"]  # the fixture, imported for the tests here

PROBE = """O1000 (PROBE THROUGH AN M CODE)
M165 P9814 D1.415 S1.
M98 P2000
M30
O9022 (M165: THE CALL RECEIVES D AS #7)
#3=1/[#7-1.415]
M99
"""


async def test_custom_calls_and_programs_on_control_from_the_settings(
    client: LanguageClient,
) -> None:
    await start(client, None)
    uri = "untitled:probe.nc"
    open_text(client, uri, PROBE)
    found = await diagnostics(client, uri, lambda d: "MB409" in codes(d))
    # Before the setting: M165 with a P of a program looks like a call (MB409), so its D is
    # an argument, not a tool offset number (no MB601).
    assert {"MB409", "MB403"} <= codes(found) and "MB601" not in codes(found)
    client.workspace_did_change_configuration(
        types.DidChangeConfigurationParams(
            settings={
                "fanuc-macro": {
                    "machine": {
                        "customCalls": {"M165": 9022},
                        "programsOnControl": ["O2000-O2999"],
                    }
                }
            }
        )
    )
    found = await diagnostics(client, uri, lambda d: "MB502" in codes(d))
    assert not {"MB409", "MB601", "MB403"} & codes(found)
    divide = next(d for d in found if d.code == "MB502")
    assert divide.range.start.line == 5 and "#7=1.415" in divide.message
    text = await hover(client, uri, 1, 1)
    assert "**M165** — calls O9022 as a macro, like G65" in text


async def test_hover_of_a_known_cycle_names_it_and_its_arguments(client: LanguageClient) -> None:
    await start(client, None, {"machine": {"programsOnControl": [1]}})
    uri = "untitled:bore.nc"
    open_text(client, uri, "O1000 (BORE CHECK)\nG65 P9814 D50. Z-10. S1.\nM30\n")
    found = await diagnostics(client, uri, lambda d: "MB408" in codes(d))
    hint = next(d for d in found if d.code == "MB408")
    assert hint.severity == types.DiagnosticSeverity.Hint
    text = await hover(client, uri, 1, 6)
    assert "Renishaw Inspection Plus: bore or boss measurement" in text
    assert "**Z** the depth to measure a boss at" in text
    argument = await hover(client, uri, 1, 16)
    assert "G65 argument **Z** → **#26** in O9814: the depth to measure a boss at" in argument


async def test_a_custom_call_the_manual_does_not_allow_is_logged(client: LanguageClient) -> None:
    await start(client, None, {"machine": {"customCalls": {"M165": 9010, "G100": 9010}}})
    uri = "untitled:probe.nc"
    open_text(client, uri, PROBE)
    await diagnostics(client, uri, lambda d: "MB409" in codes(d))
    logged = [m.message for m in client.log_messages]
    assert (
        "fanuc-macro: machine.customCalls: 'M165' calls O9010: an M code can call only "
        "O9020-O9029 (parameters 6080-6089) or O9001-O9009 (parameters 6071-6079)"
    ) in logged
