// sensor_msgs/LaserScan: one point per beam with a return, coloured by range (red near, violet
// far) or in the display's colour. The buffers are allocated once per beam count and rewritten
// in place, so a 360-beam scan at 5 Hz costs one small upload per scan.

import * as THREE from "three";
import { BadData, rainbow } from "../ros_math.js";
import { Display, round } from "./display.js";

const MAX_BEAMS = 100_000;
const _color = new THREE.Color();
const _point = new THREE.Vector3();

export class LaserScanDisplay extends Display {
  static rate = 30;
  static colored = true;
  static options = {
    byRange: { label: "colour by range", type: "bool", default: true },
    size: { label: "point size (px)", type: "number", default: 4, min: 1, max: 20, step: 1 },
  };

  constructor(...args) {
    super(...args);
    this.geometry = new THREE.BufferGeometry();
    this.points = new THREE.Points(this.geometry, new THREE.PointsMaterial({ sizeAttenuation: false, vertexColors: true }));
    this.points.frustumCulled = false;
    this.root.add(this.points);
    this.count = 0;
    this._ranges = new Float32Array(0); // range of each drawn point, for recolouring
    this._limits = [0, 1];
    this._allocate(360);
    this.restyle();
  }

  _allocate(beams) {
    this.geometry.dispose(); // frees the old buffers on the GPU; the new ones upload at the next draw
    this.geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(beams * 3), 3));
    this.geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(beams * 3), 3));
    this._ranges = new Float32Array(beams);
  }

  apply(msg, ctx) {
    const { frame, stamp } = this.headerFrame(msg.header);
    const ranges = msg.ranges;
    if (!Array.isArray(ranges)) throw new BadData("ranges is not a list");
    if (ranges.length > MAX_BEAMS) throw new BadData(`${ranges.length} beams is more than ${MAX_BEAMS}`);
    const { angle_min: angleMin, angle_increment: increment } = msg;
    if (!Number.isFinite(angleMin) || !Number.isFinite(increment)) throw new BadData("angle_min or angle_increment is not finite");
    const rangeMin = Number.isFinite(msg.range_min) ? msg.range_min : 0;
    const rangeMax = Number.isFinite(msg.range_max) && msg.range_max > rangeMin ? msg.range_max : Infinity;
    if (this._ranges.length < ranges.length) this._allocate(ranges.length);
    const position = this.geometry.attributes.position.array;
    let n = 0;
    let skipped = 0;
    let farthest = 1;
    for (let i = 0; i < ranges.length; i++) {
      const r = ranges[i];
      // 0.0 is "no return" (the Neato's convention); outside [range_min, range_max] is invalid (rviz).
      if (!Number.isFinite(r) || r < rangeMin || r > rangeMax || r <= 0) {
        if (typeof r !== "number") skipped += 1;
        continue;
      }
      const angle = angleMin + i * increment;
      position[n * 3] = r * Math.cos(angle);
      position[n * 3 + 1] = r * Math.sin(angle);
      position[n * 3 + 2] = 0;
      this._ranges[n] = r;
      if (r > farthest) farthest = r;
      n += 1;
    }
    if (skipped) this.setStatus("Ranges", "warn", `${skipped} ranges were not numbers and were skipped`);
    else this.clearStatus("Ranges");
    this.count = n;
    this._limits = [rangeMin, Number.isFinite(rangeMax) ? rangeMax : farthest];
    this.geometry.setDrawRange(0, n);
    this.geometry.attributes.position.needsUpdate = true;
    this._recolor();
    this.place(ctx, frame, stamp, this.root);
  }

  restyle() {
    this.points.material.size = this.options.size;
    this._recolor();
  }

  _recolor() {
    const colors = this.geometry.attributes.color.array;
    const [low, high] = this._limits;
    const flat = _color.set(this.color).clone();
    for (let i = 0; i < this.count; i++) {
      const c = this.options.byRange ? rainbow(_color, (this._ranges[i] - low) / (high - low || 1)) : flat;
      colors[i * 3] = c.r;
      colors[i * 3 + 1] = c.g;
      colors[i * 3 + 2] = c.b;
    }
    this.geometry.attributes.color.needsUpdate = true;
  }

  drawn() {
    const position = this.geometry.attributes.position.array;
    const points = [];
    for (let i = 0; i < this.count; i++) {
      _point.set(position[i * 3], position[i * 3 + 1], position[i * 3 + 2]).applyMatrix4(this.points.matrixWorld);
      points.push([round(_point.x), round(_point.y), round(_point.z)]);
    }
    return { objects: this.count ? 1 : 0, points };
  }
}
