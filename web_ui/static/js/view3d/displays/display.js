// What every display shares, as rviz's: a topic subscription, a colour, visibility, options, a
// group of objects in the scene, and a status of named entries ("Transform", "Message", one per
// skipped marker...) that the panel shows. Messages are coalesced: the socket handler only keeps
// the newest, and the view applies it at its next frame, so a fast topic never queues up.

import * as THREE from "three";
import { TopicSocket } from "../../api.js";
import { BadData, frameName, stampSeconds } from "../ros_math.js";
import { StatusList } from "../status_list.js";
import { CLOCK_MISMATCH_S } from "../tf_tree.js";

const MAX_WAIT_S = 0.5; // longest a message waits for the transforms at its stamp
const AHEAD_EPSILON_S = 1e-4;
const _scratch = new THREE.Matrix4();

export class Display {
  /** The socket's rate (Hz) for this kind of display; null reads every message. */
  static rate = 30;
  /** Options beyond colour and visibility: name -> {label, type: "bool" | "number", default, min, max, step}. */
  static options = {};
  /** Whether the colour picker means anything for this display. */
  static colored = true;

  /** `env`: what the view lends its displays ({tf, images}: the tree, the image panels' box). */
  constructor(topic, type, { color, visible = true, options = {} } = {}, env = {}) {
    this.env = env;
    this.topic = topic;
    this.type = type;
    this.color = color || "#ff5fd2";
    this.visible = visible;
    this.options = {};
    for (const [name, spec] of Object.entries(this.constructor.options)) {
      this.options[name] = validOption(spec, options[name]) ? options[name] : spec.default;
    }
    this.root = new THREE.Group();
    this.root.matrixAutoUpdate = false;
    this.root.visible = visible;
    this.received = 0;
    this.applied = 0;
    this.statuses = new StatusList();
    this._pending = null;
    this._waitingSince = null;
    this._socket = null;
    this._placement = null; // {frame, stamp} of the drawn message, to place again on changes
    this.setStatus("Topic", "warn", "no messages received yet");
  }

  get label() {
    return this.type.split("/").pop();
  }

  start() {
    if (this._socket) return;
    this._socket = new TopicSocket(this.topic, {
      rate: this.constructor.rate ?? undefined,
      queue: this.constructor.queue ?? undefined,
      encoding: this.constructor.encoding ?? undefined,
      mode: "subscribe",
      onMessage: (msg) => this.receive(msg),
      onStatus: ({ state, code, reason }) => {
        if (state === "closed" && code !== 1000) {
          this.setStatus("Topic", "error", `connection closed (${code}${reason ? `: ${reason}` : ""}); reconnecting…`);
        }
        else if (state === "waiting") this.setStatus("Topic", "warn", "nobody publishes it yet");
        else if (state === "open" && !this.received) this.setStatus("Topic", "warn", "no messages received yet");
      },
    }).openWhenPublished();
  }

  stop() {
    if (this._socket) this._socket.close();
    this._socket = null;
  }

  /** The socket's handler: keep only the newest message (coalescing); the frame applies it. */
  receive(msg) {
    this.received += 1;
    this._pending = msg;
  }

  /** Once per animation frame: apply the pending message, place again when frames changed. */
  update(ctx) {
    if (this.received && this.statuses.get("Topic").level !== "ok") this.setStatus("Topic", "ok", "receiving messages");
    let changed = this.applyPending(ctx);
    if (ctx.fixedFrameChanged || ctx.tfStructureChanged) changed = this.placeAgain(ctx) || changed;
    return this.tick(ctx) || changed;
  }

  /** Apply the newest message received since the last frame; true when there was one. A message
   * stamped a little ahead of the transforms it needs waits for them (up to MAX_WAIT_S), as rviz's
   * message filter does, so a scan is placed where the robot was, not where it was 50 ms before. */
  applyPending(ctx) {
    if (this._pending === null) return false;
    const msg = this._pending;
    if (this._waitsForTransforms(msg, ctx)) return false;
    this._pending = null;
    this._waitingSince = null;
    this.applied += 1;
    try {
      this.apply(msg, ctx);
      this.clearStatus("Message");
    } catch (error) {
      if (!(error instanceof BadData)) throw error;
      this.setStatus("Message", "error", `message skipped: ${error.message}`);
    }
    return true;
  }

  _waitsForTransforms(msg, ctx) {
    const header = msg && msg.header;
    const frame = frameName(header && header.frame_id);
    const stamp = stampSeconds(header && header.stamp);
    if (!frame || stamp === null) return false;
    const found = ctx.lookup(frame, stamp, _scratch);
    if (found.error || !(found.ahead > AHEAD_EPSILON_S && found.ahead < CLOCK_MISMATCH_S)) return false;
    this._waitingSince ??= ctx.now;
    return ctx.now - this._waitingSince < MAX_WAIT_S;
  }

  /** The fixed frame changed, or frames appeared: place the drawn message again, at its stamp while
   * the history has it, else with the latest transforms. True when it did. */
  placeAgain(ctx) {
    if (!this._placement || !(ctx.fixedFrameChanged || this._placement.failed)) return false;
    this.place(ctx, this._placement.frame, this._placement.stamp, this.root, "Transform", { again: true });
    return true;
  }

  /** Draw one message (subclasses); throw BadData to skip it with a note. */
  apply(_msg, _ctx) {}

  /** Per-frame work beyond messages (lifetimes, frame-locked objects); true when it changed. */
  tick(_ctx) {
    return false;
  }

  /**
   * Set `object.matrix` to the transform from `frame` (at `stamp`) into the fixed frame; when there
   * is none, hide the object and say why in the "Transform" status, as rviz does.
   */
  place(ctx, frame, stamp, object, statusKey = "Transform", { again = false } = {}) {
    if (object === this.root) this._placement = { frame, stamp, failed: false };
    // A null frame is the fixed frame itself (a message without a header or frame_id).
    const found = frame === null ? { matrix: object.matrix.identity(), clockNote: "" } : ctx.lookup(frame, stamp, object.matrix);
    if (found.error) {
      object.visible = false;
      if (object === this.root) this._placement.failed = true;
      this.setStatus(statusKey, "error", found.error);
      return false;
    }
    object.visible = object === this.root ? this.visible : true;
    object.matrixWorldNeedsUpdate = true;
    // Placed again long after it came, a message is outside the history by age, not by clock.
    if (found.clockNote && !again) this.setStatus(statusKey, "warn", found.clockNote);
    else this.setStatus(statusKey, "ok", frame === null ? "in the fixed frame" : `in frame ${frame}`);
    return true;
  }

  /** The frame and stamp of a message's header; an empty frame is the fixed frame, with a note. */
  headerFrame(header) {
    const frame = frameName(header && header.frame_id);
    if (!frame) {
      this.setStatus("Frame", "warn", "the message has no frame_id: drawn in the fixed frame");
      return { frame: null, stamp: null };
    }
    this.clearStatus("Frame");
    return { frame, stamp: stampSeconds(header.stamp) };
  }

  setColor(color) {
    this.color = color;
    this.restyle();
  }

  /** Apply the colour and options to what is drawn (subclasses). */
  restyle() {}

  setVisible(visible) {
    this.visible = visible;
    this.root.visible = visible && !(this._placement && this._placement.failed);
  }

  setOption(name, value) {
    const spec = this.constructor.options[name];
    if (!spec || !validOption(spec, value)) return;
    this.options[name] = value;
    this.restyle();
  }

  setStatus(key, level, text) {
    this.statuses.set(key, level, text);
  }

  clearStatus(key) {
    this.statuses.clear(key);
  }

  clearStatuses(prefix) {
    this.statuses.clearPrefix(prefix);
  }

  status() {
    return this.statuses.summary();
  }

  /** The saved form of this display (persistence). */
  settings() {
    return { topic: this.topic, type: this.type, color: this.color, visible: this.visible, options: { ...this.options } };
  }

  /** Plain data for the debug hook; `points` are what is drawn, in the fixed frame. */
  snapshot() {
    this.root.updateMatrixWorld(true);
    return {
      topic: this.topic,
      type: this.type,
      color: this.color,
      visible: this.visible,
      options: { ...this.options },
      received: this.received,
      applied: this.applied,
      status: this.status(),
      drawn: this.root.visible,
      frame: this._placement ? this._placement.frame : null,
      stamp: this._placement ? this._placement.stamp : null,
      ...this.drawn(),
    };
  }

  /** {objects, points} as drawn (subclasses). */
  drawn() {
    return { objects: 0, points: [] };
  }

  dispose() {
    this.stop();
    this.root.removeFromParent();
  }
}

function validOption(spec, value) {
  if (spec.type === "bool") return typeof value === "boolean";
  if (spec.type === "number") {
    return typeof value === "number" && Number.isFinite(value) && value >= (spec.min ?? -Infinity) && value <= (spec.max ?? Infinity);
  }
  return false;
}

/** World (fixed-frame) positions of `object`'s points, rounded to the millimetre. */
export function worldPoint(object, local) {
  const p = local.clone().applyMatrix4(object.matrixWorld);
  return [round(p.x), round(p.y), round(p.z)];
}

export function round(value) {
  return Math.round(value * 1000) / 1000;
}
