// sensor_msgs/Image and CompressedImage: a panel over the 3D view, as rviz's Image display.
// Images are heavy, so the topic is read at a low rate and only while the display is shown.
// Read in msgpack, so the bytes come as bytes (image_frame.js draws them).

import { BadImage, drawRaw, showCompressed } from "../../image_frame.js";
import { BadData } from "../ros_math.js";
import { Display } from "./display.js";

export class ImageDisplay extends Display {
  static rate = 5;
  static queue = 1;
  static encoding = "msgpack";
  static colored = false;

  constructor(topic, type, settings, env) {
    super(topic, type, settings, env);
    this.figure = document.createElement("figure");
    this.figure.className = "view3d-image";
    this.figure.dataset.topic = topic;
    this.compressed = type.endsWith("/CompressedImage");
    this.picture = document.createElement(this.compressed ? "img" : "canvas");
    this.picture.alt = topic;
    this.caption = document.createElement("figcaption");
    this.caption.textContent = `waiting for ${topic}…`;
    this.figure.append(this.picture, this.caption);
    this.figure.hidden = !this.visible;
    env.images.append(this.figure);
    this.frames = 0;
    this.size = null;
  }

  start() {
    if (this.visible) super.start();
  }

  setVisible(visible) {
    super.setVisible(visible);
    this.figure.hidden = !visible;
    if (visible) super.start();
    else this.stop(); // nobody looks: read nothing
  }

  apply(msg) {
    if (this.compressed) this._showCompressed(msg);
    else this._showRaw(msg);
    this.frames += 1;
  }

  _showCompressed(msg) {
    const kind = asBadData(() => showCompressed(this.picture, msg));
    this.caption.textContent = `${this.topic} · ${kind}`;
  }

  _showRaw(msg) {
    this.size = asBadData(() => drawRaw(this.picture, msg));
    this.caption.textContent = `${this.topic} · ${this.size[0]}x${this.size[1]} ${msg.encoding}`;
  }

  drawn() {
    return { objects: this.frames && this.visible ? 1 : 0, points: [], frames: this.frames, size: this.size };
  }

  dispose() {
    if (this.picture.dataset.blobUrl) URL.revokeObjectURL(this.picture.dataset.blobUrl);
    this.figure.remove();
    super.dispose();
  }
}

/** The view reports a display's bad data as BadData. */
function asBadData(show) {
  try {
    return show();
  } catch (error) {
    if (error instanceof BadImage) throw new BadData(error.message);
    throw error;
  }
}
