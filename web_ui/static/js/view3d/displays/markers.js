// visualization_msgs/Marker and MarkerArray: markers keyed by (ns, id), with ADD/MODIFY, DELETE,
// DELETEALL and lifetime, each marker in its own header's frame. Markers are incremental, so the
// socket reads every message (no throttle) and each one is folded into a map of the newest state
// per marker at once; a frame then draws what changed. However fast they come, the work waiting
// is at most one entry per marker.

import * as THREE from "three";
import { InstanceBatch } from "../instance_batch.js";
import { BadData, durationSeconds, frameName, rgba, setPoseMatrix, setVector, stampSeconds } from "../ros_math.js";
import { disposeObject, unitGeometry } from "../shapes.js";
import { MARKER_TYPES, markerObject, markerWarnings } from "../marker_shapes.js";
import { Display, round, worldPoint } from "./display.js";

const ADD = 0;
const DELETE = 2;
const DELETEALL = 3;
const MAX_MARKERS = 20_000; // per display; more is a runaway publisher, said on the display
const _frameMatrix = new THREE.Matrix4();
const _matrix = new THREE.Matrix4();
const _scale = new THREE.Vector3();
const _origin = new THREE.Vector3();
// Opaque shapes of these types are drawn as instances of one mesh per type (one draw call each).
const BATCHED = { 0: "arrow", 1: "box", 2: "sphere", 3: "cylinder" };

/** The batch a marker goes in, or null when it is drawn as an object of its own. */
function batchShape(marker) {
  const shape = BATCHED[marker.type];
  if (!shape || !(marker.color && marker.color.a >= 1)) return null;
  if (shape === "arrow" && Array.isArray(marker.points) && marker.points.length >= 2) return null;
  return shape;
}

export class MarkerDisplay extends Display {
  static rate = null;
  static queue = 1000;
  static colored = false; // markers carry their own colours

  constructor(...args) {
    super(...args);
    this._incoming = new Map(); // key -> {marker, receivedAt} to draw, or null to delete
    this._clearAll = false;
    this.objects = new Map(); // key -> {holder | batch, pose, color, type, frame, stamp, locked, expiresAt, failed}
    this.batches = new Map(); // shape -> InstanceBatch
    this._nextExpiry = Infinity;
  }

  _batch(shape) {
    let batch = this.batches.get(shape);
    if (!batch) {
      batch = new InstanceBatch(unitGeometry()[shape]);
      this.batches.set(shape, batch);
      this.root.add(batch.mesh);
    }
    return batch;
  }

  receive(msg) {
    this.received += 1;
    const markers = this.type.endsWith("/MarkerArray") ? msg && msg.markers : [msg];
    if (!Array.isArray(markers)) {
      this.setStatus("Message", "error", "message skipped: markers is not a list");
      return;
    }
    const now = performance.now() / 1000;
    for (const marker of markers) this._fold(marker, now);
  }

  _fold(marker, now) {
    if (!marker || typeof marker !== "object") return;
    if (marker.action === DELETEALL) {
      this._incoming.clear();
      this._clearAll = true;
      return;
    }
    const key = `${typeof marker.ns === "string" ? marker.ns : ""}/${marker.id}`;
    if (marker.action === DELETE) {
      this._incoming.set(key, null);
    } else if (marker.action === ADD || marker.action === 1) {
      // 1 was MODIFY in early ROS 1; rviz treats it as ADD too.
      if (!this._incoming.has(key) && this._incoming.size + this.objects.size >= MAX_MARKERS && !this.objects.has(key)) {
        this.setStatus("Markers", "error", `more than ${MAX_MARKERS} markers: the rest are not drawn`);
        return;
      }
      this._incoming.set(key, { marker, receivedAt: now });
    } else {
      this.setStatus(`Marker ${key}`, "error", `unknown action ${JSON.stringify(marker.action)}: skipped`);
    }
  }

  applyPending(ctx) {
    let changed = false;
    if (this._clearAll) {
      for (const key of [...this.objects.keys()]) this._remove(key);
      this.clearStatuses("Marker ");
      this.clearStatus("Markers");
      this._clearAll = false;
      changed = true;
    }
    if (this._incoming.size) {
      for (const [key, entry] of this._incoming) {
        if (entry === null) {
          this._remove(key);
          this.clearStatus(`Marker ${key}`);
        } else {
          this._draw(key, entry.marker, entry.receivedAt, ctx);
        }
        this.applied += 1;
      }
      this._incoming.clear();
      changed = true;
    }
    if (ctx.now >= this._nextExpiry) changed = this._expire(ctx.now) || changed;
    for (const batch of this.batches.values()) batch.flush();
    return changed;
  }

  _draw(key, marker, receivedAt, ctx) {
    const statusKey = `Marker ${key}`;
    let old = this.objects.get(key);
    try {
      const pose = setPoseMatrix(new THREE.Matrix4(), marker.pose, "pose");
      const shape = batchShape(marker);
      if (old && (shape === null) !== (old.batch === null)) {
        this._remove(key); // moving between a batch and an object of its own
        old = null;
      }
      const entry = {
        holder: null,
        batch: null,
        pose,
        color: null,
        type: marker.type,
        frame: frameName(marker.header && marker.header.frame_id) || null,
        stamp: stampSeconds(marker.header && marker.header.stamp),
        locked: marker.frame_locked === true,
        expiresAt: Infinity,
        failed: false,
      };
      if (shape) {
        setVector(_scale, marker.scale, "scale");
        entry.pose = pose.scale(_scale);
        entry.color = rgba(marker.color, "color")[0];
        if (old && old.batch !== this._batch(shape)) old.batch.remove(key);
        entry.batch = this._batch(shape);
      } else {
        const object = markerObject(marker, old ? old.holder.children[0] : null);
        entry.holder = old ? old.holder : new THREE.Group();
        entry.holder.matrixAutoUpdate = false;
        if (!old) this.root.add(entry.holder.add(object));
        else if (entry.holder.children[0] !== object) {
          entry.holder.remove(entry.holder.children[0]);
          entry.holder.add(object);
        }
      }
      const lifetime = durationSeconds(marker.lifetime);
      entry.expiresAt = lifetime > 0 ? receivedAt + lifetime : Infinity;
      this.objects.set(key, entry);
      this._nextExpiry = Math.min(this._nextExpiry, entry.expiresAt);
      const warnings = markerWarnings(marker);
      if (entry.frame === null) warnings.push("no frame_id: drawn in the fixed frame");
      if (warnings.length) this.setStatus(statusKey, "warn", warnings.join("; "));
      else this.clearStatus(statusKey);
      this._place(key, entry, ctx, entry.stamp);
    } catch (error) {
      if (!(error instanceof BadData)) throw error;
      if (old) this._remove(key);
      this.setStatus(statusKey, "error", `${MARKER_TYPES[marker.type] ?? "marker"} skipped: ${error.message}`);
    }
  }

  /** (frame -> fixed frame) * pose, into the marker's holder or batch slot; a frame with no path
   * hides the marker and says why. */
  _place(key, entry, ctx, stamp) {
    const found = entry.frame === null ? { matrix: _frameMatrix.identity() } : ctx.lookup(entry.frame, stamp, _frameMatrix);
    const statusKey = `Frame ${entry.frame}`;
    if (found.error) {
      entry.failed = true;
      if (entry.batch) entry.batch.remove(key);
      else entry.holder.visible = false;
      this.setStatus(statusKey, "error", found.error);
      return;
    }
    entry.failed = false;
    if (entry.batch) {
      entry.batch.set(key, _matrix.multiplyMatrices(found.matrix, entry.pose), entry.color);
    } else {
      entry.holder.visible = true;
      entry.holder.matrix.multiplyMatrices(found.matrix, entry.pose);
      entry.holder.matrixWorldNeedsUpdate = true;
    }
    if (found.clockNote) this.setStatus(statusKey, "warn", found.clockNote);
    else this.clearStatus(statusKey);
  }

  placeAgain(ctx) {
    let changed = false;
    for (const [key, entry] of this.objects) {
      if (ctx.fixedFrameChanged || entry.failed) {
        this._place(key, entry, ctx, null);
        changed = true;
      }
    }
    return changed;
  }

  /** frame_locked markers follow their frame as it moves. */
  tick(ctx) {
    if (!ctx.tfChanged) return false;
    let changed = false;
    for (const [key, entry] of this.objects) {
      if (entry.locked) {
        this._place(key, entry, ctx, null);
        changed = true;
      }
    }
    return changed;
  }

  _expire(now) {
    let next = Infinity;
    let changed = false;
    for (const [key, entry] of this.objects) {
      if (entry.expiresAt <= now) {
        this._remove(key);
        changed = true;
      } else {
        next = Math.min(next, entry.expiresAt);
      }
    }
    this._nextExpiry = next;
    return changed;
  }

  _remove(key) {
    const entry = this.objects.get(key);
    if (!entry) return;
    if (entry.batch) {
      entry.batch.remove(key);
    } else {
      entry.holder.removeFromParent();
      disposeObject(entry.holder);
    }
    this.objects.delete(key);
  }

  drawn() {
    const markers = [];
    for (const [key, entry] of this.objects) {
      if (entry.failed || (entry.holder && !entry.holder.children[0].visible)) continue;
      const [ns, id] = [key.slice(0, key.lastIndexOf("/")), Number(key.slice(key.lastIndexOf("/") + 1))];
      const position = entry.batch
        ? entry.batch.positionOf(key).applyMatrix4(this.root.matrixWorld).toArray().map(round)
        : worldPoint(entry.holder, _origin);
      markers.push({ ns, id, type: MARKER_TYPES[entry.type], position, batched: !!entry.batch });
    }
    return { objects: markers.length, markers, points: markers.map((m) => m.position) };
  }

  dispose() {
    for (const key of [...this.objects.keys()]) this._remove(key);
    for (const batch of this.batches.values()) batch.dispose();
    super.dispose();
  }
}
