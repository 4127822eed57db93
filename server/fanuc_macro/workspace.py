"""A set of program files analysed together, so that calls between them resolve."""

from __future__ import annotations

import functools
import threading
from collections.abc import Callable, Iterable, Mapping, Sequence
from collections.abc import Set as AbstractSet
from dataclasses import dataclass, replace
from typing import Concatenate, ParamSpec, TypeVar

from .analysis import Analysis, analyse, keep_caches_within_budget
from .cancel import CancelToken
from .config import Config
from .database import Database
from .evaluator import Facts
from .program.index import Call, ProgramIndex, build_index, index_after_edit
from .program.machine_kind import callers_machine, machine_config, mill_reading
from .program_files import PROGRAM_SUFFIXES as PROGRAM_SUFFIXES  # for the server, the debugger
from .program_files import is_program_file as is_program_file
from .syntax.diff import line_diff
from .syntax.lines import BINARY, ReadLimits, decode_bytes
from .syntax.parser import BlockParser, default_parser, parse_text, quiet_gc
from .syntax.tree import Document


@dataclass(eq=False, repr=False)
class _Entry:
    text: str
    doc: Document
    index: ProgramIndex
    encoding: str
    decode_note: str | None
    # Changes when an edit may change what the program does; not for comments and spaces.
    execution: int = 0
    limits: ReadLimits | None = None  # those the document was read with


def same_execution(old: Document, new: Document) -> bool:
    """Whether two versions of a document run the same: an edit in comments or spaces only.

    Lines an edit did not touch keep their block (the ``is`` test); a touched line counts as
    the same when its statement, label, block delete, tape mark and the variable a block that
    does not parse plainly assigns (``#9=#5*0.[#7]`` sets #9 all the same) are equal.
    """
    if len(old.blocks) != len(new.blocks) or old.unread_from != new.unread_from:
        return False
    diff = line_diff(old, new)  # the lines outside it are the same
    x, y = old.blocks, new.blocks
    for line in range(diff.start, diff.end):
        a, b = x[line], y[line]
        if a is b:
            continue
        p, q = a.parsed, b.parsed
        if (
            p.statement != q.statement
            or p.seq != q.seq
            or p.skip != q.skip
            or p.tape_mark != q.tape_mark
            or p.failed_assignment != q.failed_assignment
            or (p.problem is None) != (q.problem is None)
        ):
            return False
    return True


# Another document an analysis reads: its URI, its syntax tree and its index.
OtherDocument = tuple[str, Document, ProgramIndex]

P = ParamSpec("P")
R = TypeVar("R")


def _in_database(
    method: Callable[Concatenate[Workspace, P], R],
) -> Callable[Concatenate[Workspace, P], R]:
    """Run a workspace's method inside its database (:meth:`Database.active`): what it derives
    (parsed lines, line maps, what rules keep) is the workspace's."""

    @functools.wraps(method)
    def in_database(self: Workspace, /, *args: P.args, **kwargs: P.kwargs) -> R:
        with self.db.active():
            return method(self, *args, **kwargs)

    return in_database


class Workspace:
    """The documents analysed together, and the database (:mod:`fanuc_macro.database`) that
    owns every value derived from them."""

    def __init__(
        self,
        config: Config | None = None,
        parser: BlockParser | None = None,
        db: Database | None = None,  # the language server makes it before the workspace
        keep_runs: bool = True,
    ) -> None:
        """``keep_runs``: keep each analysis's run to reuse or resume after an edit (an
        editor's); a command that analyses each document once (``check``) does not, so that
        its memory does not grow with the files."""
        self.config = config or Config()
        self.keep_runs = keep_runs
        self.db = db or Database()
        with self.db.active():
            self.parser = parser or default_parser()
        self._entries: dict[str, _Entry] = {}
        self._executions = 0
        # uri -> (the config, the executions of the documents run, the evaluator's facts)
        self._facts: dict[str, tuple[Config, tuple[tuple[str, int], ...], Facts]] = {}
        # The same for the mill's reading of a document whose machine is not known.
        self._mill_facts: dict[str, tuple[Config, tuple[tuple[str, int], ...], Facts]] = {}
        # Every document's (document, index): replaced on each change, never changed, so that
        # another thread (the language server's requests) may read the one it got.
        self._indexes: dict[str, tuple[Document, ProgramIndex]] = {}
        # The program graph of the current indexes, dropped when they change (it holds no
        # document: a closed one is freed with its snapshot).
        self._graph: ProgramGraph | None = None
        self._graph_lock = threading.Lock()

    def _reindexed(self, uri: str) -> None:
        indexes = dict(self._indexes)
        entry = self._entries.get(uri)
        if entry is None:
            indexes.pop(uri, None)
        else:
            indexes[uri] = (entry.doc, entry.index)
        with self._graph_lock:
            self._indexes = indexes
            self._graph = None

    def _next_execution(self) -> int:
        self._executions += 1
        return self._executions

    @_in_database
    def add_text(self, uri: str, text: str, cancel: CancelToken | None = None) -> Document:
        """Read a new text of ``uri``. Cancelled (see :mod:`fanuc_macro.cancel`), the workspace
        keeps the text it had: nothing is stored before the whole text is read."""
        old = self._entries.get(uri)
        limits = self.config.read_limits
        keep_caches_within_budget(self.parser)
        # The previous version's blocks are reused for the lines an edit did not touch.
        previous = old.doc if old is not None else None
        doc = parse_text(
            text,
            uri,
            self.parser,
            previous,
            limits,
            cancel,
            old.limits if old else None,
            old.text if old is not None else None,
        )
        if old is not None and same_execution(old.doc, doc):
            execution = old.execution
        else:
            execution = self._next_execution()
        index = index_after_edit(old.index, old.doc, doc) if old is not None else build_index(doc)
        self._entries[uri] = _Entry(text, doc, index, "utf-8", None, execution, limits)
        self._reindexed(uri)
        return doc

    @_in_database
    def add_bytes(self, uri: str, data: bytes) -> Document:
        decoded = decode_bytes(data)
        limits = self.config.read_limits
        doc = parse_text(decoded.text, uri, self.parser, limits=limits)
        doc = replace(doc, encoding=decoded.encoding, decode_note=decoded.note)
        self._entries[uri] = _Entry(
            decoded.text,
            doc,
            build_index(doc),
            decoded.encoding,
            decoded.note,
            self._next_execution(),
            limits,
        )
        self._reindexed(uri)
        return doc

    @_in_database
    def set_config(self, config: Config) -> list[str]:
        """Analyse with ``config`` from now on; the documents it reads differently (another
        limit on lines, blocks or size) are read again. Returns their URIs."""
        self.config = config
        limits = config.read_limits
        reread: list[str] = []
        for uri, entry in self._entries.items():
            if entry.limits == limits:
                continue
            doc = parse_text(entry.text, uri, self.parser, entry.doc, limits)
            doc = replace(doc, encoding=entry.encoding, decode_note=entry.decode_note)
            entry.doc, entry.index, entry.limits = doc, build_index(doc), limits
            entry.execution = self._next_execution()
            self._reindexed(uri)
            reread.append(uri)
        return reread

    def remove(self, uri: str) -> None:
        """Forget ``uri`` (see :meth:`remove_all`)."""
        self.remove_all([uri])

    def remove_all(self, uris: Iterable[str]) -> None:
        """Forget each of ``uris``, and what the database derived from them: their tables'
        entries, and the shared caches and parsed lines, which may hold their lines (the
        other documents keep their own). The caches are dropped once, however many go."""
        gone = set(uris)
        for uri in gone:
            self._entries.pop(uri, None)
            self._facts.pop(uri, None)
            self._mill_facts.pop(uri, None)
        self.db.close_documents(gone)
        self.parser.clear_cache()
        with self._graph_lock:
            self._indexes = {u: i for u, i in self._indexes.items() if u not in gone}
            self._graph = None

    def not_text(self, uri: str) -> str | None:
        """Why the file ``uri`` was not read, when its bytes are not a program text (the
        MB007 note; ``syntax.lines.not_text_reason``); None for a text."""
        entry = self._entries.get(uri)
        return entry.decode_note if entry is not None and entry.encoding == BINARY else None

    def uris(self) -> list[str]:
        return list(self._entries)

    def document(self, uri: str) -> Document | None:
        entry = self._entries.get(uri)
        return entry.doc if entry else None

    def index(self, uri: str) -> ProgramIndex:
        return self._entries[uri].index

    def indexes(self) -> Mapping[str, tuple[Document, ProgramIndex]]:
        """Every document and its index, in workspace order: a snapshot that later changes
        replace and never change, so any thread may read it."""
        return self._indexes

    def has(self, uri: str) -> bool:
        return uri in self._entries

    def document_links(self, uri: str) -> DocumentLinks:
        """What of ``uri`` the program graph reads (:func:`document_links`)."""
        entry = self._entries[uri]
        return document_links(entry.doc, entry.index)

    @_in_database
    def links_of(self, uri: str, data: bytes) -> DocumentLinks:
        """:meth:`document_links` of the file ``uri`` of bytes ``data``, read as
        :meth:`add_bytes` reads it, without keeping it: how an archive's files are tied is
        known without holding them all (the parser keeps their lines within the caches'
        budget)."""
        keep_caches_within_budget(self.parser)
        doc = parse_text(decode_bytes(data).text, uri, self.parser, limits=self.config.read_limits)
        return document_links(doc, build_index(doc))

    def order_as(self, uris: Sequence[str]) -> None:
        """Puts the documents in the order of ``uris`` (those it has; the others after)."""
        entries = {u: self._entries[u] for u in uris if u in self._entries}
        entries.update(self._entries)
        self._entries = entries
        indexes = {u: self._indexes[u] for u in entries if u in self._indexes}
        with self._graph_lock:
            self._indexes = indexes
            self._graph = None

    def graph(self) -> ProgramGraph:
        """The :func:`program_graph` of the current indexes, built once for them."""
        with self._graph_lock:  # a request's thread may ask while an edit replaces them
            graph = self._graph
            if graph is None:
                graph = self._graph = program_graph(self._indexes)
            return graph

    def links(self, uri: str) -> frozenset[tuple[str, int | None]]:
        """What ties ``uri`` to other documents: see :func:`program_links`."""
        entry = self._entries.get(uri)
        return frozenset() if entry is None else program_links(entry.doc, entry.index)

    def readers(self, uris: AbstractSet[str], of: Iterable[str]) -> list[str]:
        """Those of ``of`` (but ``uris``) whose analysis reads one of ``uris``
        (:func:`related_documents`)."""
        readers: list[str] = []
        indexes, graph = self._indexes, self.graph()
        for key in of:
            if key in uris or key not in indexes:
                continue
            needed = related_documents(key, indexes, self._custom_called(), graph)
            if needed is None or not uris.isdisjoint(needed):
                readers.append(key)
        return readers

    def others(self, uri: str) -> list[OtherDocument]:
        """The other documents an analysis of ``uri`` needs: see :func:`related_documents`."""
        indexes = self._indexes
        needed = related_documents(uri, indexes, self._custom_called(), self.graph())
        keys = [u for u in indexes if u != uri] if needed is None else needed
        return [(u, *indexes[u]) for u in keys]

    def _callers(self, uri: str) -> list[tuple[Document, ProgramIndex]]:
        """The other documents with a call of a program of ``uri`` (by number), in order."""
        indexes, graph = self._indexes, self.graph()
        keys: set[str] = set()
        for number in graph.defines.get(uri, frozenset()):
            keys |= graph.direct_callers.get(number, set())
        keys.discard(uri)
        return [indexes[k] for k in sorted(keys, key=graph.order.__getitem__)]

    def _custom_called(self) -> frozenset[int]:
        """The programs the settings' custom calls run (``M165`` -> O9022): any block of any
        document may call them, and the index holds none of those calls."""
        return frozenset(c.program for c in self.config.custom_calls)

    def program_numbers(self) -> frozenset[int]:
        return frozenset(
            p.number
            for entry in self._entries.values()
            for p in entry.index.programs
            if p.number is not None
        )

    def find_program(self, number: int) -> tuple[str, int] | None:
        """The document and header line of O<number> (its first block when the file's name
        gives the number)."""
        for uri, entry in self._entries.items():
            program = entry.index.by_number(number)
            if program is not None:
                line = program.header_line
                return uri, line if line is not None else program.first_line
        return None

    @_in_database
    def analyse(
        self,
        uri: str,
        workspace_programs: frozenset[int] | None = None,
        cancel: CancelToken | None = None,
        others: list[tuple[str, Document, ProgramIndex]] | None = None,
        config: Config | None = None,
    ) -> Analysis:
        """Analyse ``uri`` with the programs of the workspace it calls (``others``, when the
        caller has them already from :meth:`others`), with the workspace's settings or
        ``config`` (a document's own: the configuration file nearest it). Its facts are kept
        with the settings they were found with, so a document always analysed with its own
        reuses them.

        The evaluator's facts are kept while no document it ran changed what it does: typing in
        a comment re-runs the rules (comments name parameters and suppress diagnostics), not
        the program. A cancelled analysis (``cancel``) keeps nothing.
        """
        entry = self._entries[uri]
        programs = self.program_numbers() if workspace_programs is None else workspace_programs
        others = self.others(uri) if others is None else others
        runs = ((uri, entry.execution), *((u, self._entries[u].execution) for u, _, _ in others))
        # The machine the document's codes show (controller 0i-F): a run of another machine's
        # reading is neither kept nor resumed. A look at every line, as the analysis's: without
        # the cyclic collector, which would scan the parsed lines again and again.
        with quiet_gc():
            config = machine_config(config or self.config, entry.doc, entry.index)
            if not config.machine_known:
                config = callers_machine(config, self._callers(uri)) or config
        facts, previous = _kept_facts(self._facts.get(uri), config, runs)
        mill_facts, mill_previous = _kept_facts(
            self._mill_facts.get(uri), mill_reading(config), runs
        )
        analysis = analyse(
            entry.text,
            uri,
            config,
            programs,
            self.parser,
            doc=entry.doc,
            index=entry.index,
            other_documents=others,
            facts=facts,
            previous_facts=previous,
            cancel=cancel,
            mill_facts=mill_facts,
            mill_previous=mill_previous,
        )
        if analysis.facts is not None and self.keep_runs:
            self._facts[uri] = (config, runs, analysis.facts)
        if analysis.mill_facts is not None and self.keep_runs:
            self._mill_facts[uri] = (mill_reading(config), runs, analysis.mill_facts)
        return analysis


def _kept_facts(
    cached: tuple[Config, tuple[tuple[str, int], ...], Facts] | None,
    config: Config,
    runs: tuple[tuple[str, int], ...],
) -> tuple[Facts | None, Facts | None]:
    """The facts kept of a run with ``config`` to use as they are (no document it ran changed
    what it does), else to resume (the evaluator resumes the earlier run where the edit begins
    to matter): (facts, previous)."""
    if cached is None or not (cached[0] is config or cached[0] == config):
        return None, None
    if cached[1] == runs:
        return cached[2], None
    return None, cached[2]


def _called_numbers(doc: Document, call: Call) -> list[int] | None:
    """The program numbers a call may reach (None: computed at run time). ``M98 P0013331``
    may be O3331 (4-digit controls) or O13331 (30i): both are kept."""
    if call.program is None:
        return None
    numbers = [call.program]
    if call.kind == "M98" and call.program_span is not None:
        digits = doc.blocks[call.line].source(call.program_span)[1:].split(".")[0].strip()
        if digits.lstrip("+").isdigit() and int(digits) != call.program:
            numbers.append(int(digits))
    return numbers


def program_links(doc: Document, index: ProgramIndex) -> frozenset[tuple[str, int | None]]:
    """The program numbers a document defines ("defines", n) and calls ("calls", n; n None
    for a number computed at run time): two versions with the same links relate the same
    documents in :func:`related_documents`."""
    links: set[tuple[str, int | None]] = set()
    for program in index.programs:
        if program.number is not None:
            links.add(("defines", program.number))
        for call in program.calls:
            numbers = _called_numbers(doc, call)
            if numbers is not None:
                links.update(("calls", n) for n in numbers)  # an M97 too: counted as a caller
            elif call.kind != "M97":  # a Haas local call is a sequence number
                links.add(("calls", None))
    return frozenset(links)


@dataclass(frozen=True, eq=False, repr=False)
class ProgramGraph:
    """Which documents define and call which program numbers, built once for a snapshot of
    the workspace's indexes (:meth:`Workspace.indexes`): :func:`related_documents` then
    follows a document's calls without looking at every other document, so that an archive
    of thousands of files, many with the same O number, is not read the square of times."""

    order: dict[str, int]  # the documents, by their place in workspace order
    definers: dict[int, list[str]]  # number -> the documents defining it, in order
    defines: dict[str, frozenset[int]]  # document -> the numbers it defines
    # document -> the numbers its calls reach (not M97's); None: one is computed at run time
    calls: dict[str, frozenset[int] | None]
    callers: dict[int, set[str]]  # number -> the documents with a call that may reach it
    direct_callers: dict[int, set[str]]  # number -> the documents calling it as written


@dataclass(frozen=True, slots=True)
class DocumentLinks:
    """What of one document the program graph reads: the numbers it defines, those its calls
    reach (not M97's; None when one is computed at run time), those any of its calls may reach
    (an M97's too: it counts as a caller) and those its calls write."""

    defines: tuple[int, ...]
    reaches: tuple[int, ...] | None
    may_reach: tuple[int, ...]
    written: tuple[int, ...]


def document_links(doc: Document, index: ProgramIndex) -> DocumentLinks:
    defines: list[int] = []
    reaches: set[int] | None = set()
    may_reach: set[int] = set()
    written: set[int] = set()
    for program in index.programs:
        if program.number is not None:
            defines.append(program.number)
        for call in program.calls:
            found = _called_numbers(doc, call)
            may_reach.update(found or ())
            if call.program is not None:
                written.add(call.program)
            if call.kind == "M97" or reaches is None:
                continue  # Haas local call: a sequence number, not a program
            if found is None:
                reaches = None
            else:
                reaches.update(found)
    return DocumentLinks(
        tuple(defines),
        None if reaches is None else tuple(sorted(reaches)),
        tuple(sorted(may_reach)),
        tuple(sorted(written)),
    )


def program_graph(indexes: Mapping[str, tuple[Document, ProgramIndex]]) -> ProgramGraph:
    return graph_of_links({k: document_links(doc, index) for k, (doc, index) in indexes.items()})


def graph_of_links(links: Mapping[str, DocumentLinks]) -> ProgramGraph:
    """The program graph of documents by their links, in the mapping's order."""
    order: dict[str, int] = {}
    definers: dict[int, list[str]] = {}
    defines: dict[str, frozenset[int]] = {}
    calls: dict[str, frozenset[int] | None] = {}
    callers: dict[int, set[str]] = {}
    direct: dict[int, set[str]] = {}
    for k, link in links.items():
        order[k] = len(order)
        for number in link.defines:
            definers.setdefault(number, []).append(k)
        for number in link.may_reach:
            callers.setdefault(number, set()).add(k)
        for number in link.written:
            direct.setdefault(number, set()).add(k)
        defines[k] = frozenset(link.defines)
        calls[k] = None if link.reaches is None else frozenset(link.reaches)
    return ProgramGraph(order, definers, defines, calls, callers, direct)


def related_documents(
    key: str,
    indexes: Mapping[str, tuple[Document, ProgramIndex]],
    custom_called: frozenset[int] = frozenset(),
    graph: ProgramGraph | None = None,
) -> list[str] | None:
    """The documents the evaluator needs to analyse ``key``, in workspace order; None when all
    of them may be (a call whose program is computed, ``M98 P#1``).

    Those are the documents defining the programs ``key`` calls, transitively, and those calling
    a program of ``key`` (they decide which of its programs are entry points), and those
    defining the programs of ``custom_called``, which a code set up as a call runs. The others are
    never run: handing them over only makes the evaluator compile them, which with a scanned
    workspace of a few thousand files costs seconds per keystroke. ``graph``: the indexes'
    :func:`program_graph`, when the caller keeps it.
    """
    if key not in indexes:
        return None
    return related_in_graph(key, graph or program_graph(indexes), custom_called)


def related_in_graph(
    key: str, graph: ProgramGraph, custom_called: frozenset[int] = frozenset()
) -> list[str] | None:
    """:func:`related_documents` of a document of ``graph``."""
    own = graph.defines.get(key, frozenset())
    definers = graph.definers

    def owner(number: int) -> str | None:
        # The first definition wins, the analysed document's first, as in the evaluator.
        if number in own:
            return key
        found = definers.get(number)
        return found[0] if found else None

    needed = {key}
    todo = [key]
    # A code the settings set up as a call may stand in any block: its program is needed.
    for number in sorted(custom_called):
        target = owner(number)
        if target is not None and target not in needed:
            needed.add(target)
            todo.append(target)
    while todo:
        numbers = graph.calls.get(todo.pop(), frozenset())
        if numbers is None:
            return None
        for number in numbers:
            target = owner(number)
            if target is not None and target not in needed:
                needed.add(target)
                todo.append(target)
    for number in own:
        needed |= graph.callers.get(number, set())
    needed.discard(key)
    return sorted(needed, key=graph.order.__getitem__)
