// visualization_msgs/Marker and MarkerArray: markers keyed by (ns, id), with ADD/MODIFY, DELETE,
// DELETEALL and lifetime, each marker in its own header's frame. Markers are incremental, so the
// socket reads every message (no throttle) and each one is folded into a map of the newest state
// per marker at once; a frame then draws what changed. However fast they come, the work waiting
// is at most one entry per marker.

import * as THREE from "three";
import { BadData, durationSeconds, frameName, setPoseMatrix, stampSeconds } from "../ros_math.js";
import { disposeObject } from "../shapes.js";
import { MARKER_TYPES, markerObject, markerWarnings } from "../marker_shapes.js";
import { Display, worldPoint } from "./display.js";

const ADD = 0;
const DELETE = 2;
const DELETEALL = 3;
const MAX_MARKERS = 20_000; // per display; more is a runaway publisher, said on the display
const _frameMatrix = new THREE.Matrix4();
const _origin = new THREE.Vector3();

export class MarkerDisplay extends Display {
  static rate = null;
  static queue = 1000;
  static colored = false; // markers carry their own colours

  constructor(...args) {
    super(...args);
    this._incoming = new Map(); // key -> {marker, receivedAt} to draw, or null to delete
    this._clearAll = false;
    this.objects = new Map(); // key -> {holder, marker, frame, stamp, locked, expiresAt, failed}
    this._nextExpiry = Infinity;
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
    return changed;
  }

  _draw(key, marker, receivedAt, ctx) {
    const statusKey = `Marker ${key}`;
    const old = this.objects.get(key);
    try {
      const pose = setPoseMatrix(new THREE.Matrix4(), marker.pose, "pose");
      const shape = markerObject(marker, old ? old.holder.children[0] : null);
      const holder = old ? old.holder : new THREE.Group();
      holder.matrixAutoUpdate = false;
      if (!old) {
        holder.add(shape);
        this.root.add(holder);
      } else if (holder.children[0] !== shape) {
        holder.remove(holder.children[0]);
        holder.add(shape);
      }
      const lifetime = durationSeconds(marker.lifetime);
      const entry = {
        holder,
        pose,
        type: marker.type,
        frame: frameName(marker.header && marker.header.frame_id) || null,
        stamp: stampSeconds(marker.header && marker.header.stamp),
        locked: marker.frame_locked === true,
        expiresAt: lifetime > 0 ? receivedAt + lifetime : Infinity,
        failed: false,
      };
      this.objects.set(key, entry);
      this._nextExpiry = Math.min(this._nextExpiry, entry.expiresAt);
      const warnings = markerWarnings(marker);
      if (entry.frame === null) warnings.push("no frame_id: drawn in the fixed frame");
      if (warnings.length) this.setStatus(statusKey, "warn", warnings.join("; "));
      else this.clearStatus(statusKey);
      this._place(entry, ctx, entry.stamp);
    } catch (error) {
      if (!(error instanceof BadData)) throw error;
      if (old) this._remove(key);
      this.setStatus(statusKey, "error", `${MARKER_TYPES[marker.type] ?? "marker"} skipped: ${error.message}`);
    }
  }

  /** holder.matrix = (frame -> fixed frame) * pose; a frame with no path hides the marker. */
  _place(entry, ctx, stamp) {
    const found = entry.frame === null ? { matrix: _frameMatrix.identity() } : ctx.lookup(entry.frame, stamp, _frameMatrix);
    const statusKey = `Frame ${entry.frame}`;
    if (found.error) {
      entry.failed = true;
      entry.holder.visible = false;
      this.setStatus(statusKey, "error", found.error);
      return;
    }
    entry.failed = false;
    entry.holder.visible = true;
    entry.holder.matrix.multiplyMatrices(found.matrix, entry.pose);
    entry.holder.matrixWorldNeedsUpdate = true;
    if (found.clockNote) this.setStatus(statusKey, "warn", found.clockNote);
    else this.clearStatus(statusKey);
  }

  placeAgain(ctx) {
    let changed = false;
    for (const entry of this.objects.values()) {
      if (ctx.fixedFrameChanged || entry.failed) {
        this._place(entry, ctx, null);
        changed = true;
      }
    }
    return changed;
  }

  /** frame_locked markers follow their frame as it moves. */
  tick(ctx) {
    if (!ctx.tfChanged) return false;
    let changed = false;
    for (const entry of this.objects.values()) {
      if (entry.locked) {
        this._place(entry, ctx, null);
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
    entry.holder.removeFromParent();
    disposeObject(entry.holder);
    this.objects.delete(key);
  }

  drawn() {
    const markers = [];
    for (const [key, entry] of this.objects) {
      if (!entry.holder.visible) continue;
      const [ns, id] = [key.slice(0, key.lastIndexOf("/")), Number(key.slice(key.lastIndexOf("/") + 1))];
      markers.push({ ns, id, type: MARKER_TYPES[entry.type], position: worldPoint(entry.holder, _origin) });
    }
    return { objects: markers.length, markers, points: markers.map((m) => m.position) };
  }

  dispose() {
    for (const key of [...this.objects.keys()]) this._remove(key);
    super.dispose();
  }
}
