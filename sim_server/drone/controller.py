"""The drone's on-board cascaded flight controller: pure math, no physics engine.

The cascade is the one PX4 and ArduPilot fly::

    position --P--> velocity setpoint          (saturated at MAX_SPEED_XY / MAX_SPEED_Z)
    velocity --PI-> acceleration               (+ hover thrust and drag feed-forward)
    acceleration -> attitude + collective      (thrust vector; tilt limited to MAX_TILT_DEG)
    attitude --P--> body rates                 (geometric error on SO(3))
    body rates --P--> torques -> mixer -> four rotor thrusts in [0, max]

Like a real flight stack the outer loops run slower than the inner ones: the world calls
:meth:`CascadedController.update_position` at a fraction of the physics rate and
:meth:`CascadedController.update_attitude` every physics step. Below
HORIZONTAL_CONTROL_MIN_Z_M the horizontal loops are off and the drone climbs or descends level;
on the ground with nowhere to go the motors stop (``idle``).

Frames: world is ENU-like (x, y horizontal, z up); body is FLU; quaternions are (x, y, z, w),
as PyBullet hands them out. Angular velocities come in the world frame, as PyBullet reports them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim_server.drone.airframe import IRIS, Airframe
from sim_server.drone.limits import (
    GRAVITY_M_S2,
    HORIZONTAL_CONTROL_MIN_Z_M,
    MAX_SPEED_XY,
    MAX_SPEED_Z,
    MAX_TILT_DEG,
    MAX_YAW_RATE,
    ON_GROUND_Z_M,
)

__all__ = ["CascadedController", "Gains", "Mixer", "Reference"]


@dataclass(frozen=True, slots=True)
class Gains:
    """Loop gains and limits of the cascade (per second unless stated)."""

    # position -> velocity
    position_xy: float = 1.2
    position_z: float = 1.5
    # velocity -> acceleration
    velocity_xy_p: float = 2.4
    velocity_xy_i: float = 0.4
    velocity_z_p: float = 4.0
    velocity_z_i: float = 1.0
    velocity_integral_limit_m_s2: float = 2.0
    velocity_integral_band_m_s: float = 0.5
    """Integrate only velocity errors smaller than this: the integrators trim steady errors
    and must not wind up during manoeuvres (which would add a slow creep after each one)."""
    max_accel_up_m_s2: float = 0.7 * GRAVITY_M_S2
    max_accel_down_m_s2: float = 0.6 * GRAVITY_M_S2
    land_speed_m_s: float = 0.5
    """Least descent speed for the last metre when the target is on the ground."""
    # attitude -> body rates
    attitude_roll_pitch: float = 7.0
    attitude_yaw: float = 2.5
    max_rate_roll_pitch_rad_s: float = math.radians(220.0)
    # body rates -> torque
    rate_roll_pitch: float = 25.0
    rate_yaw: float = 8.0


@dataclass(slots=True)
class Reference:
    """What the outer loop tracks: a position, a yaw, and velocity feed-forward (world frame)."""

    x: float = 0.0
    y: float = 0.0
    z: float = 0.0
    yaw: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    vz: float = 0.0
    yaw_rate: float = 0.0


class Mixer:
    """Turns collective thrust and body torques into four rotor thrusts, each in [0, max].

    When the rotors cannot give everything, roll and pitch win over collective thrust and
    collective wins over yaw, as in PX4's mixer: an attitude the drone cannot hold is worse
    than a brief loss of altitude or heading.
    """

    __slots__ = ("_max", "_per_torque_rp", "_per_torque_yaw", "_moment")

    def __init__(self, airframe: Airframe = IRIS) -> None:
        d = airframe.arm_length_m / math.sqrt(2.0)
        self._max = airframe.max_rotor_thrust_n
        self._per_torque_rp = 1.0 / (4.0 * d)
        self._per_torque_yaw = 1.0 / (4.0 * airframe.moment_constant_m)
        self._moment = airframe.moment_constant_m

    def mix(
        self, collective_n: float, tx: float, ty: float, tz: float
    ) -> tuple[float, float, float, float, float]:
        """Rotor thrusts (front-right, back-left, front-left, back-right) and their yaw torque."""
        top = self._max
        k = self._per_torque_rp
        a0 = (-tx - ty) * k  # front-right; back-left gets -a0
        a2 = (tx - ty) * k  # front-left; back-right gets -a2
        spread = abs(a0) if abs(a0) > abs(a2) else abs(a2)
        if 2.0 * spread > top:
            scale = top / (2.0 * spread)
            a0 *= scale
            a2 *= scale
            spread = 0.5 * top
        base = 0.25 * collective_n
        if base < spread:
            base = spread
        elif base > top - spread:
            base = top - spread
        y = tz * self._per_torque_yaw  # front-left and back-right get +y, the others -y
        if y > 0.0:
            room = min(top - base - abs(a2), base - abs(a0))
            if y > room:
                y = room if room > 0.0 else 0.0
        elif y < 0.0:
            room = min(top - base - abs(a0), base - abs(a2))
            if -y > room:
                y = -room if room > 0.0 else 0.0
        t0 = _clamp(base + a0 - y, 0.0, top)
        t1 = _clamp(base - a0 - y, 0.0, top)
        t2 = _clamp(base + a2 + y, 0.0, top)
        t3 = _clamp(base - a2 + y, 0.0, top)
        return t0, t1, t2, t3, self._moment * (t2 + t3 - t0 - t1)


class CascadedController:
    """Position, velocity, attitude and rate loops of a quadrotor, with its mixer.

    Example::

        ctl = CascadedController()
        ref = Reference(z=3.0)
        ctl.update_position(ref, px, py, pz, vx, vy, vz, dt_s=1 / 60)      # at 60 Hz
        t0, t1, t2, t3, yaw_torque = ctl.update_attitude(qx, qy, qz, qw, wx, wy, wz)  # 240 Hz
    """

    def __init__(self, airframe: Airframe = IRIS, gains: Gains | None = None) -> None:
        self.airframe = airframe
        self.gains = gains or Gains()
        self.mixer = Mixer(airframe)
        self._mass = airframe.mass_kg
        self._drag_per_mass = airframe.linear_drag_n_s_m / airframe.mass_kg
        self._tan_max_tilt = math.tan(math.radians(MAX_TILT_DEG))
        self._jx, self._jy, self._jz = airframe.inertia_kg_m2
        self.reset()

    def reset(self) -> None:
        """Forget integrators and setpoints: the state of a drone that has just been switched on."""
        self.idle = True
        """Motors stopped: on the ground with no reason to leave it."""
        self.velocity_setpoint = (0.0, 0.0, 0.0)
        self.accel_setpoint = (0.0, 0.0, 0.0)
        self._ix = self._iy = self._iz = 0.0
        # Desired thrust vector (acceleration + gravity), desired attitude as matrix columns.
        self._ax, self._ay, self._az = 0.0, 0.0, GRAVITY_M_S2
        self._rd = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
        self._yaw_rate_ff = 0.0

    # -- outer loops ---------------------------------------------------------------------------

    def update_position(
        self,
        ref: Reference,
        px: float,
        py: float,
        pz: float,
        vx: float,
        vy: float,
        vz: float,
        dt_s: float,
    ) -> None:
        """Run the position and velocity loops; sets the attitude and thrust the inner loop flies."""
        g = self.gains
        if pz <= ON_GROUND_Z_M and ref.z <= ON_GROUND_Z_M and ref.vz <= 0.0:
            self.reset()
            return
        self.idle = False

        # position -> velocity setpoint
        svz = ref.vz + g.position_z * (ref.z - pz)
        if ref.z <= ON_GROUND_Z_M and pz < 1.0 and svz > -g.land_speed_m_s:
            svz = -g.land_speed_m_s
        svz = _clamp(svz, -MAX_SPEED_Z, MAX_SPEED_Z)
        horizontal = pz >= HORIZONTAL_CONTROL_MIN_Z_M
        if horizontal:
            svx = ref.vx + g.position_xy * (ref.x - px)
            svy = ref.vy + g.position_xy * (ref.y - py)
            speed = math.hypot(svx, svy)
            if speed > MAX_SPEED_XY:
                svx *= MAX_SPEED_XY / speed
                svy *= MAX_SPEED_XY / speed
        else:
            svx = svy = 0.0
            self._ix = self._iy = 0.0
        self.velocity_setpoint = (svx, svy, svz)

        # velocity -> acceleration (PI, drag feed-forward; integrate only while unsaturated)
        ilim = g.velocity_integral_limit_m_s2
        band = g.velocity_integral_band_m_s
        ez = svz - vz
        az = g.velocity_z_p * ez + self._iz + self._drag_per_mass * svz
        if -band < ez < band and -g.max_accel_down_m_s2 < az < g.max_accel_up_m_s2:
            self._iz = _clamp(self._iz + g.velocity_z_i * ez * dt_s, -ilim, ilim)
        az = _clamp(az, -g.max_accel_down_m_s2, g.max_accel_up_m_s2)
        if horizontal:
            ex = svx - vx
            ey = svy - vy
            ax = g.velocity_xy_p * ex + self._ix + self._drag_per_mass * svx
            ay = g.velocity_xy_p * ey + self._iy + self._drag_per_mass * svy
            # tilt limit: the horizontal share of the thrust vector, given its vertical share
            max_axy = (GRAVITY_M_S2 + az) * self._tan_max_tilt
            axy = math.hypot(ax, ay)
            if axy > max_axy:
                ax *= max_axy / axy
                ay *= max_axy / axy
            elif -band < ex < band and -band < ey < band:
                self._ix = _clamp(self._ix + g.velocity_xy_i * ex * dt_s, -ilim, ilim)
                self._iy = _clamp(self._iy + g.velocity_xy_i * ey * dt_s, -ilim, ilim)
        else:
            ax = ay = 0.0
        self.accel_setpoint = (ax, ay, az)

        # acceleration -> desired attitude: body z along the thrust vector, body x toward yaw
        tx, ty, tz = ax, ay, az + GRAVITY_M_S2
        norm = math.sqrt(tx * tx + ty * ty + tz * tz)
        zx, zy, zz = tx / norm, ty / norm, tz / norm
        cx, cy = math.cos(ref.yaw), math.sin(ref.yaw)
        # y_d = z_d x c with c = (cx, cy, 0); never degenerate since the tilt is limited
        yx, yy, yz = -zz * cy, zz * cx, zx * cy - zy * cx
        n = math.sqrt(yx * yx + yy * yy + yz * yz)
        yx, yy, yz = yx / n, yy / n, yz / n
        xx, xy, xz = yy * zz - yz * zy, yz * zx - yx * zz, yx * zy - yy * zx
        self._rd = (xx, yx, zx, xy, yy, zy, xz, yz, zz)  # row-major: R_d[i][j]
        self._ax, self._ay, self._az = tx, ty, tz
        self._yaw_rate_ff = ref.yaw_rate

    # -- inner loops ---------------------------------------------------------------------------

    def update_attitude(
        self,
        qx: float,
        qy: float,
        qz: float,
        qw: float,
        wx: float,
        wy: float,
        wz: float,
    ) -> tuple[float, float, float, float, float]:
        """Run the attitude and rate loops and the mixer: four rotor thrusts and the yaw torque.

        ``q`` is the attitude (x, y, z, w); ``w`` the angular velocity in the world frame.
        """
        if self.idle:
            return 0.0, 0.0, 0.0, 0.0, 0.0
        g = self.gains
        # rotation matrix R (body -> world), row-major
        xx, yy, zz = qx * qx, qy * qy, qz * qz
        xy, xz, yz = qx * qy, qx * qz, qy * qz
        wqx, wqy, wqz = qw * qx, qw * qy, qw * qz
        r00, r01, r02 = 1.0 - 2.0 * (yy + zz), 2.0 * (xy - wqz), 2.0 * (xz + wqy)
        r10, r11, r12 = 2.0 * (xy + wqz), 1.0 - 2.0 * (xx + zz), 2.0 * (yz - wqx)
        r20, r21, r22 = 2.0 * (xz - wqy), 2.0 * (yz + wqx), 1.0 - 2.0 * (xx + yy)
        # body rates: R^T w
        bx = r00 * wx + r10 * wy + r20 * wz
        by = r01 * wx + r11 * wy + r21 * wz
        bz = r02 * wx + r12 * wy + r22 * wz
        # attitude error e_R = vee(R_d^T R - R^T R_d) / 2  (Lee, Leok, McClamroch 2010)
        d00, d01, d02, d10, d11, d12, d20, d21, d22 = self._rd
        e21 = d02 * r01 + d12 * r11 + d22 * r21
        e12 = d01 * r02 + d11 * r12 + d21 * r22
        e02 = d00 * r02 + d10 * r12 + d20 * r22
        e20 = d02 * r00 + d12 * r10 + d22 * r20
        e10 = d01 * r00 + d11 * r10 + d21 * r20
        e01 = d00 * r01 + d10 * r11 + d20 * r21
        lim = g.max_rate_roll_pitch_rad_s
        sx = _clamp(-0.5 * g.attitude_roll_pitch * (e21 - e12), -lim, lim)
        sy = _clamp(-0.5 * g.attitude_roll_pitch * (e02 - e20), -lim, lim)
        sz = _clamp(
            self._yaw_rate_ff - 0.5 * g.attitude_yaw * (e10 - e01), -MAX_YAW_RATE, MAX_YAW_RATE
        )
        # rates -> torques
        tx = self._jx * g.rate_roll_pitch * (sx - bx)
        ty = self._jy * g.rate_roll_pitch * (sy - by)
        tz = self._jz * g.rate_yaw * (sz - bz)
        # collective: the thrust vector's share along the current body z
        collective = self._mass * (self._ax * r02 + self._ay * r12 + self._az * r22)
        return self.mixer.mix(collective if collective > 0.0 else 0.0, tx, ty, tz)


def _clamp(value: float, low: float, high: float) -> float:
    return low if value < low else high if value > high else value
