// The TF tree, as tf2 keeps it: each child frame has one parent and a transform from it, with the
// last seconds of history for moving frames (so a scan is placed where the robot was when it was
// taken) and one value for static ones. `lookup` answers "where is frame S in frame T at time t",
// or says why it cannot, in rviz's words.

import * as THREE from "three";
import { BadData, frameName, setQuaternion, setVector, stampSeconds } from "./ros_math.js";

const HISTORY_S = 10; // how far back a moving frame can be looked up
const HISTORY_MAX = 2000; // samples per frame, whatever the rate
const MAX_DEPTH = 64; // deeper than this is a loop in the data
export const CLOCK_MISMATCH_S = 1; // further than this outside the history: another clock; say so

/** One child frame's transform from its parent: samples [t, tx, ty, tz, qx, qy, qz, qw]. */
class Edge {
  constructor(parent, isStatic) {
    this.parent = parent;
    this.isStatic = isStatic;
    this.samples = [];
  }

  add(t, values) {
    if (this.isStatic || t === null) {
      this.samples = [[t ?? 0, ...values]];
      return;
    }
    const samples = this.samples;
    const last = samples[samples.length - 1];
    if (last && t < last[0]) {
      // Time went back (a simulator reset, a replayed bag): start the history again, as tf2 does.
      samples.length = 0;
    }
    samples.push([t, ...values]);
    if (samples.length > HISTORY_MAX || t - samples[0][0] > HISTORY_S) {
      let drop = 0;
      while (drop < samples.length - 1 && (samples.length - drop > HISTORY_MAX || t - samples[drop][0] > HISTORY_S)) drop++;
      samples.splice(0, drop);
    }
  }

  /** Write the transform at `t` (null: the latest) into (position, rotation); returns how far
   * outside the history `t` was: > 0 ahead of the newest sample, < 0 before the oldest, 0 inside. */
  sample(t, position, rotation) {
    const samples = this.samples;
    const last = samples[samples.length - 1];
    if (this.isStatic || t === null || samples.length === 1 || t >= last[0]) {
      set(last, position, rotation);
      return this.isStatic || t === null ? 0 : t - last[0];
    }
    const first = samples[0];
    if (t <= first[0]) {
      set(last, position, rotation); // older than we keep: the latest is the best guess
      return t - first[0];
    }
    let lo = 0;
    let hi = samples.length - 1;
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (samples[mid][0] <= t) lo = mid;
      else hi = mid;
    }
    const a = samples[lo];
    const b = samples[hi];
    const f = (t - a[0]) / (b[0] - a[0] || 1);
    position.set(a[1] + (b[1] - a[1]) * f, a[2] + (b[2] - a[2]) * f, a[3] + (b[3] - a[3]) * f);
    rotation.set(a[4], a[5], a[6], a[7]).slerp(_q.set(b[4], b[5], b[6], b[7]), f);
    return 0;
  }
}

const _q = new THREE.Quaternion();
const _p = new THREE.Vector3();
const _r = new THREE.Quaternion();
const _unit = new THREE.Vector3(1, 1, 1);
const _edge = new THREE.Matrix4();

function set(sample, position, rotation) {
  position.set(sample[1], sample[2], sample[3]);
  rotation.set(sample[4], sample[5], sample[6], sample[7]);
}

export class TfTree {
  constructor() {
    this._edges = new Map(); // child -> Edge
    this._frames = new Set(); // every frame named by TF or by the worlds' own topics
    /** Bumped when a frame or an edge appears or moves to another parent (not on every update). */
    this.structureVersion = 0;
    /** Bumped on every transform received. */
    this.version = 0;
    this.rejected = 0; // transforms skipped as bad data
    this.lastRejection = "";
  }

  /** Apply a tf2_msgs/TFMessage; bad transforms are skipped and counted, the rest applied. */
  applyMessage(msg, isStatic) {
    const transforms = msg && Array.isArray(msg.transforms) ? msg.transforms : [];
    for (const transform of transforms) {
      try {
        this.setTransform(transform, isStatic);
      } catch (error) {
        if (!(error instanceof BadData)) throw error;
        this.rejected += 1;
        this.lastRejection = error.message;
      }
    }
  }

  /** Apply one geometry_msgs/TransformStamped (parent header.frame_id -> child_frame_id). */
  setTransform(ts, isStatic) {
    const parent = frameName(ts && ts.header && ts.header.frame_id);
    const child = frameName(ts && ts.child_frame_id);
    if (!parent || !child) throw new BadData("a transform without a frame_id or child_frame_id");
    if (parent === child) throw new BadData(`a transform from ${parent} to itself`);
    const transform = ts.transform || {};
    setVector(_p, transform.translation, `transform ${parent} -> ${child} translation`);
    setQuaternion(_r, transform.rotation, `transform ${parent} -> ${child} rotation`);
    let edge = this._edges.get(child);
    if (!edge || edge.parent !== parent || edge.isStatic !== isStatic) {
      edge = new Edge(parent, isStatic);
      this._edges.set(child, edge);
      this.structureVersion += 1;
    }
    this.addFrame(parent);
    this.addFrame(child);
    edge.add(stampSeconds(ts.header.stamp), [_p.x, _p.y, _p.z, _r.x, _r.y, _r.z, _r.w]);
    this.version += 1;
  }

  /** A frame the worlds' own topics name (`map` of /drone/pose): known, even without TF. */
  addFrame(name) {
    const frame = frameName(name);
    if (!frame || this._frames.has(frame)) return;
    this._frames.add(frame);
    this.structureVersion += 1;
  }

  has(frame) {
    return this._frames.has(frame);
  }

  frames() {
    return [...this._frames].sort();
  }

  parentOf(frame) {
    const edge = this._edges.get(frame);
    return edge ? edge.parent : null;
  }

  /** The chain [frame, parent, grandparent, ..., root]; throws BadData on a loop. */
  chain(frame) {
    const chain = [frame];
    for (let edge = this._edges.get(frame); edge; edge = this._edges.get(edge.parent)) {
      chain.push(edge.parent);
      if (chain.length > MAX_DEPTH) throw new BadData(`the TF tree has a loop through ${frame}`);
    }
    return chain;
  }

  /** The fixed frame to use when the user has not chosen one: the root of the biggest tree,
   * `map` before `odom` before the rest on a tie (rviz's default is `map`). */
  defaultFixedFrame() {
    const sizes = new Map();
    for (const frame of this._frames) {
      let root;
      try {
        const chain = this.chain(frame);
        root = chain[chain.length - 1];
      } catch {
        continue;
      }
      sizes.set(root, (sizes.get(root) || 0) + 1);
    }
    const rank = (name) => (name === "map" ? 0 : name === "odom" ? 1 : 2);
    const roots = [...sizes.keys()].sort((a, b) => sizes.get(b) - sizes.get(a) || rank(a) - rank(b) || a.localeCompare(b));
    return roots[0] || "map";
  }

  /**
   * Where `source` is in `target` at `stamp` (seconds, or null for the latest):
   * {matrix, clockNote, ahead} — `out` set to the transform from source to target coordinates, a
   * note when the stamp was far outside the history (different clocks?), and how many seconds the
   * stamp is ahead of the newest transform on the way (a message may wait for them) — or {error}.
   */
  lookup(target, source, stamp, out) {
    if (!this._frames.has(target)) return { error: `Fixed frame [${target}] does not exist` };
    if (!source) return { error: "the message has no frame_id" };
    if (!this._frames.has(source)) return { error: `Frame [${source}] does not exist` };
    if (source === target) return { matrix: out.identity(), clockNote: "", ahead: 0 };
    let sourceChain;
    let targetChain;
    try {
      sourceChain = this.chain(source);
      targetChain = this.chain(target);
    } catch (error) {
      return { error: error.message };
    }
    const inTarget = new Map(targetChain.map((frame, index) => [frame, index]));
    const common = sourceChain.findIndex((frame) => inTarget.has(frame));
    if (common < 0) {
      return {
        error:
          `No transform from [${source}] to [${target}]: they are in unconnected trees ` +
          `(${source} under ${sourceChain[sourceChain.length - 1]}, ${target} under ${targetChain[targetChain.length - 1]})`,
      };
    }
    let outside = 0;
    let ahead = 0;
    // source -> common ancestor, then common ancestor -> target (the inverse of target -> common).
    const up = (chain, count, matrix) => {
      matrix.identity();
      for (let i = 0; i < count; i++) {
        const off = this._edges.get(chain[i]).sample(stamp, _p, _r);
        outside = Math.max(outside, Math.abs(off));
        ahead = Math.max(ahead, off);
        matrix.premultiply(_edge.compose(_p, _r, _unit));
      }
      return matrix;
    };
    const toCommon = up(sourceChain, common, out);
    const targetToCommon = up(targetChain, inTarget.get(sourceChain[common]), _targetMatrix);
    out.premultiply(targetToCommon.invert());
    const clockNote =
      outside > CLOCK_MISMATCH_S
        ? `the stamp is ${outside.toFixed(1)} s outside the transforms' times (an old message, or another clock?): ` +
          "drawn with the latest transforms"
        : "";
    return { matrix: toCommon, clockNote, ahead };
  }

  /** Plain data for the debug hook: frames with their parents. */
  snapshot() {
    return this.frames().map((frame) => {
      const edge = this._edges.get(frame);
      return { frame, parent: edge ? edge.parent : null, static: edge ? edge.isStatic : null };
    });
  }
}

const _targetMatrix = new THREE.Matrix4();
