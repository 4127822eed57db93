"""The messages in the user's language: the catalogues are complete, and the server speaks the
client's locale (or the `language` setting) over stdio."""

from __future__ import annotations

from collections.abc import Sequence

from lsprotocol import types
from pytest_lsp import LanguageClient

from fanuc_macro.analysis import RULES
from fanuc_macro.ide.messages import catalogue, locale_of
from test_lsp import client, diagnostics, open_seed, start

__all__ = ["client"]


def test_every_rule_has_a_summary_in_every_catalogue() -> None:
    for locale in ("zh-cn", "ja"):
        said = {code: catalogue(locale).summary(code, info.summary) for code, info in RULES.items()}
        untranslated = sorted(code for code, text in said.items() if text == RULES[code].summary)
        assert not untranslated, f"{locale}: rules without a summary: {untranslated}"
        assert catalogue(locale).locale == locale


def test_locale_names_from_the_editors() -> None:
    # Traditional Chinese too: the simplified catalogue is nearer its readers than English.
    for name in ("zh-cn", "zh-CN", "zh_CN.UTF-8", "zh", "zh-Hans"):
        assert locale_of(name) == "zh-cn", name
    # Traditional Chinese falls back to the simplified catalogue, message by message.
    for name in ("zh-TW", "zh_TW.UTF-8", "zh-Hant", "zh-HK"):
        assert locale_of(name) == "zh-tw", name
    assert catalogue("zh-tw").summary("MB101", RULES["MB101"].summary) == catalogue(
        "zh-cn"
    ).summary("MB101", RULES["MB101"].summary)
    for name in ("ja", "ja-JP", "ja_JP.UTF-8"):
        assert locale_of(name) == "ja", name
    for name in (None, "", "en", "en-US", "de", "C.UTF-8"):
        assert locale_of(name) == "en", name


def test_a_message_is_the_summary_then_the_rules_own_words() -> None:
    # A message with no translation yet: the summary in Chinese, then the English.
    chinese = catalogue("zh-cn")
    summary = RULES["MB101"].summary
    text = chinese.message("MB101", "GOTO 99: no N99 in O1000", summary)
    assert text == "GOTO 的顺序号不在程序中。\nGOTO 99: no N99 in O1000"
    assert catalogue("en").message("MB101", "GOTO 99", summary) == "GOTO 99"
    assert chinese.message("MB999", "unknown") == "unknown"


def mb601(found: Sequence[types.Diagnostic]) -> str:
    return next(d.message for d in found if d.code == "MB601")


async def test_the_server_speaks_the_clients_locale(client: LanguageClient) -> None:
    await start(client, locale="zh-cn")
    uri = open_seed(client, "o2_arc_thread_roughing.nc")
    found = await diagnostics(client, uri, lambda d: any(x.code == "MB601" for x in d))
    chinese = mb601(found)
    # The rule's own words in Chinese, with the value that caused it.
    assert "只能取整数" in chinese and "93.82" in chinese and "\n" not in chinese
    # The setting overrides the client's locale, and the diagnostics are published again.
    client.workspace_did_change_configuration(
        types.DidChangeConfigurationParams(
            settings={"fanuc-macro": {"language": "en", "analysis": {"debounceMs": 20}}}
        )
    )
    found = await diagnostics(client, uri, lambda d: mb601(d) != chinese)
    english = mb601(found)
    assert "takes a whole number" in english and "93.82" in english
