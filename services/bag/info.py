"""``bag info``'s text, laid out as ``ros2 bag info`` lays it out, with each topic's rate."""

from __future__ import annotations

import time

from services.bag.reader import BagSummary

__all__ = ["format_info", "format_size"]

_LABEL = 19  # width of "Topic information: "


def format_size(size_bytes: float) -> str:
    """``1.2 MiB``: bytes in binary units, as ros2 bag info prints them."""
    for unit in ("B", "KiB", "MiB", "GiB"):
        if size_bytes < 1024 or unit == "GiB":
            return f"{size_bytes:.0f} {unit}" if unit == "B" else f"{size_bytes:.1f} {unit}"
        size_bytes /= 1024
    raise AssertionError("unreachable")


def _stamp(ns: int) -> str:
    seconds, rest = divmod(ns, 1_000_000_000)
    return f"{time.strftime('%b %d %Y %H:%M:%S', time.localtime(seconds))}.{rest:09d} ({seconds}.{rest:09d})"


def format_info(summary: BagSummary) -> str:
    """The lines of ``skydeck bag info FILE``."""
    lines = [
        ("Files:", summary.path.name),
        ("Bag size:", format_size(summary.size_bytes)),
        ("Storage id:", "mcap"),
        ("Duration:", f"{summary.duration_s:.9f}s"),
        ("Start:", _stamp(summary.start_ns)),
        ("End:", _stamp(summary.end_ns)),
        ("Messages:", str(summary.message_count)),
    ]
    if summary.recovered:
        lines.append(("Recovered:", f"not finished: read up to its last complete chunk ({summary.ignored_bytes} bytes after it left out)"))
    info = summary.metadata.get("skydeck", {})
    for key, label in (("skydeck_version", "Skydeck:"), ("world_seed", "World seed:"), ("command_line", "Command line:")):
        if info.get(key):
            lines.append((label, info[key]))
    text = [f"{label:<{_LABEL}}{value}" for label, value in lines]
    duration = summary.duration_s
    for index, topic in enumerate(summary.topics):
        rate = f"{topic.count / duration:.2f} Hz" if duration > 0 else "-"
        row = (
            f"Topic: {topic.topic} | Type: {topic.type_name} | Count: {topic.count} | Rate: {rate} | "
            f"Serialization Format: {topic.encoding}"
        )
        text.append(f"{'Topic information:' if index == 0 else '':<{_LABEL}}{row}")
    if not summary.topics:
        text.append(f"{'Topic information:':<{_LABEL}}none")
    return "\n".join(text)
