"""Running benchmark families: repetitions, pairs interleaved, medians, a progress bar.

A :class:`Family` is a set of trials measured together (Skydeck and its reference) and a
``summarise`` that turns every trial's readings into result rows. Each repetition runs all
trials of the family once, alternating the order (A B C, then C B A, ...) so that neither
side always runs first, on a warmer or a colder machine. One family failing (a worker that
never gets ready, say) turns its rows into errors; the others still run.
"""

from __future__ import annotations

import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, TextIO

from benchmarks.processes import BenchError
from benchmarks.report import Result

__all__ = ["Family", "Progress", "Trial", "median_of", "run_families"]

Readings = dict[str, list[dict[str, Any]]]


@dataclass
class Trial:
    """One measurement run once per repetition; ``run`` returns its readings."""

    key: str
    label: str
    run: Callable[[], dict[str, Any]]


@dataclass
class Family:
    """Trials measured together and the rows made from them."""

    name: str
    trials: list[Trial]
    repetitions: int
    summarise: Callable[[Readings], list[Result]]
    rows: tuple[str, ...] = ()  # the result names this family produces (for --only)
    close: Callable[[], None] = field(default=lambda: None)


def median_of(readings: list[dict[str, Any]], key: str) -> float:
    """The median over repetitions of one reading."""
    return statistics.median(reading[key] for reading in readings)


class Progress:
    """A text progress bar on stderr (a line per step when stderr is not a terminal)."""

    def __init__(self, total: int, stream: TextIO = sys.stderr, width: int = 28) -> None:
        self.total = max(total, 1)
        self.done = 0
        self.stream = stream
        self.width = width
        self.started = time.monotonic()
        self.tty = stream.isatty()

    def show(self, label: str) -> None:
        elapsed = time.monotonic() - self.started
        filled = round(self.width * self.done / self.total)
        bar = "#" * filled + "." * (self.width - filled)
        text = f"[{bar}] {self.done:>3}/{self.total} {elapsed:5.0f}s  {label}"
        if self.tty:
            self.stream.write("\r\x1b[2K" + text[:118])
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def step(self) -> None:
        self.done += 1

    def finish(self) -> None:
        self.done = self.total
        self.show("done")
        if self.tty:
            self.stream.write("\n")
        self.stream.flush()


def run_families(families: list[Family], progress: Progress | None = None) -> list[Result]:
    """Run every family and return all rows, in family order."""
    progress = progress or Progress(sum(len(f.trials) * f.repetitions for f in families))
    results: list[Result] = []
    for family in families:
        readings: Readings = {trial.key: [] for trial in family.trials}
        family_end = progress.done + len(family.trials) * family.repetitions
        try:
            for repetition in range(family.repetitions):
                order = family.trials if repetition % 2 == 0 else list(reversed(family.trials))
                for trial in order:
                    progress.show(f"{family.name}: {trial.label} ({repetition + 1}/{family.repetitions})")
                    readings[trial.key].append(trial.run())
                    progress.step()
            results.extend(family.summarise(readings))
        except (BenchError, OSError, ValueError, KeyError) as error:
            message = f"{type(error).__name__}: {error}" if not isinstance(error, BenchError) else str(error)
            results.extend(
                Result(name=name, value=None, unit="", error=message.splitlines()[0]) for name in family.rows
            )
            sys.stderr.write(f"\n{family.name} failed: {message}\n")
            progress.done = family_end
        finally:
            family.close()
    progress.finish()
    return results
