"""The symmetric thread module of seed 000: a main program in the shape of O4009 (external) /
O4010 (internal) that enters ``#100``-``#104`` from the ISO 965-1 tables, and the sub-program
O3331 / O3330 with the paper's statements.

The numbers in the generated comments (thread height, depths, pass counts, final X ...) are
read from executing the generated program with the project's evaluator, not from the
formulas: a comment then states what the control will do with this very text.  The generator
renders the program once without those numbers, runs it, and renders it again with them;
comments do not change what runs, so the values hold for the final text.  The arc thread and
the drum groove have their own generators (``arc_thread_generator``, ``drum_groove_generator``).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..analysis import Analysis
from ..evaluator import Facts
from ..threads.designation import ThreadDesignation, parse_designation
from ..threads.iso965 import tolerances
from .generated_program import (
    GENERATED_URI,
    FreeNumbers,
    Lines,
    count_of,
    entered,
    execute,
    free_numbers,
    mm,
    num,
    program_number,
)

__all__ = (
    "INFEEDS",
    "MATERIAL_COEFFICIENTS",
    "ThreadModule",
    "build_module",
    "build_module_from_values",
    "default_program_numbers",
    "generate_module",
    "module_numbers",
)

# Depth coefficient of the paper: 0.2 for ordinary steel, a third of it for molybdenum.
STEEL_COEFFICIENT = 0.2
MOLYBDENUM_COEFFICIENT = 0.2 / 3.0

_SUPPRESS_MB701 = "FANUC-MACRO: IGNORE MB701"


def _written(facts: Facts, line: int) -> float:
    """The first value the block at ``line`` assigned."""
    write = facts.document(GENERATED_URI).writes.get(line)
    if write is None or not isinstance(write[1].first, float):
        raise RuntimeError(f"the generated block at line {line + 1} assigned no number")
    return write[1].first


def _runs(facts: Facts, line: int) -> int:
    return facts.document(GENERATED_URI).runs.get(line, 0)


def _constant_conditions(analysis: Analysis, lines: Mapping[int, str]) -> dict[int, str]:
    """MB701 at the given lines (key names): 'TRUE' or 'FALSE' for each such line."""
    facts = analysis.facts
    assert facts is not None
    found: dict[int, str] = {}
    for diag in analysis.diagnostics:
        if diag.code == "MB701" and diag.line in lines:
            jc = facts.document(GENERATED_URI).jumps.get(diag.line)
            found[diag.line] = "TRUE" if jc is not None and jc.taken else "FALSE"
    return found


@dataclass(frozen=True)
class ThreadModule:
    """A generated symmetric thread module and what executing it gave (radius values, mm)."""

    text: str
    internal: bool
    main_number: int
    sub_number: int
    nose_radius: float  # r, #3
    height: float  # h, #4
    ap_max: float  # #5
    ap_min: float  # #6
    first_offset: float  # u of the first rough pass, #10
    rough_passes: int  # left + right G92 pair per pass
    g92_cuts: int  # every G92 cut of the sub-program
    final_x: float  # X of the last G92 cut (diameter)

    @property
    def lines(self) -> list[str]:
        return self.text.splitlines()

    def sub_program_lines(self) -> list[str]:
        """The sub-program, from its O line to its M99 (without the tape's ``%``)."""
        lines = self.lines
        head = f"O{self.sub_number:04d}"
        start = next(i for i, text in enumerate(lines) if text.split(" ")[0] == head)
        end = next(i for i in range(start, len(lines)) if lines[i].split(" ")[0] == "M99")
        return lines[start : end + 1]

    def call_line(self) -> str:
        """The main program's M98 block that calls the sub-program, with its comment."""
        return next(text for text in self.lines if text.startswith("M98 "))

    def value_line(self, number: int) -> str:
        """The main program's assignment of ``#number`` (#100-#104), with its comment."""
        return next(text for text in self.lines if text.startswith(f"#{number}="))


def default_program_numbers(internal: bool) -> tuple[int, int]:
    """(main, sub): the paper's O4010/O3330 internal, O4009/O3331 external."""
    return (4010, 3330) if internal else (4009, 3331)


def module_numbers(designation: str, internal: bool | None, taken: Collection[int]) -> FreeNumbers:
    """(main, sub) for the module of ``designation`` going into a file that has the programs
    ``taken``: the paper's numbers, or the first free ones after them.  A designation that does
    not say its side with ``internal`` None gets the external numbers: the generator refuses
    it anyway."""
    if internal is None:
        try:
            internal = parse_designation("".join(designation.split())).internal
        except ValueError:
            internal = False
    main, sub = default_program_numbers(bool(internal))
    return free_numbers((("main program", main), ("sub-program", sub)), taken)


def _coefficient_text(coefficient: float) -> str:
    """``0.2/3.`` for the paper's molybdenum coefficient, else the number."""
    if not coefficient > 0 or not math.isfinite(coefficient):
        raise ValueError(f"the depth coefficient {coefficient} must be a positive number")
    for divisor in range(2, 13):
        top = coefficient * divisor
        # A fraction of a short decimal (0.2/3) is entered as the paper does, exactly.
        if abs(coefficient - round(coefficient, 6)) > 1e-12 and abs(top - round(top, 6)) < 1e-12:
            return f"{num(round(top, 6), 6)}/{divisor}."
    if abs(coefficient - round(coefficient, 8)) > 1e-15:
        raise ValueError(
            f"the depth coefficient {coefficient} has more than 8 decimals; "
            "give it as a short decimal or a fraction of one (0.2/3)"
        )
    return num(coefficient, 8)


# How the rough passes reach the depth (seed 000, "参数调整方法": with fewer statements the
# module becomes the left-right method; one flank only is G76's infeed).
INFEEDS: Mapping[str, str] = MappingProxyType(
    {
        "symmetric": "SYMMETRIC LEFT-RIGHT CUTTING",  # both flanks every pass: the paper's
        "alternate": "ALTERNATE FLANK INFEED",  # left flank one pass, right flank the next
        "left": "LEFT FLANK INFEED",  # every pass on the -Z flank
        "right": "RIGHT FLANK INFEED",  # every pass on the +Z flank
    }
)


@dataclass(frozen=True)
class _ModuleSpec:
    diameter: float
    pitch: float
    length: float
    deviation: float  # |es| or EI, as the paper enters it
    pitch_tolerance: float  # Td2 / TD2
    internal: bool
    coefficient: str
    spring_passes: int
    main_number: int
    sub_number: int
    spindle_speed: int
    title: str  # designation (or "M50x3") for the header, in the case ISO 965-1 writes it
    deviation_note: str
    tolerance_note: str
    infeed: str = "symmetric"
    taper: float = 0.0  # diameter change per mm of length (#106); 0: a parallel thread
    starts: int = 1  # lead = starts x pitch (#105)
    left_hand: bool = False  # cut toward +Z


def _taper_text(taper: float) -> str:
    """``1:16`` for a ratio of whole numbers, else the diameter change per mm."""
    ratio = 1.0 / abs(taper)
    if abs(ratio - round(ratio)) < 1e-9:
        return f"{'-' if taper < 0 else ''}1:{round(ratio)}"
    return f"{num(taper, 6)} PER MM"


def _render_module(spec: _ModuleSpec, notes: Mapping[str, str]) -> Lines:
    """The module text; ``notes`` adds measured numbers to the keyed blocks' comments.

    Without the options (symmetric infeed, parallel, one start, right hand) the statements
    are the paper's, character for character."""
    out = Lines()
    out.add("%")
    _render_main(out, spec, notes)
    # The sub-program: the paper's statements; the options change only the words they need.
    _render_depths(out, spec, notes)
    if spec.taper != 0.0:
        out.add(_taper_r(spec), "TAPER R OF THE CUT, RADIUS")
    cut = _cut_of(spec)
    out.add(f"G01 X{cut.start_x} {cut.position} G99 F0.5", "POSITION")
    _render_rough_passes(out, spec, notes, cut)
    _render_finish(out, spec, notes, cut)
    out.add("M99", "BACK TO THE MAIN PROGRAM")
    out.add("%")
    return out


def _side(spec: _ModuleSpec) -> str:
    return "INTERNAL" if spec.internal else "EXTERNAL"


def _render_main(out: Lines, spec: _ModuleSpec, notes: Mapping[str, str]) -> None:
    """The main program: it enters #100-#104 (and #105, #106 for the options), then calls."""
    internal = spec.internal
    d = spec.diameter
    tapered = spec.taper != 0.0
    side = _side(spec)
    out.add(
        f"O{spec.main_number:04d}",
        f"MAIN - {side} THREAD {spec.title} L={spec.length:g}",
        keep_case=spec.title,
    )
    out.add("T0101", f"{side} THREADING TOOL")
    home_x = num(math.ceil(d + 50.0))
    if internal:
        # Below the minor diameter with 1 mm to spare, as the paper's X45. for D1 46.752.
        bore_x = num(max(0.0, math.floor(d - 1.25 * math.sqrt(3.0) / 2.0 * spec.pitch - 1.0)))
        out.add(f"G00 X{home_x} Z100.", "POSITION")
        out.add(f"X{bore_x}", "INTO THE BORE")
        out.add("Z10.", "POSITION")
        out.add("G01 Z0 F0.5", "POSITION")
    else:
        out.add(f"G00 X{num(d + 5.0)} Z0.", "POSITION")
    out.add(f"G97 S{spec.spindle_speed} M03 M8", "THREADING SPEED, COOLANT ON")
    out.add(f"#100={num(d)}", "NOMINAL DIAMETER" + (" AT Z0" if tapered else ""))
    out.add(f"#101={num(spec.pitch)}", "PITCH")
    out.add(f"#102={num(spec.length)}", "THREAD LENGTH")
    out.add(f"#103={num(spec.deviation)}", spec.deviation_note)
    out.add(f"#104={num(spec.pitch_tolerance)}", spec.tolerance_note)
    if spec.starts > 1:
        out.add(
            f"#105={num(spec.starts * spec.pitch)}",
            f"LEAD PH = {spec.starts} STARTS X PITCH",
        )
    if tapered:
        grows = "SHRINKS" if internal else "GROWS"
        out.add(
            f"#106={num(spec.taper, 8)}",
            f"TAPER {_taper_text(spec.taper)}: THE DIAMETER {grows} BY #106 PER MM TOWARD -Z",
        )
    call = notes.get("call", f"CALL O{spec.sub_number:04d}")
    out.add(f"M98 P001{spec.sub_number:04d}", call, key="call")
    if internal:
        out.add("G00 Z100.", "OUT OF THE BORE")
        out.add(f"X{home_x}", "RETURN")
    else:
        out.add(f"G00 X{home_x} Z100.", "RETURN")
    out.add("T0100", "CANCEL OFFSET")
    out.add("M5", "SPINDLE STOP")
    out.add("M9", "COOLANT OFF")
    out.add("M30", "END OF PROGRAM")


def _render_depths(out: Lines, spec: _ModuleSpec, notes: Mapping[str, str]) -> None:
    """The sub-program's head: run-in and run-out, the thread height, the depths of the
    passes, the side offset, and the counters of the starts, spring passes and flanks."""
    internal = spec.internal
    multi = spec.starts > 1
    coef = spec.coefficient
    lead = "#105" if multi else "#101"
    title = INFEEDS[spec.infeed] + (", LEFT HAND" if spec.left_hand else "")
    out.add(f"O{spec.sub_number:04d}", f"{_side(spec)} THREAD SUB - {title}, G92")
    if multi:
        out.add(f"#1=1.*{lead}", "RUN-OUT DELTA2 FROM THE LEAD")
        out.add(f"#2=2.*{lead}+{lead}+FIX[#102/{lead}]*{lead}-#102", "RUN-IN DELTA1 FROM THE LEAD")
    else:
        out.add("#1=1.*#101", "RUN-OUT DELTA2")
        out.add("#2=2.*#101+#101+FIX[#102/#101]*#101-#102", "RUN-IN DELTA1")
    radius = notes.get("r", "TOOL NOSE RADIUS")
    height = notes.get("h", "THREAD HEIGHT")
    if internal:
        out.add("#3=#101/[16*SIN[60]]", radius, key="r")
        out.add("#4=[6./8.]*SIN[60]*#101-#3+#103/2.+#104/4.", height, key="h")
    else:
        out.add("#3=#101/[8*SIN[60]]", radius, key="r")
        out.add("#4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.", height, key="h")
    out.add(f"#5=[{coef}]*SQRT[#4]", notes.get("apmax", "FIRST DEPTH AP MAX"), key="apmax")
    apmin = notes.get("apmin", "MIN DEPTH AND ALLOWANCE AP MIN")
    out.add(f"#6=[{coef}]*SQRT[#5]", apmin, key="apmin")
    if multi:
        # One call cuts every start: the passes of all the starts are one thread.
        out.add("#16=0.", "START NUMBER, 0 THE FIRST")
        out.add("#17=ROUND[#105/#101]", "STARTS = LEAD / PITCH")
        out.add("WHILE[#16LT#17]DO1", "EACH START, ONE PITCH FURTHER IN Z", key="start")
        out.add("#15=#16*#101", "Z SHIFT OF THIS START")
    out.add("#7=1.", "PASS NUMBER")
    out.add("#8=#5*[SQRT[#7]-SQRT[#7-1.]]", "DEPTH OF THE PASS")
    out.add("#9=#5*SQRT[#7]", "TOTAL DEPTH")
    out.add("#10=[#4+#3-#6-#9]*TAN[30]-#3*TAN[30]", notes.get("u", "SIDE OFFSET U"), key="u")
    if internal:
        d1 = notes.get("d1", "MINOR DIAMETER D1")
        out.add("#11=#100-2.*[5./8.]*SIN[60]*#101", d1, key="d1")
    if spec.spring_passes >= 2:
        out.add(f"#12={spec.spring_passes}.", "SPRING PASSES")
    if spec.infeed == "alternate":
        out.add("#13=-1.", "FLANK OF THE PASS: -1 LEFT, +1 RIGHT")


@dataclass(frozen=True)
class _Cut:
    """The words of one G92 cut of the sub-program, for the module's options."""

    ref: str  # the diameter the depths are taken from: #100, or #11 (D1) inside
    sign: str  # toward the depth: "-" outside, "+" inside
    back: str  # away from it
    position: str  # the W move to the cut's start
    start_x: str  # the X the tool starts from
    words: str  # the cut's W, R and F words
    cone: str  # "+"/"-": which way the cone's diameter changes; "" parallel
    end: str  # where the cut ends, as a distance toward -Z from Z0

    def target(self, depth: str, flank: str = "") -> str:
        """The cut's X: the cone at the cut's end (moved ``flank`` along Z), less the depth."""
        if not self.cone:
            return f"X[{self.ref}{depth}]"
        return f"X[{self.ref}{self.cone}#106*[{self.end}{flank}]{depth}]"


def _cut_of(spec: _ModuleSpec) -> _Cut:
    """The cut's words; a tapered module adds #14, the cut's R, as it works them out."""
    internal = spec.internal
    multi = spec.starts > 1
    ref = "#11" if internal else "#100"
    lead = "#105" if multi else "#101"
    # The run-in of a start past the first is one pitch longer per start (#15): every start
    # ends where the first does, and the spindle's one-turn signal puts it a pitch further.
    shift = "+#15" if multi else ""
    run = f"#2{shift}+#102+#1"  # the cut's length along Z
    if spec.left_hand:
        # Toward +Z: the run-in lies left of the thread, the run-out right of Z0.
        position = f"W[-#102-#2{shift.replace('+', '-')}]"
        travel = f"W[{run}]"
        end = "-#1"
    else:
        position = f"W[#2{shift}]"
        travel = f"W[-#2{shift.replace('+', '-')}-#102-#1]"
        end = "#102+#1"
    if spec.taper != 0.0:
        taper_word = "R#14"
        cone = "-" if internal else "+"
        clear = "-" if internal else "+"
        start_x = f"[{ref}{clear}ABS[#106]*[{run}]{clear}1.]"
    else:
        taper_word = "R0"
        cone = ""
        start_x = "[#11-1.]" if internal else "[#100+1.]"
    return _Cut(
        ref=ref,
        sign="+" if internal else "-",
        back="-" if internal else "+",
        position=position,
        start_x=start_x,
        words=f"{travel} {taper_word} F{lead}",
        cone=cone,
        end=end,
    )


def _taper_r(spec: _ModuleSpec) -> str:
    """#14, the tapered cut's R: the radius at the cut's start minus the radius at its end.
    An external cone grows toward -Z, an internal one shrinks (#106 > 0)."""
    run = f"#2{'+#15' if spec.starts > 1 else ''}+#102+#1"
    towards_minus_z = (not spec.internal) != spec.left_hand
    return f"#14={'-' if towards_minus_z else ''}#106*[{run}]/2."


def _render_rough_passes(
    out: Lines, spec: _ModuleSpec, notes: Mapping[str, str], cut: _Cut
) -> None:
    """The loop of rough passes, each by the square-root rule, on the flanks of the infeed."""
    infeed = spec.infeed
    words = cut.words
    rough = f"{cut.sign}2.*#9"
    if infeed == "symmetric":
        out.add("N10 G01 W[-#10]", "LOOP START - STEP LEFT BY U", key="n10")
        out.add(f"G92 {cut.target(rough, '+#10')} {words}", "CUT")
        out.add("G01 W[2.*#10]", "STEP RIGHT BY 2U")
        out.add(f"G92 {cut.target(rough, '-#10')} {words}", "CUT")
        out.add("G01 W[-#10]", "BACK TO THE MIDDLE")
    elif infeed == "alternate":
        out.add("N10 G01 W[#13*#10]", "LOOP START - STEP TO THE FLANK BY U", key="n10")
        out.add(f"G92 {cut.target(rough, '-#13*#10')} {words}", "CUT")
        out.add("G01 W[-#13*#10]", "BACK TO THE MIDDLE")
        out.add("#13=-#13", "THE OTHER FLANK NEXT PASS")
    else:
        left = infeed == "left"
        out.add(
            f"N10 G01 W[{'-' if left else ''}#10]",
            f"LOOP START - STEP {infeed.upper()} BY U",
            key="n10",
        )
        out.add(f"G92 {cut.target(rough, '+#10' if left else '-#10')} {words}", "CUT")
        out.add(f"G01 W[{'' if left else '-'}#10]", "BACK TO THE MIDDLE")
    out.add("#7=#7+1.", "NEXT PASS")
    out.add("#8=#5*[SQRT[#7]-SQRT[#7-1.]]", "DEPTH OF THE NEXT PASS")
    out.add(
        "IF[#8GE#6] THEN #9=#5*SQRT[#7]",
        notes.get("if_ge", "AP-N GE AP-MIN - TOTAL BY THE SQUARE-ROOT RULE"),
        key="if_ge",
    )
    out.add(
        "IF[#8LT#6] THEN #9=#9+#6",
        notes.get("if_lt", "AP-N LT AP-MIN - ADD AP-MIN"),
        key="if_lt",
    )
    out.add("#10=[#4+#3-#6-#9]*TAN[30]-#3*TAN[30]", "NEXT SIDE OFFSET")
    paper = infeed == "symmetric" and spec.taper == 0.0
    # The paper's pairs cut the last depth left and right of the straight rough pass; a
    # single cut there within 0.001 mm of H-AP MIN would only repeat that pass.
    out.add(
        "IF[#9LT[#4-#6]] GOTO10" if paper else "IF[#9LT[#4-#6-0.001]] GOTO10",
        notes.get("loop", "UNTIL THE TOTAL DEPTH REACHES H-AP MIN"),
        key="loop",
    )


def _render_finish(out: Lines, spec: _ModuleSpec, notes: Mapping[str, str], cut: _Cut) -> None:
    """The straight infeed to the full depth, the spring passes, and the next start."""
    sign, back, words = cut.sign, cut.back, cut.words
    out.add(
        f"G92 {cut.target(f'{sign}2.*#4{back}2.*#6')} {words}",
        "STRAIGHT INFEED ROUGH - LEAVE AP MIN",
    )
    finish = notes.get("finish", "STRAIGHT INFEED FINISH")
    out.add(cut.target(f"{sign}2.*#4"), finish, key="finish")
    if spec.spring_passes >= 1:
        spring = notes.get("spring", "SPRING PASS")
        out.add(f"N20 G92 {cut.target(f'{sign}2.*#4')} {words}", spring, key="spring")
    if spec.spring_passes >= 2:
        out.add("#12=#12-1.", "COUNT THE SPRING PASSES")
        out.add("IF[#12GT0.] GOTO20", "REPEAT THE SPRING PASS")
    if spec.starts > 1:
        back_to_z0 = "W[#102+#2+#15]" if spec.left_hand else "W[-#2-#15]"
        out.add(f"G01 {back_to_z0} F0.5", "BACK TO Z0")
        out.add("#16=#16+1.", "NEXT START")
        out.add("END1")


def build_module_from_values(
    diameter: float,
    pitch: float,
    length: float,
    deviation: float,
    pitch_tolerance: float,
    *,
    internal: bool,
    coefficient: float = MOLYBDENUM_COEFFICIENT,
    spring_passes: int = 8,
    main_number: int | None = None,
    sub_number: int | None = None,
    spindle_speed: int = 400,
    designation: ThreadDesignation | None = None,
    deviation_note: str | None = None,
    tolerance_note: str | None = None,
    infeed: str = "symmetric",
    taper: float = 0.0,
    starts: int = 1,
    left_hand: bool = False,
) -> ThreadModule:
    """The module for explicit values; ``deviation`` is |es| or EI, a magnitude (#103).

    ``infeed`` is one of :data:`INFEEDS`; ``taper`` the diameter change per mm of length
    (1/16 for a 1:16 cone; positive: an external thread grows toward -Z, an internal one
    shrinks, the nominal diameter being the one at Z0); ``starts`` the number of starts (the
    lead is ``starts`` x ``pitch``); ``left_hand`` cuts toward +Z."""
    _check_thread(diameter, pitch, length, deviation, pitch_tolerance)
    _check_options(spring_passes, spindle_speed, infeed, taper, starts)
    deviation = abs(deviation)  # the paper enters es as a magnitude
    default_main, default_sub = default_program_numbers(internal)
    main = program_number(default_main if main_number is None else main_number, "main")
    sub = program_number(default_sub if sub_number is None else sub_number, "sub")
    if main == sub:
        raise ValueError(f"the main program and the sub-program are both O{main:04d}")
    # The designation as ISO 965-1 writes it, the class's case telling the kind (5g6g external,
    # 5G6G internal): the checker reads the comment back as the same thread and side.
    if designation is not None:
        title = designation.canonical()
    else:
        title = f"M{num(diameter).rstrip('.')}x{num(pitch).rstrip('.')}"
    which = "EI" if internal else "ES"
    if deviation_note is None:
        signed = deviation if internal else -deviation
        deviation_note = f"{which}={signed:g}" + ("" if internal else " AS A MAGNITUDE")
    spec = _ModuleSpec(
        diameter=diameter,
        pitch=pitch,
        length=length,
        deviation=deviation,
        pitch_tolerance=pitch_tolerance,
        internal=internal,
        coefficient=_coefficient_text(coefficient),
        spring_passes=spring_passes,
        main_number=main,
        sub_number=sub,
        spindle_speed=spindle_speed,
        title=title,
        deviation_note=deviation_note,
        tolerance_note="TD2 TOLERANCE" if tolerance_note is None else tolerance_note,
        infeed=infeed,
        taper=taper,
        starts=starts,
        left_hand=left_hand,
    )
    draft = _render_module(spec, {})
    analysis = execute(draft.text())
    measured = _measured(spec, draft, analysis)
    notes = _measured_notes(spec, measured, draft, analysis)
    return ThreadModule(
        text=_render_module(spec, notes).text(),
        internal=internal,
        main_number=main,
        sub_number=sub,
        nose_radius=measured.nose_radius,
        height=measured.height,
        ap_max=measured.ap_max,
        ap_min=measured.ap_min,
        first_offset=measured.first_offset,
        rough_passes=measured.rough_passes,
        g92_cuts=measured.g92_cuts,
        final_x=measured.final_x,
    )


def _check_thread(
    diameter: float, pitch: float, length: float, deviation: float, pitch_tolerance: float
) -> None:
    """Refuses a thread the module cannot cut: sizes not positive, a pitch not below the
    diameter, a deviation or tolerance not a finite number."""
    for name, value in (("diameter", diameter), ("pitch", pitch), ("length", length)):
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"the thread {name} {value} must be a positive number")
    if pitch >= diameter:
        raise ValueError(f"pitch {pitch:g} is not smaller than the diameter {diameter:g}")
    if not math.isfinite(deviation) or not math.isfinite(pitch_tolerance) or pitch_tolerance < 0:
        raise ValueError(
            f"the deviation {deviation} and the pitch-diameter tolerance {pitch_tolerance} "
            "must be finite numbers, the tolerance not negative"
        )


def _check_options(
    spring_passes: int, spindle_speed: int, infeed: str, taper: float, starts: int
) -> None:
    """Refuses options outside what the module's statements can do."""
    if not 0 <= spring_passes <= 99:
        raise ValueError(f"spring passes {spring_passes} must be 0-99")
    if not 1 <= spindle_speed <= 99999:
        raise ValueError(f"spindle speed S{spindle_speed} is outside 1-99999")
    if infeed not in INFEEDS:
        raise ValueError(f"the infeed {infeed} is not one of {', '.join(INFEEDS)}")
    # Beyond 1:2 (a half-angle of 14 degrees) a G92 thread's depth is no longer the
    # radial depth the module computes; pipe threads are 1:16.
    if not math.isfinite(taper) or abs(taper) > 0.5:
        raise ValueError(f"the taper {taper} must be a diameter change of at most 0.5 per mm (1:2)")
    if not 1 <= starts <= 9:
        raise ValueError(f"{starts} starts: the module cuts 1-9")


@dataclass(frozen=True)
class _Measured:
    """What executing the draft module gave: the values its comments state."""

    nose_radius: float
    height: float
    ap_max: float
    ap_min: float
    first_offset: float
    rough_passes: int  # of each start
    g92_cuts: int
    final_x: float
    where: str  # the final cut's X, and its Z on a cone


def _measured(spec: _ModuleSpec, draft: Lines, analysis: Analysis) -> _Measured:
    facts = analysis.facts
    assert facts is not None
    at = draft.at
    g92 = [m for m in facts.motions if m.code == "G92"]
    if not g92 or "X" not in g92[-1].words:
        raise RuntimeError("executing the generated module gave no G92 cut")
    final_x = g92[-1].words["X"]
    # On a cone the final X is the one at the cut's end.
    where = f"X{mm(final_x)}"
    if spec.taper and g92[-1].z is not None:
        where += f" Z{mm(g92[-1].z)}"
    return _Measured(
        nose_radius=_written(facts, at["r"]),
        height=_written(facts, at["h"]),
        ap_max=_written(facts, at["apmax"]),
        ap_min=_written(facts, at["apmin"]),
        first_offset=_written(facts, at["u"]),
        rough_passes=_runs(facts, at["n10"]) // spec.starts,
        g92_cuts=len(g92),
        final_x=final_x,
        where=where,
    )


def _measured_notes(
    spec: _ModuleSpec, measured: _Measured, draft: Lines, analysis: Analysis
) -> dict[str, str]:
    """The keyed blocks' comments with the measured numbers, and the conditions that are
    decided for this thread (which the checker reports) said to be."""
    passes = measured.rough_passes
    per_pass = 2 if spec.infeed == "symmetric" else 1
    where = measured.where
    sub = spec.sub_number
    starts = spec.starts
    g92_cuts = measured.g92_cuts
    notes = {
        "r": f"TOOL NOSE RADIUS R={mm(measured.nose_radius)}",
        "h": f"THREAD HEIGHT H={mm(measured.height)}",
        "apmax": f"FIRST DEPTH AP MAX={mm(measured.ap_max)}",
        "apmin": f"MIN DEPTH AND FINISH ALLOWANCE AP MIN={mm(measured.ap_min)}",
        "u": f"SIDE OFFSET U={mm(measured.first_offset)} OF THE FIRST PASS",
        "loop": f"UNTIL THE TOTAL DEPTH REACHES H-AP MIN: {count_of(passes, 'ROUGH PASS')}, "
        f"{per_pass * passes} G92 CUTS",
        "finish": f"STRAIGHT INFEED FINISH AT {where}",
        "spring": f"{count_of(spec.spring_passes, 'SPRING PASS')} AT {where}",
        "call": f"CALL O{sub:04d}: {g92_cuts} G92 CUTS, FINAL {where}"
        if starts == 1
        else f"CALL O{sub:04d}: {starts} STARTS OF {g92_cuts // starts} G92 CUTS, FINAL {where}",
    }
    at = draft.at
    if spec.internal:
        facts = analysis.facts
        assert facts is not None
        notes["d1"] = f"MINOR DIAMETER D1={mm(_written(facts, at['d1']))}"
    keyed = {at[k]: k for k in ("if_ge", "if_lt", "loop")}
    bases = {
        "if_ge": "AP-N GE AP-MIN",
        "if_lt": "AP-N LT AP-MIN",
        "loop": f"LOOP CONDITION: {count_of(passes, 'ROUGH PASS')},",
    }
    for line, outcome in _constant_conditions(analysis, keyed).items():
        # The paper's statements are kept for every thread; for this one the branch is
        # decided, which the checker rightly reports: say so where it happens.
        key = keyed[line]
        notes[key] = f"{bases[key]} ALWAYS {outcome} FOR THIS THREAD - {_SUPPRESS_MB701}"
    return notes


def build_module(
    designation: str | ThreadDesignation,
    length: float,
    internal: bool | None = None,
    *,
    coefficient: float = MOLYBDENUM_COEFFICIENT,
    spring_passes: int = 8,
    main_number: int | None = None,
    sub_number: int | None = None,
    td2_override: float | None = None,
    deviation_override: float | None = None,
    spindle_speed: int = 400,
    infeed: str = "symmetric",
    taper: float = 0.0,
) -> ThreadModule:
    """:func:`generate_module` with the measured values (see :class:`ThreadModule`)."""
    if isinstance(designation, str):
        des = parse_designation(designation, internal=internal)
    else:
        des = designation
        if internal is not None and internal != des.internal:
            raise ValueError(
                f"{des.canonical()} is an {des.side} thread, but an "
                f"{'external' if des.internal else 'internal'} one was asked for"
            )
    # What the user typed goes into the main program as typed, or is refused.
    # (The taper's eighth decimal is far below the control's increment over any length.)
    entered("thread length", length)
    for name, override in (("Td2/TD2", td2_override), ("es/EI", deviation_override)):
        if override is not None:
            entered(name, override)
    grade = des.pitch_class
    which = "EI" if des.internal else "ES"
    tol_name = "TD2" if des.internal else "Td2"
    if td2_override is None or deviation_override is None:
        tol = tolerances(des)
        deviation = tol.fundamental_deviation
        pitch_tolerance = tol.pitch_diameter_tolerance
        derived = tol_name in tol.derived
    else:
        deviation = pitch_tolerance = 0.0
        derived = False
    if deviation_override is not None:
        deviation_note = f"{which} MAGNITUDE {num(abs(deviation_override))} GIVEN"
        deviation = abs(deviation_override)
    else:
        position = f"{grade.position}".upper()
        deviation_note = f"{which}={deviation:g} POSITION {position} ISO 965-1" + (
            "" if des.internal else ", AS A MAGNITUDE"
        )
    if td2_override is not None:
        if td2_override < 0:
            raise ValueError(f"{tol_name} override {td2_override:g} must not be negative")
        tolerance_note = f"{tol_name.upper()} {num(td2_override)} GIVEN"
        pitch_tolerance = td2_override
    else:
        source = "FROM THE ISO FORMULA" if derived else "ISO 965-1"
        tolerance_note = f"{tol_name.upper()} GRADE {grade.grade} {source}"
    return build_module_from_values(
        des.nominal_diameter,
        des.pitch,
        length,
        abs(deviation),
        pitch_tolerance,
        internal=des.internal,
        coefficient=coefficient,
        spring_passes=spring_passes,
        main_number=main_number,
        sub_number=sub_number,
        spindle_speed=spindle_speed,
        designation=des,
        deviation_note=deviation_note,
        tolerance_note=tolerance_note,
        infeed=infeed,
        taper=taper,
        starts=des.starts,
        left_hand=des.left_hand,
    )


def generate_module(
    designation: str,
    length: float,
    internal: bool | None = None,
    *,
    coefficient: float = MOLYBDENUM_COEFFICIENT,
    spring_passes: int = 8,
    main_number: int | None = None,
    sub_number: int | None = None,
    td2_override: float | None = None,
    deviation_override: float | None = None,
    infeed: str = "symmetric",
    taper: float = 0.0,
) -> str:
    """The symmetric thread module (main + sub-program) for ``designation``, thread length L.

    ``#103`` is es (external) or EI (internal) as a magnitude and ``#104`` Td2 / TD2, both
    from ISO 965-1 unless overridden.  ``coefficient`` is 0.2 for steel, 0.2/3 (default, the
    paper's) for molybdenum; ``spring_passes`` is n' (``#12``).  Raises ValueError for a bad
    designation or a thread the tables do not cover (give both overrides then).

    ``internal`` says the kind of thread when the designation does not: all capitals with a
    class both kinds have in ISO 965-1 (``M50X3-5G6G``), or no class.  Such a designation with
    ``internal`` None raises :class:`~fanuc_macro.threads.designation.SideUndecided`, one
    whose class says the other kind :class:`~fanuc_macro.threads.designation.SideConflict`
    (both ValueErrors): the kind is never guessed.  The main program's comment writes the
    designation in the case of ISO 965-1 (``M50x3-5g6g``, ``M50x3-5G6G``).

    A multi-start designation (``M24xPh4P2-6g``) cuts each start in turn, one pitch further
    in Z, with the lead as F and the depth from the pitch; a left-hand one (``...-LH``) cuts
    toward +Z.  ``infeed`` and ``taper``: see :func:`build_module_from_values`.
    """
    return build_module(
        designation,
        length,
        internal,
        coefficient=coefficient,
        spring_passes=spring_passes,
        main_number=main_number,
        sub_number=sub_number,
        td2_override=td2_override,
        deviation_override=deviation_override,
        infeed=infeed,
        taper=taper,
    ).text


# For callers that pick a material by name.
MATERIAL_COEFFICIENTS: Mapping[str, float] = MappingProxyType(
    {
        "steel": STEEL_COEFFICIENT,
        "molybdenum": MOLYBDENUM_COEFFICIENT,
    }
)
