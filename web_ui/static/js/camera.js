// The simulator's camera over the map: subscribed (at 5 Hz) only while shown and the tab is
// visible, because the simulator renders only while someone reads /simulator/camera.

import { TopicSocket } from "./api.js";

const TOPIC = "/simulator/camera";

export class CameraView {
  constructor({ toggle, figure, image, caption }) {
    this.toggle = toggle;
    this.figure = figure;
    this.image = image;
    this.caption = caption;
    this.socket = null;
    this.frames = 0;
    toggle.addEventListener("change", () => this._update());
    document.addEventListener("visibilitychange", () => this._update());
  }

  _update() {
    const wanted = this.toggle.checked && document.visibilityState === "visible";
    this.figure.hidden = !this.toggle.checked;
    if (wanted && !this.socket) {
      this.caption.textContent = `waiting for ${TOPIC}…`;
      this.socket = new TopicSocket(TOPIC, {
        rate: 5,
        onMessage: (msg) => this._show(msg),
        onStatus: ({ state }) => {
          if (state === "closed") this.caption.textContent = `${TOPIC}: reconnecting…`;
        },
      }).open();
    } else if (!wanted && this.socket) {
      this.socket.close();
      this.socket = null;
    }
  }

  _show(msg) {
    if (typeof msg.data !== "string" || !msg.data) return;
    const format = String(msg.format || "jpeg").toLowerCase().includes("png") ? "png" : "jpeg";
    this.image.src = `data:image/${format};base64,${msg.data}`;
    this.frames += 1;
    this.caption.textContent = `${TOPIC} · ${format}`;
  }
}
