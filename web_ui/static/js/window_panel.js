// One OpenCV window of a program as a panel: its image (the window's topic, a JPEG
// CompressedImage, read in msgpack only while the panel is watched), a slider per trackbar, and
// the viewer's keys and mouse sent back in OpenCV's terms (window_input.js). Mouse positions are
// image pixels, however large the image is drawn.

import { TopicSocket } from "./api.js";
import { BadImage, showCompressed } from "./image_frame.js";
import { buttonEvent, EVENT, keyCode, mouseFlags, wheelEvent } from "./window_input.js";

const RATE_HZ = 15; // the program sends at most 15 a second too
const SLIDER_QUIET_MS = 800; // a slider the viewer moved this recently is not moved by the program's echo

function element(tag, className, text) {
  const el = document.createElement(tag);
  if (className) el.className = className;
  if (text !== undefined) el.textContent = text;
  return el;
}

export class WindowPanel {
  /** `node`: the program's node; `description`: its skydeck_opencv/msg/Window; `input`: the node's InputQueue. */
  constructor(node, description, input) {
    this.node = node;
    this.input = input;
    this.description = null;
    this.frames = 0;
    this.error = "";
    this.socket = null;
    this.sliders = new Map(); // trackbar name -> {input, output, movedAt}
    this.el = element("section", "cv-window");
    this.el.tabIndex = 0; // focus it to type keys into the window
    const head = element("header", "cv-head");
    this.titleEl = element("strong", "cv-title");
    head.append(this.titleEl, element("span", "dim small-text", node));
    this.image = element("img", "cv-image");
    this.image.alt = "OpenCV window";
    this.image.draggable = false;
    this.caption = element("div", "cv-caption mono dim");
    this.trackbarsEl = element("div", "cv-trackbars");
    this.result = element("div", "result");
    this.result.dataset.kind = "none";
    this.el.append(head, this.image, this.caption, this.trackbarsEl, this.result);
    this._listen();
    this.update(description);
  }

  get name() {
    return this.description.name;
  }

  update(description) {
    const before = this.description;
    this.description = description;
    this.el.dataset.window = description.name;
    this.el.dataset.topic = description.topic;
    this.titleEl.textContent = description.title || description.name;
    this.image.style.width = description.display_width ? `${description.display_width}px` : "";
    this.image.classList.toggle("clickable", description.mouse);
    if (!this.frames) this.caption.textContent = `waiting for ${description.topic}…`;
    if (before && before.topic !== description.topic && this.socket) {
      this.setWatched(false);
      this.setWatched(true);
    }
    this._updateTrackbars(description.trackbars);
  }

  /** Read the window's images while watched (the program encodes only while someone reads). */
  setWatched(watched) {
    if (watched === Boolean(this.socket)) return;
    if (!watched) {
      this.socket.close();
      this.socket = null;
      return;
    }
    this.socket = new TopicSocket(this.description.topic, {
      rate: RATE_HZ,
      queue: 1,
      encoding: "msgpack",
      onMessage: (msg) => this._show(msg),
    }).open();
  }

  close() {
    this.setWatched(false);
    this.el.remove();
  }

  /** Client (page) coordinates of image pixel (x, y): where a click lands on that pixel. A mouse
   * event's clientX/Y are whole CSS pixels, so the first whole one inside the pixel, if any. */
  clientPoint(x, y) {
    const rect = this.image.getBoundingClientRect();
    const scaleX = rect.width / (this.image.naturalWidth || this.description.width);
    const scaleY = rect.height / (this.image.naturalHeight || this.description.height);
    const inside = (start, size) => (Math.ceil(start) < start + size ? Math.ceil(start) : start + size / 2);
    return { x: inside(rect.left + x * scaleX, scaleX), y: inside(rect.top + y * scaleY, scaleY) };
  }

  snapshot() {
    const d = this.description;
    return {
      node: this.node,
      name: d.name,
      title: d.title,
      topic: d.topic,
      width: d.width,
      height: d.height,
      mouse: d.mouse,
      frames: this.frames,
      error: this.error,
      shown: [this.image.naturalWidth, this.image.naturalHeight],
      trackbars: d.trackbars.map((t) => ({ ...t, slider: Number(this.sliders.get(t.name)?.input.value) })),
    };
  }

  _show(msg) {
    try {
      const kind = showCompressed(this.image, msg);
      this.caption.textContent = `${this.description.topic} · ${this.description.width}x${this.description.height} ${kind}`;
      this.error = "";
    } catch (error) {
      if (!(error instanceof BadImage)) throw error;
      this.error = error.message;
      this.caption.textContent = `${this.description.topic}: ${error.message}`;
      return;
    }
    this.frames += 1;
  }

  _updateTrackbars(trackbars) {
    const names = new Set(trackbars.map((t) => t.name));
    for (const [name, slider] of this.sliders) {
      if (!names.has(name)) {
        slider.row.remove();
        this.sliders.delete(name);
      }
    }
    trackbars.forEach((trackbar, index) => {
      let slider = this.sliders.get(trackbar.name);
      if (!slider) {
        slider = this._slider(trackbar.name);
        this.sliders.set(trackbar.name, slider);
      }
      // In the program's order; a row already in place is not moved (that would end a drag).
      const here = this.trackbarsEl.children[index] || null;
      if (here !== slider.row) this.trackbarsEl.insertBefore(slider.row, here);
      slider.input.min = String(trackbar.minimum);
      slider.input.max = String(trackbar.maximum);
      if (performance.now() - slider.movedAt > SLIDER_QUIET_MS) {
        slider.input.value = String(trackbar.value);
        slider.output.textContent = String(trackbar.value);
      }
    });
  }

  _slider(name) {
    const row = element("label", "cv-trackbar");
    const input = element("input");
    input.type = "range";
    input.step = "1";
    input.dataset.trackbar = name;
    const output = element("output", "mono");
    row.append(element("span", "cv-trackbar-name", name), input, output);
    const slider = { row, input, output, movedAt: -Infinity };
    input.addEventListener("input", () => {
      slider.movedAt = performance.now();
      output.textContent = input.value;
      this._send({ kind: "trackbar", trackbar: name, value: Number(input.value) }, `trackbar:${this.name}:${name}`);
    });
    return slider;
  }

  _listen() {
    const image = this.image;
    image.addEventListener("mousedown", (event) => {
      this.el.focus({ preventScroll: true }); // keys typed next go to this window
      const opencv = buttonEvent(event.button, "down");
      if (opencv === null) return;
      event.preventDefault();
      this._mouse(event, opencv);
      if (event.detail === 2) this._mouse(event, buttonEvent(event.button, "double"));
    });
    image.addEventListener("mouseup", (event) => {
      const opencv = buttonEvent(event.button, "up");
      if (opencv !== null) this._mouse(event, opencv);
    });
    image.addEventListener("mousemove", (event) => this._mouse(event, EVENT.MOUSEMOVE));
    image.addEventListener("contextmenu", (event) => event.preventDefault()); // right clicks are the program's
    image.addEventListener("wheel", (event) => {
      if (!this.description.mouse) return;
      event.preventDefault();
      const [opencv, flags] = wheelEvent(event);
      this._mouse(event, opencv, flags);
    }, { passive: false });
    this.el.addEventListener("keydown", (event) => {
      if (event.target instanceof HTMLInputElement) return; // a slider's own arrow keys
      const key = keyCode(event);
      if (key === null) return;
      event.preventDefault();
      event.stopPropagation(); // not teleop's
      this._send({ kind: "key", key });
    });
  }

  _mouse(event, opencv, flags = mouseFlags(event)) {
    if (!this.description.mouse || !this.image.naturalWidth) return; // no callback listens, or no image yet
    const rect = this.image.getBoundingClientRect();
    const x = Math.floor(((event.clientX - rect.left) * this.image.naturalWidth) / rect.width);
    const y = Math.floor(((event.clientY - rect.top) * this.image.naturalHeight) / rect.height);
    const fold = opencv === EVENT.MOUSEMOVE ? `move:${this.name}` : null;
    this._send({ kind: "mouse", event: opencv, x, y, flags }, fold);
  }

  _send(fields, fold = null) {
    this.input.send({ window: this.name, ...fields }, {
      fold,
      onAnswer: (answer) => {
        if (answer.kind === "success") {
          this.result.dataset.kind = "none";
          this.result.textContent = "";
        } else {
          this.result.dataset.kind = answer.kind;
          this.result.textContent = answer.message;
        }
      },
    });
  }
}
