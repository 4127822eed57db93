"""docs/rules.md, written from docs/rules-intro.md and the ``RuleDoc`` beside each rule's function.

The intro holds the general sections (the families, suppressing and disabling a rule, how the
evaluator runs a program, how the threading rules know the thread); then comes one section per
registered code, in code order, headed ``## MBxxx name``: the language server links each
diagnostic to that heading's anchor (lsp/convert.py), so the heading form must not change.
``scripts/rules_doc.py`` writes the files or, with ``--check``, says whether one is stale.

The Chinese page says each intro paragraph, label, part and severity note as the ``rules_doc``
catalogue (server/fanuc_macro/data/locale/zh_CN/LC_MESSAGES/rules_doc.po) translates it, in
English where it does not yet; the headings of the rules stay as they are, so the anchors are
the English page's.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from types import MappingProxyType

from .analysis import RULE_DOCS, RULES
from .diagnostics import RuleDoc, RuleInfo, Severity
from .translation import FALLBACK, translate

GENERATED = """\
<!-- Generated: do not edit. Each rule's section comes from the RuleDoc beside its registration
(server/fanuc_macro/rules/*.py, MB000 in analysis.py), the sections before them from
docs/rules-intro.md. Edit those, then run `python3 scripts/rules_doc.py`. -->

"""
# The translated page's: its texts come from the catalogue.
GENERATED_TRANSLATED = """\
<!-- Generated: do not edit. The English page docs/rules.md said in Chinese: each text from
server/fanuc_macro/data/locale/zh_CN/LC_MESSAGES/rules_doc.po (run `python3 scripts/catalogues.py`
when docs/rules.md changes, translate the new entries there, then `python3 scripts/rules_doc.py`).
-->

"""

# The parts of a section, in their order, with their bold labels.
PARTS: tuple[tuple[str, str], ...] = (
    ("reports", "What it reports."),
    ("why", "Why it matters on the machine."),
    ("example", "Example."),
    ("fix", "How to fix."),
    ("not_reported", "What it does not report."),
)


RULES_URL = "https://github.com/fanuc-macro/fanuc-macro/blob/main/docs/rules.md"
# The pages in other languages, by locale; a locale falls back as its messages do (zh-tw to
# zh-cn), then to the English page.
PAGES: Mapping[str, str] = MappingProxyType({"zh-cn": "rules.zh-cn.md"})
DOMAIN = "rules_doc"


def page_locale(locale: str) -> str:
    """The locale of the page a reader of ``locale`` reads: its own, one it falls back to, or
    English."""
    return next((each for each in FALLBACK.get(locale, ()) if each in PAGES), "en")


def page_name(locale: str = "en") -> str:
    """The file name, in docs/, of the page for ``locale``."""
    return PAGES.get(page_locale(locale), "rules.md")


def rule_url(code: str, locale: str = "en") -> str:
    """The section of docs/rules.md (docs/rules.zh-cn.md for a Chinese reader): headings are
    ``MBxxx name``, anchors ``mbxxx-name``, in every language."""
    info = RULES.get(code)
    anchor = code.lower() if info is None else f"{code.lower()}-{info.name}"
    return f"{RULES_URL.removesuffix('rules.md')}{page_name(locale)}#{anchor}"


def part_texts(doc: RuleDoc) -> dict[str, str]:
    """Each part of a rule's documentation, without the blank lines around it."""
    return {name: str(getattr(doc, name)).strip("\n") for name, _label in PARTS}


def intro_paragraphs(intro: str) -> list[str]:
    """The intro's paragraphs: blocks between blank lines, a fenced code block whole."""
    paragraphs: list[str] = []
    current: list[str] = []
    fenced = False
    for line in intro.splitlines():
        if line.startswith("```"):
            fenced = not fenced
        if not line.strip() and not fenced:
            if current:
                paragraphs.append("\n".join(current))
            current = []
        else:
            current.append(line)
    if current:
        paragraphs.append("\n".join(current))
    return paragraphs


def translatable_texts(intro: str) -> list[tuple[str, str]]:
    """The texts of docs/rules.md a translation says, each with where it comes from: the
    intro's paragraphs and headings, the labels, then each rule's parts and severity note.
    Headings of rules (their anchors) and code blocks are not among them."""
    texts = [(p, "rules-intro") for p in intro_paragraphs(intro) if not p.startswith("```")]
    texts += [(label, "rules_doc") for _name, label in PARTS]
    texts.append(("Severity:", "rules_doc"))
    texts += [(severity.value, "rules_doc") for severity in Severity]
    for code in sorted(RULE_DOCS):
        doc = RULE_DOCS[code]
        texts += [(text, code) for text in part_texts(doc).values()]
        if doc.severity_note:
            texts.append((doc.severity_note, code))
    return texts


def missing_docs() -> list[str]:
    """The registered codes without documentation, and the documented codes not registered."""
    return sorted(set(RULES) ^ set(RULE_DOCS))


def said(text: str, locale: str) -> str:
    """A text of the page in ``locale``: the catalogue's translation, else the English."""
    return text if locale == "en" else translate(text, locale, domain=DOMAIN)


def untranslated_parts(code: str, locale: str = "zh-cn") -> list[str]:
    """The parts of a rule's documentation (and its severity note) the catalogue of
    ``locale`` does not say yet."""
    doc = RULE_DOCS[code]
    texts = part_texts(doc)
    if doc.severity_note:
        texts["severity_note"] = doc.severity_note
    # A part that is only a code block is the same in every language.
    return [
        name
        for name, text in texts.items()
        if said(text, locale) == text and re.sub(r"```.*?```", "", text, flags=re.S).strip()
    ]


def section(info: RuleInfo, doc: RuleDoc, locale: str = "en") -> str:
    severity = said(info.severity.value, locale)
    if doc.severity_note:
        note = said(doc.severity_note, locale)
        severity += f"; {note}" if note == doc.severity_note else f"；{note}"
    lines = [f"## {info.code} {info.name}", "", f"**{said('Severity:', locale)}** {severity}", ""]
    texts = part_texts(doc)
    for name, label in PARTS:
        text = said(texts[name], locale)
        # A part that opens with a code block starts on its own line after the label.
        gap = "\n\n" if text.startswith("```") else " "
        lines.append(f"**{said(label, locale)}**" + gap + text)
        lines.append("")
    return "\n".join(lines)


def said_intro(intro: str, locale: str) -> str:
    """The intro in ``locale``: each paragraph translated, the code blocks as they are."""
    if locale == "en":
        return intro.rstrip("\n")
    return "\n\n".join(
        p if p.startswith("```") else said(p, locale) for p in intro_paragraphs(intro)
    )


def render(intro: str, locale: str = "en") -> str:
    """The text of docs/rules.md (or, for a locale with a page, of its page): the intro, then
    each registered rule's section."""
    missing = missing_docs()
    if missing:
        raise ValueError(
            f"codes registered without a RuleDoc, or documented unregistered: {missing}"
        )
    locale = page_locale(locale)
    sections = [section(RULES[code], RULE_DOCS[code], locale) for code in sorted(RULES)]
    head = GENERATED if locale == "en" else GENERATED_TRANSLATED
    return head + said_intro(intro, locale) + "\n\n" + "\n".join(sections)
