"""Lockstep runs: the world steps only when every process of the run has done what the last step
asked of it, so that the same programs and the same seed give the same run, however fast or
loaded the machine (``skydeck grade``).

    coordinator (services.grading)          each process of the run (SKYDECK_LOCKSTEP_URL)
      step: advance ───────────────────────► the simulator steps one period, publishes sensors
      settle ──────────────────────────────► every process: "settled" when it has nothing to do
      step: clock ─────────────────────────► the simulator publishes /clock (timers fire)
      settle ──────────────────────────────► ... and again, until the run's length

The coordinator takes the run as settled when every process says so and every message a node
sent another has arrived (the two ends' counts agree, per topic). The process side is the agent
(:mod:`.agent`), what it counts is :mod:`.activity`, the wire :mod:`.frames`.
"""

from services.runtime.lockstep.activity import ACTIVITY, Activity
from services.runtime.lockstep.agent import LockstepNode, Stepper, join, leave, set_stepper

__all__ = ["ACTIVITY", "Activity", "LockstepNode", "Stepper", "join", "leave", "set_stepper"]
