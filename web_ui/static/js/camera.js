// The simulator's camera over the map, JPEG (/simulator/camera) or raw rgb8
// (/simulator/camera/image_raw): read at 5 Hz in msgpack (bytes as bytes, no base64) only while
// shown and the tab is visible, because the simulator renders only while someone reads it.
// The socket's rate= thins this reader alone: other viewers keep the simulator's rate.

import { TopicSocket } from "./api.js";
import { BadImage, drawRaw, showCompressed } from "./image_frame.js";

export const CAMERA_TOPICS = { jpeg: "/simulator/camera", raw: "/simulator/camera/image_raw" };
const RATE_HZ = 5;

export class CameraView {
  constructor({ toggle, kind, figure, image, canvas, caption }) {
    this.toggle = toggle;
    this.kind = kind; // a <select>: "jpeg" or "raw"
    this.figure = figure;
    this.image = image;
    this.canvas = canvas;
    this.caption = caption;
    this.socket = null;
    this.topic = null;
    this.frames = 0;
    this.error = "";
    toggle.addEventListener("change", () => this._update());
    kind.addEventListener("change", () => this._update());
    document.addEventListener("visibilitychange", () => this._update());
  }

  _update() {
    const wanted = this.toggle.checked && document.visibilityState === "visible";
    const topic = wanted ? CAMERA_TOPICS[this.kind.value] || CAMERA_TOPICS.jpeg : null;
    this.figure.hidden = !this.toggle.checked;
    if (topic === this.topic) return;
    if (this.socket) this.socket.close();
    this.socket = null;
    this.topic = topic;
    if (!topic) return;
    const raw = topic === CAMERA_TOPICS.raw;
    this.image.hidden = raw;
    this.canvas.hidden = !raw;
    this.caption.textContent = `waiting for ${topic}…`;
    this.socket = new TopicSocket(topic, {
      rate: RATE_HZ,
      queue: 1,
      encoding: "msgpack",
      onMessage: (msg) => this._show(msg, raw),
      onStatus: ({ state }) => {
        if (state === "closed") this.caption.textContent = `${topic}: reconnecting…`;
        else if (state === "waiting") this.caption.textContent = `nobody publishes ${topic} yet: is the simulator running?`;
      },
    }).openWhenPublished();
  }

  _show(msg, raw) {
    try {
      if (raw) {
        const [width, height] = drawRaw(this.canvas, msg);
        this.caption.textContent = `${this.topic} · ${width}x${height} ${msg.encoding}`;
      } else {
        this.caption.textContent = `${this.topic} · ${showCompressed(this.image, msg)}`;
      }
    } catch (error) {
      if (!(error instanceof BadImage)) throw error;
      this.error = error.message;
      this.caption.textContent = `${this.topic}: ${error.message}`;
      return;
    }
    this.frames += 1;
  }
}
