// nav_msgs/Odometry: an arrow at the latest pose and a trail of where the robot has been. The
// trail takes every message (not only the ones a frame gets to draw) into a bounded buffer, kept
// in the odometry's own frame and drawn through the latest transform, so with the fixed frame
// base_link it shows the path behind the robot rather than a pile of arrows at the origin.

import * as THREE from "three";
import { BadData, frameName, setPoseMatrix } from "../ros_math.js";
import { solidMaterial, unitGeometry } from "../shapes.js";
import { Display, worldPoint } from "./display.js";

const TRAIL_MIN_STEP_M = 0.01;
const _scale = new THREE.Matrix4();
const _origin = new THREE.Vector3();

export class OdometryDisplay extends Display {
  static options = {
    length: { label: "arrow length (m)", type: "number", default: 0.4, min: 0.05, max: 10, step: 0.05 },
    trail: { label: "trail (points)", type: "number", default: 500, min: 0, max: 5000, step: 100 },
  };

  constructor(...args) {
    super(...args);
    this.pose = null; // Matrix4 of the latest pose, in `frame`
    this.frame = "";
    this.arrow = new THREE.Mesh(unitGeometry().arrow, solidMaterial(this.color));
    this.arrow.matrixAutoUpdate = false;
    this.arrow.visible = false;
    this.trailLine = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ transparent: true, opacity: 0.8 }));
    this.trailLine.frustumCulled = false;
    this.root.add(this.arrow, this.trailLine);
    this._trail = new Float32Array(0);
    this._trailCount = 0;
    this._trailDirty = false;
    this.skippedPoses = 0;
    this._resizeTrail();
    this.restyle();
  }

  /** Every message extends the trail at once (bounded); the arrow takes only the newest. */
  receive(msg) {
    super.receive(msg);
    const frame = frameName(msg && msg.header && msg.header.frame_id);
    const p = msg && msg.pose && msg.pose.pose && msg.pose.pose.position;
    if (!p || ![p.x, p.y, p.z].every(Number.isFinite)) return; // apply() says why
    if (frame !== this.frame) {
      this._trailCount = 0; // another frame: the old trail means nothing in it
      this.frame = frame;
    }
    const capacity = this._trail.length / 3;
    if (!capacity) return;
    const n = this._trailCount;
    if (n) {
      const i = (n - 1) * 3;
      if (Math.hypot(p.x - this._trail[i], p.y - this._trail[i + 1], p.z - this._trail[i + 2]) < TRAIL_MIN_STEP_M) return;
    }
    if (n === capacity) this._trail.copyWithin(0, 3);
    const at = Math.min(n, capacity - 1) * 3;
    this._trail[at] = p.x;
    this._trail[at + 1] = p.y;
    this._trail[at + 2] = p.z;
    this._trailCount = Math.min(n + 1, capacity);
    this._trailDirty = true;
  }

  apply(msg, ctx) {
    const pose = msg.pose && msg.pose.pose;
    this.pose = setPoseMatrix(new THREE.Matrix4(), pose, "pose.pose");
    this.frame = frameName(msg.header && msg.header.frame_id);
    if (!this.frame) throw new BadData("the odometry has no header.frame_id");
    this.arrow.visible = true;
    this.restyle();
  }

  tick(ctx) {
    let changed = false;
    if (this._trailDirty) {
      this.trailLine.geometry.attributes.position.needsUpdate = true;
      this.trailLine.geometry.setDrawRange(0, this._trailCount);
      this._trailDirty = false;
      changed = true;
    }
    // Frame-locked: the robot moves in the fixed frame between messages when it is not odom.
    if (this.frame && (ctx.tfChanged || ctx.fixedFrameChanged || changed || !this._placedOnce)) {
      this.place(ctx, this.frame, null, this.root);
      this._placedOnce = true;
      changed = true;
    }
    return changed;
  }

  restyle() {
    const length = this.options.length;
    if (this.pose) this.arrow.matrix.multiplyMatrices(this.pose, _scale.makeScale(length, length * 0.25, length * 0.25));
    this.arrow.matrixWorldNeedsUpdate = true;
    this.arrow.material.color.set(this.color);
    this.trailLine.material.color.set(this.color);
    if (this._trail.length / 3 !== this.options.trail) this._resizeTrail();
  }

  _resizeTrail() {
    const capacity = this.options.trail;
    const kept = Math.min(this._trailCount, capacity);
    const trail = new Float32Array(capacity * 3);
    trail.set(this._trail.subarray((this._trailCount - kept) * 3, this._trailCount * 3));
    this._trail = trail;
    this._trailCount = kept;
    this.trailLine.geometry.setAttribute("position", new THREE.BufferAttribute(trail, 3));
    this.trailLine.geometry.setDrawRange(0, kept);
  }

  drawn() {
    if (!this.arrow.visible) return { objects: 0, points: [], trail: 0 };
    return {
      objects: 1,
      points: [worldPoint(this.arrow, _origin)],
      trail: this._trailCount,
    };
  }
}
