"""Completion: variables, G and M codes, functions, keywords, snippets and the thread module."""

from __future__ import annotations

import json
import re
from importlib import resources

from .. import database
from ..config import Config
from ..database import TableKey
from ..program import knowledge
from ..program.variables import classify
from ..syntax.lines import cut_comments
from ..translation import tr
from .data import CompletionItem, CompletionKind, CompletionList, Range
from .locate import number_of, uses
from .thread_completion import thread_insertions, trigger_for
from .values import variable_kind
from .view import View, comment_of, lines_of

# What is being typed: a variable (#51), letters with the digits after them (SQ, G9, GOTO1), or
# the Chinese word for thread (螺纹, 螺紋) that finds the thread module.
_PREFIX = re.compile(r"#\d*$|[A-Za-z]+\d*\.?\d*$|[\u87ba\u7eb9\u7d0b]+$")
_CODE_PREFIX = re.compile(r"([GgMm])(\d*\.?\d*)$")

NOTHING = CompletionList(())


# The snippets, read once per database from the package's data.
_SNIPPETS: TableKey[str, tuple[tuple[str, str, str, str], ...]] = TableKey(
    "ide.completion.snippets"
)


def snippets() -> tuple[tuple[str, str, str, str], ...]:
    """(prefix, name, description, body) of the extension's snippets, shipped with the package."""
    read = database.current().table(_SNIPPETS)
    found = read.get("snippets")
    if found is None:
        found = read["snippets"] = _read_snippets()
    return found


def _read_snippets() -> tuple[tuple[str, str, str, str], ...]:
    try:
        raw = (resources.files("fanuc_macro") / "data" / "fanuc-macro.code-snippets").read_text(
            "utf-8"
        )
        data = json.loads(raw)
    except (OSError, ValueError):
        return ()
    out: list[tuple[str, str, str, str]] = []
    if not isinstance(data, dict):
        return ()
    for name, entry in data.items():
        if not isinstance(entry, dict):
            continue
        prefixes = entry.get("prefix")
        body = entry.get("body")
        if isinstance(prefixes, str):
            prefixes = [prefixes]
        if isinstance(body, list):
            body = "\n".join(str(b) for b in body)
        if not isinstance(prefixes, list) or not isinstance(body, str):
            continue
        for prefix in prefixes:
            out.append((str(prefix), str(name), str(entry.get("description", "")), body))
    return tuple(out)


def completion(
    line_text: str,
    line: int,
    column: int,
    config: Config,
    view: View | None = None,
    *,
    snippets_supported: bool = False,
    has_snippets: bool = False,
    eol: str = "\n",
) -> CompletionList:
    """What may be typed at ``column`` (code points) of ``line_text``, the text of ``line``.

    ``snippets_supported``: the front end can insert placeholders (``SQRT[$1]``);
    ``has_snippets``: it has the package's snippets already (the VS Code extension). ``view``,
    the newest analysis there is, of the same lines, adds the program's variables and the
    thread module; ``eol`` is the document's line end, for the lines the module inserts.
    """
    before = line_text[:column]
    for comment in cut_comments(line_text).comments:
        if comment.span.start < column and (column < comment.span.end or not comment.closed):
            return NOTHING  # typing a comment
    prefix = _PREFIX.search(before)
    start = prefix.start() if prefix is not None else column
    word = before[start:]
    edit_range = Range.of(line, start, line, column)
    items: list[CompletionItem] = []

    def add(
        label: str,
        kind: CompletionKind,
        detail: str,
        new_text: str,
        documentation: str = "",
        sort: str = "5",
        snippet: bool = False,
    ) -> None:
        items.append(
            CompletionItem(
                label=label,
                kind=kind,
                detail=detail,
                documentation=documentation,
                insert_text=new_text,
                snippet=snippet,
                sort_text=f"{sort}{label}",
                filter_text=label,
                replace=edit_range,
            )
        )

    if word.startswith("#"):
        if view is not None:
            for number, note in _program_variables(view, line):
                add(
                    f"#{number}",
                    CompletionKind.VARIABLE,
                    note or variable_kind(number),
                    f"#{number}",
                    sort="0",
                )
        for number in knowledge.SYSTEM_VARIABLES:
            add(
                f"#{number}",
                CompletionKind.VARIABLE,
                classify(number).meaning,
                f"#{number}",
                sort="1",
            )
        return CompletionList(_unique(items))
    code_prefix = _CODE_PREFIX.fullmatch(word)
    lathe = config.is_lathe
    codes = knowledge.completion_codes(lathe, config.g_code_system)
    if code_prefix is not None:
        letter = code_prefix.group(1).upper()
        for name, title in codes:
            if name.startswith(letter):
                value = float(name[1:])
                add(
                    name,
                    CompletionKind.CODE,
                    title,
                    name,
                    knowledge.code_markdown(
                        letter, value, lathe, config.g_code_system, config.machine_known
                    )
                    or "",
                    sort="0",
                )
        if letter == "M":
            items.extend(_thread_items(view, line, word, edit_range, eol))
        return CompletionList(tuple(items))
    for info in knowledge.FUNCTIONS.values():
        add(
            info.name,
            CompletionKind.FUNCTION,
            tr("{signature} — {title}", signature=info.signature, title=info.title),
            info.snippet if snippets_supported else f"{info.name}[]",
            knowledge.function_markdown(info.name) or "",
            sort="1",
            snippet=snippets_supported,
        )
    for name, (title, text) in knowledge.KEYWORDS.items():
        add(name, CompletionKind.KEYWORD, title, name, text, sort="2")
    if snippets_supported and not has_snippets:
        for prefix_text, name, description, body in snippets():
            add(
                prefix_text,
                CompletionKind.SNIPPET,
                f"{name} — {description}",
                body,
                f"```\n{body}\n```",
                sort="3",
                snippet=True,
            )
    if not word or word[:1].upper() in ("G", "M"):
        for name, title in codes:
            add(name, CompletionKind.CODE, title, name, sort="4")
    items.extend(_thread_items(view, line, word, edit_range, eol))
    return CompletionList(tuple(items))


def _thread_items(
    view: View | None, line: int, word: str, edit_range: Range, eol: str
) -> list[CompletionItem]:
    """The thread module into the program at ``line``, found by "thread", "M98" or "螺纹"."""
    trigger = trigger_for(word)
    if view is None or trigger is None:
        return []
    return [
        CompletionItem(
            label=tr("thread module {title}", title=found.title),
            kind=CompletionKind.SNIPPET,
            detail=tr(
                "symmetric thread module (G92, left-right): the call here, the sub-program "
                "after this program"
            ),
            documentation=found.preview,
            insert_text=found.at_cursor,
            filter_text=trigger,
            sort_text="0",
            replace=edit_range,
            additional_edits=(found.sub_program,),
        )
        # Both kinds when the program does not tell an external thread from an internal one.
        for found in thread_insertions(view, line, eol)
    ]


def _unique(items: list[CompletionItem]) -> tuple[CompletionItem, ...]:
    seen: set[str] = set()
    out: list[CompletionItem] = []
    for item in items:
        if item.label not in seen:
            seen.add(item.label)
            out.append(item)
    return tuple(out)


def _program_variables(view: View, line: int) -> list[tuple[int, str]]:
    """Variables the program at ``line`` uses, with the comment of an assignment."""
    program = view.index.program_at(min(line, max(0, len(view.doc.blocks) - 1)))
    first, end = lines_of(program, view.doc)
    found: dict[int, str] = {}
    for use in uses(view.doc.blocks, first, end):
        n = number_of(use.var)
        if n is None:
            continue
        comment = comment_of(view.doc.blocks[use.line]) if use.assign is not None else ""
        if n not in found or (comment and not found[n]):
            found[n] = comment
    return sorted(found.items())
