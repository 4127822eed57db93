"""Words a user reads, written once in English with named parameters and said in the user's
language by gettext catalogues.

A message is made with :func:`tr` (or :func:`tr_n` when it counts something): the result is a
:class:`Text`, a ``str`` holding the English, so every consumer that wants English (the JSON
output, the snapshots, the corpus tables) reads it as before, and which also keeps its template
and parameters, so that a front end can say it again in the user's language with
:func:`render`. The templates are the catalogue's message ids: ``scripts/catalogues.py``
extracts them with Babel (keywords ``tr`` and ``tr_n:1,2``) into
``data/locale/<locale>/LC_MESSAGES/<domain>.po``, which the translators fill. Numbers and
program text reach a message as parameters and are never translated.

A locale without a catalogue, a template without a translation, or a ``str`` that is not a
``Text`` stays English. Traditional Chinese falls back to the simplified catalogue, then to
English, message by message.
"""

from __future__ import annotations

import gettext
import re
from collections.abc import Callable, Iterable, Mapping
from importlib import resources
from types import MappingProxyType
from typing import Any

from . import database
from .database import TableKey

# The locales with catalogues, and the order a locale falls back through them.
LOCALES = ("en", "zh-cn", "zh-tw", "ja")
FALLBACK: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"en": (), "zh-cn": ("zh-cn",), "zh-tw": ("zh-tw", "zh-cn"), "ja": ("ja",)}
)
# gettext's directory names of the locales.
DIRECTORY: Mapping[str, str] = MappingProxyType({"zh-cn": "zh_CN", "zh-tw": "zh_TW", "ja": "ja"})
DOMAINS = ("messages", "rules_doc")

# The names editors and shells give the locales: VS Code's display language "zh-cn",
# $LANG "zh_CN.UTF-8", BCP 47 "zh-Hans", "zh-Hant-TW".
_ALIASES: Mapping[str, str] = MappingProxyType(
    {
        "zh": "zh-cn",
        "zh-cn": "zh-cn",
        "zh-hans": "zh-cn",
        "zh-hans-cn": "zh-cn",
        "zh-sg": "zh-cn",
        "zh-tw": "zh-tw",
        "zh-hk": "zh-tw",
        "zh-mo": "zh-tw",
        "zh-hant": "zh-tw",
        "zh-hant-tw": "zh-tw",
        "zh-hant-hk": "zh-tw",
        "ja": "ja",
        "ja-jp": "ja",
    }
)


def locale_of(name: str | None) -> str:
    """The locale of a name an editor or a shell gives; English for any without a catalogue."""
    if not name:
        return "en"
    tag = name.split(".")[0].split("@")[0].replace("_", "-").lower()
    if tag in _ALIASES:
        return _ALIASES[tag]
    return tag if tag in LOCALES else _ALIASES.get(tag.split("-")[0], "en")


class Text(str):
    """English text that remembers its template and parameters (see the module's doc)."""

    template: str
    params: Mapping[str, object]
    plural: str | None  # tr_n's plural template; ``number`` picks the form
    number: int  # (not ``count``: str has a method of that name)

    def __new__(
        cls, template: str, params: Mapping[str, object], plural: str | None = None, number: int = 1
    ) -> Text:
        english = _fill(plural if plural is not None and number != 1 else template, params, None)
        made = super().__new__(cls, english)
        made.template = template
        made.params = params
        made.plural = plural
        made.number = number
        return made

    def __reduce__(self) -> tuple[Any, ...]:
        return (Text, (self.template, dict(self.params), self.plural, self.number))


def tr(template: str, /, **params: object) -> Text:
    """A message: ``template`` is English with ``{named}`` fields (format specs allowed), each
    filled from ``params``; a parameter may be another :class:`Text`, said in the same
    language."""
    return Text(template, params)


def tr_n(singular: str, plural: str, count: int, /, **params: object) -> Text:
    """A message that counts: the form for ``count`` (``{count}`` is a parameter too)."""
    return Text(singular, {"count": count, **params}, plural, count)


def joined(separator: str, parts: Iterable[str]) -> str:
    """Parts said one after another: a :class:`Text` when any part is one, so each part is
    translated; a list's ", " and "; " are said as the language writes them (Chinese "，")."""
    items = list(parts)
    if not any(isinstance(p, Text) for p in items):
        return separator.join(items)
    names = [f"p{i}" for i in range(len(items))]
    template = separator.replace("{", "{{").replace("}", "}}").join(f"{{{n}}}" for n in names)
    return Text(template, dict(zip(names, items, strict=True)))


def render(text: str, locale: str, domain: str = "messages") -> str:
    """``text`` in ``locale``: its template's translation with its parameters said the same
    way; English (the text itself) where no translation is written."""
    if not isinstance(text, Text) or locale == "en":
        return str(text)
    template = _translated(text, locale, domain)
    if template is text.template and _JOINED.fullmatch(template):
        for english, said in _SEPARATORS.get(locale, {}).items():
            template = template.replace("}" + english + "{", "}" + said + "{")
    return _fill(template, text.params, (locale, domain))


# The punctuation between the parts of :func:`joined`, as each language writes a list.
_SEPARATORS: Mapping[str, Mapping[str, str]] = MappingProxyType(
    {
        "zh-cn": MappingProxyType({", ": "，", "; ": "；"}),
        "zh-tw": MappingProxyType({", ": "，", "; ": "；"}),
        "ja": MappingProxyType({", ": "、", "; ": "；"}),
    }
)
_JOINED = re.compile(r"\{p0\}(?:(?:, |; )\{p\d+\})*")


def translate(message_id: str, locale: str, domain: str = "messages") -> str:
    """A catalogue's translation of a constant text (a rule's summary, a heading), or itself."""
    for each in FALLBACK.get(locale, ()):
        found = _catalogue(each, domain).get(message_id)
        if found:
            return found[0]
    return message_id


def has_translation(text: Text, locale: str, domain: str = "messages") -> bool:
    """Whether a catalogue of ``locale`` (or of one it falls back to) says ``text``."""
    return any(text.template in _catalogue(each, domain) for each in FALLBACK.get(locale, ()))


def _translated(text: Text, locale: str, domain: str) -> str:
    for each in FALLBACK.get(locale, ()):
        forms = _catalogue(each, domain).get(text.template)
        if forms:
            if text.plural is None:
                return forms[0]
            return forms[min(_plural_index(each, domain)(text.number), len(forms) - 1)]
    return text.plural if text.plural is not None and text.number != 1 else text.template


def _fill(template: str, params: Mapping[str, object], said: tuple[str, str] | None) -> str:
    if not params:
        return template.replace("{{", "{").replace("}}", "}")
    values = {
        k: (render(v, *said) if said is not None and isinstance(v, Text) else v)
        for k, v in params.items()
    }
    return template.format_map(values)


# The catalogues read, by (locale, domain): each's translations (message id -> its forms, one
# or a plural's in their order) and its plural rule. Read once per database, on first use.
_CATALOGUES: TableKey[
    tuple[str, str], tuple[Mapping[str, tuple[str, ...]], Callable[[int], int]]
] = TableKey("translation.catalogues")


def _catalogue(locale: str, domain: str) -> Mapping[str, tuple[str, ...]]:
    return _read(locale, domain)[0]


def _plural_index(locale: str, domain: str) -> Callable[[int], int]:
    return _read(locale, domain)[1]


def _read(locale: str, domain: str) -> tuple[Mapping[str, tuple[str, ...]], Callable[[int], int]]:
    table = database.current().table(_CATALOGUES)
    found = table.get((locale, domain))
    if found is None:
        entries: dict[str, tuple[str, ...]] = {}
        expression = "0"
        directory = DIRECTORY.get(locale)
        if directory is not None:
            source = resources.files("fanuc_macro") / "data" / "locale" / directory
            try:
                text = (source / "LC_MESSAGES" / f"{domain}.po").read_text("utf-8")
            except OSError:
                text = ""
            if text:
                entries, expression = read_po_text(text)
        found = table[(locale, domain)] = (MappingProxyType(entries), gettext.c2py(expression))
    return found


def read_po_text(text: str) -> tuple[dict[str, tuple[str, ...]], str]:
    """The translated entries of a .po file (fuzzy and empty ones left out), and its plural
    expression; read with Babel, the catalogues' tool."""
    from io import StringIO

    from babel.messages.pofile import read_po

    catalog = read_po(StringIO(text))
    entries: dict[str, tuple[str, ...]] = {}
    for message in catalog:
        if not message.id or message.fuzzy:
            continue
        if isinstance(message.id, tuple):
            forms = tuple(str(s) for s in message.string or ())
            if all(forms):
                entries[str(message.id[0])] = forms
        elif message.string:
            entries[str(message.id)] = (str(message.string),)
    return entries, str(catalog.plural_expr)
