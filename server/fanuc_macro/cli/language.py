"""The language the command line speaks: ``--lang LOCALE`` when given (anywhere among the
arguments; ``auto``, the default, is the environment's), else the first of ``LC_ALL``,
``LC_MESSAGES`` and ``LANG`` that is set, in gettext's order (``C`` and ``POSIX`` are
English), read by :func:`..translation.locale_of`.

Every text the command line writes for a person is a :func:`..translation.tr` said with
:func:`said`; the forms other programs read (JSON, SARIF, GitHub annotations, JUnit XML) stay
English. A command runs in one language, chosen once in ``main``: :func:`use` sets it (a
context variable; a check's processes are told it, check_command._FORKED).

argparse says its own words ("usage:", "options", "show this help message and exit", its
errors) through the module-level ``_`` and ``ngettext`` it imports from gettext, which look in
the system's catalogue of the domain "argparse" (none is installed with Python): while a
command line in another language is parsed, :func:`argparse_in` puts this package's catalogue
in their place. :data:`ARGPARSE_WORDS` names those words for the catalogue's extraction.
"""

from __future__ import annotations

import argparse
import contextlib
import contextvars
import os
import unicodedata
from collections.abc import Iterable, Iterator, Mapping, Sequence

from ..translation import locale_of, render, tr, tr_n

OPTION = "--lang"
AUTO = "auto"
ENVIRONMENT = ("LC_ALL", "LC_MESSAGES", "LANG")  # gettext's order (LANGUAGE aside)

# The language of this run: set once by ``main`` (and in each process of a parallel check).
_LOCALE: contextvars.ContextVar[str] = contextvars.ContextVar("cli_locale", default="en")


def chosen_locale(argv: Sequence[str], environ: Mapping[str, str] | None = None) -> str:
    """The locale of a command line: its ``--lang`` (the last one given, before any ``--``)
    unless ``auto``, else the environment's."""
    given = AUTO
    words = iter(argv)
    for word in words:
        if word == "--":
            break
        if word == OPTION:
            given = next(words, AUTO)
        elif word.startswith(OPTION + "="):
            given = word.partition("=")[2]
    if given.strip().lower() != AUTO:
        return locale_of(given)
    env = os.environ if environ is None else environ
    for name in ENVIRONMENT:
        value = env.get(name)
        if value:
            return locale_of(value)
    return "en"


def use(locale: str) -> None:
    """Speak ``locale`` from now on, in this process."""
    _LOCALE.set(locale)


def current() -> str:
    return _LOCALE.get()


def said(text: str) -> str:
    """``text`` in the command line's language (a plain ``str`` as it is)."""
    return render(text, _LOCALE.get())


def said_error(error: BaseException) -> str:
    """An exception's message said: its one argument (a ``Text`` when the message was made
    with ``tr``; ``str`` of the exception is the English)."""
    first = error.args[0] if len(error.args) == 1 else None
    return said(first if isinstance(first, str) else str(error))


def listed(parts: Iterable[str]) -> str:
    """Parts said one after another, with the language's comma."""
    return said(tr(", ")).join(said(part) for part in parts)


# argparse's words, for the catalogue (Babel extracts these literals); they are %-templates.
ARGPARSE_WORDS = (
    tr("usage: "),
    tr("positional arguments"),
    tr("options"),
    tr("show this help message and exit"),
    tr("show program's version number and exit"),
    tr("argument %(argument_name)s: %(message)s"),
    tr("unrecognized arguments: %s"),
    tr("not allowed with argument %s"),
    tr("ignored explicit argument %r"),
    tr("the following arguments are required: %s"),
    tr("one of the arguments %s is required"),
    tr("expected one argument"),
    tr("expected at most one argument"),
    tr("expected at least one argument"),
    tr_n("expected %s argument", "expected %s arguments", 1),
    tr("ambiguous option: %(option)s could match %(matches)s"),
    tr("unexpected option string: %s"),
    tr("invalid %(type)s value: %(value)r"),
    tr("invalid choice: %(value)r (choose from %(choices)s)"),
    tr("%(prog)s: error: %(message)s\n"),
    tr("unknown parser %(parser_name)r (choices: %(choices)s)"),
)


def _argparse_gettext(message: str) -> str:
    return said(tr(message))


def _argparse_ngettext(singular: str, plural: str, count: int) -> str:
    return said(tr_n(singular, plural, count))


def width_of(text: str) -> int:
    """The columns ``text`` takes on a terminal: two for a Chinese or Japanese character."""
    return sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in text)


_CLOSING = frozenset("，。；：、）》」』！？")  # never first on a line
_OPENING = frozenset("（《「『“")  # never last on a line


def wrapped(text: str, width: int) -> list[str]:
    """``text``'s words in lines of ``width`` columns at most, as textwrap does for English,
    where a Chinese or Japanese text may break between any two characters (not before its
    closing punctuation, nor after its opening), and a character takes two columns."""
    tokens: list[str] = []  # a space, a wide character, or a word of the others
    after_word = False
    for char in " ".join(text.split()):
        word = char != " " and unicodedata.east_asian_width(char) not in "WF"
        if word and after_word:
            tokens[-1] += char
        else:
            tokens.append(char)
        after_word = word
    lines: list[str] = []
    line = ""
    for token in tokens:
        if line and width_of(line.rstrip() + token) > width and token not in _CLOSING:
            kept = line.rstrip()
            carried = kept[-1] if kept[-1] in _OPENING and len(kept) > 1 else ""
            lines.append(kept[: len(kept) - len(carried)])
            line = carried
        if line or token != " ":
            line += token
    if line.strip():
        lines.append(line.rstrip())
    return lines


class WideHelpFormatter(argparse.HelpFormatter):
    """argparse's help, its text wrapped by :func:`wrapped`."""

    def _split_lines(self, text: str, width: int) -> list[str]:
        return wrapped(text, width)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        return "\n".join(indent + line for line in wrapped(text, width - len(indent)))


class WideRawDescriptionHelpFormatter(argparse.RawDescriptionHelpFormatter, WideHelpFormatter):
    """:class:`WideHelpFormatter` for a parser whose description and epilog are laid out."""


def wide_help(parser: argparse.ArgumentParser) -> None:
    """The help of ``parser`` and of its commands wrapped for Chinese and Japanese text."""
    parsers = [parser]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            parsers.extend(action.choices.values())
    for each in parsers:
        kind = each.formatter_class
        raw = isinstance(kind, type) and issubclass(kind, argparse.RawDescriptionHelpFormatter)
        each.formatter_class = WideRawDescriptionHelpFormatter if raw else WideHelpFormatter


@contextlib.contextmanager
def argparse_in(locale: str) -> Iterator[None]:
    """argparse says its words in ``locale`` while in the block (see the module's doc)."""
    if locale == "en":
        yield
        return
    module = vars(argparse)
    before = module["_"], module["ngettext"]
    module["_"], module["ngettext"] = _argparse_gettext, _argparse_ngettext
    try:
        yield
    finally:
        module["_"], module["ngettext"] = before


__all__ = (
    "ARGPARSE_WORDS",
    "argparse_in",
    "chosen_locale",
    "current",
    "listed",
    "said",
    "said_error",
    "use",
    "wide_help",
    "wrapped",
)
