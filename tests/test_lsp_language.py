"""The language server in Chinese (``initialize.locale`` zh-cn): every rule's fixture, opened
over stdio, is published with each diagnostic's message as the catalogue says it, the message
that tests/test_translation_fixtures.py holds free of English."""

from __future__ import annotations

import asyncio
from collections.abc import Sequence
from pathlib import Path

from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.ide import catalogue
from fanuc_macro.workspace import Workspace
from test_lsp import CAPABILITIES, WAIT, client, diagnostics, open_text
from test_rules import FIXTURE_FILES, decode_bytes, fixture_settings

__all__ = ["client"]

# The fixtures the editor's default settings analyse as the tests do (the others give their
# settings in a comment, which an editor does not read).
PLAIN_FIXTURES = [p for p in FIXTURE_FILES if not fixture_settings(p)]


def text_of(path: Path) -> str:
    return decode_bytes(path.read_bytes()).text  # GB18030 fixtures too, as an editor reads them


def expected(uris: dict[str, Path]) -> dict[str, dict[tuple[int, str], list[str]]]:
    """Each document's messages in Chinese, analysed with the others as the server has them."""
    workspace = Workspace()
    for uri, path in uris.items():
        workspace.add_text(uri, text_of(path))
    programs = workspace.program_numbers()
    chinese = catalogue("zh-cn")
    out = {}
    for uri in uris:
        found: dict[tuple[int, str], list[str]] = {}
        for d in chinese.localised(workspace.analyse(uri, programs).diagnostics):
            found.setdefault((d.line, d.code), []).append(d.message)
        out[uri] = {key: sorted(messages) for key, messages in found.items()}
    return out


async def test_every_fixture_is_published_in_chinese(client: LanguageClient) -> None:
    await asyncio.wait_for(
        client.initialize_session(
            types.InitializeParams(
                capabilities=CAPABILITIES,
                locale="zh-cn",
                initialization_options={"analysis": {"debounceMs": 20}},
            )
        ),
        WAIT,
    )
    assert len(PLAIN_FIXTURES) > 100
    uris = {}
    for number, path in enumerate(PLAIN_FIXTURES):
        uri = f"untitled:fixture{number}.nc"
        uris[uri] = path
        open_text(client, uri, text_of(path))
    said = expected(uris)
    chinese = 0
    for uri in uris:
        # Opening the others may publish a document again (a call it makes now resolves).
        found = await diagnostics(client, uri, lambda d, u=uri: by_place(d) == said[u])
        # Wholly Chinese: not the fallback of a Chinese summary above the English message.
        chinese += sum(1 for ms in by_place(found).values() for m in ms if "\n" not in m)
    assert chinese > 100


def by_place(found: Sequence[types.Diagnostic]) -> dict[tuple[int, str], list[str]]:
    published: dict[tuple[int, str], list[str]] = {}
    for d in found:
        published.setdefault((d.range.start.line, str(d.code)), []).append(d.message)
    return {key: sorted(messages) for key, messages in published.items()}
