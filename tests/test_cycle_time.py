"""The cycle time (evaluator/cycle_time.py): each figure is worked out by hand in the comments,
from the FANUC 0i-TF/0i-MF operator's manuals' definitions (F per minute or per revolution,
G96's n = 1000 V / (π D), G04's P in milliseconds, a thread's F the lead) and the settings'
rates; the seed module O4009's from the paper's formulas (../shared/reference/thread-math.md)."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from fanuc_macro.config import Config
from fanuc_macro.evaluator import evaluate
from fanuc_macro.evaluator.cycle_time import CycleTime, cycle_time, minutes_seconds
from fanuc_macro.program.index import build_index
from fanuc_macro.syntax.parser import parse_text

ROOT = Path(__file__).resolve().parents[1]
SEED = ROOT / "tests" / "fixtures" / "seeds" / "o4009_external_m50x3.nc"
LATHE = Config()
MILL = Config(controller="0i-MF")
# The default rapid rates (mm/min) and tool change (s) the figures below divide by.
RAPID_X, RAPID_Y, RAPID_Z, TOOL_CHANGE = 20_000.0, 20_000.0, 24_000.0, 2.0


def timed(text: str, config: Config = LATHE, uri: str = "t.nc") -> CycleTime:
    doc = parse_text(text, uri)
    facts = evaluate([(uri, doc, build_index(doc))], config, toolpath=True)
    found = cycle_time(facts, config)
    assert found is not None
    return found


def program(*blocks: str) -> str:
    return "%\nO1000\n" + "\n".join(blocks) + "\nM30\n%\n"


def parts(cycle: CycleTime) -> dict[str, float]:
    """The parts that took time, rounded to the microsecond."""
    return {k: round(v, 6) for k, v in cycle.total.parts().items() if v}


def test_the_defaults_are_the_documented_ones() -> None:
    config = Config()
    assert (config.rapid_rate_x, config.rapid_rate_y, config.rapid_rate_z) == (
        RAPID_X,
        RAPID_Y,
        RAPID_Z,
    )
    assert config.tool_change_seconds == TOOL_CHANGE and config.m_code_seconds == ()


def test_a_feed_per_minute_on_a_lathe_g98() -> None:
    # G00 X40. Z2. starts where the run began (not known): no time. G98 G01 Z-48. F200.:
    # 50 mm at 200 mm/min = 0.25 min = 15 s.
    cycle = timed(program("G00 X40. Z2.", "G98 G01 Z-48. F200."))
    assert parts(cycle) == {"cutting": 15.0}


def test_a_mill_feed_in_g94_mm_per_minute() -> None:
    # G01 X30. Y40. F600. from X0 Y0: 50 mm (3-4-5) at 600 mm/min = 1/12 min = 5 s.
    cycle = timed(program("G90 G94 G00 X0 Y0 Z0", "G01 X30. Y40. F600."), MILL)
    assert parts(cycle) == {"cutting": 5.0}


def test_a_feed_per_revolution_at_the_g97_speed() -> None:
    # A lathe in G99 (power on): F0.2 mm/rev x S500 = 100 mm/min; Z2. to Z-48.: 50 mm in
    # 0.5 min = 30 s. The X move G00 X40. -> X20. (10 mm of radius) at 20000 mm/min: 0.03 s.
    cycle = timed(program("G97 S500 M03", "G00 X40. Z2.", "X20.", "G01 Z-48. F0.2"))
    assert parts(cycle) == {"cutting": 30.0, "rapid": 0.03}


def test_a_mill_feed_per_revolution_g95() -> None:
    # G95 F0.1 x S1000 = 100 mm/min; Z0 to Z-20.: 20 mm in 0.2 min = 12 s.
    cycle = timed(program("G90 G00 X0 Y0 Z0", "S1000 M03", "G95 G01 Z-20. F0.1"), MILL)
    assert parts(cycle) == {"cutting": 12.0}


def test_g96_at_a_diameter_the_g50_clamp_holds() -> None:
    # At D20 the surface speed 200 m/min asks n = 1000 x 200 / (π x 20) = 3183.1 rpm; G50
    # S1500 clamps it to 1500: F0.1 x 1500 = 150 mm/min; Z2. to Z-30.: 32 mm = 12.8 s.
    cycle = timed(
        program("G50 S1500", "G96 S200 M03", "G00 X20. Z2.", "G01 Z-30. F0.1"),
    )
    assert parts(cycle) == {"cutting": 12.8}


def test_g96_below_the_clamp_and_the_machines_maximum() -> None:
    # At D80: n = 200000 / (80π) = 795.77 rpm, under no clamp; 32 mm at F0.1 x n mm/min:
    # t = 32 x 80π / (0.1 x 200000) min.
    cycle = timed(program("G96 S200 M03", "G00 X80. Z2.", "G01 Z-30. F0.1"))
    assert cycle.total.cutting == pytest.approx(32 * 80 * math.pi / (0.1 * 200_000) * 60)
    # At D20 with no G50 but a machine's maximum of 1000 rpm: 32 / (0.1 x 1000) min = 19.2 s.
    clamped = Config(max_spindle_speed=1000.0)
    cycle = timed(program("G96 S200 M03", "G00 X20. Z2.", "G01 Z-30. F0.1"), clamped)
    assert parts(cycle) == {"cutting": 19.2}


def test_g96_facing_to_the_centre_crosses_the_clamp() -> None:
    # Facing X100. -> X0 at F0.1, V = 200, G50 S1500: n = k / D with k = 200000 / π until
    # D* = k / 1500 = 42.44 (r* = 21.22), then 1500. Above r*: dt = dr / (F n) with
    # n = k / (2r): t = (50² - r*²) / (F k) min; below: r* / (F x 1500) min.
    k = 200_000 / math.pi
    r_star = k / 1500 / 2
    minutes = (50**2 - r_star**2) / (0.1 * k) + r_star / (0.1 * 1500)
    cycle = timed(program("G50 S1500", "G96 S200 M03", "G00 X100. Z0", "G01 X0 F0.1"))
    assert cycle.total.cutting == pytest.approx(minutes * 60, rel=1e-12)


def test_dwells_in_milliseconds_and_seconds() -> None:
    # G04 P1500: 1500 ms; G04 X1.5 and G04 U1.5: 1.5 s each. 4.5 s in all.
    cycle = timed(program("G04 P1500", "G04 X1.5", "G04 U1.5"))
    assert parts(cycle) == {"dwell": 4.5}
    assert timed(program("G04 P1500"), MILL).total.dwell == 1.5


def test_tool_changes_on_a_lathe_and_a_mill() -> None:
    # T0101, T0202: two tools; T0200 cancels the offset of tool 2 (no change). At 5 s each:
    # 10 s.
    config = Config(tool_change_seconds=5.0)
    cycle = timed(program("T0101", "T0202", "T0200"), config)
    assert parts(cycle) == {"tool change": 10.0}
    assert cycle.runs[0].tool_changes == 2
    # A mill's M06, twice: 2 x 2 s.
    assert parts(timed(program("T1 M06", "T2 M06"), MILL)) == {"tool change": 4.0}


def test_m_codes_take_the_seconds_the_settings_give() -> None:
    # M08 twice at 0.5 s and M10 once at 1.5 s: 2.5 s; M09 is not named: no time.
    config = Config.from_settings({"cycleTime": {"mCodeSeconds": {"M08": 0.5, "10": 1.5}}})
    assert config.m_code_seconds == ((8.0, 0.5), (10.0, 1.5))
    cycle = timed(program("M08", "M10", "M09", "M08"), config)
    assert parts(cycle) == {"M codes": 2.5}
    assert parts(timed(program("M08"))) == {}  # none by default


def test_a_rapid_is_as_long_as_its_slowest_axis() -> None:
    # G00 X20. Z0 -> X100. Z-10.: X moves 40 mm of radius at 20000 mm/min (0.12 s), Z 10 mm
    # at 24000 (0.025 s): each axis at its own rate, 0.12 s.
    cycle = timed(program("G00 X20. Z0", "X100. Z-10."))
    assert parts(cycle) == {"rapid": 0.12}
    # A mill with X at 10000 mm/min: X0 Y0 Z0 -> X100. Y30. Z-5.: X 0.6 s, Y 30/20000 min
    # = 0.09 s, Z 5/24000 min = 0.0125 s: 0.6 s.
    config = Config(controller="0i-MF", rapid_rate_x=10_000.0)
    assert parts(timed(program("G00 X0 Y0 Z0", "X100. Y30. Z-5."), config)) == {"rapid": 0.6}


def test_inches_feed_in_inches_per_minute() -> None:
    # G20 G98: Z0.1 -> Z-1.9 (2 inches) at F10. in/min: 0.2 min = 12 s. The rapid back to
    # Z0.1: 2 inches = 50.8 mm at 24000 mm/min = 0.127 s.
    cycle = timed(program("G20", "G00 X2. Z0.1", "G98 G01 Z-1.9 F10.", "G00 Z0.1"))
    assert parts(cycle) == {"cutting": 12.0, "rapid": 0.127}


def test_a_thread_at_the_lead_times_the_speed() -> None:
    # G32 Z-30. F2. from Z2. at S500: 32 mm at 2 x 500 = 1000 mm/min: 1.92 s.
    cycle = timed(program("G97 S500 M03", "G00 X30. Z2.", "G32 Z-30. F2."))
    assert parts(cycle) == {"threading": 1.92}


def test_a_turning_cycle_g90_is_its_four_legs() -> None:
    # G90 X40. Z-30. F0.2 from X50. Z2. at S500 (100 mm/min): rapid in X 5 mm of radius
    # (0.015 s), cut 32 mm along Z (19.2 s), feed out 5 mm in X (3 s), rapid back 32 mm in Z
    # (32 / 24000 min = 0.08 s).
    cycle = timed(program("G97 S500 M03", "G00 X50. Z2.", "G90 X40. Z-30. F0.2"))
    assert parts(cycle) == {"cutting": 22.2, "rapid": 0.095}


def test_a_threading_cycle_g92_and_its_returns() -> None:
    # G92 X28. Z-20. F1.5 from X32. Z3. at S600: rapid in 2 mm of radius (0.006 s), thread 23
    # mm at 1.5 x 600 = 900 mm/min (23 / 900 min = 1.5333 s), rapid out (0.006 s), rapid back
    # 23 mm in Z (0.0575 s); the repeat X27.6 the same but 2.2 mm of radius each way.
    cycle = timed(program("G97 S600 M03", "G00 X32. Z3.", "G92 X28. Z-20. F1.5", "X27.6"))
    assert cycle.total.threading == pytest.approx(2 * 23 / 900 * 60)
    assert cycle.total.rapid == pytest.approx((2 * 2 + 2 * 2.2) / RAPID_X * 60 + 2 * 23 / 400)


def test_an_arc_is_timed_along_its_length() -> None:
    # G02 X20. Y0 R10. from X0 Y0: half a circle of radius 10, 10π mm at 100 mm/min.
    cycle = timed(program("G90 G00 X0 Y0 Z0", "G02 X20. Y0 R10. F100."), MILL)
    assert cycle.total.cutting == pytest.approx(10 * math.pi / 100 * 60)


def test_a_move_with_no_speed_is_counted_not_timed() -> None:
    # F0.2 per revolution with no S: the run cannot know the time of the cut.
    cycle = timed(program("G00 X40. Z2.", "G01 Z-48. F0.2"))
    assert cycle.untimed == 1 and cycle.runs[0].untimed == 1
    assert parts(cycle) == {}


def test_the_time_so_far_at_each_motion_record() -> None:
    # T0101 (2 s), then G98 G01 Z-48. F200. (15 s), G04 P500 (0.5 s), G01 Z-98. (15 s).
    cycle = timed(program("T0101", "G00 X40. Z2.", "G98 G01 Z-48. F200.", "G04 P500", "Z-98."))
    # Motion records: 0 the G00, 1 the first G01, 2 the second.
    # The dwell ran before record 2's block: 2 + 15 + 0.5.
    assert [cycle.so_far(i) for i in range(4)] == [2.0, 2.0, 17.5, 32.5]
    assert cycle.so_far(3) == cycle.total.total


def test_minutes_and_seconds_to_a_tenth() -> None:
    assert minutes_seconds(372.44) == "6 min 12.4 s"
    assert minutes_seconds(59.96) == "1 min 0.0 s"
    assert minutes_seconds(12.34) == "12.3 s"


def o4009_by_hand() -> dict[str, float]:
    """The seed module's cycle time, from the paper's formulas (thread-math.md): each
    quantity as the sub-program O3331 computes it, positions at the control's 0.001 mm."""
    pitch, nominal, length, es, td2 = 3.0, 50.0, 50.0, 0.048, 0.170
    sin60, tan30 = math.sin(math.radians(60)), math.tan(math.radians(30))
    run_in = 2 * pitch + pitch + math.floor(length / pitch) * pitch - length  # #2 = 7
    run_out = pitch  # #1 = 3
    r = pitch / (8 * sin60)  # #3, the nose radius
    h = (7 / 8) * sin60 * pitch - r + es / 2 + td2 / 4  # #4, the thread height
    ap_max = (0.2 / 3) * math.sqrt(h)  # #5
    ap_min = (0.2 / 3) * math.sqrt(ap_max)  # #6
    rpm, lead, g99_feed = 400.0, pitch, 0.5
    # G01 ... G99 F0.5 at S400: 200 mm/min; after the first G92 F3 the modal F is the lead,
    # and the G01s that shift the tool run at 3 mm/rev, 1200 mm/min (FANUC keeps F modal).
    feed = {"F": g99_feed * rpm}
    thread_length = run_in + length + run_out  # W-60.
    seconds = {"cutting": 0.0, "threading": 0.0, "rapid": 0.0, "tool change": TOOL_CHANGE}
    # G01 X51. W7. from X55. Z0: 2 mm of radius and 7 of Z, sqrt(53) mm.
    seconds["cutting"] += math.sqrt(2**2 + 7**2) / feed["F"] * 60
    start_x, z = 51.0, 7.0

    def g92(x: float) -> None:
        x = round(x, 3)
        # Rapid in X to the cut's diameter and back out: (51 - x) / 2 each way at X's rate;
        # the thread along Z at F3 x S400 = 1200 mm/min; the rapid back in Z at Z's rate.
        seconds["rapid"] += 2 * ((start_x - x) / 2) / RAPID_X * 60
        seconds["threading"] += thread_length / (lead * rpm) * 60
        seconds["rapid"] += thread_length / RAPID_Z * 60
        feed["F"] = lead * rpm

    def g01_w(step: float) -> None:
        nonlocal z
        new = round(z + step, 3)
        seconds["cutting"] += abs(new - z) / feed["F"] * 60
        z = new

    n = 1.0
    total = ap_max * math.sqrt(n)
    u = (h + r - ap_min - total) * tan30 - r * tan30
    cuts = 0
    while True:  # N10 ... IF[#9LT[#4-#6]] GOTO10
        g01_w(-u)
        g92(nominal - 2 * total)
        g01_w(2 * u)
        g92(nominal - 2 * total)
        g01_w(-u)
        cuts += 2
        n += 1
        ap = ap_max * (math.sqrt(n) - math.sqrt(n - 1))
        total = ap_max * math.sqrt(n) if ap >= ap_min else total + ap_min
        u = (h + r - ap_min - total) * tan30 - r * tan30
        if not total < h - ap_min:
            break
    g92(nominal - 2 * h + 2 * ap_min)  # the last rough cut, straight in
    for _ in range(9):  # the finishing cut, then eight spring passes at the root
        g92(nominal - 2 * h)
    cuts += 10
    assert cuts == 186  # the paper's count
    # G00 X100. Z100. from X51. Z7.: X 24.5 mm of radius (0.0735 s), Z 93 mm (0.2325 s).
    seconds["rapid"] += max(24.5 / RAPID_X, (100 - z) / RAPID_Z) * 60
    return seconds


def test_the_seed_module_o4009_as_worked_out_by_hand() -> None:
    by_hand = o4009_by_hand()
    # The figures: cutting 11.409 s (the G01 shifts), threading 558 s, rapid 29.865 s (27.9
    # of them the G92s' returns in Z), one tool change 2 s: 601.274 s, 10 min 1.3 s.
    assert {k: round(v, 3) for k, v in by_hand.items()} == {
        "cutting": 11.409,
        "threading": 558.0,
        "rapid": 29.865,
        "tool change": 2.0,
    }
    cycle = timed(SEED.read_text("utf-8"), uri=str(SEED))
    # 186 G92 cuts of 60 mm at 1200 mm/min: 3 s each, 558 s of threading.
    assert by_hand["threading"] == pytest.approx(558.0)
    assert cycle.total.threading == pytest.approx(by_hand["threading"], abs=1e-9)
    assert cycle.total.cutting == pytest.approx(by_hand["cutting"], abs=1e-6)
    assert cycle.total.rapid == pytest.approx(by_hand["rapid"], abs=1e-6)
    assert cycle.total.tool_change == by_hand["tool change"]
    assert cycle.total.total == pytest.approx(sum(by_hand.values()), abs=1e-6)
    assert cycle.untimed == 0
    [run] = cycle.runs
    assert (run.program, run.tool_changes) == ("O4009", 1)
    assert minutes_seconds(run.seconds) == "10 min 1.3 s"


def test_a_run_for_the_cycle_time_is_a_full_one_whatever_came_before() -> None:
    # The moves and the timed events live on the toolpath, which only a full run records: a
    # run given an earlier evaluation's facts still runs whole, and times the same.
    text = program("T0101", "G00 X40. Z2.", "G98 G01 Z-48. F200.", "G04 P500", "M08")
    config = Config(m_code_seconds=((8.0, 1.0),))
    doc = parse_text(text, "t.nc")
    earlier = evaluate([("t.nc", doc, build_index(doc))], config)
    edited = parse_text(text.replace("P500", "P800"), "t.nc")
    facts = evaluate(
        [("t.nc", edited, build_index(edited))], config, previous=earlier, toolpath=True
    )
    found = cycle_time(facts, config)
    assert found is not None
    # 2 s tool change + 15 s cut + 0.8 s dwell + 1 s M08.
    assert parts(found) == {"cutting": 15.0, "dwell": 0.8, "tool change": 2.0, "M codes": 1.0}


def test_the_settings_come_from_the_configuration_file(tmp_path: Path) -> None:
    from fanuc_macro.config_file import load_config_file

    file = tmp_path / "fanuc-macro.toml"
    file.write_text(
        "[cycle-time]\nrapid-rate-x = 10000\nrapid-rate-z = 12000\n"
        "tool-change-seconds = 4.5\nm-code-seconds = { M08 = 0.5, M10 = 1.5 }\n",
        encoding="utf-8",
    )
    config = Config.from_settings(load_config_file(file).settings)
    assert (config.rapid_rate_x, config.rapid_rate_y, config.rapid_rate_z) == (
        10_000.0,
        RAPID_Y,
        12_000.0,
    )
    assert config.tool_change_seconds == 4.5
    assert config.m_code_seconds == ((8.0, 0.5), (10.0, 1.5))


def test_m_code_seconds_that_cannot_be_read_are_said() -> None:
    config = Config.from_settings({"cycleTime": {"mCodeSeconds": {"X8": 1, "M09": "long"}}})
    assert config.m_code_seconds == ()
    assert config.setting_problems == (
        "cycleTime.mCodeSeconds: 'X8' is not an M code (M08, 8)",
        "cycleTime.mCodeSeconds: 'M09': 'long' is not a number of seconds",
    )
