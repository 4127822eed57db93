"""What G codes, M codes, macro functions, keywords and addresses mean: hover and completion texts.

Lathe meanings are those of FANUC G code system A (the 0i-TF default); mill meanings those of
0i-MF. Where a code means something else on the other machine type, both are kept, so the hover
can say which one applies under the configured controller and what the other would be. Facts
that the shared reference (macro-b.md) marks as unverified are worded with that caution.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

from ..translation import joined, tr
from .g_code_systems import ABSOLUTE, INCREMENTAL, system_a_code, written

# ---- G and M codes ---------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Meaning:
    title: str  # a few words: the completion detail
    text: str = ""  # markdown: use, format, pitfalls
    modal: str = ""  # "modal, group 01", "one-shot" ...


@dataclass(frozen=True, slots=True)
class CodeInfo:
    code: str  # "G00", "G66.1", "M98"
    lathe: Meaning | None  # None: no meaning on a lathe (G code system A)
    mill: Meaning | None  # None: no meaning on a mill

    def for_machine(self, lathe: bool) -> Meaning | None:
        return self.lathe if lathe else self.mill

    @property
    def same_on_both(self) -> bool:
        return self.lathe is self.mill


def _both(title: str, text: str = "", modal: str = "") -> tuple[Meaning, Meaning]:
    m = Meaning(title, text, modal)
    return m, m


_G: tuple[tuple[str, Meaning | None, Meaning | None], ...] = (
    ("G00", *_both(
        tr("Rapid positioning"),
        tr("Moves to the end point at rapid traverse. Depending on a parameter the axes move "
        "independently, so the path need not be a straight line: keep clear of the part."),
        tr("modal, group 01"))),
    ("G01", *_both(
        tr("Linear interpolation"),
        tr("Straight move at the feed F. On a lathe F is usually per revolution (G99), on a mill "
        "per minute (G94)."),
        tr("modal, group 01"))),
    ("G02", *_both(
        tr("Circular interpolation, clockwise"),
        tr("Arc to the end point, with the radius R or the centre offsets I/J/K from the start "
        "point. On a lathe X is a diameter and I/K are radius values; the direction is as seen "
        "from the +Y side of the ZX plane, so it depends on where the turret is."),
        tr("modal, group 01"))),
    ("G03", *_both(
        tr("Circular interpolation, counter-clockwise"),
        tr("Arc to the end point, with R or I/J/K as for G02."),
        tr("modal, group 01"))),
    ("G04", *_both(
        tr("Dwell"),
        tr("Waits before the next block: `G04 X1.5` (or `U1.5` on a lathe) waits 1.5 s; "
        "`G04 P1500` waits 1500 ms; P takes no decimal point."),
        tr("one-shot"))),
    ("G05.1", *_both(
        tr("AI contour control / look-ahead"),
        tr("`G05.1 Q1` switches AI (advanced preview) contour control on, `G05.1 Q0` off. Programs "
        "switch it off before they poll variables so that macro statements are not executed "
        "blocks ahead of the motion."),
        tr("modal"))),
    ("G07.1", *_both(
        tr("Cylindrical interpolation"),
        tr("Programs a rotary axis as a distance on the cylinder's surface (option)."),
        tr("modal"))),
    ("G09", *_both(
        tr("Exact stop"), tr("Decelerates and checks the in-position at the end of this block "
           "only."),
        tr("one-shot"))),
    ("G10", *_both(
        tr("Programmable data input"),
        tr("Writes offsets or parameters from the program, e.g. `G10 L2 P1 X.. Z..` sets the G54 "
        "work offset. The macro system variables (#2001..., #5221...) do the same from "
        "expressions."),
        tr("one-shot"))),
    ("G11", *_both(tr("Programmable data input cancel"), "", tr("modal"))),
    ("G12.1", Meaning(
        tr("Polar coordinate interpolation"),
        tr("Lathe with a C axis and live tools: X and C are programmed as a Cartesian plane "
           "(option)."),
        tr("modal")), None),
    ("G13.1", Meaning(tr("Polar coordinate interpolation cancel"), "", tr("modal")), None),
    ("G17", *_both(tr("XY plane"), tr("Plane for arcs and cutter compensation (mill default)."),
                   tr("modal, group 02 (mill) / 16 (lathe)"))),
    ("G18", *_both(tr("ZX plane"), tr("Plane for arcs and nose radius compensation (lathe "
     "default)."),
                   tr("modal, group 02 (mill) / 16 (lathe)"))),
    ("G19", *_both(tr("YZ plane"), "", tr("modal, group 02 (mill) / 16 (lathe)"))),
    ("G20", *_both(
        tr("Inch input"),
        tr("Values are inches. Program it alone at the head of the program, before the work "
        "coordinate system is set; mixing units in one program is a classic crash."),
        tr("modal, group 06"))),
    ("G21", *_both(tr("Metric input"), tr("Values are millimetres. See G20."), tr("modal, "
     "group 06"))),
    ("G27", *_both(tr("Reference position return check"), "", tr("one-shot"))),
    ("G28", *_both(
        tr("Return to reference position"),
        tr("Moves through the intermediate point given in the block to the machine reference "
        "position. Lathe: `G28 U0 W0` (incremental zero: straight home); mill: `G91 G28 Z0`."),
        tr("one-shot"))),
    ("G30", *_both(
        tr("Return to 2nd/3rd/4th reference position"),
        tr("`G30 P2 ...` (P2 to P4) via the intermediate point, like G28."), tr("one-shot"))),
    ("G31", *_both(
        tr("Skip function"),
        tr("Linear move that stops when the skip signal (probe) comes on; the position where it "
        "stopped is in #5061 and up."),
        tr("one-shot"))),
    ("G32",
     Meaning(
         tr("Thread cutting (constant lead)"),
         tr("One threading pass along the programmed path at the lead F; the spindle encoder "
         "synchronises the start. Each pass, with its infeed and retract, is programmed "
         "separately (G92 and G76 do it as cycles). Feed hold and override are not effective."),
         tr("modal, group 01")),
     None),
    ("G33",
     Meaning(tr("Thread cutting (G code systems B/C)"), tr("System A uses G32."),
             tr("modal, group 01")),
     Meaning(tr("Thread cutting"), tr("Constant-lead thread cutting along Z."), tr("modal, "
                "group 01"))),
    ("G34", Meaning(tr("Variable lead thread cutting"), tr("K is the lead change per revolution."),
                    tr("modal, group 01")), None),
    ("G40",
     Meaning(tr("Tool nose radius compensation cancel"),
             tr("Cancel with a move, not on an arc."), tr("modal, group 07")),
     Meaning(tr("Cutter radius compensation cancel"),
             tr("Cancel with a move, not on an arc."), tr("modal, group 07"))),
    ("G41",
     Meaning(tr("Tool nose radius compensation, left"),
             tr("The tool is on the left of the path, looking in the direction of motion; the "
             "nose radius and imaginary tip number come from the tool's offset (T)."),
             tr("modal, group 07")),
     Meaning(tr("Cutter radius compensation, left"),
             tr("The cutter is on the left of the path (climb milling with a right-hand cutter); "
             "the radius is offset D."), tr("modal, group 07"))),
    ("G42",
     Meaning(tr("Tool nose radius compensation, right"), tr("See G41."), tr("modal, group 07")),
     Meaning(tr("Cutter radius compensation, right"),
             tr("The cutter is on the right of the path (conventional milling); radius from D."),
             tr("modal, group 07"))),
    ("G43", None, Meaning(tr("Tool length compensation +"),
                          tr("Adds the length offset H to Z: `G43 H01 Z..`."), tr("modal, "
                             "group 08"))),
    ("G44", None, Meaning(tr("Tool length compensation -"), "", tr("modal, group 08"))),
    ("G49", None, Meaning(tr("Tool length compensation cancel"), "", tr("modal, group 08"))),
    ("G50",
     Meaning(tr("Coordinate system setting / maximum spindle speed"),
             tr("`G50 X.. Z..` makes the current position these coordinates (prefer G54-G59 "
             "work offsets). `G50 S2000` clamps the spindle speed under constant surface speed "
             "(G96): always set it before G96, or small diameters can over-speed the chuck."),
             tr("one-shot")),
     Meaning(tr("Scaling cancel"), "", tr("modal, group 11"))),
    ("G51", None, Meaning(tr("Scaling"), tr("Scales the programmed path about a centre (option)."),
                          tr("modal, group 11"))),
    ("G52", *_both(tr("Local coordinate system"),
                   tr("Shifts the work coordinate system by the given values until `G52` with "
                   "zeros."), tr("one-shot"))),
    ("G53", *_both(tr("Machine coordinate system"),
                   tr("Moves to machine coordinates in this block only (absolute, rapid); "
                   "it stops look-ahead."), tr("one-shot"))),
    *[
        (f"G{54 + k}", *_both(
            f"Work coordinate system {k + 1}",
            f"Selects work offset {k + 1}; its values are #{5221 + 20 * k}-"
            f"#{5240 + 20 * k} (axis = number - {5220 + 20 * k}).",
            tr("modal, group 14")))
        for k in range(6)
    ],
    ("G54.1", *_both(tr("Additional work coordinate systems"),
                     tr("`G54.1 P1`..`P48` (#7001 and up), P1-P300 as an option."),
                     tr("modal, group 14"))),
    ("G61", *_both(tr("Exact stop mode"), "", tr("modal, group 15"))),
    ("G62", *_both(tr("Automatic corner override"), "", tr("modal, group 15"))),
    ("G63", *_both(tr("Tapping mode"), "", tr("modal, group 15"))),
    ("G64", *_both(tr("Cutting mode"), tr("Blocks blend without an exact stop."),
                   tr("modal, group 15"))),
    ("G65", *_both(
        tr("Macro call"),
        tr("`G65 P<program> [L<repeat>] <arguments>` runs the macro once (or L times) with a new "
        "set of locals #1-#33: the argument letters fill them (specification I: A #1, B #2, "
        "C #3, I #4, J #5, K #6, D #7, E #8, F #9, H #11, M #13, Q #17, R #18, S #19, T #20, "
        "U #21, V #22, W #23, X #24, Y #25, Z #26), all other locals start vacant. G, L, N, O "
        "and P cannot be arguments. Write arguments with a decimal point: `X10` may arrive as "
        "0.01 on an IS-B machine."),
        tr("one-shot, group 00"))),
    ("G66", *_both(
        tr("Modal macro call (after each move)"),
        tr("`G66 P<program> <arguments>` calls the macro after every following block that moves "
        "an axis, until G67."),
        tr("modal, group 12"))),
    ("G66.1", *_both(
        tr("Modal macro call (every block)"),
        tr("`G66.1 P<program> <arguments>` calls the macro for every following block, whose words "
        "become the arguments (G too), until G67."),
        tr("modal, group 12"))),
    ("G67", *_both(tr("Modal macro call cancel"), tr("Ends G66 / G66.1."), tr("modal, group 12"))),
    ("G68",
     Meaning(tr("Mirror image for double turrets / balance cut"),
             tr("Option- and builder-dependent on lathes."), tr("modal")),
     Meaning(tr("Coordinate rotation"), tr("`G68 X.. Y.. R<angle>` rotates the program about a "
             "centre."), tr("modal, group 16"))),
    ("G69",
     Meaning(tr("Mirror image for double turrets cancel"), "", tr("modal")),
     Meaning(tr("Coordinate rotation cancel"), "", tr("modal, group 16"))),
    ("G70",
     Meaning(tr("Finishing cycle"),
             tr("`G70 P<ns> Q<nf>` runs the finishing shape (blocks Nns to Nnf) described for a "
             "G71/G72/G73 roughing cycle, with the F, S, T of that shape."),
             tr("one-shot, group 00")),
     None),
    ("G71",
     Meaning(tr("Stock removal in turning (rough OD/ID)"),
             tr("`G71 U<depth> R<retract>` then `G71 P<ns> Q<nf> U<X allowance> W<Z allowance> "
             "F..`: roughs the shape Nns..Nnf in passes along Z, leaving the allowances for "
             "G70. The shape must be monotonic in X (type I)."),
             tr("one-shot, group 00")),
     None),
    ("G72",
     Meaning(tr("Stock removal in facing"),
             tr("`G72 W<depth> R<retract>` then `G72 P<ns> Q<nf> U.. W.. F..`: like G71 but the "
             "passes run along X."),
             tr("one-shot, group 00")),
     None),
    ("G73",
     Meaning(tr("Pattern repeating cycle"),
             tr("`G73 U<X relief> W<Z relief> R<passes>` then `G73 P<ns> Q<nf> U.. W.. F..`: "
             "repeats the shape offset inwards, for forged or cast blanks."),
             tr("one-shot, group 00")),
     Meaning(tr("High-speed peck drilling cycle"),
             tr("Pecks of Q with a small retract (parameter) instead of a full return."),
             tr("modal, group 09"))),
    ("G74",
     Meaning(tr("End face peck drilling / face grooving cycle"),
             tr("`G74 R<retract>` then `G74 X(U).. Z(W).. P<X step> Q<Z peck> F..` (P and Q in "
             "least increments, no decimal point)."),
             tr("one-shot, group 00")),
     Meaning(tr("Left-hand tapping cycle"),
             tr("Counter tapping: spindle CCW in, reverses at the bottom."), tr("modal, group "
                "09"))),
    ("G75",
     Meaning(tr("Outer/inner diameter grooving cycle"),
             tr("`G75 R<retract>` then `G75 X(U).. Z(W).. P<X peck> Q<Z step> F..`."),
             tr("one-shot, group 00")),
     None),
    ("G76",
     Meaning(tr("Multiple threading cycle"),
             tr("`G76 P<m><r><a> Q<min depth> R<finish allowance>` then `G76 X(U).. Z(W).. "
             "R<taper> P<thread height> Q<first depth> F<lead>`: m finishing passes, r chamfer, "
             "a tool angle; depths in least increments (no decimal point). Each pass cuts "
             "equal area, with flank infeed."),
             tr("one-shot, group 00")),
     Meaning(tr("Fine boring cycle"),
             tr("Bores, orients the spindle at the bottom, shifts by Q away from the wall and "
             "retracts at rapid."),
             tr("modal, group 09"))),
    ("G80", *_both(tr("Canned cycle cancel"), tr("Cancels the drilling cycles (G81-G89 / "
     "G83-G89 on "
                   "lathes)."), tr("modal, group 09"))),
    ("G81", None, Meaning(tr("Drilling cycle, spot drilling"),
                          tr("Feed to Z, rapid out to the R point (G99) or initial level (G98)."),
                          tr("modal, group 09"))),
    ("G82", None, Meaning(tr("Drilling cycle with dwell (counterboring)"),
                          tr("Like G81 with a dwell P at the bottom."), tr("modal, group 09"))),
    ("G83",
     Meaning(tr("Face drilling cycle"), tr("Live-tool drilling along Z (C-axis lathes)."),
             tr("modal, group 10")),
     Meaning(tr("Peck drilling cycle"), tr("Pecks of Q, retracting to the R point after each."),
             tr("modal, group 09"))),
    ("G84",
     Meaning(tr("Face tapping cycle"), tr("Live-tool tapping along Z."), tr("modal, group 10")),
     Meaning(tr("Tapping cycle"),
             tr("Spindle CW in, reverses at the bottom. In G94 F = pitch x S; with M29 it is "
             "rigid tapping."),
             tr("modal, group 09"))),
    ("G85",
     Meaning(tr("Face boring cycle"), "", tr("modal, group 10")),
     Meaning(tr("Boring cycle"), tr("Feed in, feed out."), tr("modal, group 09"))),
    ("G86", None, Meaning(tr("Boring cycle"), tr("Feed in, spindle stop at the bottom, rapid out "
                          "(leaves a line)."), tr("modal, group 09"))),
    ("G87",
     Meaning(tr("Side drilling cycle"), tr("Live-tool drilling along X."), tr("modal, group 10")),
     Meaning(tr("Back boring cycle"), "", tr("modal, group 09"))),
    ("G88",
     Meaning(tr("Side tapping cycle"), "", tr("modal, group 10")),
     Meaning(tr("Boring cycle"), tr("Dwell and spindle stop at the bottom, then manual retract."),
             tr("modal, group 09"))),
    ("G89",
     Meaning(tr("Side boring cycle"), "", tr("modal, group 10")),
     Meaning(tr("Boring cycle"), tr("Dwell at the bottom, feed out."), tr("modal, group 09"))),
    ("G90",
     Meaning(tr("Outer/inner diameter cutting cycle"),
             tr("`G90 X(U).. Z(W).. [R<taper>] F..`: one roughing pass (rapid in, feed along Z, "
             "feed out, rapid back). Modal: the next blocks with only X repeat it at new "
             "depths. On a lathe (system A) there is no G90/G91 absolute/incremental: X/Z are "
             "absolute, U/W incremental."),
             tr("modal, group 01")),
     Meaning(tr("Absolute programming"), tr("Coordinates are positions in the work system."),
             tr("modal, group 03"))),
    ("G91",
     None,
     Meaning(tr("Incremental programming"), tr("Coordinates are distances from the current "
             "position."), tr("modal, group 03"))),
    ("G92",
     Meaning(tr("Threading cycle"),
             tr("`G92 X(U).. Z(W).. [R<taper>] F<lead>`: one threading pass from the start point "
             "(rapid in to X, thread along Z, rapid out, rapid back). Modal: blocks with only X "
             "repeat it at new depths. Approach distance must allow the spindle to "
             "synchronise; S x lead is limited by the machine's threading feed."),
             tr("modal, group 01")),
     Meaning(tr("Workpiece coordinate system setting"),
             tr("`G92 X.. Y.. Z..` declares the current position to have these coordinates (a "
             "G54-G59 offset is safer)."),
             tr("one-shot, group 00"))),
    ("G93", None, Meaning(tr("Inverse time feed"), tr("F is the reciprocal of the block's time in "
                          "minutes (for rotary axes)."), tr("modal, group 05"))),
    ("G94",
     Meaning(tr("End face turning cycle"),
             tr("`G94 X(U).. Z(W).. [R..] F..`: one facing pass along X."), tr("modal, group 01")),
     Meaning(tr("Feed per minute"), tr("F is mm/min (inch/min)."), tr("modal, group 05"))),
    ("G95", None, Meaning(tr("Feed per revolution"), tr("F is mm/rev."), tr("modal, group 05"))),
    ("G96", *_both(
        tr("Constant surface speed"),
        tr("S is the cutting speed in m/min (ft/min): the spindle speeds up as the diameter gets "
        "smaller. Clamp it first (`G50 S..` on lathes). Threading uses G97."),
        tr("modal, group 02 (lathe) / 13 (mill)"))),
    ("G97", *_both(tr("Constant surface speed cancel"), tr("S is spindle speed in rpm."),
                   tr("modal, group 02 (lathe) / 13 (mill)"))),
    ("G98",
     Meaning(tr("Feed per minute"), tr("F is mm/min (system A lathe)."), tr("modal, group 05")),
     Meaning(tr("Canned cycle: return to initial level"), "", tr("modal, group 10"))),
    ("G99",
     Meaning(tr("Feed per revolution"), tr("F is mm/rev: the lathe's power-on default; for "
                "threading "
             "F is the lead."), tr("modal, group 05")),
     Meaning(tr("Canned cycle: return to R point level"), "", tr("modal, group 10"))),
)  # fmt: skip

_M: tuple[tuple[str, str, str], ...] = (
    (
        "M00",
        tr("Program stop"),
        tr(
            "Stops after the block; cycle start resumes. Stops look-ahead, so macro statements "
            "after "
            "it wait for it."
        ),
    ),
    ("M01", tr("Optional stop"), tr("Like M00 when the optional stop switch is on.")),
    ("M02", tr("End of program"), tr("Ends and resets the program (locals become vacant).")),
    ("M03", tr("Spindle on clockwise (forward)"), tr("Speed from S.")),
    ("M04", tr("Spindle on counter-clockwise (reverse)"), tr("Speed from S.")),
    ("M05", tr("Spindle stop"), ""),
    ("M06", tr("Tool change"), tr("Mill ATC; the sequence is the machine builder's.")),
    ("M07", tr("Mist coolant on"), tr("Builder-defined.")),
    ("M08", tr("Coolant on"), ""),
    ("M09", tr("Coolant off"), ""),
    ("M19", tr("Spindle orientation"), tr("Builder-defined.")),
    (
        "M29",
        tr("Rigid tapping"),
        tr("Before G84: the spindle follows the Z axis (parameter-dependent M code)."),
    ),
    (
        "M30",
        tr("End of program and rewind"),
        tr(
            "Ends, resets and returns to the program head; locals become vacant; parts count #3901 "
            "goes up."
        ),
    ),
    ("M96", tr("Interrupt-type macro enable"), tr("Option; parameter-dependent M code.")),
    (
        "M97",
        tr("Interrupt-type macro disable (FANUC) / local subprogram call (Haas)"),
        tr(
            "On Haas `M97 P<n>` calls the block Nn of the same program; FANUC controls have no "
            "such call."
        ),
    ),
    (
        "M98",
        tr("Subprogram call"),
        tr(
            "`M98 P<program> [L<repeat>]`, or on 4-digit controls `M98 P<rrrr><pppp>`: M98 "
            "P0013331 runs O3331 once, P50010 runs O0010 five times. No arguments and no new local "
            "level: the subprogram shares the caller's #1-#33."
        ),
    ),
    (
        "M99",
        tr("End of subprogram (return)"),
        tr(
            "Returns to the block after the call; `M99 P<n>` returns to Nn of the caller "
            "instead. In a "
            "main program M99 restarts it from the head (an endless repetition)."
        ),
    ),
)

G_CODES: Mapping[str, CodeInfo] = MappingProxyType(
    {code: CodeInfo(code, lathe, mill) for code, lathe, mill in _G}
)
M_CODES: Mapping[str, CodeInfo] = MappingProxyType(
    {code: CodeInfo(code, m, m) for code, m in ((c, Meaning(t, x)) for c, t, x in _M)}
)

_BUILDER_M = tr(
    "Not a standard FANUC code: M codes other than M00-M02, M30, M98 and M99 are defined by "
    "the machine builder (or call macros O9020-O9029 by parameter)."
)


def code_name(letter: str, value: float) -> str:
    """``G1.`` -> ``G01``, ``G66.1`` -> ``G66.1``, ``M3`` -> ``M03``."""
    letter = letter.upper()
    rounded = round(value, 1)
    if rounded == int(rounded):
        return f"{letter}{int(rounded):02d}"
    whole = int(rounded)
    return f"{letter}{whole:02d}.{round((rounded - whole) * 10):d}"


def code_info(letter: str, value: float) -> CodeInfo | None:
    table = G_CODES if letter.upper() == "G" else M_CODES if letter.upper() == "M" else None
    if table is None:
        return None
    return table.get(code_name(letter, value))


_GROUP = re.compile(r"group (\d\d)(?: \((mill|lathe)\) / (\d\d) \((mill|lathe)\))?")


def modal_group(value: float, lathe: bool) -> str | None:
    """The modal group of G``value`` on the machine type ("01", "14"), from the table above;
    None for a one-shot code (group 00) or a code the table gives no group."""
    info = code_info("G", value)
    meaning = info.for_machine(lathe) if info is not None else None
    if meaning is None or not meaning.modal.startswith("modal"):
        return None
    found = _GROUP.search(meaning.modal)
    if found is None:
        return None
    first, first_for, second, _ = found.groups()
    if second is not None and first_for != ("lathe" if lathe else "mill"):
        return str(second)
    return str(first)


def code_markdown(
    letter: str, value: float, lathe: bool, system: str = "A", machine_known: bool = True
) -> str | None:
    """Hover text of a G or M code under the configured machine type (a lathe's G codes in
    G code ``system``: see program.g_code_systems): its name and meaning, then what more there
    is. The other machine's meaning of the code is given only when the machine is not known
    (``machine_known``: a document that shows neither, read both ways)."""
    parts = code_parts(letter, value, lathe, system, machine_known)
    return joined("\n\n", parts) if parts else None


def code_parts(
    letter: str, value: float, lathe: bool, system: str = "A", machine_known: bool = True
) -> list[str]:
    """``code_markdown``'s paragraphs: the first is the code's name and meaning in a line."""
    if lathe and system != "A" and letter.upper() == "G":
        said = _other_system_parts(value, system)
        if said is not None:
            return said
    name = code_name(letter, value)
    info = code_info(letter, value)
    if info is None:
        if letter.upper() == "M":
            return [f"**{name}**", _BUILDER_M]
        return [
            f"**{name}**",
            tr("Not a G code this checker knows (builder option or other control)."),
        ]
    here = info.for_machine(lathe)
    other = info.for_machine(not lathe)
    parts: list[str] = []
    if here is not None:
        head = tr("**{code}** — {title}", code=name, title=here.title)
        if here.modal:
            head = tr("{head} *({modal})*", head=head, modal=here.modal)
        parts.append(head)
        if here.text:
            parts.append(here.text)
    else:
        parts.append(
            tr("**{code}** — no meaning on a lathe (G code system A)", code=name)
            if lathe
            else tr("**{code}** — no meaning on a mill", code=name)
        )
    if not info.same_on_both and other is not None and not (machine_known and here is not None):
        if lathe:
            said_other = tr("On a mill: {title}.", title=other.title)
        else:
            said_other = tr("On a lathe: {title}.", title=other.title)
        parts.append(
            tr("{meaning} {text}", meaning=said_other, text=other.text)
            if other.text
            else said_other
        )
    return parts


def _other_system_parts(value: float, system: str) -> list[str] | None:
    """The hover's paragraphs of a G code whose function in G code ``system`` (B, C) is not
    system A's G``value``; None for a code the same in both."""
    name = code_name("G", value)
    if value in (ABSOLUTE, INCREMENTAL):
        mill = G_CODES[name].mill
        assert mill is not None
        head = tr(
            "**{code}** — {title} *(modal, group 03; lathe, G code system {system})*",
            code=name,
            title=mill.title,
            system=system,
        )
        return [head, mill.text]
    a = system_a_code(value, system)
    if a == value:
        return None
    if a is None:
        return [
            tr(
                "**{code}** — no meaning on a lathe of G code system {system}",
                code=name,
                system=system,
            )
        ]
    info = code_info("G", a)
    meaning = info.lathe if info is not None else None
    if meaning is None:
        return None
    head = tr(
        "**{code}** — {title} *(G code system {system}; system A's {code_a})*",
        code=name,
        title=meaning.title,
        system=system,
        code_a=code_name("G", a),
    )
    return [head, meaning.text] if meaning.text else [head]


def completion_codes(lathe: bool, system: str = "A") -> list[tuple[str, str]]:
    """(code, title) of the G and M codes that mean something on this machine type (a lathe's
    G codes named as G code ``system`` names them)."""
    out: list[tuple[str, str]] = []
    other_system = lathe and system != "A"
    for info in (*G_CODES.values(), *M_CODES.values()):
        meaning = info.for_machine(lathe)
        if meaning is None:
            continue
        out.append((info.code, meaning.title))
    if not other_system:
        return out
    # Each function under the number the system gives it: system A's G92 is B's G78.
    named = {written(code, system): title for code, title in out}
    for value in (ABSOLUTE, INCREMENTAL):
        mill = G_CODES[code_name("G", value)].mill
        assert mill is not None
        named[code_name("G", value)] = mill.title
    return sorted(named.items(), key=lambda item: (item[0][0] != "G", item[0]))


# ---- macro functions -------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class FunctionInfo:
    name: str
    signature: str
    title: str
    text: str
    snippet: str  # LSP snippet syntax


_FUNCTIONS: tuple[FunctionInfo, ...] = (
    FunctionInfo(
        "SIN", "SIN[a]", tr("Sine"), tr("Angles are in degrees. `SIN[30]` = 0.5."), "SIN[$1]"
    ),
    FunctionInfo(
        "COS", "COS[a]", tr("Cosine"), tr("Angles are in degrees. `COS[60]` = 0.5."), "COS[$1]"
    ),
    FunctionInfo(
        "TAN",
        "TAN[a]",
        tr("Tangent"),
        tr(
            "Angles are in degrees. Computed as SIN/COS, so `TAN[90]` stops with alarm PS0112 "
            "ZERO DIVIDE."
        ),
        "TAN[$1]",
    ),
    FunctionInfo(
        "ASIN",
        "ASIN[x]",
        tr("Arcsine"),
        tr(
            "Result in degrees, -90 to 90 (a parameter can give 270 to 90). An argument "
            "outside -1..1 stops with alarm PS0119 ARGUMENT VALUE OUT OF RANGE."
        ),
        "ASIN[$1]",
    ),
    FunctionInfo(
        "ACOS",
        "ACOS[x]",
        tr("Arccosine"),
        tr("Result in degrees, 0 to 180. An argument outside -1..1 stops with alarm PS0119."),
        "ACOS[$1]",
    ),
    FunctionInfo(
        "ATAN",
        "ATAN[a]/[b]",
        tr("Arctangent"),
        tr(
            "`ATAN[a]/[b]` is the angle of the point (b, a): the signs choose the "
            "quadrant, it is *not* a division. The result is 0 to 360 degrees by default "
            "(parameter NAT, 6004#0, gives -180 to 180; unverified). `ATAN[a,b]` and the "
            "one-argument `ATAN[x]` exist on 30i-class controls only; 16i has the slash "
            "form only. `ATAN[0]/[0]` has no angle."
        ),
        "ATAN[$1]/[$2]",
    ),
    FunctionInfo(
        "SQRT",
        "SQRT[x]",
        tr("Square root"),
        tr(
            "A negative argument stops with alarm PS0119 ARGUMENT VALUE OUT OF RANGE; a "
            "vacant one counts as 0."
        ),
        "SQRT[$1]",
    ),
    FunctionInfo("ABS", "ABS[x]", tr("Absolute value"), "", "ABS[$1]"),
    FunctionInfo(
        "ROUND",
        "ROUND[x]",
        tr("Round"),
        tr(
            "In a macro statement: to the nearest integer, halves away from zero "
            "(`ROUND[-1.5]` = -2). Inside an NC address (`X[ROUND[#1]]`) it rounds to the "
            "address's least input increment instead."
        ),
        "ROUND[$1]",
    ),
    FunctionInfo(
        "FIX",
        "FIX[x]",
        tr("Truncate"),
        tr(
            "Drops the fraction, towards zero: `FIX[1.7]` = 1, `FIX[-1.2]` = -1. Values "
            "computed as 2.9999999 become 2: add a small epsilon when the exact value is "
            "an integer."
        ),
        "FIX[$1]",
    ),
    FunctionInfo(
        "FUP",
        "FUP[x]",
        tr("Round up"),
        tr(
            "Raises any fraction to the next integer away from zero: `FUP[1.2]` = 2, "
            "`FUP[-1.2]` = -2; integers stay."
        ),
        "FUP[$1]",
    ),
    FunctionInfo(
        "LN",
        "LN[x]",
        tr("Natural logarithm"),
        tr("An argument of 0 or less stops with alarm PS0119."),
        "LN[$1]",
    ),
    FunctionInfo(
        "EXP",
        "EXP[x]",
        tr("Exponential (e^x)"),
        tr("A result too large stops with alarm PS0111 OVERFLOW."),
        "EXP[$1]",
    ),
    FunctionInfo(
        "POW",
        "POW[a,b]",
        tr("Power (a^b)"),
        tr(
            "30i-B class controls only (unverified for 0i-F). No real result (negative "
            "base with a fractional exponent) stops with alarm PS0119."
        ),
        "POW[$1,$2]",
    ),
    FunctionInfo(
        "ADP",
        "ADP[#n]",
        tr("Add decimal point"),
        tr(
            "Rescales an argument (#1-#33) that was passed without a decimal point, so "
            "that `X10` means 10. rather than 10 least increments. Exact behaviour is "
            "unverified."
        ),
        "ADP[$1]",
    ),
    FunctionInfo(
        "BIN",
        "BIN[x]",
        tr("BCD to binary"),
        tr("For PMC signals. A negative argument or a digit above 9 stops with alarm PS0119."),
        "BIN[$1]",
    ),
    FunctionInfo(
        "BCD",
        "BCD[x]",
        tr("Binary to BCD"),
        tr("For PMC signals. A negative argument stops with alarm PS0119."),
        "BCD[$1]",
    ),
)
FUNCTIONS: Mapping[str, FunctionInfo] = MappingProxyType({f.name: f for f in _FUNCTIONS})


def function_markdown(name: str) -> str | None:
    info = FUNCTIONS.get(name.upper())
    if info is None:
        return None
    if info.text:
        return tr(
            "**{signature}** — {title}\n\n{text}",
            signature=info.signature,
            title=info.title,
            text=info.text,
        )
    return tr("**{signature}** — {title}", signature=info.signature, title=info.title)


# ---- keywords and operators ------------------------------------------------------------------

_VACANT_NOTE = tr(
    "A vacant variable counts as 0 in GT/GE/LT/LE but differs from 0 in EQ/NE "
    "(`#1 EQ #0` is true only when #1 is vacant)."
)

KEYWORDS: Mapping[str, tuple[str, str]] = MappingProxyType(
    {
        "IF": (
            tr("Conditional"),
            tr(
                "`IF [cond] GOTO n` jumps when the condition is true; `IF [cond] "
                "THEN <one macro statement>` runs one assignment. An NC statement after THEN is "
                "not FANUC (Haas)."
            ),
        ),
        "THEN": (
            tr("Conditional statement"),
            tr("`IF [cond] THEN #1=...`: exactly one macro statement."),
        ),
        "GOTO": (
            tr("Branch"),
            tr(
                "`GOTO n` jumps to the block Nn of the same program. The control "
                "searches forward from here, then from the program head, so backward jumps are "
                "slower. n may be an expression (`GOTO#10`); a missing or out-of-range n stops "
                "with alarm PS0128 (ILLEGAL MACRO SEQUENCE NUMBER)."
            ),
        ),
        "WHILE": (
            tr("Loop"),
            tr(
                "`WHILE [cond] DOm` ... `ENDm` repeats the blocks while the condition is "
                "true; m is 1, 2 or 3, loops nest at most three deep and must not cross. Jumping "
                "out of a loop is allowed, into one is not."
            ),
        ),
        "WH": (tr("Loop (abbreviation of WHILE)"), tr("Accepted on input by FANUC controls.")),
        "DO": (
            tr("Loop start"),
            tr(
                "`DOm` without WHILE loops forever. m is 1-3 (alarm PS0126 "
                "otherwise); a DO without its END stops with alarm PS0124."
            ),
        ),
        "END": (
            tr("Loop end"),
            tr(
                "`ENDm` goes back to the WHILE of the same number; the number must "
                "match the open DO (alarm PS0126)."
            ),
        ),
        "EQ": (tr("Equal"), _VACANT_NOTE),
        "NE": (tr("Not equal"), _VACANT_NOTE),
        "GT": (tr("Greater than"), _VACANT_NOTE),
        "GE": (tr("Greater than or equal"), _VACANT_NOTE),
        "LT": (tr("Less than"), _VACANT_NOTE),
        "LE": (tr("Less than or equal"), _VACANT_NOTE),
        "AND": (
            tr("And"),
            tr(
                "Between conditions in IF/WHILE: logical (`[[c1] AND [c2]]`, compound "
                "conditions need a recent control). In an expression: bitwise on the integer "
                "values, with the priority of `*`."
            ),
        ),
        "OR": (
            tr("Or"),
            tr(
                "Logical between conditions; bitwise on integers in an expression, with the "
                "priority of `+`."
            ),
        ),
        "XOR": (
            tr("Exclusive or"),
            tr("Logical between conditions; bitwise on integers in an expression."),
        ),
        "MOD": (
            tr("Remainder"),
            tr(
                "`a MOD b` on the integer parts (30i / 0i-F; not on 16i). `MOD 0` stops with alarm "
                "PS0112."
            ),
        ),
        "DPRNT": (
            tr("Print data"),
            tr(
                "`DPRNT[text#100[53]]` sends text and variables (3 integer and 5 "
                "decimal digits here) to the output device; `*` prints a space. Open the device "
                "with POPEN first."
            ),
        ),
        "BPRNT": (tr("Print binary data"), tr("Like DPRNT with variables in binary.")),
        "POPEN": (tr("Open output device"), tr("Before DPRNT/BPRNT.")),
        "PCLOS": (tr("Close output device"), tr("After DPRNT/BPRNT.")),
    }
)


def keyword_markdown(word: str) -> str | None:
    entry = KEYWORDS.get(word.upper())
    if entry is None:
        return None
    title, text = entry
    return tr("**{keyword}** — {title}\n\n{text}", keyword=word.upper(), title=title, text=text)


# ---- addresses -------------------------------------------------------------------------------

# letter: (lathe, mill); one text when the same.
_ADDRESSES: Mapping[str, tuple[str, str]] = MappingProxyType(
    {
        "A": (tr("A axis (rotary about X) or chamfer angle"), tr("A axis (rotary about X)")),
        "B": (tr("B axis or second auxiliary function"), tr("B axis (rotary about Y)")),
        "C": (tr("C axis (spindle as an axis) or chamfer size"), tr("C axis (rotary about Z)")),
        "D": (tr("Depth in some cycles"), tr("Cutter radius offset number (G41/G42)")),
        "E": (tr("Thread lead, precise"), tr("Thread lead, precise")),
        "F": (
            tr("Feed (mm/rev in G99, mm/min in G98); the lead in threading"),
            tr("Feed (mm/min in G94, mm/rev in G95)"),
        ),
        "G": (tr("Preparatory function"), tr("Preparatory function")),
        "H": (tr("Incremental C axis (some machines)"), tr("Tool length offset number (G43/G44)")),
        "I": (
            tr("Arc centre X offset (radius) / cycle parameter"),
            tr("Arc centre X offset / cycle parameter"),
        ),
        "J": (tr("Arc centre Y offset"), tr("Arc centre Y offset")),
        "K": (
            tr("Arc centre Z offset / cycle parameter"),
            tr("Arc centre Z offset / repeat count of drilling cycles"),
        ),
        "L": (tr("Repeat count (M98, G65)"), tr("Repeat count (M98, G65)")),
        "M": (tr("Miscellaneous function"), tr("Miscellaneous function")),
        "N": (tr("Sequence number (GOTO target)"), tr("Sequence number (GOTO target)")),
        "O": (tr("Program number"), tr("Program number")),
        "P": (
            tr("Program number (M98, G65), dwell in ms (G04), first block of a cycle shape"),
            tr("Program number (M98, G65), dwell in ms (G04, G82)"),
        ),
        "Q": (
            tr("Last block of a cycle shape / cycle depth"),
            tr("Peck depth (G73, G83) / shift (G76)"),
        ),
        "R": (
            tr("Arc radius, taper of a cycle, retract"),
            tr("Arc radius, R point of a drilling cycle"),
        ),
        "S": (
            tr("Spindle speed (rpm in G97, m/min in G96); maximum speed with G50"),
            tr("Spindle speed"),
        ),
        "T": (
            tr("Tool and offset: T0101 = tool 1, offset 1; T0100 cancels the offset"),
            tr("Tool number"),
        ),
        "U": (tr("Incremental X (diameter)"), tr("U axis")),
        "V": (tr("Incremental Y"), tr("V axis")),
        "W": (tr("Incremental Z"), tr("W axis")),
        "X": (tr("X position, a diameter"), tr("X position")),
        "Y": (tr("Y position"), tr("Y position")),
        "Z": (tr("Z position"), tr("Z position")),
        # after a move in G01 (G02, G03): 0i-MF "Optional chamfering and corner R", 0i-TF
        # "Chamfering and corner R" and "Direct drawing dimension programming"
        ",A": (
            tr("Angle of the line from the +Z axis (direct drawing dimensions)"),
            tr("Angle of the line in the plane (direct drawing dimensions)"),
        ),
        ",C": (
            tr("Chamfer to the next move: the length cut off the corner"),
            tr("Chamfer to the next move: the length cut off the corner"),
        ),
        ",R": (tr("Corner radius to the next move"), tr("Corner radius to the next move")),
    }
)


def address_markdown(letter: str, lathe: bool) -> str | None:
    entry = _ADDRESSES.get(letter.upper())
    if entry is None:
        return None
    return tr(
        "**{address}** — {meaning}", address=letter.upper(), meaning=entry[0] if lathe else entry[1]
    )


# ---- system variables worth offering in completion -------------------------------------------

SYSTEM_VARIABLES: tuple[int, ...] = (
    0, 1000, 1032, 1100, 1132, 2001, 2201, 2501, 2601, 2701, 3000, 3001, 3002, 3003, 3004,
    3005, 3006, 3007, 3011, 3012, 3901, 3902, 4000, 4001, 4002, 4003, 4005, 4006, 4007,
    4008, 4014, 4102, 4107, 4109, 4111, 4113, 4114, 4115, 4119, 4120, 5001, 5002, 5003,
    5021, 5022, 5023, 5041, 5042, 5043, 5061, 5062, 5063, 5081, 5083, 5101, 5201, 5221,
    5222, 5223, 5241, 5261, 5281, 5301, 5321, 7001,
)  # fmt: skip
