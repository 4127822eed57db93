"""MB015: suppression comments, what they hide, and those that hide nothing.

A comment ``(fanuc-macro: ignore MB301)`` hides codes on its line, ``ignore-file`` in the whole
file, ``ignore-start`` to the next ``ignore-end`` over a stretch of lines
(:func:`..diagnostics.suppression_in`). The analysis applies them after every rule ran
(:class:`Hidden`), and reports a comment that hid nothing (MB015), as ruff reports an unused
``noqa`` (RUF100): a suppression left after its finding went hides the next mistake of its
kind."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

from ..diagnostics import (
    END,
    FILE,
    LINE,
    START,
    Diagnostic,
    Fix,
    FixEdit,
    RuleDoc,
    RuleInfo,
    Severity,
    Tag,
    make,
    suppression_in,
)
from ..syntax.tree import ParsedLine
from ..translation import tr

FAMILY = "suppression"

# fmt: off
MB015 = RuleInfo("MB015", "unused-suppression", Severity.HINT,
                 "A suppression comment that hides nothing: no diagnostic of its codes is there.",
                 FAMILY, frozenset({Tag.UNNECESSARY}))
# fmt: on

ALL = "*"


@dataclass(frozen=True, slots=True)
class Mark:
    """One suppression comment: where it acts, the codes it names (none: every code), and
    its columns on its line."""

    where: str
    codes: frozenset[str]
    column: int
    end_column: int


Marks = tuple[Mark, ...]


def marks_of(parsed: ParsedLine) -> Marks | None:
    """The suppression comments of a line, None when it has none."""
    found: list[Mark] = []
    for comment in parsed.comments:
        if "ignore" not in comment.text.lower():
            continue
        mark = suppression_in(comment.text)
        if mark is not None:
            found.append(Mark(mark[0], mark[1], comment.span.start, comment.span.end))
    return tuple(found) or None


@dataclass
class _Scope:
    """Where one comment hides its codes: lines ``first`` to ``last``; what it hid."""

    line: int  # the comment's
    mark: Mark
    first: int
    last: int
    hid: set[str] = field(default_factory=set)

    def hides(self, line: int, code: str) -> bool:
        codes = self.mark.codes
        if self.first <= line <= self.last and (not codes or code in codes):
            self.hid.add(code)
            return True
        return False


class Hidden:
    """What a document's suppression comments hide, and which of them hid something."""

    def __init__(self, marks: dict[int, Marks]) -> None:
        self.scopes: list[_Scope] = []
        self.by_line: dict[int, list[_Scope]] = {}
        open_from: list[_Scope] = []  # the ignore-start comments not ended yet
        self.ends: list[tuple[int, Mark, list[_Scope]]] = []
        for line in sorted(marks):
            for mark in marks[line]:
                if mark.where == END:
                    ended = [s for s in open_from if not mark.codes or s.mark.codes & mark.codes]
                    for scope in ended:
                        scope.last = line
                        open_from.remove(scope)
                    self.ends.append((line, mark, ended))
                    continue
                first, last = (0, 1 << 62) if mark.where == FILE else (line, line)
                scope = _Scope(line, mark, first, last if mark.where != START else 1 << 62)
                self.scopes.append(scope)
                if mark.where == LINE:
                    self.by_line.setdefault(line, []).append(scope)
                if mark.where == START:
                    open_from.append(scope)
        self.wide = [s for s in self.scopes if s.mark.where != LINE]

    def hides(self, line: int, code: str) -> bool:
        """Whether a comment hides ``code`` on ``line`` (each one that does is marked used)."""
        found = False
        for scope in self.by_line.get(line, ()):
            found |= scope.hides(line, code)
        for scope in self.wide:
            found |= scope.hides(line, code)
        return found

    def unused(self, judged: frozenset[str] | None) -> Iterator[Diagnostic]:
        """MB015 for each comment that hid none of its codes, or some of them not: of the
        codes ``judged`` says a rule ran for (None: every code)."""
        for scope in self.scopes:
            yield from _unused_scope(scope, judged)
        for line, mark, ended in self.ends:
            if not ended:
                yield _unused(line, mark, tr("ends no ignore-start before it"), remove=True)


def _unused_scope(scope: _Scope, judged: frozenset[str] | None) -> Iterator[Diagnostic]:
    mark, line = scope.mark, scope.line
    where = {
        LINE: tr("on this line"),
        FILE: tr("in this file"),
        START: tr("up to its ignore-end"),
    }[mark.where]
    if not mark.codes:
        if not scope.hid:
            told = tr("hides nothing {where}: no diagnostic is there", where=where)
            yield _unused(line, mark, told, True)
        return
    idle = sorted(c for c in mark.codes - scope.hid if judged is None or c in judged)
    if not idle:
        return
    remove = len(idle) == len(mark.codes)
    what = ", ".join(idle)
    told = (
        tr("hides nothing {where}: no {codes} is reported there", where=where, codes=what)
        if remove
        else tr(
            "hides nothing {where}: no {codes} is reported there; take {codes} out of it",
            where=where,
            codes=what,
        )
    )
    yield _unused(line, mark, told, remove)


MB015_DOC = RuleDoc(
    "MB015",
    reports="""
A suppression comment, `(fanuc-macro: ignore MBxxx)`, `ignore-file`, `ignore-start` or
`ignore-end`, that hides no diagnostic: none of the codes it names is reported where it acts,
or an `ignore-end` that ends no `ignore-start`. A comment naming several codes is reported
for those that hide nothing. Each message quotes the comment and says where it acts.
""",
    why="""
A suppression outlives the finding it was written for: once the block is corrected, the
comment stays, and hides the next mistake of that kind on that line (or in that file) from
every check, before the program reaches the machine.
""",
    example="""
```nc
O1000
#1=SIN[30.] (fanuc-macro: ignore MB301)
M30
```

Nothing on line 2 gives MB301 (brackets nested too deep): the comment hides nothing.
""",
    fix="""
Remove the comment (the quick fix does, and `fanuc-macro check --fix` applies it), or take the
codes that hide nothing out of it.
""",
    not_reported="""
A comment when the analysis did not run the whole program (the safety net stopped it, or a rule
failed), nor codes whose rules are turned off or not selected: whether they would hide
something is not known. A comment of another tool is not one of these.
""",
)


def _unused(line: int, mark: Mark, told: str, remove: bool) -> Diagnostic:
    kind = "ignore" if mark.where == LINE else f"ignore-{mark.where}"
    codes = " ".join(sorted(mark.codes))
    comment = f"(fanuc-macro: {kind}{' ' + codes if codes else ''})"
    fixes = (
        (
            Fix(
                tr("Remove the suppression comment"),
                (FixEdit(line, mark.column, line, mark.end_column, ""),),
                True,
                True,
            ),
        )
        if remove
        else ()
    )
    message = tr("{comment} {told}", comment=comment, told=told)
    return make(MB015, message, line, mark.column, mark.end_column, fixes=fixes)
