"""What thread each threading job cuts, and where that is known from.

In order of trust (the first source that tells a fact gives it):

1. the executed cuts (:mod:`.jobs`): the lead (``F``), the side, the X range of the passes;
2. a designation anywhere in the file's comments (``M50X3-5G6G``, ``M50×3``, ``M10-6g``,
   ``M20X1.5LH``, ``M16xPh3P1.5`` or ``M50X6(P3`` multi-start, ``2 START``) whose size fits
   the passes.  Its class's case tells the side (ISO 965-1: ``5g6g`` external, ``5G6G``
   internal) unless the text is all capitals; then a class only one kind has tells it
   (``6E``, ``4H5H``), and one both kinds have (``5G6G``), or none, is read on the side the
   cuts (or the program's first comments) show, and not used when nothing shows it;
3. a thread module recognised by the shape of its formulas (:mod:`.module_shape`): its
   nominal diameter, lead, nose radius and the es / Td2 it adds to the height;
4. the words of comments on assignments (:mod:`fanuc_macro.program.meanings`).

The tolerance class comes from the designation (ISO 965-1: none written is 6g / 6H), else from
the module's es and Td2 when a class of the ISO 965-1 tables has them, else the program's own
es and Td2 are taken as they are; with neither, the loosest class of the tables stands in, so
that a pass past its root is past the root of every class. A thread that cannot be identified
gets no verdict that needs it; :attr:`Thread.missing` says why.

Only ISO metric 60° threads (ISO 68-1, ISO 965-1) are checked against a profile; a
designation of another form (trapezoidal, pipe, Unified) and a taper cut are named in
:attr:`Thread.unsupported`.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

from ..evaluator.facts import DocumentFacts, Motion, RunValues
from ..evaluator.values import fmt_address
from ..line_maps import Found, LineMap
from ..per_line import PerLine
from ..program.index import Program, ProgramIndex
from ..program.meanings import Meaning, program_is_internal, variable_roles
from ..syntax.tree import Document, ParsedLine
from ..translation import tr, tr_n
from .designation import SideUndecided, ThreadDesignation, parse_designation
from .geometry import SIN60
from .iso965 import PitchClass, loosest_pitch_class, pitch_classes
from .jobs import ThreadJob, thread_jobs
from .module_shape import (
    D1_FACTOR,
    ModuleShape,
    fitting_radii,
    in_turn,
    module_shape,
    written_value,
)
from .pipe import PipeThread, pipe_threads
from .surface import SurfaceWanted, TurnedSurface, turned_surfaces

INCH = 25.4

_NUM = r"\d+(?:[.,]\d+)?"
# A metric designation needs a pitch or a class: "M30" or "M8" alone is an M code.
_DESIGNATION = re.compile(
    rf"(?<![A-Z0-9#.])M\s*(?P<d>{_NUM})"
    rf"(?:\s*[X×*]\s*(?:PH\s*(?P<ph>{_NUM})\s*P\s*(?P<pp>{_NUM})"
    rf"|(?P<p>{_NUM})(?:\s*\(\s*P\s*(?P<old>{_NUM}))?))?"
    r"(?P<lh1>\s*LH)?(?:\s*-\s*(?P<cls>\d[A-Z](?:\d[A-Z])?)(?![A-Z0-9]))?(?P<lh2>\s*-\s*LH)?",
    re.I,
)
_OTHER_FORMS = (
    (re.compile(r"(?<![A-Z])TR\s*\d+\s*[X×*]\s*\d", re.I), "a trapezoidal thread (ISO 2904 Tr)"),
    (re.compile(r"\d+/\d+\s*-?\s*\d+\s*UN[CFEJ]?|\bUN[CF]\b", re.I), "a Unified inch thread"),
    (re.compile(r"\bNPTF?\b|\bNPS\b|\bBSPT?\b", re.I), "a pipe thread"),
    (re.compile(r"(?<![A-Z])(?:RC|RP|R|G)\s*\d+(?:/\d+)\b", re.I), "a pipe thread (ISO 7 / 228)"),
)
_STARTS = re.compile(r"(?<![\w.])(?P<n>[2-6])\s*-?\s*STARTS?\b|(?P<cn>[双两三四])线", re.I)
_CHINESE_STARTS: Mapping[str, int] = MappingProxyType({"双": 2, "两": 2, "三": 3, "四": 4})
# What every pattern above and pipe_threads' need: a Latin letter (as the same case-blind
# matching finds one), or the Chinese starts' 线. A comment of neither names no thread.
_MAY_NAME_A_THREAD = re.compile(r"[a-z]|线", re.I)


@dataclass(frozen=True, eq=False, repr=False)
class FoundDesignation:
    text: str  # as written
    form: str  # what parse_designation reads
    line: int


@dataclass(frozen=True, eq=False, repr=False)
class LineThreadWords:
    designations: tuple[tuple[str, str], ...]  # (as written, normalised)
    other_forms: tuple[str, ...]
    starts: int | None
    pipes: tuple[PipeThread, ...] = ()


def _line_words(parsed: ParsedLine) -> LineThreadWords:
    found: list[tuple[str, str]] = []
    others: list[str] = []
    pipes: list[PipeThread] = []
    starts: int | None = None
    for comment in parsed.comments:
        text = comment.text
        if _MAY_NAME_A_THREAD.search(text) is None:
            continue
        for m in _DESIGNATION.finditer(text):
            if m["p"] is None and m["ph"] is None and m["cls"] is None:
                continue
            written = m.group(0)
            # Keep the writer's case: it may tell an internal thread (5H) from an external.
            lower = "×" in written or any(ch.islower() for ch in written)
            x, ph = ("x", "Ph") if lower else ("X", "PH")
            form = f"M{m['d']}"
            if m["ph"] is not None:
                form += f"{x}{ph}{m['ph']}P{m['pp']}"
            elif m["old"] is not None:  # GB/T 197's older "M50×6(P3)": lead 6, pitch 3
                form += f"{x}{ph}{m['p']}P{m['old']}"
            elif m["p"] is not None:
                form += f"{x}{m['p']}"
            if m["lh1"] or m["lh2"]:
                form += "LH"
            if m["cls"]:
                form += f"-{m['cls']}"
            found.append((m.group(0).strip(), form.replace(",", ".")))
        for pattern, what in _OTHER_FORMS:
            if pattern.search(text):
                others.append(what)
        pipes.extend(pipe_threads(text))
        s = _STARTS.search(text)
        if s is not None:
            starts = int(s["n"]) if s["n"] else _CHINESE_STARTS[s["cn"]]
    return LineThreadWords(tuple(found), tuple(others), starts, tuple(pipes))


# Thread designations and other thread words in a line's comments, per distinct line.
thread_words: PerLine[LineThreadWords] = PerLine(_line_words)


@dataclass(frozen=True, eq=False, repr=False)
class Evidence:
    text: str
    line: int | None = None  # 0-based, in the document


@dataclass(eq=False, repr=False)
class Thread:
    """One job and the thread it cuts, as far as the program tells."""

    job: ThreadJob
    internal: bool | None = None
    major: float | None = None
    pitch: float | None = None
    # Where the pitch comes from: "designation", "comment" (a variable named PITCH) or "lead"
    # (the cut's F, taken for the pitch of a one-start thread).
    pitch_source: str = ""
    starts: int = 1
    starts_line: int | None = None
    designation: ThreadDesignation | None = None
    designation_line: int | None = None
    pitch_class: PitchClass | None = None
    class_reason: str = ""
    class_exact: bool = False  # False: the loosest class stands in for an unknown one
    nose_radius: float | None = None
    nose_line: int | None = None
    nose_reason: str = ""
    module: ModuleShape | None = None
    deviation_var: int | None = None  # the module's input that is es (EI)
    tolerance_var: int | None = None  # and the one that is Td2 (TD2)
    evidence: list[Evidence] = field(default_factory=list)
    unsupported: str | None = None
    missing: str | None = None
    # A taper pipe thread (ISO 7-1, NPT) the comments name that fits the passes, and its line.
    pipe: PipeThread | None = None
    pipe_line: int | None = None
    # The surface the program turned for the thread before cutting it, where it did.
    surface: TurnedSurface | None = None

    @property
    def cut_pitch(self) -> float | None:
        """The pitch the passes are cut to: the designation's, or the lead over the starts."""
        if self.pitch is not None:
            return self.pitch
        if self.pipe is not None:
            return self.pipe.pitch / (INCH if self.job.passes[0].inch else 1.0)
        lead = self.job.lead
        return None if lead is None else lead / max(self.starts, 1)

    @property
    def identified(self) -> bool:
        """Known well enough to check the passes against its profile."""
        return (
            self.major is not None
            and self.pitch is not None
            and self.internal is not None
            and self.unsupported is None
            and not self.lead_conflict
        )

    @property
    def lead_conflict(self) -> bool:
        """The cut's F is not the lead of the thread its designation or comments name: one of
        them is wrong, and which cannot be told (MB810 says so)."""
        lead = self.job.lead
        return (
            self.pitch_source in ("designation", "comment")
            and lead is not None
            and self.lead is not None
            and abs(lead - self.lead) > 1e-6
        )

    @property
    def lead(self) -> float | None:
        return None if self.pitch is None else self.pitch * self.starts

    @property
    def name(self) -> str:
        if self.designation is not None:
            return self.designation.canonical()
        if self.pipe is not None:
            return self.pipe.text
        if self.major is None or self.pitch is None:
            return tr("the thread")
        return f"M{self.major:g}x{self.pitch:g}"

    @property
    def fundamental_height(self) -> float:
        assert self.pitch is not None
        return SIN60 * self.pitch

    def pitch_band(self) -> tuple[float, float] | None:
        """(d2 min, d2 max) or (D2 min, D2 max) of the class, mm."""
        if self.major is None or self.pitch is None or self.pitch_class is None:
            return None
        basic = self.major - 0.75 * self.fundamental_height
        low = basic + self.pitch_class.deviation
        if self.internal:
            return low, low + self.pitch_class.tolerance
        return low - self.pitch_class.tolerance, low

    def effective_nose_radius(self) -> float:
        """The tool's nose radius when known; else the one that allows the deepest root: 0.125P
        external (ISO 965-1's least root radius), 0 internal."""
        if self.nose_radius is not None and self.nose_radius >= 0.0:
            return self.nose_radius
        assert self.pitch is not None
        return 0.0 if self.internal else 0.125 * self.pitch

    def root_x(self) -> float | None:
        """The deepest X a pass may reach and keep the pitch diameter inside the class with
        this tool: d2 min − H + 2r external (d3 min for r = 0.125P), D2 max + H − 2r internal."""
        band = self.pitch_band()
        if band is None or self.internal is None:
            return None
        r = self.effective_nose_radius()
        if self.internal:
            return band[1] + self.fundamental_height - 2.0 * r
        return band[0] - self.fundamental_height + 2.0 * r

    def full_depth(self) -> float | None:
        """Radius from the crest (d external, D1 internal) to :meth:`root_x`."""
        root = self.root_x()
        if root is None or self.major is None or self.pitch is None:
            return None
        if self.internal:
            return (root - (self.major - D1_FACTOR * self.pitch)) / 2.0
        return (self.major - root) / 2.0

    def class_text(self) -> str:
        if self.pitch_class is None:
            return ""
        if self.pitch_class.position == "?":
            return (
                tr("the program's own es and Td2")
                if not self.internal
                else tr("the program's own EI and TD2")
            )
        if self.class_exact:
            return self.pitch_class.name
        return tr(
            "any class (the loosest, {tolerance_class})", tolerance_class=self.pitch_class.name
        )

    def known_from(self) -> str:
        return in_turn([e.text for e in self.evidence])

    def limit_text(self) -> str:
        """How the root was worked out, for a message."""
        band = self.pitch_band()
        if band is None or self.pitch is None:
            return ""
        r = self.effective_nose_radius()
        which = "D2 max" if self.internal else "d2 min"
        limit = band[1] if self.internal else band[0]
        if self.nose_radius is not None:
            tool = tr("with the tool's nose radius {radius:.4g}", radius=r)
        elif self.internal:
            tool = tr("with a sharp tool")
        else:
            tool = tr("with the least root radius 0.125P = {radius:.4g}", radius=r)
        return tr(
            "{which} {limit:.3f} of {tolerance_class}, {nose}",
            which=which,
            limit=limit,
            tolerance_class=self.class_text(),
            nose=tool,
        )


def _thread_line(parsed: ParsedLine) -> LineThreadWords | None:
    if not parsed.comments:
        return None
    # Not through the per-line cache: the map keeps what it finds and looks at a line again
    # only when it changed, so an entry per commented line would only hold memory.
    words = _line_words(parsed)
    if words.designations or words.other_forms or words.pipes or words.starts is not None:
        return words
    return None


# The lines whose comments say something of a thread, looked at again only where they changed.
_thread_lines: LineMap[LineThreadWords] = LineMap(_thread_line)


def _designations(lines: Found[LineThreadWords]) -> list[FoundDesignation]:
    return [
        FoundDesignation(text, form, line)
        for line, words in lines
        for text, form in words.designations
    ]


def _parse(found: FoundDesignation, internal: bool | None) -> ThreadDesignation | None:
    """The designation read on the side ``internal`` (the cuts'), or as its text says; None
    when it cannot be read, or the side is known from neither (never guessed)."""
    try:
        return parse_designation(found.form, internal=internal)
    except ValueError:
        try:
            return parse_designation(found.form) if internal is not None else None
        except ValueError:
            return None


def _undecided(
    found: list[FoundDesignation], job: ThreadJob
) -> tuple[FoundDesignation, SideUndecided] | None:
    """A designation whose size fits the passes but whose side nothing tells (all capitals with
    a class both kinds have, or no class): for the message that says why it is not used."""
    for f in found:
        try:
            parse_designation(f.form)
        except SideUndecided as err:
            if _fits(err.external, job, False) or _fits(err.internal, job, True):
                return f, err
        except ValueError:
            continue
    return None


def _fits(des: ThreadDesignation, job: ThreadJob, internal: bool) -> bool:
    """Whether the passes lie where this size's thread is cut: the deepest one within its
    profile, give or take, and the first ones no further off than 2P (radius) in the air
    (a G76 whose height P was given as a diameter starts that far out)."""
    low, high = job.x_range
    d, p = des.nominal_diameter, des.pitch
    if internal:
        minor = d - D1_FACTOR * p
        return minor - 1.0 - 0.5 * p <= high <= d + 2.0 * p and low >= minor - 4.0 * p
    return d - 4.0 * p <= low <= d + 0.2 and high <= d + 4.0 * p


def _choose_designation(
    found: list[FoundDesignation], job: ThreadJob, internal: bool | None
) -> tuple[ThreadDesignation, FoundDesignation] | None:
    lead = job.lead
    fitting: list[tuple[ThreadDesignation, FoundDesignation]] = []
    for f in found:
        des = _parse(f, internal)
        if des is None:
            continue
        side = des.internal if internal is None else internal
        if _fits(des, job, side):
            fitting.append((des, f))
    if not fitting:
        return None
    if lead is not None:
        same = [c for c in fitting if abs(c[0].thread_lead - lead) < 1e-6]
        if same:
            fitting = same
    sizes = {(c[0].nominal_diameter, c[0].pitch, c[0].internal) for c in fitting}
    if len(sizes) > 1:
        return None  # several threads fit: which one this is cannot be told
    return fitting[0]


@dataclass(frozen=True, eq=False, repr=False)
class _ProgramWords:
    """What one program's comments and formulas say of its threads, read once per program."""

    starts: tuple[int, int] | None  # (number of starts, line), in the program or else the file
    other_form: tuple[str, int] | None  # (a thread form not checked, line)
    fitting: bool  # an arc thread by the fitting method
    # Taper pipe threads the comments name (the program's first, then the file's), with line.
    pipes: tuple[tuple[PipeThread, int], ...] = ()


def _program_words(
    doc: Document,
    facts: DocumentFacts,
    program: Program,
    roles: dict[tuple[int, int], Meaning],
    lines: Found[LineThreadWords],
) -> _ProgramWords:
    starts: tuple[int, int] | None = None
    file_starts: tuple[int, int] | None = None
    other: tuple[str, int] | None = None
    pipes: list[tuple[PipeThread, int]] = []
    file_pipes: list[tuple[PipeThread, int]] = []
    for line, words in lines:
        if words.starts is not None and file_starts is None:
            file_starts = (words.starts, line)
        file_pipes += [(p, line) for p in words.pipes]
        if not program.contains(line):
            continue
        if starts is None and words.starts is not None:
            starts = (words.starts, line)
        if other is None and words.other_forms:
            other = (words.other_forms[0], line)
        pipes += [(p, line) for p in words.pipes]
    fitting = fitting_radii(doc, facts, program) is not None or any(
        f == program.first_line and m.role == "groove_radius" for (f, _v), m in roles.items()
    )
    return _ProgramWords(starts or file_starts, other, fitting, (*pipes, *file_pipes))


def _input_roles(thread: Thread, shape: ModuleShape) -> dict[str, int]:
    """Which of the module's inputs is es (EI) and which Td2 (TD2): by their values when a
    class of the tables has both (the class known first), else by the formula's coefficients
    (es/2, Td2/4 as the paper writes them)."""
    inputs = shape.inputs
    if thread.major is not None and thread.pitch is not None and thread.internal is not None:
        classes = pitch_classes(thread.major, thread.pitch, internal=thread.internal)
        if thread.pitch_class is not None and thread.class_exact:
            classes = [thread.pitch_class, *classes]
        for c in classes:
            for es_var, es in inputs.items():
                for tol_var, tol in inputs.items():
                    if (
                        tol_var != es_var
                        and abs(abs(es) - abs(c.deviation)) < 5e-4
                        and abs(tol - c.tolerance) < 5e-4
                    ):
                        return {"deviation": es_var, "tolerance": tol_var}
    form = shape.height_form
    roles: dict[str, int] = {}
    if form is not None:
        for n in inputs:
            coefficient = form.coefficient(n)
            if abs(coefficient - 0.5) < 1e-6:
                roles["deviation"] = n
            elif abs(coefficient - 0.25) < 1e-6:
                roles["tolerance"] = n
    return roles


def _class_from_inputs(thread: Thread, shape: ModuleShape) -> tuple[PitchClass, str] | None:
    """The module's es and Td2 (the terms it adds to the height): a class of the tables when
    one has them both, else the program's own values."""
    if thread.major is None or thread.pitch is None or thread.internal is None:
        return None
    es_var, tol_var = thread.deviation_var, thread.tolerance_var
    if es_var is None or tol_var is None:
        return None
    es, tol = shape.inputs[es_var], shape.inputs[tol_var]
    tol_name = "TD2" if thread.internal else "Td2"
    for c in pitch_classes(thread.major, thread.pitch, internal=thread.internal):
        if abs(abs(es) - abs(c.deviation)) < 5e-4 and abs(tol - c.tolerance) < 5e-4:
            reason = tr(
                "its es {es:g} (#{es_var}) and {tol_name} {tol:g} (#{tol_var})",
                es=es,
                es_var=es_var,
                tol_name=tol_name,
                tol=tol,
                tol_var=tol_var,
            )
            return c, reason
    # The module enters es as a magnitude (seed paper 000, table 2); EI is positive anyway.
    signed = abs(es) if thread.internal else -abs(es)
    reason = tr(
        "the module's own es {es:g} (#{es_var}) and {tol_name} {tol:g} (#{tol_var}), which "
        "no ISO 965-1 class has",
        es=es,
        es_var=es_var,
        tol_name=tol_name,
        tol=tol,
        tol_var=tol_var,
    )
    return PitchClass("?", 0, signed, tol), reason


def _role_value(
    roles: dict[tuple[int, int], Meaning], facts: DocumentFacts, program_line: int, role: str
) -> tuple[float, int] | None:
    for (first, _var), meaning in roles.items():
        if first == program_line and meaning.role == role and meaning.line >= 0:
            value = written_value(facts, meaning.line)
            if value is not None:
                return value, meaning.line
    return None


def _mm(value: float) -> str:
    return fmt_address(value)


def _describe_cuts(job: ThreadJob) -> str:
    xs = job.xs
    lead = job.lead
    cutting = job.shown if lead is None else tr("{code} at F{feed:g}", code=job.shown, feed=lead)
    count = len(job.passes)
    passes: str = tr_n("{count} pass", "{count} passes", count)
    if xs and xs[0] != xs[-1]:
        passes = tr(
            "{passes} X{first} to X{last}", passes=passes, first=_mm(xs[0]), last=_mm(xs[-1])
        )
    elif xs:
        passes = tr("{passes} at X{x}", passes=passes, x=_mm(xs[0]))
    return tr("the cuts ({cutting}, {passes})", cutting=cutting, passes=passes)


def identify(
    doc: Document,
    index: ProgramIndex,
    facts: DocumentFacts,
    motions: list[Motion],
    runs: dict[int, RunValues] | None = None,
    roles: dict[tuple[int, int], Meaning] | None = None,
) -> list[Thread]:
    """Every threading job of ``doc``'s programs with its thread; ``runs``: the variables of
    each execution when it began to cut (:attr:`fanuc_macro.evaluator.Facts.run_values`)."""
    jobs = thread_jobs(motions, doc.uri)
    if not jobs:
        return []
    lines = _thread_lines(doc)
    found = _designations(lines)
    if roles is None:
        roles = variable_roles(doc, index)
    runs = runs or {}
    words: dict[int, _ProgramWords] = {}
    threads: list[Thread] = []
    # The threads whose turned surface is looked for, all in one walk over the motions.
    surfaces: list[tuple[Thread, SurfaceWanted]] = []
    for job in jobs:
        program = index.program_at(job.program_line)
        if program is None:
            continue
        if program.first_line not in words:
            words[program.first_line] = _program_words(doc, facts, program, roles, lines)
        run = runs.get(job.run)
        thread = _identify(doc, index, facts, job, found, roles, run, words[program.first_line])
        pitch = thread.cut_pitch
        # Arc threads (the fitting method) are cut by a round tool; threads of another
        # form than the ones the cut knows are not cut.
        cut_known = thread.unsupported is None or thread.pipe is not None or job.taper is not None
        internal = thread.internal if thread.internal is not None else job.internal
        fitting = words[program.first_line].fitting
        if cut_known and pitch is not None and internal is not None and job.xs and not fitting:
            wanted = SurfaceWanted(job.passes, internal, pitch, job.x_range[0])
            surfaces.append((thread, wanted))
        threads.append(thread)
    if surfaces:
        surfaces_found = turned_surfaces([w for _t, w in surfaces], motions)
        for (thread, _w), surface in zip(surfaces, surfaces_found, strict=True):
            thread.surface = surface
    return threads


def _identify(
    doc: Document,
    index: ProgramIndex,
    facts: DocumentFacts,
    job: ThreadJob,
    found: list[FoundDesignation],
    roles: dict[tuple[int, int], Meaning],
    run: RunValues | None,
    words: _ProgramWords,
) -> Thread:
    """The thread of one job, from the sources in the module's order of trust."""
    thread = Thread(job, internal=job.internal)
    if not job.xs:
        thread.missing = "the passes' X is not known"
        return thread
    thread.evidence.append(Evidence(_describe_cuts(job), job.passes[0].line))
    chosen = _read_designation(thread, doc, index, found)
    pitch_is_lead = _read_module(thread, doc, index, facts, run)
    pitch_is_lead = _read_assignment_comments(thread, roles, facts) or pitch_is_lead
    _read_starts(thread, words, pitch_is_lead)
    _read_tolerance_class(thread)
    if thread.designation is None:
        _read_pipe(thread, words)
    undecided = _undecided(found, job) if chosen is None and thread.internal is None else None
    _unsupported(job, thread, words, undecided)
    return thread


# How far the deepest pass may lie from a pipe thread's tabulated diameter, in pitches (its
# height is 0.64-0.8P on a side; along a taper of 1:16 the diameter changes 1/16 of the length).
PIPE_NEAR_PITCHES = 4.0


def _read_pipe(thread: Thread, words: _ProgramWords) -> None:
    """The taper pipe thread the comments name whose pitch is the cut's lead and whose
    diameter is nearest the passes'."""
    job = thread.job
    lead, xs = job.lead, job.xs
    if lead is None or not xs or not words.pipes:
        return
    scale = INCH if job.passes[0].inch else 1.0
    lead_mm = lead * scale
    best: tuple[float, PipeThread, int] | None = None
    for pipe, line in words.pipes:
        if abs(lead_mm - pipe.pitch) > 0.01 * pipe.pitch:
            continue
        internal = thread.internal if thread.internal is not None else job.internal
        if pipe.internal is not None and internal is not None and pipe.internal != internal:
            continue
        deepest = (max(xs) if internal else min(xs)) * scale
        off = abs(deepest - pipe.diameter)
        if off <= PIPE_NEAR_PITCHES * pipe.pitch and (best is None or off < best[0]):
            best = (off, pipe, line)
    if best is not None:
        _off, thread.pipe, thread.pipe_line = best
        if thread.internal is None and best[1].internal is not None:
            thread.internal = best[1].internal
        thread.evidence.append(Evidence(tr("{pipe} in the comments", pipe=best[1].name), best[2]))


def _read_designation(
    thread: Thread, doc: Document, index: ProgramIndex, found: list[FoundDesignation]
) -> tuple[ThreadDesignation, FoundDesignation] | None:
    """The designation that fits the passes, taken into ``thread``: its letter case tells the
    side if the cuts do not, then the program's first comments."""
    job = thread.job
    chosen = _choose_designation(found, job, thread.internal)
    if thread.internal is None and chosen is None:
        program = index.program_at(job.program_line)
        end = program.end_line if program is not None else job.program_line + 1
        said = program_is_internal(doc, job.program_line, end)
        if said is not None:
            thread.internal = said
            thread.evidence.append(Evidence(tr("the program's first comments"), job.program_line))
            chosen = _choose_designation(found, job, said)
    if chosen is None:
        return None
    des, where = chosen
    thread.designation, thread.designation_line = des, where.line
    if thread.internal is None:
        thread.internal = des.internal
    thread.major, thread.pitch, thread.starts = des.nominal_diameter, des.pitch, des.starts
    thread.pitch_source = "designation"
    thread.evidence.append(
        Evidence(
            tr(
                "the designation {designation_text} at line {line}",
                designation_text=where.text,
                line=where.line + 1,
            ),
            where.line,
        )
    )
    tabulated = next(
        (
            c
            for c in pitch_classes(des.nominal_diameter, des.pitch, internal=des.internal)
            if c.position == des.pitch_class.position and c.grade == des.pitch_class.grade
        ),
        None,
    )
    if tabulated is not None:
        thread.pitch_class, thread.class_exact = tabulated, True
        thread.class_reason = (
            tr("the designation, whose class is not written: 6g / 6H by ISO 965-1")
            if des.class_omitted
            else tr("the designation")
        )
    return chosen


def _read_module(
    thread: Thread,
    doc: Document,
    index: ProgramIndex,
    facts: DocumentFacts,
    run: RunValues | None,
) -> bool:
    """What the thread module's formulas say, taken into ``thread``; whether the pitch taken
    is the cut's lead (to be divided by the starts a comment names)."""
    if thread.internal is None:
        return False
    shape = module_shape(doc, index, facts, thread.job, thread.internal, run)
    if shape is None or (shape.major is None and shape.height is None):
        return False
    thread.module = shape
    pitch_is_lead = False
    if thread.major is None and shape.major is not None and shape.pitch is not None:
        thread.major, thread.pitch, pitch_is_lead = shape.major, shape.pitch, True
        thread.pitch_source = "lead"
        thread.evidence.append(Evidence(shape.describe(), shape.height_line))
    if shape.radius is not None:
        thread.nose_radius, thread.nose_line = shape.radius, shape.radius_line
        thread.nose_reason = tr(
            "#{var}, the radius {how}", var=shape.radius_var, how=shape.radius_how
        )
    return pitch_is_lead


def _read_assignment_comments(
    thread: Thread, roles: dict[tuple[int, int], Meaning], facts: DocumentFacts
) -> bool:
    """What the comments on assignments say (the last source), taken into ``thread`` where
    nothing said it before; whether the pitch taken is the cut's lead."""
    job = thread.job
    first = job.program_line
    pitch_is_lead = False
    if thread.major is None:
        major = _role_value(roles, facts, first, "nominal_diameter")
        pitch = _role_value(roles, facts, first, "pitch")
        if major is not None:
            thread.major = major[0]
            thread.evidence.append(
                Evidence(tr("the nominal diameter at line {line}", line=major[1] + 1), major[1])
            )
            if pitch is not None:
                thread.pitch, thread.pitch_source = pitch[0], "comment"
            elif job.lead is not None:
                thread.pitch, thread.pitch_source, pitch_is_lead = job.lead, "lead", True
    if thread.nose_radius is None:
        nose = _role_value(roles, facts, first, "nose_radius")
        if nose is not None:
            thread.nose_radius, thread.nose_line = nose
            thread.nose_reason = tr("named by the comment at line {line}", line=nose[1] + 1)
    return pitch_is_lead


def _read_starts(thread: Thread, words: _ProgramWords, pitch_is_lead: bool) -> None:
    """The number of starts a comment names, when the designation did not: a pitch taken from
    the lead is the lead over the starts."""
    if thread.starts != 1 or words.starts is None:
        return
    starts = words.starts
    thread.starts, thread.starts_line = starts
    if pitch_is_lead and thread.pitch is not None:
        thread.pitch /= thread.starts
    thread.evidence.append(
        Evidence(
            tr(
                "{count} starts, by the comment at line {line}",
                count=thread.starts,
                line=starts[1] + 1,
            ),
            starts[1],
        )
    )


def _read_tolerance_class(thread: Thread) -> None:
    """The module's es and Td2 inputs, and the class when no designation gave it: from those
    inputs, else the loosest of ISO 965-1 for the size."""
    if thread.module is not None:
        roles_of_inputs = _input_roles(thread, thread.module)
        thread.deviation_var = roles_of_inputs.get("deviation")
        thread.tolerance_var = roles_of_inputs.get("tolerance")
    if thread.pitch_class is None and thread.module is not None:
        from_inputs = _class_from_inputs(thread, thread.module)
        if from_inputs is not None:
            thread.pitch_class, thread.class_reason = from_inputs
            thread.class_exact = True
            thread.evidence.append(
                Evidence(
                    thread.class_reason
                    if thread.pitch_class.position == "?"
                    else tr(
                        "class {tolerance_class} from {reason}",
                        tolerance_class=thread.class_text(),
                        reason=thread.class_reason,
                    )
                )
            )
    if thread.pitch_class is None and thread.major is not None and thread.pitch is not None:
        try:
            loosest = loosest_pitch_class(
                thread.major, thread.pitch, internal=bool(thread.internal)
            )
        except ValueError:
            loosest = None
        if loosest is not None:
            thread.pitch_class = loosest
            thread.class_reason = tr("no class is known: the loosest of ISO 965-1 stands in")


def _unsupported(
    job: ThreadJob,
    thread: Thread,
    words: _ProgramWords,
    undecided: tuple[FoundDesignation, SideUndecided] | None = None,
) -> None:
    if words.fitting:
        thread.unsupported = (
            "an arc (round) thread cut by the fitting method: its profile is an arc, not the "
            "ISO 60° one; the tool radius is checked against the groove's (MB806)"
        )
        return
    taper = job.taper
    if taper is not None and job.is_cycle:
        thread.unsupported = (
            f"a taper thread ({taper.shown} R{taper.words['R']:g} at line {taper.line + 1}): the "
            "root and radius checks are for parallel ISO metric threads"
        )
        return
    if thread.designation is None and words.other_form is not None:
        what, line = words.other_form
        thread.unsupported = (
            f"{what} (line {line + 1}): only ISO metric 60° threads are checked against their "
            "profile"
        )
        return
    if undecided is not None and (thread.major is None or thread.internal is None):
        where, err = undecided
        case = "" if err.written_class is None else " in the standard's case"
        thread.missing = (
            f"the designation {where.text} at line {where.line + 1} {err.fits()}, and neither "
            f"the cuts nor the program's first comments tell which: write the class{case} "
            f"({err.external.canonical()} or {err.internal.canonical()}), or say EXTERNAL or "
            "INTERNAL in the program's first comment"
        )
    elif thread.major is None:
        thread.missing = (
            "the thread's size is not known: no designation such as (M50x3-5g6g) in the "
            "file's comments fits these passes, no thread module's formulas name the nominal "
            "diameter, and no comment on an assignment does"
        )
    elif thread.internal is None:
        thread.missing = "the passes do not tell an internal thread from an external one"
    elif thread.pitch is None:
        thread.missing = "the pitch is not known"
    elif thread.pitch_class is None:
        thread.missing = f"ISO 965-1 tabulates no tolerance for M{thread.major:g}x{thread.pitch:g}"


def describe(thread: Thread) -> str:
    """What the analysis knows of a thread, for a hover (Markdown)."""
    job = thread.job
    side = {True: "internal", False: "external", None: "side not known"}[thread.internal]
    if thread.unsupported is not None:
        return (
            f"**Thread** cut by {job.shown} in {job.program}: {thread.unsupported}. Only the "
            "passes among themselves are checked (order, depth per pass, feed, start point)."
        )
    if thread.lead_conflict:
        return (
            f"**Thread {thread.name}** cut by {job.shown} in {job.program}: its lead is "
            f"{thread.lead:g}, but the cuts use F{job.lead:g} (MB810); the root and radius "
            f"checks wait until the two agree. Known from {thread.known_from()}."
        )
    if not thread.identified:
        return (
            f"**Thread** cut by {job.shown} in {job.program}: not identified, {thread.missing}. "
            "The root, nose-radius and lead checks need it; the passes are still checked among "
            "themselves (order, depth per pass, feed, start point). A comment such as "
            "(M50x3-5g6g) names the thread."
        )
    reason = f" ({job.side_reason})" if job.side_reason else ""
    lines = [f"**Thread {thread.name}**, {side}{reason}"]
    lines.append(f"- known from {thread.known_from()}")
    assert thread.pitch is not None
    starts = f"{thread.starts} starts" if thread.starts > 1 else "one start"
    lines.append(f"- pitch {thread.pitch:g}, lead {thread.lead:g}, {starts}")
    band = thread.pitch_band()
    if thread.pitch_class is not None and band is not None:
        which = "D2" if thread.internal else "d2"
        lines.append(
            f"- class {thread.class_text()} ({thread.class_reason}): {which} "
            f"{band[0]:.3f}–{band[1]:.3f}"
        )
    root = thread.root_x()
    if root is not None:
        deep = job.deepest(bool(thread.internal))
        assert deep.x is not None
        margin = (root - deep.x) / 2.0 if thread.internal else (deep.x - root) / 2.0
        where = "above" if margin >= 0 else "past"
        lines.append(
            f"- root X{_mm(root)} ({thread.limit_text()}); deepest pass X{_mm(deep.x)}, "
            f"{abs(margin):.3f} mm (radius) {where} it"
        )
    if thread.nose_radius is not None:
        lines.append(f"- nose radius {thread.nose_radius:.4g} ({thread.nose_reason})")
    module = thread.module
    if module is not None and module.height is not None:
        lines.append(f"- thread height #{module.height_var} = {_mm(module.height)} (radius)")
    return "\n".join(lines)


def module_meanings(thread: Thread) -> dict[int, str]:
    """What each variable of a thread module recognised by its formulas stands for."""
    shape = thread.module
    if shape is None:
        return {}
    internal = bool(thread.internal)
    names: dict[int, str] = {
        shape.height_var: "h, thread height (radius): the depth of the last pass",
    }
    if shape.major_var is not None:
        names[shape.major_var] = "d / D, nominal diameter of the thread"
    if internal and shape.base_var != shape.major_var:
        names[shape.base_var] = "D1, minor diameter of the internal thread"
    if shape.pitch_var is not None:
        names[shape.pitch_var] = "the lead the thread is cut with (F), the pitch of one start"
    if shape.radius_var is not None:
        names[shape.radius_var] = f"r, tool nose radius: the radius {shape.radius_how}"
    if thread.deviation_var is not None:
        names[thread.deviation_var] = (
            "EI, fundamental deviation" if internal else "es, fundamental deviation (magnitude)"
        )
    if thread.tolerance_var is not None:
        names[thread.tolerance_var] = (
            "TD2, pitch-diameter tolerance" if internal else "Td2, pitch-diameter tolerance"
        )
    return names
