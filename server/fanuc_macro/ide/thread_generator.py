"""Program generators for the thread programs of the seed papers.

* :func:`generate_module`: the symmetric thread module (seed 000): a main program in the shape
  of O4009 (external) / O4010 (internal) that enters ``#100``-``#104`` from the ISO 965-1
  tables, and the sub-program O3331 / O3330 with the paper's statements.
* :func:`generate_arc_thread`: the large-pitch arc thread by the fitting method (seed 002): a
  main program, one G65 roughing macro called once per layer, one G65 finishing macro.
* :func:`generate_drum_groove`: the drum-shaped spiral groove (seed 003): chained taper
  threads (continuous G32) through the profile points, layer by layer, in one G65 macro.

The numbers in the generated comments (thread height, depths, pass counts, final X ...) are
read from executing the generated program with the project's evaluator, not from the
formulas: a comment then states what the control will do with this very text.  Each
generator renders the program once without those numbers, runs it, and renders it again
with them; comments do not change what runs, so the values hold for the final text.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..analysis import Analysis, analyse
from ..evaluator import Facts, Motion
from ..threads.designation import ThreadDesignation, parse_designation
from ..threads.iso965 import tolerances
from ..threads.profile import CrownFit, fit_crown

__all__ = [
    "DRUM_PROFILE",
    "ArcThreadProgram",
    "DrumGrooveProgram",
    "ThreadModule",
    "build_arc_thread",
    "build_drum_groove",
    "build_module",
    "build_module_from_values",
    "default_program_numbers",
    "generate_arc_thread",
    "generate_drum_groove",
    "generate_module",
]

# Depth coefficient of the paper: 0.2 for ordinary steel, a third of it for molybdenum.
STEEL_COEFFICIENT = 0.2
MOLYBDENUM_COEFFICIENT = 0.2 / 3.0

# Seed 003, table 1: the drum profile (X diameter, Z), 5 segments right of Z0, 6 left.
DRUM_PROFILE: tuple[tuple[float, float], ...] = (
    (298.91, 205.0),
    (302.104, 173.0),
    (304.83, 140.0),
    (307.092, 105.0),
    (308.708, 70.0),
    (309.677, 35.0),
    (310.0, 0.0),
    (309.677, -35.0),
    (308.708, -70.0),
    (307.092, -105.0),
    (304.83, -140.0),
    (303.246, -160.0),
)

_URI = "generated:thread-program.nc"
_SUPPRESS_MB701 = "FANUC-MACRO: IGNORE MB701"


# ---------------------------------------------------------------------------------------------
# Text helpers
# ---------------------------------------------------------------------------------------------


def _num(value: float, places: int = 4) -> str:
    """A FANUC number with a decimal point: ``50.``, ``0.048``, ``-0.5``."""
    text = f"{value:.{places}f}".rstrip("0")
    if text in ("-0.", "0.", "-."):
        return "0."
    return text


def _mm(value: float) -> str:
    """A measured length for a comment, to the least input increment (0.001 mm)."""
    text = f"{value:.3f}"
    return "0.000" if text == "-0.000" else text


def _count(n: int, word: str) -> str:
    """``1 SPRING PASS``, ``8 SPRING PASSES``."""
    plural = word + ("ES" if word.endswith("S") else "S")
    return f"{n} {word if n == 1 else plural}"


def _clean_comment(text: str) -> str:
    # Old controls read only upper-case ASCII in comments, and a ')' would end the comment.
    cleaned = text.upper().replace("(", "").replace(")", "").replace("%", " PCT")
    if not cleaned.isascii():
        raise ValueError(f"comment {text!r} must be ASCII for old controls")
    return " ".join(cleaned.split())


class _Lines:
    """A program text under construction; ``key`` remembers where a block landed."""

    def __init__(self) -> None:
        self.lines: list[str] = []
        self.at: dict[str, int] = {}

    def add(self, code: str, comment: str = "", key: str | None = None) -> None:
        if key is not None:
            self.at[key] = len(self.lines)
        note = _clean_comment(comment)
        if code and note:
            self.lines.append(f"{code} ({note})")
        elif note:
            self.lines.append(f"({note})")
        else:
            self.lines.append(code)

    def text(self) -> str:
        return "\n".join(self.lines) + "\n"


def _program_number(value: int, what: str) -> int:
    if not 1 <= value <= 9999:
        raise ValueError(f"{what} program number O{value} is outside O0001-O9999")
    return value


# ---------------------------------------------------------------------------------------------
# Running a generated program
# ---------------------------------------------------------------------------------------------


def _execute(text: str) -> Analysis:
    """Analyse (parse, evaluate, check) a generated program; fail loudly if it did not run."""
    analysis = analyse(text, _URI)
    facts = analysis.facts
    if facts is None:
        raise RuntimeError("the evaluator failed on the generated program")
    if facts.stopped is not None:
        raise RuntimeError(f"the evaluator stopped early on the generated program: {facts.stopped}")
    alarms = [f.message for f in facts.document(_URI).findings if f.kind.startswith("alarm:")]
    if alarms:
        raise RuntimeError(f"the generated program raises an alarm: {alarms[0]}")
    return analysis


def _written(facts: Facts, line: int) -> float:
    """The first value the block at ``line`` assigned."""
    write = facts.document(_URI).writes.get(line)
    if write is None or not isinstance(write[1].first, float):
        raise RuntimeError(f"the generated block at line {line + 1} assigned no number")
    return write[1].first


def _runs(facts: Facts, line: int) -> int:
    return facts.document(_URI).runs.get(line, 0)


def _constant_conditions(analysis: Analysis, lines: Mapping[int, str]) -> dict[int, str]:
    """MB701 at the given lines (key names): 'TRUE' or 'FALSE' for each such line."""
    facts = analysis.facts
    assert facts is not None
    found: dict[int, str] = {}
    for diag in analysis.diagnostics:
        if diag.code == "MB701" and diag.line in lines:
            jc = facts.document(_URI).jumps.get(diag.line)
            found[diag.line] = "TRUE" if jc is not None and jc.taken else "FALSE"
    return found


# ---------------------------------------------------------------------------------------------
# The symmetric thread module (seed 000: O4009/O3331 external, O4010/O3330 internal)
# ---------------------------------------------------------------------------------------------


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


def _coefficient_text(coefficient: float) -> str:
    """``0.2/3.`` for the paper's molybdenum coefficient, else the number."""
    if not coefficient > 0 or not math.isfinite(coefficient):
        raise ValueError(f"depth coefficient {coefficient!r} must be a positive number")
    for divisor in range(2, 13):
        top = coefficient * divisor
        # A fraction of a short decimal (0.2/3) is entered as the paper does, exactly.
        if abs(coefficient - round(coefficient, 6)) > 1e-12 and abs(top - round(top, 6)) < 1e-12:
            return f"{_num(round(top, 6), 6)}/{divisor}."
    if abs(coefficient - round(coefficient, 8)) > 1e-15:
        raise ValueError(
            f"depth coefficient {coefficient!r} has more than 8 decimals; "
            "give it as a short decimal or a fraction of one (0.2/3)"
        )
    return _num(coefficient, 8)


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
    title: str  # designation (or "M50X3") for the header
    deviation_note: str
    tolerance_note: str


def _render_module(spec: _ModuleSpec, notes: Mapping[str, str]) -> _Lines:
    """The module text; ``notes`` adds measured numbers to the keyed blocks' comments."""

    def note(key: str, base: str) -> str:
        return notes.get(key, base)

    internal = spec.internal
    d = spec.diameter
    side = "INTERNAL" if internal else "EXTERNAL"
    out = _Lines()
    out.add("%")
    out.add(f"O{spec.main_number:04d}", f"MAIN - {side} THREAD {spec.title} L={spec.length:g}")
    out.add("T0101", f"{side} THREADING TOOL")
    home_x = _num(math.ceil(d + 50.0))
    if internal:
        # Below the minor diameter with 1 mm to spare, as the paper's X45. for D1 46.752.
        bore_x = _num(max(0.0, math.floor(d - 1.25 * math.sqrt(3.0) / 2.0 * spec.pitch - 1.0)))
        out.add(f"G00 X{home_x} Z100.", "POSITION")
        out.add(f"X{bore_x}", "INTO THE BORE")
        out.add("Z10.", "POSITION")
        out.add("G01 Z0 F0.5", "POSITION")
    else:
        out.add(f"G00 X{_num(d + 5.0)} Z0.", "POSITION")
    out.add(f"G97 S{spec.spindle_speed} M03 M8", "THREADING SPEED, COOLANT ON")
    out.add(f"#100={_num(d)}", "NOMINAL DIAMETER")
    out.add(f"#101={_num(spec.pitch)}", "PITCH")
    out.add(f"#102={_num(spec.length)}", "THREAD LENGTH")
    out.add(f"#103={_num(spec.deviation)}", spec.deviation_note)
    out.add(f"#104={_num(spec.pitch_tolerance)}", spec.tolerance_note)
    out.add(
        f"M98 P001{spec.sub_number:04d}", note("call", f"CALL O{spec.sub_number:04d}"), key="call"
    )
    if internal:
        out.add("G00 Z100.", "OUT OF THE BORE")
        out.add(f"X{home_x}", "RETURN")
    else:
        out.add(f"G00 X{home_x} Z100.", "RETURN")
    out.add("T0100", "CANCEL OFFSET")
    out.add("M5", "SPINDLE STOP")
    out.add("M9", "COOLANT OFF")
    out.add("M30", "END OF PROGRAM")

    # The sub-program: the paper's statements; only the coefficient and n' are options.
    coef = spec.coefficient
    ref = "#11" if internal else "#100"
    sign = "+" if internal else "-"
    back = "-" if internal else "+"
    out.add(
        f"O{spec.sub_number:04d}",
        f"{side} THREAD SUB - SYMMETRIC LEFT-RIGHT CUTTING, G92",
    )
    out.add("#1=1.*#101", "RUN-OUT DELTA2")
    out.add("#2=2.*#101+#101+FIX[#102/#101]*#101-#102", "RUN-IN DELTA1")
    if internal:
        out.add("#3=#101/[16*SIN[60]]", note("r", "TOOL NOSE RADIUS"), key="r")
        out.add("#4=[6./8.]*SIN[60]*#101-#3+#103/2.+#104/4.", note("h", "THREAD HEIGHT"), key="h")
    else:
        out.add("#3=#101/[8*SIN[60]]", note("r", "TOOL NOSE RADIUS"), key="r")
        out.add("#4=[7./8.]*SIN[60]*#101-#3+#103/2.+#104/4.", note("h", "THREAD HEIGHT"), key="h")
    out.add(f"#5=[{coef}]*SQRT[#4]", note("apmax", "FIRST DEPTH AP MAX"), key="apmax")
    out.add(f"#6=[{coef}]*SQRT[#5]", note("apmin", "MIN DEPTH AND ALLOWANCE AP MIN"), key="apmin")
    out.add("#7=1.", "PASS NUMBER")
    out.add("#8=#5*[SQRT[#7]-SQRT[#7-1.]]", "DEPTH OF THE PASS")
    out.add("#9=#5*SQRT[#7]", "TOTAL DEPTH")
    out.add("#10=[#4+#3-#6-#9]*TAN[30]-#3*TAN[30]", note("u", "SIDE OFFSET U"), key="u")
    if internal:
        out.add("#11=#100-2.*[5./8.]*SIN[60]*#101", note("d1", "MINOR DIAMETER D1"), key="d1")
    if spec.spring_passes >= 2:
        out.add(f"#12={spec.spring_passes}.", "SPRING PASSES")
    start_x = "[#11-1.]" if internal else "[#100+1.]"
    cut = "W[-#2-#102-#1] R0 F#101"
    out.add(f"G01 X{start_x} W[#2] G99 F0.5", "POSITION")
    out.add("N10 G01 W[-#10]", "LOOP START - STEP LEFT BY U", key="n10")
    out.add(f"G92 X[{ref}{sign}2.*#9] {cut}", "CUT")
    out.add("G01 W[2.*#10]", "STEP RIGHT BY 2U")
    out.add(f"G92 X[{ref}{sign}2.*#9] {cut}", "CUT")
    out.add("G01 W[-#10]", "BACK TO THE MIDDLE")
    out.add("#7=#7+1.", "NEXT PASS")
    out.add("#8=#5*[SQRT[#7]-SQRT[#7-1.]]", "DEPTH OF THE NEXT PASS")
    out.add(
        "IF[#8GE#6] THEN #9=#5*SQRT[#7]",
        note("if_ge", "AP-N GE AP-MIN - TOTAL BY THE SQUARE-ROOT RULE"),
        key="if_ge",
    )
    out.add(
        "IF[#8LT#6] THEN #9=#9+#6",
        note("if_lt", "AP-N LT AP-MIN - ADD AP-MIN"),
        key="if_lt",
    )
    out.add("#10=[#4+#3-#6-#9]*TAN[30]-#3*TAN[30]", "NEXT SIDE OFFSET")
    out.add(
        "IF[#9LT[#4-#6]] GOTO10",
        note("loop", "UNTIL THE TOTAL DEPTH REACHES H-AP MIN"),
        key="loop",
    )
    out.add(f"G92 X[{ref}{sign}2.*#4{back}2.*#6] {cut}", "STRAIGHT INFEED ROUGH - LEAVE AP MIN")
    out.add(f"X[{ref}{sign}2.*#4]", note("finish", "STRAIGHT INFEED FINISH"), key="finish")
    if spec.spring_passes >= 1:
        out.add(f"N20 G92 X[{ref}{sign}2.*#4] {cut}", note("spring", "SPRING PASS"), key="spring")
    if spec.spring_passes >= 2:
        out.add("#12=#12-1.", "COUNT THE SPRING PASSES")
        out.add("IF[#12GT0.] GOTO20", "REPEAT THE SPRING PASS")
    out.add("M99", "BACK TO THE MAIN PROGRAM")
    out.add("%")
    return out


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
) -> ThreadModule:
    """The module for explicit values; ``deviation`` is |es| or EI, a magnitude (#103)."""
    for name, value in (("diameter", diameter), ("pitch", pitch), ("length", length)):
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"thread {name} {value!r} must be a positive number")
    if pitch >= diameter:
        raise ValueError(f"pitch {pitch:g} is not smaller than the diameter {diameter:g}")
    if not math.isfinite(deviation) or not math.isfinite(pitch_tolerance) or pitch_tolerance < 0:
        raise ValueError(
            f"deviation {deviation!r} and pitch-diameter tolerance {pitch_tolerance!r} "
            "must be finite, the tolerance not negative"
        )
    deviation = abs(deviation)  # the paper enters es as a magnitude
    if not 0 <= spring_passes <= 99:
        raise ValueError(f"spring passes {spring_passes} must be 0-99")
    if not 1 <= spindle_speed <= 99999:
        raise ValueError(f"spindle speed S{spindle_speed} is outside 1-99999")
    default_main, default_sub = default_program_numbers(internal)
    main = _program_number(default_main if main_number is None else main_number, "main")
    sub = _program_number(default_sub if sub_number is None else sub_number, "sub")
    if main == sub:
        raise ValueError(f"the main program and the sub-program are both O{main:04d}")
    if designation is not None:
        title = designation.canonical().upper()
    else:
        title = f"M{_num(diameter).rstrip('.')}X{_num(pitch).rstrip('.')}"
    which = "EI" if internal else "ES"
    if deviation_note is None:
        signed = deviation if internal else -deviation
        deviation_note = f"{which}={signed:g}" + ("" if internal else " AS A MAGNITUDE")
    if tolerance_note is None:
        tolerance_note = "TD2 TOLERANCE"
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
        tolerance_note=tolerance_note,
    )

    draft = _render_module(spec, {})
    analysis = _execute(draft.text())
    facts = analysis.facts
    assert facts is not None
    at = draft.at
    r = _written(facts, at["r"])
    h = _written(facts, at["h"])
    first = _written(facts, at["apmax"])
    smallest = _written(facts, at["apmin"])
    u = _written(facts, at["u"])
    passes = _runs(facts, at["n10"])
    g92 = [m for m in facts.motions if m.code == "G92"]
    if not g92 or "X" not in g92[-1].words:
        raise RuntimeError("executing the generated module gave no G92 cut")
    final_x = g92[-1].words["X"]

    notes = {
        "r": f"TOOL NOSE RADIUS R={_mm(r)}",
        "h": f"THREAD HEIGHT H={_mm(h)}",
        "apmax": f"FIRST DEPTH AP MAX={_mm(first)}",
        "apmin": f"MIN DEPTH AND FINISH ALLOWANCE AP MIN={_mm(smallest)}",
        "u": f"SIDE OFFSET U={_mm(u)} OF THE FIRST PASS",
        "loop": f"UNTIL THE TOTAL DEPTH REACHES H-AP MIN: {_count(passes, 'ROUGH PASS')}, "
        f"{2 * passes} G92 CUTS",
        "finish": f"STRAIGHT INFEED FINISH AT X{_mm(final_x)}",
        "spring": f"{_count(spring_passes, 'SPRING PASS')} AT X{_mm(final_x)}",
        "call": f"CALL O{sub:04d}: {len(g92)} G92 CUTS, FINAL X{_mm(final_x)}",
    }
    if internal:
        notes["d1"] = f"MINOR DIAMETER D1={_mm(_written(facts, at['d1']))}"
    keyed = {at[k]: k for k in ("if_ge", "if_lt", "loop")}
    bases = {
        "if_ge": "AP-N GE AP-MIN",
        "if_lt": "AP-N LT AP-MIN",
        "loop": f"LOOP CONDITION: {_count(passes, 'ROUGH PASS')},",
    }
    for line, outcome in _constant_conditions(analysis, keyed).items():
        # The paper's statements are kept for every thread; for this one the branch is
        # decided, which the checker rightly reports: say so where it happens.
        key = keyed[line]
        notes[key] = f"{bases[key]} ALWAYS {outcome} FOR THIS THREAD - {_SUPPRESS_MB701}"
    text = _render_module(spec, notes).text()
    return ThreadModule(
        text=text,
        internal=internal,
        main_number=main,
        sub_number=sub,
        nose_radius=r,
        height=h,
        ap_max=first,
        ap_min=smallest,
        first_offset=u,
        rough_passes=passes,
        g92_cuts=len(g92),
        final_x=final_x,
    )


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
) -> ThreadModule:
    """:func:`generate_module` with the measured values (see :class:`ThreadModule`)."""
    if isinstance(designation, str):
        des = parse_designation(designation, internal=internal)
    else:
        des = designation
        if internal is not None and internal != des.internal:
            raise ValueError(f"{des.text!r} is {'in' if des.internal else 'ex'}ternal")
    if des.left_hand:
        raise ValueError(
            f"{des.text!r} is left-hand; the symmetric module cuts toward -Z with M03 "
            "(right hand only)"
        )
    if des.starts > 1:
        raise ValueError(
            f"{des.text!r} has {des.starts} starts; the symmetric module cuts one start"
        )
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
        deviation_note = f"{which} MAGNITUDE {_num(abs(deviation_override))} GIVEN"
        deviation = abs(deviation_override)
    else:
        position = f"{grade.position}".upper()
        deviation_note = f"{which}={deviation:g} POSITION {position} ISO 965-1" + (
            "" if des.internal else ", AS A MAGNITUDE"
        )
    if td2_override is not None:
        if td2_override < 0:
            raise ValueError(f"{tol_name} override {td2_override:g} must not be negative")
        tolerance_note = f"{tol_name.upper()} {_num(td2_override)} GIVEN"
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
) -> str:
    """The symmetric thread module (main + sub-program) for ``designation``, thread length L.

    ``#103`` is es (external) or EI (internal) as a magnitude and ``#104`` Td2 / TD2, both
    from ISO 965-1 unless overridden.  ``coefficient`` is 0.2 for steel, 0.2/3 (default, the
    paper's) for molybdenum; ``spring_passes`` is n' (``#12``).  Raises ValueError for a bad
    designation or a thread the tables do not cover (give both overrides then).
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
    ).text


# ---------------------------------------------------------------------------------------------
# Large-pitch arc thread by the fitting method (seed 002)
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ArcThreadProgram:
    """The generated arc-thread programs and what executing them gave (angles in degrees)."""

    text: str
    layer_cuts: tuple[int, ...]  # G32 cuts of each roughing layer
    layer_angles: tuple[tuple[float, float], ...]  # first and last tool-centre angle
    finishing_cuts: int
    finishing_angles: tuple[float, float]


def _asin_argument(what: str, expression: str, value: float) -> None:
    if not -1.0 <= value <= 1.0:
        raise ValueError(
            f"{what}: ASIN argument {expression} = {value:.6g} is outside -1..1 (alarm on the "
            "control); check the diameters and radii"
        )


def _edge_argument(centre: float, outer: float, radius: float) -> float:
    return ((centre - outer) / 2.0) / radius


def _angles_from_motions(motions: Sequence[Motion], centre: float, run_in: float) -> list[float]:
    """Tool-centre angles of the cuts, from the rapid X and Z that precede each G32.

    X = centre - 2 (R-r) sin a and Z = run-in + (R-r) cos a, so a = atan2((centre-X)/2, Z-run-in).
    """
    angles: list[float] = []
    x: float | None = None
    z: float | None = None
    for m in motions:
        if m.code == "G32":
            if x is None or z is None:
                raise RuntimeError("a G32 cut without its start point")
            angles.append(math.degrees(math.atan2((centre - x) / 2.0, z - run_in)))
        else:
            x = m.words.get("X", x)
            z = m.words.get("Z", z)
    return angles


def _fitting_macro(out: _Lines, number: int, finishing: bool) -> None:
    """One G65 macro for a roughing layer (O3 of the paper) or the finishing (O5)."""
    if finishing:
        out.add(f"O{number:04d}", "ARC THREAD FINISHING - G65 MACRO, FITTING METHOD")
    else:
        out.add(f"O{number:04d}", "ARC THREAD ROUGHING LAYER - G65 MACRO, FITTING METHOD")
    out.add("", "A=#1 THREAD OD, B=#2 CUT END DISTANCE, C=#3 PITCH, I=#4 GROOVE RADIUS")
    out.add("", "J=#5 GROOVE CENTRE DIAMETER, K=#6 RUN-IN Z, D=#7 NUMBER OF CUTS")
    out.add("", "M=#13 SPINDLE M CODE, R=#18 TOOL NOSE RADIUS, S=#19 SPINDLE SPEED")
    out.add("", "T=#20 TOOL, U=#21 OFFSET, V=#22 RETRACT X, X=#24 Z=#26 START POINT")
    out.add("#10=ASIN[[[#5-#1]/2]/#4]", "RIGHT EDGE ANGLE")
    if finishing:
        out.add("#15=180-#10", "LEFT EDGE ANGLE, LAST CUT")
        out.add("#12=[#15-#10]/[#7-1]", "ANGLE STEP")
    else:
        out.add("#11=ASIN[#18/[#4-#18]]", "TANGENCY CORRECTION")
        out.add("#12=[180-2*#10+#11]/#7", "ANGLE STEP")
        out.add("#14=#10-#11", "TOOL TANGENT TO THE RIGHT EDGE")
    out.add("G54 S#19 M#13", "SPINDLE SPEED AND DIRECTION")
    out.add("T[#20*100+#21]", "TOOL AND OFFSET")
    out.add("G00 X#24 Z#26", "START POINT")
    # A counter, not an accumulated angle compared with the last one: a sum of steps can
    # overshoot the end angle by a rounding error and lose the last cut.
    out.add("#30=0" if finishing else "#30=1", "CUT COUNTER")
    if finishing:
        out.add("WHILE[#30LT#7]DO1", "ONE CUT PER ANGLE")
        out.add("#16=#10+#30*#12", "TOOL CENTRE ANGLE OF THIS CUT")
    else:
        out.add("WHILE[#30LE#7]DO1", "ONE CUT PER ANGLE")
        out.add("#16=#14+#30*#12", "TOOL CENTRE ANGLE OF THIS CUT")
    out.add("G00 Z[#6+[#4-#18]*COS[#16]]", "Z START OF THIS CUT")
    out.add("X[#5-2*[#4-#18]*SIN[#16]]", "X OF THIS CUT")
    out.add("G32 Z-#2 F#3", "CUT")
    out.add("G00 X#22", "RETRACT")
    out.add("#30=#30+1", "NEXT CUT")
    out.add("END1")
    out.add("G00 X#24 Z#26", "BACK TO THE START POINT")
    out.add("M99", "BACK TO THE MAIN PROGRAM")


@dataclass(frozen=True)
class _ArcCall:
    """The arguments of one G65 call of a fitting-method macro (letters as the paper's #n)."""

    outer: float  # A #1
    length: float  # B #2
    pitch: float  # C #3
    radius: float  # I #4
    run_in: float  # K #6
    spindle_m: int  # M #13
    retract_x: float  # V #22
    start_x: float  # X #24
    start_z: float  # Z #26

    def block(
        self, macro: int, centre: float, cuts: int, tool_radius: float, speed: int, tool: int
    ) -> str:
        # I, J, K in this order: both argument specifications read them as #4, #5, #6.
        words = [
            f"G65 P{macro:04d}",
            f"A{_num(self.outer)}",
            f"B{_num(self.length)}",
            f"C{_num(self.pitch)}",
            f"I{_num(self.radius)}",
            f"J{_num(centre)}",
            f"K{_num(self.run_in)}",
            f"D{cuts}.",
            f"M{self.spindle_m}.",
            f"R{_num(tool_radius)}",
            f"S{speed}.",
            f"T{tool}.",
            f"U{tool}.",
            f"V{_num(self.retract_x)}",
            f"X{_num(self.start_x)}",
            f"Z{_num(self.start_z)}",
        ]
        return " ".join(words)


def build_arc_thread(
    outer_diameter: float = 93.82,
    groove_radius: float = 10.0,
    tool_radius: float = 1.2,
    pitch: float = 25.0,
    length: float = 113.0,
    layers: Sequence[float] = (108.0, 103.0),
    cuts_per_layer: int = 7,
    finishing_diameter: float = 100.0,
    finishing_cuts: int = 19,
    *,
    run_in: float = 50.0,
    finishing_tool_radius: float | None = None,
    rough_speed: int = 300,
    finishing_speed: int = 400,
    spindle_m: int = 3,
    rough_tool: int = 1,
    finishing_tool: int = 2,
    retract_x: float = 140.0,
    start_x: float = 150.0,
    start_z: float = 100.0,
    main_number: int = 2,
    rough_number: int = 3,
    finishing_number: int = 5,
) -> ArcThreadProgram:
    """:func:`generate_arc_thread` with the measured cuts and angles."""
    r_fin = tool_radius if finishing_tool_radius is None else finishing_tool_radius
    big_r = groove_radius
    for name, value in (
        ("outer diameter", outer_diameter),
        ("groove radius R", big_r),
        ("tool nose radius r", tool_radius),
        ("finishing tool nose radius r", r_fin),
        ("pitch", pitch),
        ("length", length),
    ):
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"{name} {value!r} must be a positive number")
    for name, r in (("tool", tool_radius), ("finishing tool", r_fin)):
        if not r < big_r:
            raise ValueError(
                f"{name} nose radius r = {r:g} must be smaller than the groove radius R = {big_r:g}"
            )
    if not layers:
        raise ValueError("give at least one roughing layer (groove-centre diameter)")
    if not 1 <= cuts_per_layer <= 999:
        raise ValueError(f"cuts per layer {cuts_per_layer} must be 1-999")
    if not 2 <= finishing_cuts <= 999:
        raise ValueError(f"finishing cuts {finishing_cuts} must be 2-999")
    if spindle_m not in (3, 4):
        raise ValueError(f"spindle M code {spindle_m} must be 3 or 4")
    numbers = {
        _program_number(main_number, "main"),
        _program_number(rough_number, "roughing macro"),
        _program_number(finishing_number, "finishing macro"),
    }
    if len(numbers) != 3:
        raise ValueError("the main program and the two macros need three different numbers")
    highest = max([*layers, finishing_diameter, outer_diameter])
    if not retract_x > highest or not start_x >= retract_x:
        raise ValueError(
            f"retract X{retract_x:g} must clear the largest diameter {highest:g} the tool "
            f"reaches, and the start point X{start_x:g} must not be below it"
        )
    tangency = tool_radius / (big_r - tool_radius)
    _asin_argument(
        "tangency correction #11",
        f"r/[R-r] = {tool_radius:g}/[{big_r:g}-{tool_radius:g}]",
        tangency,
    )
    for n, centre in enumerate(layers, 1):
        arg = _edge_argument(centre, outer_diameter, big_r)
        _asin_argument(
            f"roughing layer {n}",
            f"[[{centre:g}-{outer_diameter:g}]/2]/{big_r:g}",
            arg,
        )
    _asin_argument(
        "finishing",
        f"[[{finishing_diameter:g}-{outer_diameter:g}]/2]/{big_r:g}",
        _edge_argument(finishing_diameter, outer_diameter, big_r),
    )

    common = _ArcCall(
        outer=outer_diameter,
        length=length,
        pitch=pitch,
        radius=big_r,
        run_in=run_in,
        spindle_m=spindle_m,
        retract_x=retract_x,
        start_x=start_x,
        start_z=start_z,
    )

    def render(notes: Mapping[str, str]) -> _Lines:
        out = _Lines()
        out.add("%")
        out.add(
            f"O{main_number:04d}",
            f"ARC THREAD BY THE FITTING METHOD - R{big_r:g} P{pitch:g}",
        )
        for n, centre in enumerate(layers, 1):
            call = common.block(
                rough_number, centre, cuts_per_layer, tool_radius, rough_speed, rough_tool
            )
            out.add(call, f"ROUGH LAYER {n} {notes.get(f'layer{n}', '')}", key=f"layer{n}")
        call = common.block(
            finishing_number,
            finishing_diameter,
            finishing_cuts,
            r_fin,
            finishing_speed,
            finishing_tool,
        )
        out.add(call, f"FINISHING {notes.get('finish', '')}", key="finish")
        out.add("M05", "SPINDLE STOP")
        out.add("M30", "END OF PROGRAM")
        _fitting_macro(out, rough_number, finishing=False)
        _fitting_macro(out, finishing_number, finishing=True)
        out.add("%")
        return out

    analysis = _execute(render({}).text())
    facts = analysis.facts
    assert facts is not None
    rough_name = f"O{rough_number:04d}"
    fin_name = f"O{finishing_number:04d}"
    rough_motions = [m for m in facts.motions if m.program.startswith(rough_name)]
    fin_motions = [m for m in facts.motions if m.program.startswith(fin_name)]
    # Each layer's cuts come in order; split them with the known centre diameters.
    layer_cuts: list[int] = []
    layer_angles: list[tuple[float, float]] = []
    cuts_by_layer = _split_by_calls(rough_motions, len(layers))
    for n, (centre, chunk) in enumerate(zip(layers, cuts_by_layer, strict=True), 1):
        angles = _angles_from_motions(chunk, centre, run_in)
        if not angles:
            raise RuntimeError(f"roughing layer {n} made no cut")
        layer_cuts.append(len(angles))
        layer_angles.append((angles[0], angles[-1]))
    fin_angles = _angles_from_motions(fin_motions, finishing_diameter, run_in)
    if not fin_angles:
        raise RuntimeError("the finishing macro made no cut")
    notes = {
        f"layer{n}": f"J{c:g}: {k} CUTS, ANGLE {a:.2f} TO {b:.2f} DEG"
        for n, (c, k, (a, b)) in enumerate(zip(layers, layer_cuts, layer_angles, strict=True), 1)
    }
    notes["finish"] = (
        f"J{finishing_diameter:g}: {len(fin_angles)} CUTS, ANGLE "
        f"{fin_angles[0]:.2f} TO {fin_angles[-1]:.2f} DEG"
    )
    return ArcThreadProgram(
        text=render(notes).text(),
        layer_cuts=tuple(layer_cuts),
        layer_angles=tuple(layer_angles),
        finishing_cuts=len(fin_angles),
        finishing_angles=(fin_angles[0], fin_angles[-1]),
    )


def _split_by_calls(motions: Sequence[Motion], calls: int) -> list[list[Motion]]:
    """Split one macro's motions into its calls: each call starts with a rapid to X Z."""
    chunks: list[list[Motion]] = []
    for m in motions:
        starts = m.code == "G00" and "X" in m.words and "Z" in m.words
        # The macro's first and last blocks are both 'G00 X#24 Z#26': a call starts at the
        # first of the pair, i.e. when the previous chunk already ended with its return.
        if starts and (not chunks or _chunk_closed(chunks[-1])):
            chunks.append([m])
        elif chunks:
            chunks[-1].append(m)
    if len(chunks) != calls:
        raise RuntimeError(f"expected {calls} macro calls in the motions, found {len(chunks)}")
    return chunks


def _chunk_closed(chunk: Sequence[Motion]) -> bool:
    last = chunk[-1]
    return len(chunk) > 1 and last.code == "G00" and "X" in last.words and "Z" in last.words


def generate_arc_thread(
    outer_diameter: float = 93.82,
    groove_radius: float = 10.0,
    tool_radius: float = 1.2,
    pitch: float = 25.0,
    length: float = 113.0,
    layers: Sequence[float] = (108.0, 103.0),
    cuts_per_layer: int = 7,
    finishing_diameter: float = 100.0,
    finishing_cuts: int = 19,
    **options: Any,
) -> str:
    """Main program + roughing G65 macro (called once per layer) + finishing G65 macro.

    Defaults are the paper's part: thread OD 93.82, groove radius R 10, tool nose radius r
    1.2, pitch 25, cut to Z-113 from a run-in Z of 50, roughing layers with groove centres on
    diameters 108 and 103 (7 cuts each), finishing on the centre diameter 100 (19 cuts).
    ``options``: the keyword arguments of :func:`build_arc_thread`.  Raises ValueError when
    r >= R or an ASIN argument leaves -1..1.
    """
    return build_arc_thread(
        outer_diameter,
        groove_radius,
        tool_radius,
        pitch,
        length,
        layers,
        cuts_per_layer,
        finishing_diameter,
        finishing_cuts,
        **options,
    ).text


# ---------------------------------------------------------------------------------------------
# Drum-shaped spiral groove (seed 003)
# ---------------------------------------------------------------------------------------------

# Profile points live in common variables: X of point i in #[110+i], Z in #[130+i].  #100-#149
# exist on every control without the extended-common option, so at most 19 points fit.
_X_BASE = 110
_Z_BASE = 130
_MAX_POINTS = 19


@dataclass(frozen=True)
class DrumGrooveProgram:
    """The generated drum-groove programs and what executing them gave."""

    text: str
    passes: int  # cuts through the whole profile
    segments_per_pass: int  # taper-thread G32 segments through the profile points
    g32_cuts: int  # every G32 block executed (run-in blocks included)


def build_drum_groove(
    points: Sequence[tuple[float, float]] | None,
    pitch: float,
    layers: int = 9,
    radial_step: float = 0.8,
    axial_step: float = 0.5,
    *,
    cuts_per_layer: int = 1,
    direction: int = -1,
    run_in: float = 10.0,
    clearance: float = 10.0,
    spindle_speed: int = 80,
    tool: int = 1,
    main_number: int = 10,
    macro_number: int = 1,
) -> DrumGrooveProgram:
    """:func:`generate_drum_groove` with the measured pass and cut counts."""
    pts = [(float(x), float(z)) for x, z in (DRUM_PROFILE if points is None else points)]
    if not 2 <= len(pts) <= _MAX_POINTS:
        raise ValueError(f"{len(pts)} profile points: give 2-{_MAX_POINTS}")
    for name, value in (("pitch", pitch), ("radial step", radial_step), ("run-in", run_in)):
        if not value > 0 or not math.isfinite(value):
            raise ValueError(f"{name} {value!r} must be a positive number")
    if not axial_step >= 0 or not math.isfinite(axial_step):
        raise ValueError(f"axial step {axial_step!r} must not be negative")
    if not 1 <= layers <= 999 or not 1 <= cuts_per_layer <= 999:
        raise ValueError(f"layers {layers} and cuts per layer {cuts_per_layer} must be 1-999")
    if direction not in (-1, 1):
        raise ValueError(f"direction {direction} must be -1 (right to left) or +1")
    if not clearance > 0:
        raise ValueError(f"clearance {clearance!r} must be positive")
    if not 1 <= spindle_speed <= 99999:
        raise ValueError(f"spindle speed S{spindle_speed} is outside 1-99999")
    if _program_number(main_number, "main") == _program_number(macro_number, "macro"):
        raise ValueError(f"the main program and the macro are both O{main_number:04d}")
    sense = math.copysign(1.0, pts[0][1] - pts[1][1])  # +1: cutting toward -Z
    for i, ((x0, z0), (x1, z1)) in enumerate(itertools.pairwise(pts), 1):
        dz = z0 - z1
        if dz == 0 or math.copysign(1.0, dz) != sense:
            raise ValueError(
                f"profile points {i} (Z{z0:g}) and {i + 1} (Z{z1:g}): Z must change in one "
                "direction along the whole profile"
            )
        if abs(x1 - x0) / 2.0 >= abs(dz):
            raise ValueError(
                f"segment {i}-{i + 1} (X{x0:g} Z{z0:g} to X{x1:g} Z{z1:g}) is steeper than "
                "45 degrees: G32 F would be the lead along X, not Z"
            )
    depth = layers * radial_step
    lowest = min(x for x, _ in pts)
    if 2.0 * depth >= lowest:
        raise ValueError(
            f"{layers} layers x {radial_step:g} = {depth:g} mm deep is more than the radius "
            f"of the smallest profile diameter {lowest:g}"
        )
    retract_x = max(x for x, _ in pts) + 2.0 * clearance
    start_z = pts[0][1] + sense * run_in
    shift = direction * axial_step
    try:
        crown: CrownFit | None = fit_crown(pts)
    except ValueError:
        crown = None  # two points, or points on a line: a taper, not a crown
    except ImportError:
        crown = None  # no numpy (the bundled server): the program is the same without it

    def render(notes: Mapping[str, str]) -> _Lines:
        out = _Lines()
        out.add("%")
        out.add(f"O{main_number:04d}", "DRUM SPIRAL GROOVE - CHAINED TAPER THREADS")
        last = len(pts)
        xs = f"#{_X_BASE + 1}-#{_X_BASE + last}"
        zs = f"#{_Z_BASE + 1}-#{_Z_BASE + last}"
        out.add("", f"PROFILE: X IN {xs}, Z IN {zs}")
        if crown is not None:
            out.add(
                "",
                f"CROWN R{crown.radius:.1f} (BEST-FIT CIRCLE, POINTS WITHIN "
                f"{crown.max_deviation:.3f} MM OF IT)",
            )
        for i, (x, z) in enumerate(pts, 1):
            out.add(f"#{_X_BASE + i}={_num(x)}", f"POINT {i} X")
            out.add(f"#{_Z_BASE + i}={_num(z)}", f"POINT {i} Z")
        out.add(f"T{tool:02d}{tool:02d}", "GROOVING TOOL")
        out.add(f"G97 S{spindle_speed} M03", "SPINDLE")
        out.add(f"G00 X{_num(retract_x)} Z{_num(start_z)}", "START POINT")
        call = " ".join(
            [
                f"G65 P{macro_number:04d}",
                f"A{last}.",
                f"B{cuts_per_layer}.",
                f"C{layers}.",
                f"D{_num(radial_step)}",
                f"E{_num(shift)}",
                f"F{_num(pitch)}",
                f"K{_num(sense * run_in)}",
                f"V{_num(retract_x)}",
            ]
        )
        out.add(call, f"{_count(layers, 'LAYER')} {notes.get('call', '')}", key="call")
        out.add(f"G00 X{_num(retract_x)} Z{_num(start_z)}", "BACK TO THE START POINT")
        out.add("M05", "SPINDLE STOP")
        out.add("M30", "END OF PROGRAM")

        out.add(f"O{macro_number:04d}", "DRUM GROOVE - LAYERS OF CHAINED G32 TAPER THREADS")
        out.add("", f"A=#1 POINTS: X IN #{_X_BASE}+I, Z IN #{_Z_BASE}+I, B=#2 CUTS PER LAYER")
        out.add("", "C=#3 LAYERS, D=#7 RADIAL STEP, E=#8 AXIAL STEP PER CUT, F=#9 PITCH")
        out.add("", "K=#6 RUN-IN BEFORE POINT 1, V=#22 RETRACT X")
        out.add("#30=1.", "LAYER")
        out.add("WHILE[#30LE#3]DO1", "EACH LAYER")
        out.add("#31=#30*#7", "RADIAL DEPTH OF THE LAYER")
        out.add("#32=0.", "CUT OF THE LAYER")
        out.add("WHILE[#32LT#2]DO2", "EACH CUT OF THE LAYER")
        out.add("#33=#32*#8", "AXIAL SHIFT OF THE CUT")
        out.add(f"G00 Z[#{_Z_BASE + 1}+#33+#6]", "RUN-IN START")
        out.add(f"X[#{_X_BASE + 1}-2.*#31]", "DEPTH OF THE LAYER")
        out.add(f"G32 Z[#{_Z_BASE + 1}+#33] F#9", "RUN-IN TO POINT 1", key="runin")
        out.add("#10=2.", "NEXT POINT")
        out.add("WHILE[#10LE#1]DO3", "THROUGH THE PROFILE")
        out.add(
            f"G32 X[#[{_X_BASE}+#10]-2.*#31] Z[#[{_Z_BASE}+#10]+#33]",
            "TAPER THREAD TO THE POINT",
            key="segment",
        )
        out.add("#10=#10+1.")
        out.add("END3")
        out.add("G00 X#22", "RETRACT")
        out.add("#32=#32+1.")
        out.add("END2")
        out.add("#30=#30+1.")
        out.add("END1")
        out.add("M99", "BACK TO THE MAIN PROGRAM")
        out.add("%")
        return out

    draft = render({})
    analysis = _execute(draft.text())
    facts = analysis.facts
    assert facts is not None
    g32 = [m for m in facts.motions if m.code == "G32"]
    segment_line = draft.at["segment"]
    segments = sum(1 for m in g32 if m.line == segment_line)
    passes = sum(1 for m in g32 if m.line == draft.at["runin"])
    if passes == 0 or segments % passes:
        raise RuntimeError("executing the drum groove macro gave no whole passes")
    notes = {
        "call": f"X {_count(cuts_per_layer, 'CUT')} = {_count(passes, 'PASS')} OF "
        f"{segments // passes} TAPER SEGMENTS, {len(g32)} G32 BLOCKS"
    }
    return DrumGrooveProgram(
        text=render(notes).text(),
        passes=passes,
        segments_per_pass=segments // passes,
        g32_cuts=len(g32),
    )


def generate_drum_groove(
    points: Sequence[tuple[float, float]] | None,
    pitch: float,
    layers: int = 9,
    radial_step: float = 0.8,
    axial_step: float = 0.5,
    **options: Any,
) -> str:
    """A main program and one G65 macro that cut the drum groove layer by layer.

    ``points`` are (X diameter, Z) of the profile (None: the paper's 12 points); each
    pass is a straight G32 run-in to point 1 and a chain of G32 taper threads through the
    rest, at the layer's depth (``radial_step`` per layer, radius).  ``cuts_per_layer``
    cuts per layer step ``axial_step`` along Z (``direction`` -1: right to left, as the
    paper's T1).  The paper does not give the pitch (its figure 2 is lost): pass it.
    """
    return build_drum_groove(
        points,
        pitch,
        layers,
        radial_step,
        axial_step,
        **options,
    ).text


# Re-exported for callers that pick a material by name.
MATERIAL_COEFFICIENTS: Mapping[str, float] = {
    "steel": STEEL_COEFFICIENT,
    "molybdenum": MOLYBDENUM_COEFFICIENT,
}
