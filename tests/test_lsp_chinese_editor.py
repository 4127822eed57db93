"""With the editor in Chinese, the words of the editor's features beyond the diagnostics are
said in Chinese over stdio: hovers, code lenses, inlay hints, code action titles, completion
details and signature help, with no English sentence left (``english_in``)."""

from __future__ import annotations

import asyncio

from lsprotocol import types
from pytest_lsp import LanguageClient

from test_lsp import WAIT, client, diagnostics, edit, hover, open_text, start
from test_lsp_editor_commands import run
from test_translation_fixtures import english_in

__all__ = ["client"]

TEXT = """%
O1000
#1=2.*3.
#2=0
WHILE[#2LT3]DO1
#2=#2+1
END1
G65 P2000 A#1
M98 P2000
GOTO 10
N10 M30
O2000
#3=#1+1
M[#3/2]
G00 X#3 Z1.
M99
%
"""


def english(*texts: str | None) -> list[str]:
    return [found for text in texts if text for found in english_in(text)]


async def test_the_editors_words_are_said_in_chinese(client: LanguageClient) -> None:
    await start(client, locale="zh-cn")
    uri = "untitled:chinese.nc"
    open_text(client, uri, TEXT)
    found = await diagnostics(client, uri, lambda d: any(x.code == "MB601" for x in d))
    ident = types.TextDocumentIdentifier(uri=uri)

    variable = await hover(client, uri, 2, 0)
    assert "局部变量" in variable and "**#1** = **6.**" in variable
    loop = await hover(client, uri, 4, len("WHILE[#2LT3]D"))
    assert "嵌套层级 1" in loop and "循环体执行了 3 次" in loop
    label = await hover(client, uri, 10, 1)
    assert "顺序号" in label
    jump = await hover(client, uri, 9, 1)
    assert "→ 第 11 行" in jump
    # A G code: its name, its group and what it does.
    rapid = await hover(client, uri, 14, 1)
    assert rapid.startswith(
        "**G00** — 快速定位 *（模态，01 组）*\n\n---\n\n以快速移动速度移到终点。"
    )
    keyword = await hover(client, uri, 4, 1)
    assert keyword.startswith("**WHILE** — 循环")
    assert not english(variable, loop, label, jump, keyword, rapid)

    lenses = await asyncio.wait_for(
        client.text_document_code_lens_async(types.CodeLensParams(text_document=ident)), WAIT
    )
    assert lenses
    titles = [lens.command.title for lens in lenses if lens.command is not None]
    tooltips = [lens.command.tooltip for lens in lenses if lens.command is not None]
    assert "进入 1 次" in titles and "调用自 O1000 · 2×" in titles
    assert not english(*titles, *tooltips)

    hints = await asyncio.wait_for(
        client.text_document_inlay_hint_async(
            types.InlayHintParams(
                text_document=ident,
                range=types.Range(
                    start=types.Position(line=0, character=0),
                    end=types.Position(line=15, character=0),
                ),
            )
        ),
        WAIT,
    )
    assert hints and hints[0].label == "= 6."
    assert not english(*(str(h.label) for h in hints), *(str(h.tooltip) for h in hints))

    coded = [d for d in found if d.code == "MB601"]
    actions = await asyncio.wait_for(
        client.text_document_code_action_async(
            types.CodeActionParams(
                text_document=ident,
                range=coded[0].range,
                context=types.CodeActionContext(diagnostics=coded[:1]),
            )
        ),
        WAIT,
    )
    titles = [a.title for a in actions or [] if isinstance(a, types.CodeAction)]
    assert f"在本行屏蔽 {coded[0].code}" in titles

    signature = await asyncio.wait_for(
        client.text_document_signature_help_async(
            types.SignatureHelpParams(
                text_document=ident,
                position=types.Position(line=7, character=len(TEXT.split("\n")[7])),
            )
        ),
        WAIT,
    )
    assert signature is not None
    (said,) = signature.signatures
    argument = (said.parameters or [])[0].documentation
    assert isinstance(argument, types.MarkupContent) and "由 O2000 在第 13 行读取" in argument.value
    assert not english(argument.value)

    # A variable typed on a new line: each item's detail says what kind of variable it is.
    edit(client, uri, 2, [types.TextDocumentContentChangePartial(
        range=types.Range(
            start=types.Position(line=3, character=0), end=types.Position(line=3, character=0)
        ),
        text="#\n",
    )])  # fmt: skip
    completion = await asyncio.wait_for(
        client.text_document_completion_async(
            types.CompletionParams(
                text_document=ident, position=types.Position(line=3, character=1)
            )
        ),
        WAIT,
    )
    assert isinstance(completion, types.CompletionList)
    details = {item.label: item.detail for item in completion.items}
    assert details["#1"] == "局部变量" and details["#5221"] is not None
    assert "G54 工件坐标系偏移" in details["#5221"]
    assert not english(*details.values())

    # The trace view: its header, its columns and its summary's words.
    view = await run(client, "fanuc-macro.traceView", uri, "/programs/chinese.nc")
    lines = view["text"].split("\n")
    assert lines[:2] == ["chinese.nc 的轨迹", "位于 /programs"]
    assert lines[5].split() == ["程序段", "代码", "字", "到", "S", "F", "时间"]
    assert any(line.startswith("O2000 第 16 行  G00") for line in lines)  # "#" typed above
    # The summary's keys (its values are the findings' own words).
    keys = [line.split(":")[0] for line in lines[lines.index("摘要") :]]
    assert "  已执行程序段" in keys
    assert not english(*lines[:6], *keys)

    # The Toolpath view's notes: why the unit is assumed.
    toolpath = await run(client, "fanuc-macro.toolpath", uri)
    assert toolpath["units_note"].startswith("假定为 mm：")
    assert not english(toolpath["units_note"])
