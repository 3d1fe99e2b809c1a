"""A class's families (issue 35): what the fences cost a message."""

from __future__ import annotations

from benchmarks.report import Result
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.suite import Suite

__all__ = ["fences"]


def fences(suite: Suite) -> Family:
    """fence_check_per_message: a student's messages through a class's core against an open one."""
    from benchmarks.fences import measure_fences, spend_ns

    messages = suite.settings.fence_messages
    trials = [
        Trial(mode, f"{messages} messages through a core, {label}", lambda mode=mode: measure_fences(messages, mode))  # type: ignore[misc]
        for mode, label in (("open", "no class"), ("class", "a student's in a class"))
    ]

    def summarise(readings: Readings) -> list[Result]:
        fenced, open_ = median_of(readings["class"], "us_per_message"), median_of(readings["open"], "us_per_message")
        row = Result("fence_check_per_message", fenced, "us", "the same through a core with no class", open_,
                     target="<= 1.1x (decided per connection; per message only the rate count)",
                     samples=[r["us_per_message"] for r in readings["class"]],
                     detail={"what": "the core's CPU per message a student publishes through it (native socket)",
                             "rate_count_ns": round(spend_ns(), 1),
                             "reference_samples": [r["us_per_message"] for r in readings["open"]]})
        row.met = row.ratio is not None and row.ratio <= 1.1
        return [row]  # fmt: skip

    return Family("fences", trials, suite.settings.topic_repetitions, summarise, rows=("fence_check_per_message",))
