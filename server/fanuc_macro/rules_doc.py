"""docs/rules.md, written from docs/rules-intro.md and the ``RuleDoc`` beside each rule's function.

The intro holds the general sections (the families, suppressing and disabling a rule, how the
evaluator runs a program, how the threading rules know the thread); then comes one section per
registered code, in code order, headed ``## MBxxx name``: the language server links each
diagnostic to that heading's anchor (lsp/convert.py), so the heading form must not change.
``scripts/rules_doc.py`` writes the file or, with ``--check``, says whether it is stale.
"""

from __future__ import annotations

from .analysis import RULE_DOCS, RULES
from .diagnostics import RuleDoc, RuleInfo

GENERATED = """\
<!-- Generated: do not edit. Each rule's section comes from the RuleDoc beside its registration
(server/fanuc_macro/rules/*.py, MB000 in analysis.py), the sections before them from
docs/rules-intro.md. Edit those, then run `python3 scripts/rules_doc.py`. -->

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


def rule_url(code: str) -> str:
    """The section of docs/rules.md: headings are ``MBxxx name``, anchors ``mbxxx-name``."""
    info = RULES.get(code)
    anchor = code.lower() if info is None else f"{code.lower()}-{info.name}"
    return f"{RULES_URL}#{anchor}"


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
    for code in sorted(RULE_DOCS):
        doc = RULE_DOCS[code]
        texts += [(text, code) for text in part_texts(doc).values()]
        if doc.severity_note:
            texts.append((doc.severity_note, code))
    return texts


def missing_docs() -> list[str]:
    """The registered codes without documentation, and the documented codes not registered."""
    return sorted(set(RULES) ^ set(RULE_DOCS))


def section(info: RuleInfo, doc: RuleDoc) -> str:
    severity = info.severity.value + (f"; {doc.severity_note}" if doc.severity_note else "")
    lines = [f"## {info.code} {info.name}", "", f"**Severity:** {severity}", ""]
    texts = part_texts(doc)
    for name, label in PARTS:
        text = texts[name]
        # A part that opens with a code block starts on its own line after the label.
        lines.append(f"**{label}**" + ("\n\n" if text.startswith("```") else " ") + text)
        lines.append("")
    return "\n".join(lines)


def render(intro: str) -> str:
    """The text of docs/rules.md: the intro, then each registered rule's section."""
    missing = missing_docs()
    if missing:
        raise ValueError(
            f"codes registered without a RuleDoc, or documented unregistered: {missing}"
        )
    sections = [section(RULES[code], RULE_DOCS[code]) for code in sorted(RULES)]
    return GENERATED + intro.rstrip("\n") + "\n\n" + "\n".join(sections)
