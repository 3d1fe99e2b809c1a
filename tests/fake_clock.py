"""A monotonic clock a test moves by hand, for code that reads a module's ``_monotonic``
(``monkeypatch.setattr(module, "_monotonic", clock)``): no timing is asserted, no sleep taken."""

from __future__ import annotations


class FakeClock:
    """Seconds that pass only when the test adds to ``now``."""

    def __init__(self, now: float = 100.0) -> None:
        self.now = now

    def __call__(self) -> float:
        return self.now
