"""Keeps the gettext catalogues in step with the sources, with Babel.

    python3 scripts/catalogues.py           # updates every locale's .po files
    python3 scripts/catalogues.py --check   # exits 1, saying which, if one is stale
    python3 scripts/catalogues.py --report  # how much of each catalogue is translated

Two domains, each a .po file per locale under server/fanuc_macro/data/locale/<dir>/LC_MESSAGES/:
``messages``, the texts the package says (extracted from the sources' ``tr("...")`` and
``tr_n("...", "...", n)`` calls, and each rule's summary), and ``rules_doc``, the rules'
documentation (each part of each rule's RuleDoc, the severity notes, the labels and the
paragraphs of docs/rules-intro.md). An update keeps every translation whose message id is still
in the sources and drops the others; entries stand in the order the sources give them, without
line numbers, so a change to a source moves only its own entries.
The package is read from this checkout's server/, whatever is installed.
"""

from __future__ import annotations

import argparse
import io
import sys
from collections.abc import Iterator
from pathlib import Path

from babel.messages.catalog import Catalog
from babel.messages.extract import extract_from_dir
from babel.messages.pofile import read_po, write_po

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "server" / "fanuc_macro"
LOCALE_DIR = PACKAGE / "data" / "locale"
KEYWORDS = {"tr": None, "tr_n": (1, 2)}
# The catalogues kept, by domain: gettext's directory -> Babel's locale. The rules'
# documentation is in Chinese only (the Japanese catalogue has the messages).
CATALOGUES = {
    "messages": {"zh_CN": "zh_Hans_CN", "ja": "ja"},
    "rules_doc": {"zh_CN": "zh_Hans_CN"},
}


def source_messages() -> Iterator[tuple[str | tuple[str, str], str]]:
    """The ``messages`` domain's ids, in the sources' order, with the file each comes from."""
    for filename, _line, message, _comments, _context in extract_from_dir(
        str(PACKAGE), method_map=[("**.py", "python")], keywords=KEYWORDS
    ):
        yield message, f"server/fanuc_macro/{filename}"
    sys.path.insert(0, str(ROOT / "server"))
    from fanuc_macro.analysis import RULES

    for code in sorted(RULES):
        yield RULES[code].summary, f"rule:{code}"


def doc_messages() -> Iterator[tuple[str | tuple[str, str], str]]:
    """The ``rules_doc`` domain's ids: the generator's own texts, then each rule's."""
    sys.path.insert(0, str(ROOT / "server"))
    from fanuc_macro.rules_doc import translatable_texts

    yield from translatable_texts((ROOT / "docs" / "rules-intro.md").read_text("utf-8"))


def template(domain: str) -> Catalog:
    catalog = Catalog(project="fanuc-macro", version="", charset="utf-8", fuzzy=False)
    found = source_messages() if domain == "messages" else doc_messages()
    for message, where in found:
        if not message:
            continue
        key = message[0] if isinstance(message, tuple) else message
        existing = catalog.get(key)
        if existing is not None:
            if (where, None) not in existing.locations:
                existing.locations.append((where, None))
            continue
        flags = ["python-brace-format"] if "{" in key else []
        catalog.add(message, locations=[(where, None)], flags=flags)
    return catalog


def updated(directory: str, locale: str, domain: str, pot: Catalog) -> tuple[Path, str]:
    path = LOCALE_DIR / directory / "LC_MESSAGES" / f"{domain}.po"
    old = read_po(path.open("rb")) if path.exists() else None
    catalog = Catalog(locale=locale, project="fanuc-macro", version="", fuzzy=False)
    for message in pot:
        if not message.id:
            continue
        catalog.add(message.id, locations=message.locations, flags=message.flags)
        if old is not None:
            before = old.get(message.id[0] if isinstance(message.id, tuple) else message.id)
            if before is not None and before.string and not before.fuzzy:
                catalog[catalog_key(message.id)].string = before.string
    out = io.BytesIO()
    write_po(out, catalog, width=100, include_lineno=False, omit_header=False, sort_output=False)
    text = out.getvalue().decode("utf-8")
    # The header's dates, year and Babel's version change without the messages changing.
    lines = [line for line in text.splitlines() if not line.startswith(_CHANGING_HEADER)]
    return path, "\n".join(lines) + "\n"


_CHANGING_HEADER = (
    '"POT-Creation-Date',
    '"PO-Revision-Date',
    '"Generated-By',
    "# Copyright (C)",
    "# FIRST AUTHOR",
)


def catalog_key(message_id: str | tuple[str, ...]) -> str:
    return message_id[0] if isinstance(message_id, tuple) else message_id


def report(path: Path) -> str:
    catalog = read_po(path.open("rb"))
    total = sum(1 for m in catalog if m.id)
    done = sum(1 for m in catalog if m.id and m.string and not m.fuzzy and all(_forms(m.string)))
    return f"{path.relative_to(ROOT)}: {done}/{total} translated"


def _forms(string: str | tuple[str, ...]) -> tuple[str, ...]:
    return string if isinstance(string, tuple) else (string,)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if a catalogue is stale")
    parser.add_argument("--report", action="store_true", help="how much is translated")
    args = parser.parse_args(argv)
    stale = []
    for domain, catalogues in CATALOGUES.items():
        pot = template(domain)
        for directory, locale in catalogues.items():
            path, text = updated(directory, locale, domain, pot)
            current = path.read_text("utf-8") if path.exists() else ""
            if args.report:
                print(report(path) if path.exists() else f"{path}: missing")
            elif current != text:
                stale.append(path)
                if not args.check:
                    path.parent.mkdir(parents=True, exist_ok=True)
                    path.write_text(text, "utf-8")
    if args.check and stale:
        for path in stale:
            print(f"{path.relative_to(ROOT)} is stale: run python3 scripts/catalogues.py")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
