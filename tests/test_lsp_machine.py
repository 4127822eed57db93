"""The machine each document is read as, over stdio (``fanuc-macro.machine``): with the
controller 0i-F, a lathe or a mill as its codes show, or not known; with a controller set, the
setting's machine whatever the codes."""

from __future__ import annotations

import asyncio
from typing import Any

from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import CAPABILITIES, WAIT, client, diagnostics, open_text, start
from test_lsp_editor_commands import run

__all__ = ["client"]  # the fixture, shared with test_lsp.py

MACHINE = "fanuc-macro.machine"

MILL = "O1000\nT1 M06\nG90 G54 G00 X0 Y0\nG43 H1 Z50.\nG91 G28 Z0\nM30\n"
LATHE = "O2000\nT0101\nG96 S200 M03\nG00 X50. Z2.\nG01 Z-20. F0.2\nM30\n"
MACRO = "O3000\n#1=10\n#2=#1*2\nM30\n"


async def machine_of(client: LanguageClient, name: str, text: str) -> dict[str, Any]:
    """Open ``text`` and ask its machine once its diagnostics came, as the editor does."""
    uri = f"untitled:{name}.nc"
    open_text(client, uri, text)
    await diagnostics(client, uri)
    return await run(client, MACHINE, uri)


async def test_the_machine_command_is_advertised(client: LanguageClient) -> None:
    result = await asyncio.wait_for(
        client.initialize_session(types.InitializeParams(capabilities=CAPABILITIES)), WAIT
    )
    provider = result.capabilities.execute_command_provider
    assert provider is not None and MACHINE in provider.commands


async def test_each_document_is_read_as_the_machine_its_codes_show(
    client: LanguageClient,
) -> None:
    await start(client, None)  # the controller setting's default: 0i-F
    assert await machine_of(client, "mill", MILL) == {
        "controller": "0i-MF",
        "kind": "mill",
        "text": "Machine: a mill (0i-F read as 0i-MF), from its codes: M06 (tool change) on "
        "line 2 and 4 more kinds of mark.",
    }
    assert await machine_of(client, "lathe", LATHE) == {
        "controller": "0i-TF",
        "kind": "lathe",
        "text": "Machine: a lathe (0i-F read as 0i-TF), from its codes: a four-digit T (tool "
        "and offset number) on line 2 and 1 more kind of mark.",
    }
    unknown = await machine_of(client, "macro", MACRO)
    assert (unknown["controller"], unknown["kind"]) == ("0i-TF", "unknown")
    assert unknown["text"].startswith(
        "Machine: not known, no code of the program is a lathe's or a mill's alone. "
        "Read as a lathe (0i-TF)"
    )


async def test_a_controller_set_is_the_machine_whatever_the_codes(
    client: LanguageClient,
) -> None:
    await start(client, None, {"controller": "0i-MF"})
    assert await machine_of(client, "lathe", LATHE) == {
        "controller": "0i-MF",
        "kind": "mill",
        "text": "Machine: a mill, as the controller setting 0i-MF says.",
    }


async def test_a_document_not_open_has_no_machine(client: LanguageClient) -> None:
    await start(client, None)
    assert await run(client, MACHINE, "untitled:closed.nc") == {
        "error": "untitled:closed.nc is not open"
    }
    assert await run(client, MACHINE) == {
        "error": f"{MACHINE} takes the document's URI as its argument"
    }


# A system B lathe's threading cycle started inside the thread (the return in Z crosses it).
SYSTEM_B_THREAD = (
    "O1001\nG90 G95 G21\nT0303\nG97 S800 M03\nG00 X26. Z5.\nG78 X29.3 Z-20. F1.5\nX28.8\n"
    "G00 X100. Z100.\nM30\n"
)


async def test_the_g_code_system_setting_reads_a_lathe_in_system_b(client: LanguageClient) -> None:
    await start(client, None, {"machine": {"gCodeSystem": "B"}})
    uri = "untitled:system-b.nc"
    open_text(client, uri, SYSTEM_B_THREAD)
    found = await diagnostics(client, uri, lambda d: any(x.code == "MB813" for x in d))
    message = next(x.message for x in found if x.code == "MB813")
    assert message.startswith("G78 starts at X26., but the thread is cut from the outside")
    machine = await run(client, MACHINE, uri)
    assert machine["kind"] == "lathe"
    assert machine["text"].endswith("A lathe's G codes are read in G code system B.")
    hover = await client.text_document_hover_async(
        types.HoverParams(
            text_document=types.TextDocumentIdentifier(uri=uri),
            position=types.Position(line=5, character=1),
        )
    )
    assert hover is not None and isinstance(hover.contents, types.MarkupContent)
    assert hover.contents.value.startswith(
        "**G78** — Threading cycle *(G code system B; system A's G92)*"
    )
