"""The plots of docs/performance.md (matplotlib, headless): latency distribution, throughput by
message size, real-time factor by box count. Each is written only when its data was gathered."""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["write_plots"]

_COLOURS = {"skydeck": "#1f77b4", "websockets": "#7f7f7f", "zenoh": "#2ca02c"}
_LABELS = {"skydeck": "Skydeck", "websockets": "bare websockets pair", "zenoh": "zenoh"}


def write_plots(data: dict[str, Any], directory: Path) -> list[Path]:
    """Write every plot whose data is in ``data`` into ``directory``; returns the files."""
    import matplotlib

    matplotlib.use("Agg")
    directory.mkdir(parents=True, exist_ok=True)
    written = []
    if "latency_samples_us" in data:
        written.append(_latency(data["latency_samples_us"], directory / "bench_latency.png"))
    if "throughput_by_size" in data:
        written.append(_throughput(data["throughput_by_size"], directory / "bench_throughput_size.png"))
    if "rtf_by_boxes" in data:
        written.append(_rtf(data["rtf_by_boxes"], directory / "bench_rtf_boxes.png"))
    if "rss" in data:
        written.append(_soak(data["rss"], directory / "bench_soak_rss.png"))
    return written


def _soak(samples: dict[str, list[tuple[float, float]]], path: Path) -> Path:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    for name, points in sorted(samples.items()):
        ax.plot([t / 60 for t, _ in points], [v for _, v in points], label=name)
    ax.set_xlabel("minutes")
    ax.set_ylabel("RSS (MiB)")
    ax.set_title("Soak: every process's memory under 50 viewers, a stalled reader, reconnects")
    return _save(fig, ax, path)


def _latency(samples: dict[str, list[float]], path: Path) -> Path:
    import matplotlib.pyplot as plt
    import numpy as np

    fig, ax = plt.subplots(figsize=(7, 4))
    for key, values in samples.items():
        if not values:
            continue
        ordered = np.sort(np.asarray(values))
        fraction = np.arange(1, len(ordered) + 1) / len(ordered)
        ax.plot(ordered, fraction, label=f"{_LABELS[key]} (p50 {np.median(ordered):.0f} us)", color=_COLOURS[key])
    ax.set_xscale("log")
    ax.set_xlabel("publish -> callback latency (us, log scale), 1,000 msg/s, separate processes")
    ax.set_ylabel("fraction of messages")
    ax.axhline(0.99, color="#cccccc", linewidth=0.8, linestyle="--")
    ax.set_title("Topic latency distribution (PoseStamped JSON)")
    return _save(fig, ax, path, legend_loc="lower right")


def _throughput(rates: dict[str, float], path: Path) -> Path:
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4))
    for transport in ("skydeck", "websockets", "zenoh"):
        points = sorted((int(key.split(":")[1]), rate) for key, rate in rates.items() if key.startswith(transport + ":"))
        if points:
            sizes, values = zip(*points, strict=True)
            ax.plot(sizes, values, marker="o", label=_LABELS[transport], color=_COLOURS[transport])
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("message size (bytes of JSON)")
    ax.set_ylabel("messages/s delivered")
    ax.set_title("Topic throughput by message size, one publisher -> one subscriber")
    return _save(fig, ax, path)


def _rtf(readings: dict[str, dict[str, float]], path: Path) -> Path:
    import matplotlib.pyplot as plt

    node = sorted((int(k.split(":")[1]), v["rtf_alone"]) for k, v in readings.items() if k.startswith("node:"))
    bare = sorted((int(k.split(":")[1]), v["bare_rtf"]) for k, v in readings.items() if k.startswith("bare:"))
    world = sorted((int(k.split(":")[1]), v["world_rtf"]) for k, v in readings.items() if k.startswith("bare:"))
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, points, colour in (
        ("bare stepSimulation loop", bare, _COLOURS["websockets"]),
        ("World (controller, no node)", world, "#ff7f0e"),
        ("simulator node, speed max", node, _COLOURS["skydeck"]),
    ):
        if points:
            boxes, values = zip(*points, strict=True)
            ax.plot(boxes, values, marker="o", label=label, color=colour)
    ax.axhline(20, color="#d62728", linewidth=0.8, linestyle="--", label="target: 20x real time")
    ax.set_xlabel("boxes in the world")
    ax.set_ylabel("real-time factor (sim s per wall s, log scale)")
    ax.set_yscale("log")
    ax.set_title("Simulator speed by box count")
    return _save(fig, ax, path)


def _save(fig: Any, ax: Any, path: Path, *, legend_loc: str = "best") -> Path:
    """The finish every plot shares: grid, legend, tight layout, PNG, figure closed."""
    import matplotlib.pyplot as plt

    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc=legend_loc)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
