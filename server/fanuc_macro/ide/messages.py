"""The diagnostics in the user's language, from the gettext catalogues of
:mod:`fanuc_macro.translation`.

English is the language of the rules, so an English user gets every message as the rule writes
it. In another locale a diagnostic whose message has a translation is said wholly in that
language (the values and program text in it are parameters, the same in every language); one
whose message has none yet is the rule's summary in that language, then the rule's English
message on the next line. The related places' messages and the fixes' titles are translated the
same way.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

from ..diagnostics import Diagnostic, Fix, Related
from ..translation import LOCALES, Text, has_translation, render, translate
from ..translation import locale_of as _locale_of

__all__ = ("LOCALES", "Catalogue", "catalogue", "locale_of")


def locale_of(name: str | None) -> str:
    """The locale of a name an editor gives (``zh-CN``, ``zh_CN.UTF-8``); English for one
    without a catalogue."""
    return _locale_of(name)


@dataclass(frozen=True)
class Catalogue:
    locale: str = "en"

    def summary(self, code: str, english: str) -> str:
        """A rule's summary (``english``) in this locale."""
        return translate(english, self.locale)

    def message(self, code: str, message: str, summary: str = "") -> str:
        """A diagnostic's message in this locale (``summary``: its rule's, in English)."""
        if self.locale == "en":
            return message
        if isinstance(message, Text) and has_translation(message, self.locale):
            return render(message, self.locale)
        said = translate(summary, self.locale) if summary else ""
        return f"{said}\n{message}" if said and said != summary else message

    def text(self, text: str) -> str:
        """Any other text (a related place's message, a fix's title) in this locale."""
        return render(text, self.locale)

    def localised(self, diagnostics: Iterable[Diagnostic]) -> list[Diagnostic]:
        """The diagnostics with their messages in this locale (the same objects in English)."""
        if self.locale == "en":
            return list(diagnostics)
        from ..analysis import RULES

        out = []
        for d in diagnostics:
            info = RULES.get(d.code)
            out.append(
                replace(
                    d,
                    message=self.message(d.code, d.message, info.summary if info else ""),
                    related=tuple(self._related(r) for r in d.related),
                    fixes=tuple(self._fix(f) for f in d.fixes),
                )
            )
        return out

    def _related(self, related: Related) -> Related:
        return replace(related, message=self.text(related.message))

    def _fix(self, fix: Fix) -> Fix:
        return replace(fix, title=self.text(fix.title))


def catalogue(locale: str | None) -> Catalogue:
    """The catalogue of a locale name (any name :func:`locale_of` knows); English for others."""
    return Catalogue(_locale_of(locale))
