// The TF display: every frame of the tree as axes with its name, and a line to its parent, as
// rviz's TF display. It draws the view's tree (fed by /tf and /tf_static), so it needs no socket
// of its own; frames with no path to the fixed frame are listed on the display, not drawn.

import * as THREE from "three";
import { disposeObject, makeAxes, setSpriteText, textSprite } from "../shapes.js";
import { Display, worldPoint } from "./display.js";

const _origin = new THREE.Vector3();
const _parent = new THREE.Vector3();

export class TfDisplay extends Display {
  static colored = false;
  static options = {
    names: { label: "names", type: "bool", default: true },
    size: { label: "axes length (m)", type: "number", default: 0.3, min: 0.02, max: 5, step: 0.05 },
  };

  constructor(topic, type, settings, env) {
    super(topic, type, settings, env);
    this.tf = env.tf;
    this.frames = new Map(); // name -> {group, label}
    this.links = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xd0b040 }));
    this.links.frustumCulled = false;
    this.root.add(this.links);
    this._drawnVersion = -1;
    this.setStatus("Topic", "ok", "draws the tree of /tf and /tf_static");
  }

  // The view's tree is the data: nothing to subscribe to.
  start() {}
  stop() {}

  update(ctx) {
    if (!(ctx.tfChanged || ctx.fixedFrameChanged || ctx.tfStructureChanged || this._drawnVersion < 0)) return false;
    this._drawnVersion = this.tf.version;
    const names = this.tf.frames();
    for (const [name, frame] of this.frames) {
      if (!names.includes(name)) {
        frame.group.removeFromParent();
        disposeObject(frame.group);
        this.frames.delete(name);
      }
    }
    const unconnected = [];
    const links = [];
    for (const name of names) {
      const frame = this.frames.get(name) || this._addFrame(name);
      const found = ctx.lookup(name, null, frame.group.matrix);
      frame.group.visible = !found.error;
      frame.group.matrixWorldNeedsUpdate = true;
      if (found.error) {
        unconnected.push(name);
        continue;
      }
      const parent = this.tf.parentOf(name);
      if (parent && !ctx.lookup(parent, null, _matrix).error) {
        links.push(_origin.clone().setFromMatrixPosition(frame.group.matrix), _parent.setFromMatrixPosition(_matrix).clone());
      }
    }
    this.links.geometry.setFromPoints(links);
    if (unconnected.length) {
      this.setStatus("Frames", "warn", `not connected to ${ctx.fixedFrame}: ${unconnected.join(", ")}`);
    } else {
      this.setStatus("Frames", "ok", `${names.length} frames`);
    }
    this.restyle();
    return true;
  }

  _addFrame(name) {
    const group = new THREE.Group();
    group.matrixAutoUpdate = false;
    const axes = makeAxes(1, 0.04);
    const label = textSprite(name, "#ffffff", 0.12);
    label.center.set(0.5, -0.3);
    group.add(axes, label);
    this.root.add(group);
    const frame = { group, axes, label };
    this.frames.set(name, frame);
    return frame;
  }

  restyle() {
    for (const [name, frame] of this.frames) {
      frame.axes.scale.setScalar(this.options.size);
      frame.label.visible = this.options.names;
      setSpriteText(frame.label, name, "#ffffff", Math.max(0.08, this.options.size * 0.4));
    }
  }

  drawn() {
    const frames = [];
    for (const [name, frame] of this.frames) {
      if (frame.group.visible) frames.push({ frame: name, position: worldPoint(frame.group, _origin) });
    }
    return { objects: frames.length, frames, points: frames.map((f) => f.position) };
  }
}

const _matrix = new THREE.Matrix4();
