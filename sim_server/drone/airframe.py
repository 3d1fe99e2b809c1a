"""The simulated quadrotor's physical parameters, modelled on the 3DR Iris.

Body frame: x forward, y left, z up (FLU). The rotors sit in an X at 45 degrees to the axes.
Pure data: both the physics (``scene``) and the on-board controller read it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim_server.drone.limits import GRAVITY_M_S2


@dataclass(frozen=True, slots=True)
class Airframe:
    """Mass, inertia, geometry and rotor model of a quadrotor in X configuration."""

    mass_kg: float = 1.5
    inertia_kg_m2: tuple[float, float, float] = (0.029, 0.029, 0.055)
    arm_length_m: float = 0.25
    """Centre to rotor axis; the Iris is 0.55 m motor to motor across the diagonal."""
    body_half_extents_m: tuple[float, float, float] = (0.16, 0.16, 0.06)
    """Collision box: hull and landing gear. Its half height is the resting altitude."""
    thrust_to_weight: float = 2.0
    moment_constant_m: float = 0.06
    """Rotor drag torque per newton of thrust (Gazebo's Iris model uses 0.06)."""
    linear_drag_n_s_m: float = 0.35
    """Air drag force per m/s of airspeed, all axes; bounds the top speed."""

    @property
    def weight_n(self) -> float:
        """Gravity's pull on the drone."""
        return self.mass_kg * GRAVITY_M_S2

    @property
    def max_rotor_thrust_n(self) -> float:
        """Thrust of one rotor at full throttle."""
        return self.thrust_to_weight * self.weight_n / 4.0

    @property
    def rest_z_m(self) -> float:
        """Altitude of the centre of mass when standing on flat ground."""
        return self.body_half_extents_m[2]

    @property
    def rotor_positions_m(self) -> tuple[tuple[float, float, float], ...]:
        """Rotor hubs in the body frame: front-right, back-left, front-left, back-right."""
        d = self.arm_length_m / math.sqrt(2.0)
        return ((d, -d, 0.0), (-d, d, 0.0), (d, d, 0.0), (-d, -d, 0.0))


ROTOR_SPIN = (-1.0, -1.0, 1.0, 1.0)
"""Sign of each rotor's drag torque about body z: the first two spin counter-clockwise (seen
from above) and so twist the body clockwise; the other two the opposite (PX4's quad X order)."""

IRIS = Airframe()
