// "Add by topic", like rviz: any topic of a drawable type becomes a coloured layer on the map,
// showing its latest message. The choice survives a reload (localStorage).

import { TopicSocket } from "./api.js";
import { yawOf } from "./geometry.js";

const STORAGE_KEY = "skydeck.layers";
const PALETTE = ["#ff5fd2", "#4dd0e1", "#ffd54f", "#aed581", "#ff8a65", "#b39ddb"];

// How to find points in each drawable type; `shape` says how the map joins them.
const EXTRACTORS = {
  "geometry_msgs/msg/PointStamped": { shape: "points", points: (m) => [m.point] },
  "geometry_msgs/msg/Point": { shape: "points", points: (m) => [m] },
  "geometry_msgs/msg/Point32": { shape: "points", points: (m) => [m] },
  "geometry_msgs/msg/PoseStamped": { shape: "poses", points: (m) => [pose(m.pose)] },
  "geometry_msgs/msg/Pose": { shape: "poses", points: (m) => [pose(m)] },
  "geometry_msgs/msg/PoseArray": { shape: "poses", points: (m) => (m.poses || []).map(pose) },
  "geometry_msgs/msg/Polygon": { shape: "polygon", points: (m) => m.points || [] },
  "geometry_msgs/msg/PolygonStamped": { shape: "polygon", points: (m) => (m.polygon ? m.polygon.points : []) },
};

function pose(p) {
  return { ...p.position, yaw: yawOf(p.orientation) };
}

export function isDrawable(type) {
  return Object.hasOwn(EXTRACTORS, type);
}

export class Layers extends EventTarget {
  constructor() {
    super();
    this._layers = new Map(); // topic -> layer
  }

  list() {
    return [...this._layers.values()];
  }

  has(topic) {
    return this._layers.has(topic);
  }

  nextColor() {
    return PALETTE[this._layers.size % PALETTE.length];
  }

  add(topic, type, color) {
    if (this._layers.has(topic) || !isDrawable(type)) return null;
    const extractor = EXTRACTORS[type];
    const layer = { topic, type, color, shape: extractor.shape, points: [], frame: "", messages: 0, socket: null };
    layer.socket = new TopicSocket(topic, {
      rate: 10,
      onMessage: (msg) => {
        try {
          layer.points = extractor.points(msg).filter((p) => p && Number.isFinite(p.x) && Number.isFinite(p.y));
        } catch {
          layer.points = [];
        }
        layer.frame = msg.header ? msg.header.frame_id : "";
        layer.messages += 1;
        this._changed();
      },
    }).openWhenPublished(); // a layer kept from another run waits for its topic
    this._layers.set(topic, layer);
    this._save();
    this._changed();
    return layer;
  }

  remove(topic) {
    const layer = this._layers.get(topic);
    if (!layer) return;
    layer.socket.close();
    this._layers.delete(topic);
    this._save();
    this._changed();
  }

  setColor(topic, color) {
    const layer = this._layers.get(topic);
    if (!layer) return;
    layer.color = color;
    this._save();
  }

  /** Re-add the layers of the last visit. */
  restore() {
    let saved = [];
    try {
      saved = JSON.parse(localStorage.getItem(STORAGE_KEY) || "[]");
    } catch {
      saved = [];
    }
    for (const { topic, type, color } of Array.isArray(saved) ? saved : []) {
      if (typeof topic === "string" && isDrawable(type)) this.add(topic, type, color || this.nextColor());
    }
  }

  /** Plain data for the debug hook. */
  snapshot() {
    return this.list().map(({ topic, type, color, frame, messages, points }) => ({
      topic,
      type,
      color,
      frame,
      messages,
      count: points.length,
      points: points.map((p) => ({ x: p.x, y: p.y, z: p.z ?? 0 })),
    }));
  }

  _save() {
    const data = this.list().map(({ topic, type, color }) => ({ topic, type, color }));
    localStorage.setItem(STORAGE_KEY, JSON.stringify(data));
  }

  _changed() {
    this.dispatchEvent(new Event("change"));
  }
}
