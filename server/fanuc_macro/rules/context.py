"""What a rule sees: the document, its program index, the workspace and the settings."""

from __future__ import annotations

from bisect import bisect_left
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple, TypeVar, cast

from ..config import Config
from ..diagnostics import Diagnostic, Fix
from ..evaluator.checkpoints import lines_with_other_facts, stretches_of
from ..evaluator.facts import DocumentFacts, Facts, Finding
from ..line_maps import Diff, line_diff
from ..program.arguments import LocalsNamed, locals_named
from ..program.index import Program, ProgramIndex
from ..syntax.tree import Block, Document, ParsedLine, Statement

if TYPE_CHECKING:
    from ..program.meanings import Meaning
    from ..threads.identify import Thread

F = TypeVar("F", bound=Finding)


def _position_in_run(indexed: tuple[int, Finding]) -> int:
    return indexed[0]


@dataclass(frozen=True, eq=False, repr=False)
class RuleContext:
    doc: Document
    index: ProgramIndex
    config: Config = field(default_factory=Config)
    # Program numbers defined anywhere in the workspace (None: only this file is known).
    workspace_programs: frozenset[int] | None = None
    facts: Facts | None = None  # the evaluator's, when it ran
    # The workspace's other files, as the evaluator got them: the programs this one calls.
    other_documents: Sequence[tuple[str, Document, ProgramIndex]] = ()
    # What several rules derive from the same facts, worked out once per analysis.
    memo: dict[str, object] = field(default_factory=dict, compare=False, repr=False)

    def program_numbered(self, number: int) -> tuple[Document, Program] | None:
        """The program ``number`` and its document: this file's, else another file's."""
        found = self.index.by_number(number)
        if found is not None:
            return self.doc, found
        for _uri, doc, index in self.other_documents:
            found = index.by_number(number)
            if found is not None:
                return doc, found
        return None

    def locals_named(
        self, doc: Document, program: Program, with_subprograms: bool = True
    ) -> LocalsNamed | None:
        """:func:`fanuc_macro.program.arguments.locals_named`, once per program in an analysis
        (the call rules and the argument checks ask of the same programs)."""
        key = f"locals {id(doc)} {program.first_line} {with_subprograms}"
        if key not in self.memo:
            self.memo[key] = locals_named(doc, program, with_subprograms)
        return cast("LocalsNamed | None", self.memo[key])

    def doc_facts(self) -> DocumentFacts | None:
        return None if self.facts is None else self.facts.by_uri.get(self.doc.uri)

    def roles(self) -> dict[tuple[int, int], Meaning]:
        """What comments and known parameter tables say each variable is
        (:func:`fanuc_macro.program.meanings.variable_roles`)."""
        found = self.memo.get("roles")
        if found is None:
            from ..program.meanings import variable_roles

            found = self.memo["roles"] = variable_roles(self.doc, self.index)
        return cast("dict[tuple[int, int], Meaning]", found)

    def undecided_programs(self) -> frozenset[int]:
        """The first lines of the programs with a jump or loop whose outcome the evaluator did
        not decide: one pass over the jumps for all the programs' questions."""
        found = self.memo.get("undecided")
        if found is None:
            facts = self.doc_facts()
            undecided: set[int] = set()
            for line, count in facts.jumps.items() if facts is not None else ():
                if count.undecided:
                    program = self.index.program_at(line)
                    if program is not None:
                        undecided.add(program.first_line)
            found = self.memo["undecided"] = frozenset(undecided)
        return cast("frozenset[int]", found)

    def threads(self) -> list[Thread]:
        """The threads this document's programs cut (:mod:`fanuc_macro.threads.identify`)."""
        found = self.memo.get("threads")
        if found is None:
            from ..threads.identify import identify

            facts = self.doc_facts()
            found = self.memo["threads"] = (
                []
                if facts is None or self.facts is None
                else identify(
                    self.doc,
                    self.index,
                    facts,
                    self.facts.motions,
                    self.facts.run_values,
                    self.roles(),
                )
            )
        return cast("list[Thread]", found)

    def findings(self, *kinds: type[F]) -> Iterator[F]:
        """The evaluator's findings in this document of the classes ``kinds`` (or their
        subclasses), in the order the run found them; not the cuts without F
        (:class:`~fanuc_macro.evaluator.facts.FeedNotSet`), which
        :meth:`DocumentFacts.feedless` gives by program."""
        by_kind = self.memo.get("findings by kind")
        if by_kind is None:
            # Grouped once per analysis: a dozen rules ask.
            facts = self.doc_facts()
            grouped: dict[type[Finding], list[tuple[int, Finding]]] = {}
            for i, finding in enumerate(facts.reported if facts is not None else ()):
                grouped.setdefault(type(finding), []).append((i, finding))
            by_kind = self.memo["findings by kind"] = grouped
        groups = cast("dict[type[Finding], list[tuple[int, F]]]", by_kind)
        chosen = [found for kind, found in groups.items() if issubclass(kind, kinds)]
        if len(chosen) == 1:
            for _, finding in chosen[0]:
                yield finding
        elif chosen:
            for _, finding in sorted((f for found in chosen for f in found), key=_position_in_run):
                yield finding

    def statements(self) -> Iterator[tuple[Block, Statement]]:
        """Every statement with its block; a mixed block gives its NC and macro parts."""
        from ..syntax.parser import statements_of

        for block in self.doc.blocks:
            for statement in statements_of(block.statement):
                yield block, statement


Check = Callable[[RuleContext], Iterable[Diagnostic]]


class Seen:
    """The version of a document and the evaluator's facts an analysis read: what a rule that
    keeps its findings from one analysis to the next keeps, to learn at the next one which
    lines may give other findings (:meth:`changes`)."""

    __slots__ = ("config", "doc", "facts", "stretches")

    def __init__(self, ctx: RuleContext) -> None:
        self.doc = ctx.doc
        self.config = ctx.config
        self.facts = ctx.doc_facts()
        self.stretches = None if ctx.facts is None else stretches_of(ctx.facts, ctx.doc.uri)

    def changes(self, ctx: RuleContext) -> Changes | None:
        """The lines of ``ctx``'s document whose text or facts may differ from this version's
        (None: not known, or most of them); worked out once per analysis for the rules that
        saw the same version."""
        memo = cast("dict[tuple[int, int, int], Changes | None]", ctx.memo.setdefault("seen", {}))
        key = (id(self.doc), id(self.facts), id(self.config))  # alive while self is
        if key not in memo:
            memo[key] = self._changes(ctx)
        return memo[key]

    def _changes(self, ctx: RuleContext) -> Changes | None:
        if self.config is not ctx.config and self.config != ctx.config:
            return None
        diff = line_diff(self.doc, ctx.doc)
        facts = ctx.doc_facts()
        if facts is None or self.facts is None:
            return None
        if facts is self.facts:
            if diff.shift:
                return None  # the facts of other line numbers: a workspace never keeps them
            fact_lines: set[int] = set()
        else:
            stretches = None if ctx.facts is None else stretches_of(ctx.facts, ctx.doc.uri)
            if stretches is None or self.stretches is None:
                return None
            fact_lines = lines_with_other_facts(self.stretches, stretches, diff)
        changes = Changes(diff, fact_lines, len(ctx.doc.blocks))
        if len(changes.sorted) > len(ctx.doc.blocks) // 2:
            return None  # most of the document: a fresh look costs less
        return changes


class Changes:
    """Where a version of a document may give other findings than an earlier one: the lines
    (new numbers) whose text changed, with one line on either side (a block removed joins its
    neighbours), and those whose facts may differ; ``diff`` says how the old lines moved."""

    __slots__ = ("diff", "lines", "sorted", "text_end", "text_start")

    def __init__(self, diff: Diff, fact_lines: set[int], lines: int) -> None:
        self.diff = diff
        if diff.start < diff.end or diff.start < diff.old_end:
            self.text_start, self.text_end = max(0, diff.start - 1), min(lines, diff.end + 1)
        else:
            self.text_start = self.text_end = 0
        self.lines = fact_lines.union(range(self.text_start, self.text_end))
        self.sorted = sorted(self.lines)

    def moved_end(self, end: int) -> int | None:
        """An old exclusive end line's new number."""
        diff = self.diff
        return end if end <= diff.start else diff.moved(end)

    def within(self, first: int, end: int) -> list[int]:
        """The changed lines from ``first`` to before ``end``, ascending."""
        found = self.sorted
        return found[bisect_left(found, first) : bisect_left(found, end)]


class LineFinding(NamedTuple):
    """A diagnostic that depends on one line's text alone, without its line number: the
    analysis computes it once per distinct line and keeps it while the line is unchanged."""

    code: str
    message: str
    start: int
    end: int
    fixes: tuple[Fix, ...] = ()  # their edits on line 0: the analysis puts them on the block's


LineCheck = Callable[[ParsedLine], Iterable[LineFinding]]


def line_statements(parsed: ParsedLine) -> Sequence[Statement]:
    from ..syntax.parser import statements_of

    return statements_of(parsed.statement)
