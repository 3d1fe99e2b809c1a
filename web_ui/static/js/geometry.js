// Maths shared by the map and the layers: quaternions, ROS time, the map's view transform.

/** Heading (rad, counter-clockwise from +x) of a quaternion {x, y, z, w}. */
export function yawOf(q) {
  if (!q) return 0;
  return Math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

/** Seconds of a builtin_interfaces/Time {sec, nanosec}, or null. */
export function stampSeconds(stamp) {
  if (!stamp || typeof stamp.sec !== "number") return null;
  return stamp.sec + (stamp.nanosec || 0) * 1e-9;
}

export function isFiniteNumber(value) {
  return typeof value === "number" && Number.isFinite(value);
}

/**
 * Top-down view of the map frame: +x to the right, +y up, `scale` pixels per metre,
 * (cx, cy) the world point at the centre of a width x height canvas (CSS pixels).
 */
export class View {
  constructor() {
    this.cx = 0;
    this.cy = 0;
    this.scale = 10;
    this.width = 1;
    this.height = 1;
  }

  resize(width, height) {
    this.width = Math.max(1, width);
    this.height = Math.max(1, height);
  }

  /** Show the square [-half, half]^2 metres around the origin. */
  fit(half) {
    this.cx = 0;
    this.cy = 0;
    this.scale = Math.min(this.width, this.height) / (2 * half * 1.04);
  }

  toScreen(x, y) {
    return [this.width / 2 + (x - this.cx) * this.scale, this.height / 2 - (y - this.cy) * this.scale];
  }

  toWorld(sx, sy) {
    return [this.cx + (sx - this.width / 2) / this.scale, this.cy - (sy - this.height / 2) / this.scale];
  }

  /** Zoom by `factor` keeping the world point under (sx, sy) fixed. */
  zoomAt(sx, sy, factor) {
    const [wx, wy] = this.toWorld(sx, sy);
    this.scale = Math.min(400, Math.max(2, this.scale * factor));
    const [nx, ny] = this.toWorld(sx, sy);
    this.cx += wx - nx;
    this.cy += wy - ny;
  }

  panBy(dxPx, dyPx) {
    this.cx -= dxPx / this.scale;
    this.cy += dyPx / this.scale;
  }
}
