"""A command run in the background by the tests and the benchmark, watched line by line.

    process = BackgroundProcess([sys.executable, "-m", "services.cli", "launch"], name="launch")
    process.wait_for_line("[launch] all", timeout_s=60)
    process.stop()                      # SIGINT to its group, SIGKILL if it lingers

The one harness for starting Skydeck processes outside the launcher: the end-to-end, browser and
reliability tests and the benchmark's workers all use it. The process runs in its own process
group, so stopping it stops whatever it started; its output is kept as lines (standard error
merged, or written to a log file when standard output carries a protocol, as the benchmark's
workers' does), and every failure says what the process printed last.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import subprocess
import threading
import time
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from services.launch.child_process import signal_group
from services.runtime.http_client import HttpError, request_once
from shared_models.errors import SkydeckError

__all__ = ["BackgroundProcess", "ProcessFailed"]

_POLL_S = 0.05


class ProcessFailed(SkydeckError):
    """A background process exited, or did not say or serve what was awaited in time."""


class BackgroundProcess:
    """One command in its own process group, its output lines kept (see the module docstring).

    ``log_path``: standard error goes there instead of into ``lines``. ``stdin``: keep a pipe
    for :meth:`send`.
    """

    def __init__(
        self,
        argv: Sequence[str],
        *,
        name: str,
        env: Mapping[str, str] | None = None,
        cwd: str | Path | None = None,
        log_path: Path | None = None,
        stdin: bool = False,
    ) -> None:
        self.name = name
        self.argv = [str(part) for part in argv]
        self.lines: list[str] = []
        self.log_path = log_path
        self._log = log_path.open("w") if log_path is not None else None
        self._changed = threading.Condition()
        self._ended = False
        self.popen = subprocess.Popen(
            self.argv,
            cwd=cwd,
            env=dict(env) if env is not None else None,
            stdin=subprocess.PIPE if stdin else subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=self._log if self._log is not None else subprocess.STDOUT,
            text=True,
            errors="replace",
            start_new_session=True,  # its own group: stopped as a whole, deaf to the test's Ctrl-C
        )
        self._reader = threading.Thread(target=self._read, name=f"output of {name}", daemon=True)
        self._reader.start()

    # -- state --------------------------------------------------------------------------------

    @property
    def pid(self) -> int:
        return self.popen.pid

    @property
    def returncode(self) -> int | None:
        return self.popen.poll()

    def tail(self, count: int = 30) -> str:
        """The last ``count`` lines it printed (and logged), for failure messages."""
        lines = list(self.lines)
        if self.log_path is not None:
            if self._log is not None:
                self._log.flush()
            with contextlib.suppress(OSError):
                lines += self.log_path.read_text(errors="replace").splitlines()
        return "\n".join(lines[-count:]) or "(no output)"

    def cpu_seconds(self) -> float:
        """User + system CPU time of the process so far (Linux /proc)."""
        with open(f"/proc/{self.pid}/stat") as stat:
            fields = stat.read().rpartition(")")[2].split()
        # Fields after the command: state is [0], utime [11], stime [12] (clock ticks).
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")

    # -- waiting ------------------------------------------------------------------------------

    def wait_for_line(
        self, match: str | Callable[[str], bool], timeout_s: float, *, after: int = 0
    ) -> int:
        """The index of the first line from ``after`` on that contains ``match`` (or satisfies it)."""
        wanted = (lambda line: match in line) if isinstance(match, str) else match
        deadline = time.monotonic() + timeout_s
        with self._changed:
            start = after
            while True:
                for index in range(start, len(self.lines)):
                    if wanted(self.lines[index]):
                        return index
                start = len(self.lines)
                if self._ended:
                    raise self._failure(f"exited ({self.popen.wait()}) before printing {match!r}")
                left = deadline - time.monotonic()
                if left <= 0:
                    raise self._failure(f"did not print {match!r} within {timeout_s:g} s")
                self._changed.wait(left)

    async def await_line(
        self, match: str | Callable[[str], bool], timeout_s: float, *, after: int = 0
    ) -> int:
        """:meth:`wait_for_line` for a coroutine (waits in a thread, the loop runs on)."""
        return await asyncio.to_thread(self.wait_for_line, match, timeout_s, after=after)

    def wait_healthy(self, url: str, timeout_s: float) -> None:
        """Poll ``url`` (its ``/health``) until it answers 200."""
        deadline = time.monotonic() + timeout_s
        while True:
            if self.returncode is not None:
                raise self._failure(f"exited ({self.returncode}) before {url} answered")
            with contextlib.suppress(HttpError):
                if request_once("GET", url, timeout_s=1.0).status == 200:
                    return
            if time.monotonic() > deadline:
                raise self._failure(f"{url} did not answer within {timeout_s:g} s")
            time.sleep(_POLL_S)

    # -- talking and stopping -----------------------------------------------------------------

    def send(self, line: str) -> None:
        """Write one line to its standard input (if it still reads it)."""
        stdin = self.popen.stdin
        if stdin is None or stdin.closed:
            return
        with contextlib.suppress(BrokenPipeError, OSError):
            stdin.write(line + "\n")
            stdin.flush()

    def stop(self, sig: signal.Signals = signal.SIGINT, timeout_s: float = 10.0) -> bool:
        """Signal its group and wait; SIGKILL the group if it has not exited by ``timeout_s``.

        Returns whether it stopped by itself (False: it had to be killed). Idempotent.
        """
        stopped_by_itself = True
        if self.popen.poll() is None:
            signal_group(self.pid, sig)
            try:
                self.popen.wait(timeout_s)
            except subprocess.TimeoutExpired:
                stopped_by_itself = False
                signal_group(self.pid, signal.SIGKILL)
                self.popen.wait()
        signal_group(self.pid, signal.SIGKILL)  # whatever it started and left behind
        self._reader.join(5)
        for stream in (self.popen.stdin, self.popen.stdout, self._log):
            with contextlib.suppress(OSError):
                if stream is not None:
                    stream.close()
        return stopped_by_itself

    # -- internals ----------------------------------------------------------------------------

    def _read(self) -> None:
        stdout = self.popen.stdout
        if stdout is not None:
            with contextlib.suppress(ValueError, OSError):  # closed by stop()
                for raw in stdout:
                    with self._changed:
                        self.lines.append(raw.rstrip("\n"))
                        self._changed.notify_all()
        with self._changed:
            self._ended = True
            self._changed.notify_all()

    def _failure(self, what: str) -> ProcessFailed:
        return ProcessFailed(f"{self.name} {what}; it printed:\n{self.tail()}")
