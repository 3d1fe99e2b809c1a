"""A class's families (issue 35): thirty students' robots in one room, thirty dashboards and the
instructor's class page on one core, and what the fences cost a message."""

from __future__ import annotations

from benchmarks.report import Result
from benchmarks.runner import Family, Readings, Trial, median_of
from benchmarks.suite import Suite

__all__ = ["class_room", "fences"]


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


def class_room(suite: Suite) -> Family:
    """class_30_robots_rtf (and per CPU), class_30_robots_delivery, class_30_dashboards_delivery."""
    from benchmarks.classroom import measure_class

    s = suite.settings
    students = s.class_students
    window = s.class_window_s
    trials = [
        Trial("world_max", f"{students} robots, every scan, odometry and bumper read, speed max",
              lambda: measure_class("world_max", students=students, window_s=window)),
        Trial("world", "the same at real time", lambda: measure_class("world", students=students, window_s=window)),
        Trial("dashboards", f"{students} dashboards and the class page, real time",
              lambda: measure_class("dashboards", students=students, window_s=window)),
    ]  # fmt: skip

    def summarise(readings: Readings) -> list[Result]:
        fast, paced, seen = readings["world_max"], readings["world"], readings["dashboards"]
        rtf = Result(f"class_{students}_robots_rtf", median_of(fast, "rtf"), "x real time",
                     target=">= 1x on 2 cores (speed max, every robot's topics read)",
                     samples=[r["rtf"] for r in fast],
                     detail={"world_cpu": median_of(fast, "sim_cpu"), "what": "sim s per wall s"})
        rtf.met = (rtf.value or 0) >= 1.0
        per_cpu = Result(f"class_{students}_robots_rtf_per_cpu", median_of(fast, "rtf_per_cpu"), "x CPU time",
                         target=">= 1x (the world keeps real time on a core of its own: the figure load changes least)",
                         samples=[r["rtf_per_cpu"] for r in fast])
        per_cpu.met = (per_cpu.value or 0) >= 1.0
        delivery = Result(f"class_{students}_robots_delivery", median_of(paced, "min_delivery"), "of the stated rates",
                          target=">= 0.95 (scan 5 Hz, odom and bump 30 Hz of sim time, every robot)",
                          samples=[r["min_delivery"] for r in paced],
                          detail={"rtf": median_of(paced, "rtf"), "world_cpu": median_of(paced, "sim_cpu"),
                                  "by_topic": paced[-1]["delivery"]})
        delivery.met = (delivery.value or 0) >= 0.95
        views = Result(f"class_{students}_dashboards_delivery", median_of(seen, "min_delivery"), "of the rates asked",
                       target=">= 0.95 (odom 20, scan 5, bump 10 Hz per dashboard, the class view 10 Hz; or what the world's pace gave)",
                       samples=[r["min_delivery"] for r in seen],
                       detail={"class_view_delivery": median_of(seen, "class_view_delivery"),
                               "class_page_p50_ms": median_of(seen, "class_page_p50_ms"),
                               "core_cpu": median_of(seen, "core_cpu"), "rtf": median_of(seen, "rtf"),
                               "by_topic": seen[-1]["delivery"], "refused": seen[-1]["closed"]})
        views.met = (views.value or 0) >= 0.95 and median_of(seen, "class_view_delivery") >= 0.95
        return [rtf, per_cpu, delivery, views]  # fmt: skip

    return Family("class", trials, s.class_repetitions, summarise,
                  rows=(f"class_{students}_robots_rtf", f"class_{students}_robots_rtf_per_cpu", f"class_{students}_robots_delivery",
                        f"class_{students}_dashboards_delivery"))  # fmt: skip
