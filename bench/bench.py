"""Benchmark of the parser, the program index and the evaluator (a script, not a test).

    python bench/bench.py            # all figures
    python bench/bench.py --quick    # smaller sizes
    python bench/bench.py --keystrokes   # only the keystrokes in big programs

Programs are generated: a lathe/mill mix of motion blocks and macro statements in the
proportion of the corpus of real programs (about 45% plain NC blocks), with numbers varied so
that no two blocks repeat (the parse cache does not help the cold figures).
"""

from __future__ import annotations

import argparse
import gc
import platform
import random
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "server"))

from fanuc_macro.analysis import analyse  # noqa: E402
from fanuc_macro.evaluator import Facts, evaluate  # noqa: E402
from fanuc_macro.evaluator.machine import CHECKPOINT_EVERY  # noqa: E402
from fanuc_macro.program.index import ProgramIndex, build_index  # noqa: E402
from fanuc_macro.syntax.parser import BlockParser, parse_text  # noqa: E402
from fanuc_macro.syntax.tree import Document  # noqa: E402


def generate(blocks: int, seed: int = 1) -> str:
    rnd = random.Random(seed)
    # The locals set first: a program that read them unset would be analysed as a macro with
    # unknown arguments, and its loops and threads would not be the workload measured here.
    out = ["%", "O1000 (GENERATED BENCHMARK PROGRAM)"]
    out += [f"#{v}=0 (LOCAL {v})" for v in range(1, 34)]
    n = 0
    label = 10
    while len(out) < blocks + 2:
        k = n % 20
        n += 1
        x, z = rnd.uniform(0, 100), rnd.uniform(-80, 0)
        v = rnd.randint(1, 33)
        if k < 9:
            out.append(f"G01 X{x:.3f} Z{z:.3f} F{rnd.uniform(0.05, 0.4):.2f}")
        elif k == 9:
            out.append(f"N{label} G00 X{x:.2f} Z{z:.2f}")
            label += 10
        elif k == 10:
            out.append(f"#{v}=#{rnd.randint(1, 33)}*{rnd.uniform(0, 5):.4f}+SQRT[#{v}]")
        elif k == 11:
            out.append(f"#{100 + v}=[#{v}+{rnd.uniform(0, 9):.3f}]*COS[{rnd.uniform(0, 90):.2f}]")
        elif k == 12:
            out.append(f"IF[#{v}GT{rnd.uniform(0, 100):.1f}]GOTO{label - 10}")
        elif k == 13:
            out.append(f"G92 X[#100-2.*#{v}] W[-#2-#102-#1] R0 F#101 (PASS {n})")
        elif k == 14:
            out.append(f"G02 X{x:.3f} Z{z:.3f} R{rnd.uniform(1, 9):.2f}")
        elif k == 15:
            out.append(f"#{v}=#{v}+{rnd.random():.4f} (STEP {n})")
        elif k == 16:
            out.append(f"WHILE[#{v}LT{rnd.randint(1, 9)}]DO1")
            out.append(f"#{v}=#{v}+1.")
            out.append("END1")
        elif k == 17:
            out.append(f"G00 X[#{v}+{x:.2f}] Z{z:.2f}")
        elif k == 18:
            # A subprogram of the file: a call outside it would leave every common unknown.
            out.append(f"M98 P9000 L{rnd.randint(1, 3)} (CALL {n})")
        else:
            out.append(f"T{rnd.randint(1, 12):02d}{rnd.randint(1, 12):02d} (TOOL {n})")
    out.append("M30")
    out += ["O9000 (CALLED SUBPROGRAM)", "M99", "%"]
    return "\n".join(out) + "\n"


def best_of(fn: Callable[[], object], repeat: int = 3) -> float:
    times = []
    for _ in range(repeat):
        gc.collect()  # the garbage of the run before is not this run's cost
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def parse_cold(text: str) -> None:
    build_index(parse_text(text, "bench", BlockParser()))


def parse_edit(text: str, parser: BlockParser, previous: Document) -> None:
    build_index(parse_text(text, "bench", parser, previous))


def bench_parse(sizes: list[int]) -> None:
    print("parse + index (cold: a new parser, no cache; edit: one line changed, as the language")
    print("server does it: cached lines and the previous version's blocks reused)")
    for size in sizes:
        text = generate(size)
        cold_s = best_of(partial(parse_cold, text), 2 if size > 20000 else 3)
        parser = BlockParser()
        previous = parse_text(text, "bench", parser)
        edited = text.splitlines()
        edited[len(edited) // 2] = "G01 X12.345 Z-6.789 F0.25 (EDITED)"
        edit_s = best_of(partial(parse_edit, "\n".join(edited) + "\n", parser, previous), 5)
        print(
            f"  {size:>7} blocks: cold {cold_s * 1000:8.1f} ms  ({size / cold_s:9.0f} blocks/s)"
            f"   one-line edit {edit_s * 1000:7.1f} ms"
        )


def _rss_mb() -> float:
    """Peak RSS of this process. VmHWM, not ru_maxrss: Linux carries ru_maxrss across exec,
    so a child started from a big parent would report the parent's peak."""
    try:
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def memory_child(size: int) -> None:
    text = generate(size)
    base = _rss_mb()
    doc = parse_text(text, "bench", BlockParser())
    build_index(doc)
    print(f"{_rss_mb():.0f} {base:.0f}")


def bench_memory(size: int) -> None:
    # A fresh process, so that the peak RSS is this parse's alone.
    out = subprocess.run(
        [sys.executable, __file__, "--memory-child", str(size)],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    peak, base = float(out[0]), float(out[1])
    print(
        f"memory: {size} blocks parsed and indexed: peak RSS {peak:.0f} MB "
        f"({base:.0f} MB before parsing: interpreter, Lark, the program text)"
    )


def bench_eval() -> None:
    seed = ROOT / "tests" / "fixtures" / "seeds" / "o4009_external_m50x3.nc"
    text = seed.read_text("utf-8")
    doc = parse_text(text, str(seed))
    index = build_index(doc)
    t = best_of(lambda: evaluate([(str(seed), doc, index)]), 5)
    facts = evaluate([(str(seed), doc, index)])
    g92 = sum(1 for m in facts.motions if m.code == "G92")
    print(
        f"evaluator: seed O4009/O3331 traced in {t * 1000:.1f} ms ({facts.steps} blocks, "
        f"{g92} G92 cuts)"
    )
    loop = "O1\n#1=0\n#2=0\nWHILE[#1LT200000]DO1\n#1=#1+1\n#2=#2+#1*0.5\nEND1\nM30\n"
    doc = parse_text(loop, "loop")
    index = build_index(doc)
    t = best_of(lambda: evaluate([("loop", doc, index)]), 3)
    facts = evaluate([("loop", doc, index)])
    print(
        f"evaluator: {facts.steps} blocks of a WHILE loop in {t * 1000:.0f} ms = "
        f"{facts.steps / t:,.0f} macro statements/s"
    )
    endless = "O2\n#1=0\n#2=0\nWHILE[#1LT10]DO1\n#2=#2+1\nEND1\nM30\n"
    t = time.perf_counter()
    result = analyse(endless, "endless")
    dt = time.perf_counter() - t
    codes = sorted({d.code for d in result.diagnostics})
    print(f"evaluator: endless loop stopped and reported in {dt * 1000:.0f} ms ({codes})")


def bench_resume(size: int) -> None:
    """A one-line code edit of a long program: a full evaluation against one resumed from
    the earlier run's checkpoints (the lines parsed and compiled in both)."""
    from bench_lsp import program  # the language server benchmark's program, seed style

    text = program(size)
    lines = text.splitlines()
    parser = BlockParser()
    uri = "resume.nc"

    def evaluated(source: str, previous: Facts | None) -> tuple[Facts, float]:
        doc = parse_text(source, uri, parser)
        index = build_index(doc)
        started = time.perf_counter()
        facts = evaluate([(uri, doc, index)], only_uri=uri, previous=previous)
        return facts, time.perf_counter() - started

    first, _ = evaluated(text, None)
    full = min(evaluated(text, None)[1] for _ in range(3))
    assignments = [i for i, t in enumerate(lines) if t.startswith("#") and "SQRT[" in t]
    for where in (0.1, 0.5, 0.9):
        line = next(i for i in assignments if i >= len(lines) * where)
        times: list[float] = []
        previous = first
        executed = 0
        for k in range(5):
            edited = list(lines)
            edited[line] = edited[line].replace("SQRT[", f"SQRT[{k + 2}.*", 1)
            facts, seconds = evaluated("\n".join(edited) + "\n", previous)
            times.append(seconds)
            assert facts.record is not None and facts is not previous
            executed = facts.record.executed
            resumed_within_bound(f"an edit at {where:.0%}", executed)
            previous = facts
        print(
            f"evaluator, {size:,} blocks ({first.steps:,} run), edit at {where:.0%} of the "
            f"program: full {full * 1000:.0f} ms, resumed median "
            f"{statistics.median(times) * 1000:.1f} ms (ran {executed:,} blocks)"
        )
    line = next(i for i in assignments if i >= len(lines) // 2)
    for what, edited in (
        ("a line added (Enter)", [*lines[:line], "", *lines[line:]]),
        ("a line removed", [*lines[:line], *lines[line + 1 :]]),
    ):
        times = []
        for _ in range(5):
            facts, seconds = evaluated("\n".join(edited) + "\n", first)
            times.append(seconds)
        assert facts.record is not None
        print(
            f"evaluator, {size:,} blocks, {what} at 50%: resumed median "
            f"{statistics.median(times) * 1000:.1f} ms (ran {facts.record.executed:,} blocks)"
        )
        resumed_within_bound(what, facts.record.executed)


# A one-line edit re-runs at most the stretch it is in and the next few, whatever the size of
# the program: more means the resumed run no longer meets the earlier one.
RESUME_BOUND = 4 * CHECKPOINT_EVERY


def resumed_within_bound(what: str, executed: int) -> None:
    """Stop the bench, loudly, when a resumed run re-ran far more blocks than it should."""
    if executed > RESUME_BOUND:
        sys.exit(
            f"FAILED: after {what} the resumed run re-ran {executed:,} blocks, over the "
            f"{RESUME_BOUND:,} an edit may cost: it did not meet the earlier run"
        )


def bench_threads() -> None:
    """The threading rules' share of an analysis: finding the threads and checking them."""
    from fanuc_macro.rules import (
        cycles,
        thread_cut,
        thread_lead,
        thread_passes,
        thread_taper,
        thread_tool,
        threading,
    )
    from fanuc_macro.rules.context import RuleContext

    checks = (threading, thread_passes, thread_tool, thread_lead, thread_cut, thread_taper, cycles)
    for name, text in (
        ("seed O4009/O3331", (ROOT / "tests/fixtures/seeds/o4009_external_m50x3.nc").read_text()),
        ("20,000 generated blocks", generate(20000)),
    ):
        doc = parse_text(text, name)
        index = build_index(doc)
        facts = evaluate([(name, doc, index)])

        def rules(doc: Document = doc, index: ProgramIndex = index, facts: Facts = facts) -> int:
            ctx = RuleContext(doc, index, facts=facts)
            return sum(len(list(module.check(ctx))) for module in checks)

        t = best_of(rules, 5)
        threads = len(RuleContext(doc, index, facts=facts).threads())
        print(
            f"threading rules: {name}: {t * 1000:.1f} ms ({threads} threads, "
            f"{len(facts.motions)} motions)"
        )


def generate_macro_dense(blocks: int, seed: int = 2) -> str:
    """A program of macro statements only: a loop every eight blocks, a GOTO in every loop
    (out of it, to the label after it) and a label before it: thousands of loops, labels and
    jumps in one program, the load of the rules that relate jumps to loops and labels."""
    rnd = random.Random(seed)
    out = ["%", "O2000 (MACRO-DENSE BENCHMARK PROGRAM)"]
    out += [f"#{v}=0" for v in range(1, 34)]
    label = 1
    while len(out) < blocks + 2:
        v = rnd.randint(1, 33)
        out += [
            f"N{label} #{v}=#{v}+{rnd.random():.4f}",
            f"WHILE[#{v}LT{rnd.randint(1, 3)}]DO1",
            f"#{100 + v}=#{v}*{rnd.uniform(0, 5):.3f}",
            f"IF[#{100 + v}GT{rnd.uniform(5, 9):.2f}]GOTO{label + 1}",
            f"#{v}=#{v}+1.",
            "END1",
            f"IF[#{v}LT0]GOTO{label}",
            f"N{label + 1} #{rnd.randint(1, 33)}=#{v}",
        ]
        label += 2
    out += ["M30", "%"]
    return "\n".join(out) + "\n"


def bench_big_rules(size: int) -> None:
    """The jumps rule and all the rules on a program dense in loops, labels and jumps."""
    from fanuc_macro.analysis import run_checks
    from fanuc_macro.rules import ALL_CHECKS, jumps
    from fanuc_macro.rules.context import RuleContext

    text = generate_macro_dense(size)
    doc = parse_text(text, "dense")
    index = build_index(doc)
    facts = evaluate([("dense", doc, index)])
    program = index.programs[0]

    def jumps_rule() -> int:
        return len(list(jumps.check(RuleContext(doc, index, facts=facts))))

    def all_rules() -> int:
        return len(run_checks(RuleContext(doc, index, facts=facts), ALL_CHECKS))

    # The first run of each: what an analysis after an edit pays (a new index, new caches).
    print(
        f"macro-dense {size:,} blocks ({len(program.loops):,} loops, {len(program.jumps):,} "
        f"GOTOs, {len(program.labels):,} labels): jumps rule {best_of(jumps_rule, 3) * 1000:.0f}"
        f" ms, whole rules {best_of(all_rules, 2) * 1000:.0f} ms"
    )


def bench_big_document(size: int) -> None:
    """The rules run again on a document of more distinct lines than the per-line caches hold
    (400,000), as after a keystroke in a comment: the evaluator's facts are kept."""
    from fanuc_macro.analysis import run_checks
    from fanuc_macro.rules import ALL_CHECKS
    from fanuc_macro.rules.context import RuleContext

    doc = parse_text(generate(size), "big", BlockParser(cache_size=2 * size))
    index = build_index(doc)
    facts = evaluate([("big", doc, index)])
    for run in range(3):
        t = time.perf_counter()
        run_checks(RuleContext(doc, index, facts=facts), ALL_CHECKS)
        dt = time.perf_counter() - t
        rss = ""
        for line in Path("/proc/self/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                rss = f", RSS {int(line.split()[1]) // 1024} MB"
        print(f"{size:,} blocks: rules, analysis {run + 1}: {dt:.2f} s{rss}")


def bench_keystrokes(name: str, text: str, edits: int = 6, kinds: tuple[str, ...] = ("",)) -> None:
    """A document opened in a workspace (read whole) and analysed, then a digit typed and
    removed again, ``edits`` times, each analysed as the language server does: the figures
    without the protocol (``bench_lsp.py`` has those). ``kinds`` of edit besides the first (a
    factor of an assignment, or a coordinate of CAM output): ``motion``, a digit of a computed
    X that a thread pass starts from; ``bracket``, that X's closing bracket removed and typed
    again (the block does not read in between)."""
    import dataclasses

    from fanuc_macro.config import Config
    from fanuc_macro.workspace import Workspace

    config = dataclasses.replace(Config(), max_blocks=10**7, max_file_size=10**10)
    workspace = Workspace(config)
    uri = f"file:///{name}.nc"
    t = time.perf_counter()
    workspace.add_text(uri, text)
    workspace.analyse(uri)
    cold = time.perf_counter() - t
    lines = text.split("\n")
    for kind in kinds:
        at = len(lines) // 2
        # A factor of an assignment (a macro program) or a coordinate (CAM output): the edit
        # keeps the block valid, as most keystrokes in a long program do.
        mark = "*" if any("*" in line for line in lines[at:]) else "X"
        if kind:
            mark = "X[#100+"
        while mark not in lines[at]:
            at += 1
        original = lines[at]
        if kind == "bracket":
            changed = original.replace("]", "", 1)
        elif kind == "motion":
            digit = original.index(mark) + len(mark)
            changed = (
                original[:digit] + str((int(original[digit]) + 1) % 10) + original[digit + 1 :]
            )
        else:
            changed = original.replace(mark, mark + "1", 1)
        times: list[float] = []
        cpu: list[float] = []
        for i in range(edits):
            lines[at] = changed if i % 2 == 0 else original
            edited = "\n".join(lines)
            t, c = time.perf_counter(), time.process_time()
            workspace.add_text(uri, edited)
            workspace.analyse(uri)
            times.append(time.perf_counter() - t)
            cpu.append(time.process_time() - c)
        lines[at] = original
        what = {"": "", "motion": ", a thread's start X", "bracket": ", a bracket typed"}[kind]
        print(
            f"{name}{what}: open -> diagnostics {cold:.2f} s; keystroke -> diagnostics min "
            f"{min(times) * 1000:.0f} ms, median {statistics.median(times) * 1000:.0f} ms "
            f"(CPU min {min(cpu) * 1000:.0f} ms, median {statistics.median(cpu) * 1000:.0f} ms; "
            f"{edits} edits)"
        )


def bench_big_keystrokes(quick: bool) -> None:
    from bench_lsp import cam_program, program

    sizes = (20_000,) if quick else (20_000, 100_000)
    for size in sizes:
        kinds = ("", "motion", "bracket") if size == 20_000 else ("",)
        bench_keystrokes(f"macro program {size:,} blocks", program(size), kinds=kinds)
    bench_keystrokes(f"macro-dense {sizes[-1]:,} blocks", generate_macro_dense(sizes[-1]))
    cam = 20_000 if quick else 200_000
    bench_keystrokes(f"CAM output {cam:,} blocks", cam_program(cam))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--memory-child", type=int, help=argparse.SUPPRESS)
    ap.add_argument(
        "--big-document",
        type=int,
        metavar="BLOCKS",
        help="only the rules on a document this big, three times (500000: minutes)",
    )
    ap.add_argument(
        "--keystrokes",
        "--keystrokes-only",
        action="store_true",
        help="only the last section: keystrokes in big programs, opened in a workspace",
    )
    args = ap.parse_args()
    if args.keystrokes:
        bench_big_keystrokes(args.quick)
        return
    if args.memory_child:
        memory_child(args.memory_child)
        return
    if args.big_document:
        bench_big_document(args.big_document)
        return
    print(
        f"machine: {platform.processor() or platform.machine()}, {platform.python_version()}, "
        f"{resource.getpagesize()} B pages"
    )
    sizes = [1000, 5000] if args.quick else [1000, 20000, 100000]
    bench_parse(sizes)
    bench_memory(sizes[-1])
    bench_eval()
    bench_resume(20000)
    bench_threads()
    bench_big_rules(20000 if args.quick else 100000)
    bench_big_keystrokes(args.quick)


if __name__ == "__main__":
    main()
