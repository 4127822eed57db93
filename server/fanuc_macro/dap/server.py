"""``fanuc-macro-dap``: a debug adapter for FANUC Macro B programs, speaking the Debug Adapter
Protocol over stdio. It converts requests to the session of :mod:`fanuc_macro.debugger`
and the session's stops, output and end to events; it holds no debugging logic of its own.

One thread reads requests; the run goes in the session's thread, whose events are written as
they come. A request that cannot be done, or is malformed, gets an error response that says
why; a message that cannot be read is reported on stderr and in an output event and skipped,
and reading goes on at the next header: the adapter stays up until the client disconnects or
the stream ends.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path
from typing import IO, Any

from .. import __version__
from ..config import Config
from ..debugger import (
    EXCEPTION_FILTERS,
    Breakpoint,
    DebugError,
    Ended,
    Listener,
    Output,
    Session,
    Stop,
    read_launch,
)
from ..framing import Reader, WireError
from ..translation import locale_of, render
from .wire import Writer

THREAD_ID = 1  # the control runs one path: one thread


class Adapter(Listener):
    def __init__(self, reader: Reader, writer: Writer) -> None:
        self.reader = reader
        self.writer = writer
        self.session: Session | None = None
        self.lines_start_at_1 = True
        self.columns_start_at_1 = True
        # The language of what the adapter says: the client's (DAP initialize "locale").
        self.locale = "en"
        # Breakpoints and filters sent before the launch are kept for it.
        self._early_breakpoints: dict[str, list[tuple[int, str, str, str]]] = {}
        self._early_filters: list[str] | None = None
        self._last_stop: Stop | None = None
        self._terminated = False
        self._done = False
        self._handlers: dict[str, Callable[[dict[str, Any]], dict[str, Any] | None]] = {
            "initialize": self.initialize,
            "launch": self.launch,
            "attach": self.attach,
            "setBreakpoints": self.set_breakpoints,
            "setExceptionBreakpoints": self.set_exception_breakpoints,
            "configurationDone": self.configuration_done,
            "threads": self.threads,
            "stackTrace": self.stack_trace,
            "scopes": self.scopes,
            "variables": self.variables,
            "setVariable": self.set_variable,
            "evaluate": self.evaluate,
            "continue": self.continue_,
            "next": self.next,
            "stepIn": self.step_in,
            "stepOut": self.step_out,
            "pause": self.pause,
            "restart": self.restart,
            "terminate": self.terminate,
            "disconnect": self.disconnect,
            "exceptionInfo": self.exception_info,
        }
        self._after: Callable[[], None] | None = None  # what a response is followed by

    # ---- the loop --------------------------------------------------------------------------
    def serve(self) -> int:
        while not self._done:
            try:
                message = self.reader.read()
            except WireError as err:
                # Said to the client too: a request lost here would otherwise wait for ever.
                text = f"fanuc-macro-dap: a message could not be read: {err}"
                sys.stderr.write(text + "\n")
                self.event("output", {"category": "stderr", "output": text + "\n"})
                continue
            if message is None:
                break
            kind = message.get("type")
            if kind == "request":
                self._handle(message)
            elif kind not in ("response", "event"):
                # Not a message the protocol knows: answered, so that no sender waits.
                self.writer.send(
                    {
                        "type": "response",
                        "request_seq": _seq_of(message),
                        "command": str(message.get("command", "")),
                        "success": False,
                        "message": f"a message whose type is {kind!r}, not 'request'",
                    }
                )
        if self.session is not None:
            self.session.terminate()
        return 0

    def _handle(self, request: dict[str, Any]) -> None:
        raw = request.get("command", "")
        command = raw if isinstance(raw, str) else ""
        handler = self._handlers.get(command)
        self._after = None
        base = {"type": "response", "request_seq": _seq_of(request), "command": command}
        wrong = _malformed(request)
        if wrong is not None:
            self.writer.send({**base, "success": False, "message": wrong})
            return
        if handler is None:
            self.writer.send({**base, "success": False, "message": f"{command} is not supported"})
            return
        args = request.get("arguments")
        try:
            body = handler(args if isinstance(args, dict) else {})
        except DebugError as err:
            self.writer.send(
                {
                    **base,
                    "success": False,
                    "message": str(err),
                    "body": {
                        "error": {"id": 1, "format": str(err), "showUser": command == "launch"}
                    },
                }
            )
            return
        except Exception as err:  # a fault here must not end the session: say it
            text = f"internal error in {command}: {err!r}"
            sys.stderr.write(f"fanuc-macro-dap: {text}\n")
            self.writer.send({**base, "success": False, "message": text})
            return
        response: dict[str, Any] = {**base, "success": True}
        if body is not None:
            response["body"] = body
        self.writer.send(response)
        after, self._after = self._after, None
        if after is not None:
            after()

    def event(self, name: str, body: dict[str, Any] | None = None) -> None:
        message: dict[str, Any] = {"type": "event", "event": name}
        if body is not None:
            message["body"] = body
        self.writer.send(message)

    def _said(self, text: str) -> str:
        """A text of the debugger in the client's language (numbers and program text as they
        are)."""
        return render(text, self.locale)

    def _session(self) -> Session:
        if self.session is None:
            raise DebugError("no program is launched")
        return self.session

    # ---- lines, as the client counts them -------------------------------------------------
    def _line_in(self, line: int) -> int:
        return line - 1 if self.lines_start_at_1 else line

    def _line_out(self, line: int) -> int:
        return line + 1 if self.lines_start_at_1 else line

    def _column_out(self, column: int) -> int:
        return column + 1 if self.columns_start_at_1 else column

    @staticmethod
    def _source(key: str) -> dict[str, Any]:
        return {"name": Path(key).name, "path": key}

    # ---- requests --------------------------------------------------------------------------
    def initialize(self, args: dict[str, Any]) -> dict[str, Any]:
        self.lines_start_at_1 = args.get("linesStartAt1", True) is not False
        self.columns_start_at_1 = args.get("columnsStartAt1", True) is not False
        given = args.get("locale")
        self.locale = locale_of(given if isinstance(given, str) else None)
        return {
            "supportsConfigurationDoneRequest": True,
            "supportsConditionalBreakpoints": True,
            "supportsHitConditionalBreakpoints": True,
            "supportsLogPoints": True,
            "supportsEvaluateForHovers": True,
            "supportsSetVariable": True,
            "supportsRestartRequest": True,
            "supportsTerminateRequest": True,
            "supportsExceptionInfoRequest": True,
            "exceptionBreakpointFilters": [
                {"filter": name, "label": self._said(label), "default": on}
                for name, label, on in EXCEPTION_FILTERS
            ],
        }

    def launch(self, args: dict[str, Any]) -> None:
        if self.session is not None:
            raise DebugError("a program is launched already")
        launch = read_launch(args, _file_config(args.get("program")))
        self.session = session = Session(launch, self)
        for key, asked in self._early_breakpoints.items():
            session.set_breakpoints(key, asked)
        if self._early_filters is not None:
            session.set_exception_filters(self._early_filters)
        self._after = lambda: self.event("initialized")
        return None

    def attach(self, args: dict[str, Any]) -> None:
        raise DebugError(
            "attach is not supported: the debugger runs the program itself (use launch)"
        )

    def set_breakpoints(self, args: dict[str, Any]) -> dict[str, Any]:
        source = args.get("source") or {}
        path = source.get("path")
        if not isinstance(path, str):
            raise DebugError("setBreakpoints: the source has no path")
        asked: list[tuple[int, str, str, str]] = []
        for bp in args.get("breakpoints") or []:
            asked.append(
                (
                    self._line_in(int(bp.get("line", 1))),
                    str(bp.get("condition") or ""),
                    str(bp.get("hitCondition") or ""),
                    str(bp.get("logMessage") or ""),
                )
            )
        if self.session is None:
            self._early_breakpoints[path] = asked
            return {
                "breakpoints": [
                    {"verified": False, "line": self._line_out(line), "message": "not yet launched"}
                    for line, *_ in asked
                ]
            }
        made = self.session.set_breakpoints(path, asked)
        return {"breakpoints": [self._breakpoint(bp) for bp in made]}

    def _breakpoint(self, bp: Breakpoint) -> dict[str, Any]:
        item: dict[str, Any] = {
            "id": bp.id,
            "verified": bp.verified,
            "source": self._source(bp.key),
            "line": self._line_out(bp.actual_line if bp.actual_line is not None else bp.line),
        }
        if bp.message:
            item["message"] = bp.message
        return item

    def set_exception_breakpoints(self, args: dict[str, Any]) -> dict[str, Any]:
        filters = [str(f) for f in args.get("filters") or []]
        if self.session is None:
            self._early_filters = filters
        else:
            self.session.set_exception_filters(filters)
        return {"breakpoints": [{"verified": True} for _ in filters]}

    def configuration_done(self, args: dict[str, Any]) -> None:
        session = self._session()
        self._after = session.start
        return None

    def threads(self, args: dict[str, Any]) -> dict[str, Any]:
        name = self.session.entry_name if self.session is not None else "program"
        return {"threads": [{"id": THREAD_ID, "name": f"{name} run"}]}

    def stack_trace(self, args: dict[str, Any]) -> dict[str, Any]:
        frames = self._session().frames()
        start = int(args.get("startFrame") or 0)
        levels = int(args.get("levels") or 0)
        shown = frames[start : start + levels] if levels > 0 else frames[start:]
        return {
            "stackFrames": [
                {
                    "id": f.id,
                    "name": f.name,
                    "source": self._source(f.key),
                    "line": self._line_out(f.line),
                    "column": self._column_out(f.column),
                }
                for f in shown
            ],
            "totalFrames": len(frames),
        }

    def scopes(self, args: dict[str, Any]) -> dict[str, Any]:
        scopes = self._session().scopes(int(args.get("frameId", 1)))
        return {
            "scopes": [
                {
                    "name": self._said(s.name),
                    "variablesReference": s.reference,
                    "namedVariables": s.count,
                    "expensive": s.expensive,
                    **({"presentationHint": "locals"} if s.reference % 10 == 1 else {}),
                }
                for s in scopes
            ]
        }

    def variables(self, args: dict[str, Any]) -> dict[str, Any]:
        found = self._session().variables(int(args.get("variablesReference", 0)))
        out = []
        for v in found:
            item: dict[str, Any] = {
                "name": self._said(v.name),
                "value": self._said(v.value),
                "variablesReference": 0,
            }
            if v.evaluate_name:
                item["evaluateName"] = v.evaluate_name
            if v.read_only:
                item["presentationHint"] = {"attributes": ["readOnly"]}
            out.append(item)
        return {"variables": out}

    def set_variable(self, args: dict[str, Any]) -> dict[str, Any]:
        value = self._session().set_variable_at(
            int(args.get("variablesReference", 0)),
            str(args.get("name", "")),
            str(args.get("value", "")),
        )
        return {"value": value}

    def evaluate(self, args: dict[str, Any]) -> dict[str, Any]:
        frame = args.get("frameId")
        result = self._session().evaluate(
            str(args.get("expression", "")), int(frame) if frame is not None else None
        )
        return {"result": result, "variablesReference": 0}

    def continue_(self, args: dict[str, Any]) -> dict[str, Any]:
        session = self._session()
        self._check_stopped(session)
        self._after = session.continue_
        return {"allThreadsContinued": True}

    def next(self, args: dict[str, Any]) -> None:
        session = self._session()
        self._check_stopped(session)
        self._after = session.step_over
        return None

    def step_in(self, args: dict[str, Any]) -> None:
        session = self._session()
        self._check_stopped(session)
        self._after = session.step_in
        return None

    def step_out(self, args: dict[str, Any]) -> None:
        session = self._session()
        self._check_stopped(session)
        self._after = session.step_out
        return None

    @staticmethod
    def _check_stopped(session: Session) -> None:
        if not session.stopped:
            raise DebugError("the program is not stopped")

    def pause(self, args: dict[str, Any]) -> None:
        self._after = self._session().pause
        return None

    def restart(self, args: dict[str, Any]) -> None:
        self._after = self._session().restart
        return None

    def terminate(self, args: dict[str, Any]) -> None:
        session = self.session
        if session is not None and session.started:
            self._after = session.terminate  # the run's end says it
        else:
            if session is not None:
                session.terminate()
            self._after = self._say_terminated
        return None

    def disconnect(self, args: dict[str, Any]) -> None:
        session = self.session
        if session is not None:
            session.terminate()
            session.join(5.0)
        self._done = True
        return None

    def exception_info(self, args: dict[str, Any]) -> dict[str, Any]:
        stop = self._last_stop
        if stop is None or stop.reason != "exception":
            raise DebugError("the program did not stop on an alarm or a message")
        return {
            "exceptionId": stop.exception,
            "description": self._said(stop.text),
            "breakMode": "always",
        }

    # ---- the session's news (from the run thread) --------------------------------------------
    def stopped(self, stop: Stop) -> None:
        self._last_stop = stop
        body: dict[str, Any] = {
            "reason": stop.reason,
            "description": self._said(stop.description),
            "threadId": THREAD_ID,
            "allThreadsStopped": True,
        }
        if stop.text:
            body["text"] = self._said(stop.text)
        if stop.breakpoints:
            body["hitBreakpointIds"] = list(stop.breakpoints)
        self.event("stopped", body)

    def output(self, output: Output) -> None:
        body: dict[str, Any] = {
            "category": output.category,
            "output": self._said(output.text) + "\n",
        }
        if output.key is not None:
            body["source"] = self._source(output.key)
            if output.line is not None:
                body["line"] = self._line_out(output.line)
        self.event("output", body)

    def ended(self, ended: Ended) -> None:
        self.event(
            "output",
            {
                "category": "console" if ended.normal else "stderr",
                "output": self._said(ended.message) + "\n",
            },
        )
        self.event("exited", {"exitCode": 0 if ended.normal else 1})
        self._say_terminated()

    def breakpoint_changed(self, breakpoint: Breakpoint) -> None:
        self.event("breakpoint", {"reason": "changed", "breakpoint": self._breakpoint(breakpoint)})

    def _say_terminated(self) -> None:
        if not self._terminated:
            self._terminated = True
            self.event("terminated")


def _seq_of(message: dict[str, Any]) -> int:
    seq = message.get("seq")
    return seq if isinstance(seq, int) and not isinstance(seq, bool) else 0


def _malformed(request: dict[str, Any]) -> str | None:
    """What makes a request unfit to handle, or None."""
    seq = request.get("seq")
    if not isinstance(seq, int) or isinstance(seq, bool):
        return "the request has no integer seq"
    command = request.get("command")
    if command is None:
        return "the request has no command"
    if not isinstance(command, str) or not command:
        return f"the request's command {command!r} is not a command name"
    args = request.get("arguments")
    if args is not None and not isinstance(args, dict):
        return f"the arguments of {command} are not an object"
    return None


def serve(stdin: IO[bytes], stdout: IO[bytes]) -> int:
    return Adapter(Reader(stdin), Writer(stdout)).serve()


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="fanuc-macro-dap",
        description="Debug adapter for FANUC Macro B programs (Debug Adapter Protocol over "
        "stdio): breakpoints, steps, the macro levels' variables, on the fanuc-macro evaluator.",
    )
    parser.add_argument("--version", action="version", version=f"fanuc-macro-dap {__version__}")
    parser.parse_args(argv)
    return serve(sys.stdin.buffer, sys.stdout.buffer)


def _file_config(program: object) -> Config:
    """The settings of the configuration file nearest the launched program (fanuc-macro.toml,
    as the command line and the language server read it); the launch's own values win."""
    from ..config_file import ConfigFileError, find_config_file, load_config_file

    if not isinstance(program, str) or not program.strip():
        return Config()  # read_launch says what is wrong with it
    path = Path(program).expanduser()
    try:
        found = find_config_file(path) if path.is_file() else None
        return Config.from_settings(load_config_file(found).settings if found else None)
    except ConfigFileError as error:
        raise DebugError(f"launch: {error}") from None
