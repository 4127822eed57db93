"""The server's words in the user's language: one catalogue per locale, shipped as
``data/messages.<locale>.json``.

English is the language of the rules, so an English user gets every message as the rule writes
it. In another locale a diagnostic's message is the rule's summary in that language, then the
rule's own message on the next line: what is wrong in the user's words, and the English details
(the values, the places, the alarm numbers), which stay exact. A locale whose catalogue lacks a
rule leaves that rule's messages in English. A new locale is one more JSON file (``rules``: code
→ summary) and one more entry in ``LOCALES``.
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from importlib import resources
from types import MappingProxyType

from .. import database
from ..database import TableKey
from ..diagnostics import Diagnostic

# The locales with a catalogue, and the names the editors give them (VS Code's display
# language "zh-cn", Neovim's $LANG "zh_CN.UTF-8", BCP 47 "zh-Hans"). FANUC's own manuals use
# the Japanese terms of the ja catalogue (シーケンス番号, コモン変数, ノーズ半径).
LOCALES = ("en", "zh-cn", "ja")
_ALIASES: Mapping[str, str] = MappingProxyType(
    {
        "zh": "zh-cn",
        "zh-cn": "zh-cn",
        "zh-hans": "zh-cn",
        "zh-sg": "zh-cn",
        "ja": "ja",
        "ja-jp": "ja",
    }
)


def locale_of(name: str | None) -> str:
    """The catalogue for a locale name; English for any locale without one."""
    if not name:
        return "en"
    tag = name.split(".")[0].replace("_", "-").lower()
    if tag in _ALIASES:
        return _ALIASES[tag]
    return tag if tag in LOCALES else _ALIASES.get(tag.split("-")[0], "en")


@dataclass(frozen=True)
class Catalogue:
    locale: str = "en"
    rules: Mapping[str, str] = field(default_factory=dict)  # code -> summary

    def message(self, code: str, message: str) -> str:
        summary = self.rules.get(code)
        return f"{summary}\n{message}" if summary else message

    def localised(self, diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
        """The diagnostics with their messages in this locale (the same objects in English)."""
        if not self.rules:
            return list(diagnostics)
        return [replace(d, message=self.message(d.code, d.message)) for d in diagnostics]


# The catalogues read, by locale, once per database.
_CATALOGUES: TableKey[str, Catalogue] = TableKey("ide.messages.catalogues")


def catalogue(locale: str) -> Catalogue:
    """The catalogue of ``locale`` (a name :func:`locale_of` knows); English when none loads."""
    read = database.current().table(_CATALOGUES)
    found = read.get(locale)
    if found is None:
        found = read[locale] = _read_catalogue(locale_of(locale))
    return found


def _read_catalogue(locale: str) -> Catalogue:
    if locale == "en":
        return Catalogue()
    try:
        raw = (resources.files("fanuc_macro") / "data" / f"messages.{locale}.json").read_text(
            "utf-8"
        )
        data = json.loads(raw)
    except (OSError, ValueError):
        return Catalogue()
    rules = data.get("rules") if isinstance(data, dict) else None
    if not isinstance(rules, dict):
        return Catalogue()
    return Catalogue(locale, {str(k): str(v) for k, v in rules.items()})
