"""The criteria library: one module per behaviour, each a list of
:class:`~services.grading.criteria.base.CriterionSpec`; :data:`CRITERIA` is every one, by name.

| family | criteria |
|---|---|
| ``drive_square`` | ``corner_error_m``, ``closure_m`` |
| ``estop`` | ``travel_m``, ``clearance_m``, ``moved_after_stop_m``, ``bumps`` |
| ``wall_follower`` | ``time_to_wall_s``, ``band_fraction``, ``followed_m``, ``bumps`` |
| ``person_follower`` | ``gap_band_fraction``, ``bumps`` |
| ``obstacle_avoider`` | ``goal_error_m``, ``progress``, ``bumps`` |
| ``fsm`` | ``switched``, ``switch_clearance_m``, ``wall_band_fraction``, ``bumps`` |
| ``drone_mission`` | ``boxes_visited``, ``path_ratio`` |
"""

from services.grading.criteria import (
    drive_square,
    drone_mission,
    estop,
    fsm,
    obstacle_avoider,
    person_follower,
    wall_follower,
)
from services.grading.criteria.base import CriterionSpec, Figure, Mark, Options

__all__ = ["CRITERIA", "CriterionSpec", "Figure", "Mark", "Options"]

CRITERIA: dict[str, CriterionSpec] = {
    spec.name: spec
    for family in (drive_square, estop, wall_follower, person_follower, obstacle_avoider, fsm, drone_mission)
    for spec in family.CRITERIA
}
"""Every criterion, by name (``family.figure``)."""
