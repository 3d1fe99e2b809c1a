// sensor_msgs/Image and CompressedImage: a panel over the 3D view, as rviz's Image display.
// Images are heavy, so the topic is read at a low rate and only while the display is shown.
// CompressedImage (jpeg/png) is shown as a data: URL; Image is decoded into a canvas.

import { BadData } from "../ros_math.js";
import { Display } from "./display.js";

// encoding -> [bytes per pixel, offsets of red, green and blue within a pixel]
const ENCODINGS = {
  rgb8: [3, 0, 1, 2],
  rgba8: [4, 0, 1, 2],
  bgr8: [3, 2, 1, 0],
  bgra8: [4, 2, 1, 0],
  mono8: [1, 0, 0, 0],
  "8UC1": [1, 0, 0, 0],
  "8UC3": [3, 2, 1, 0], // OpenCV's default order is BGR
};
const MAX_PIXELS = 4096 * 4096;

function bytesOf(base64, what) {
  if (typeof base64 !== "string") throw new BadData(`${what} is not base64 text`);
  let binary;
  try {
    binary = atob(base64);
  } catch {
    throw new BadData(`${what} is not valid base64`);
  }
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

export class ImageDisplay extends Display {
  static rate = 5;
  static queue = 1;
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
    const format = String(msg.format || "").toLowerCase();
    const mime = format.includes("png") ? "png" : format.includes("jpeg") || format.includes("jpg") || !format ? "jpeg" : null;
    if (!mime) throw new BadData(`format "${msg.format}" is not jpeg or png`);
    if (typeof msg.data !== "string" || !msg.data) throw new BadData("data is empty");
    this.picture.src = `data:image/${mime};base64,${msg.data}`;
    this.caption.textContent = `${this.topic} · ${mime}`;
  }

  _showRaw(msg) {
    const { width, height, step, encoding } = msg;
    if (!Number.isInteger(width) || !Number.isInteger(height) || width <= 0 || height <= 0) {
      throw new BadData("width and height must be positive");
    }
    if (width * height > MAX_PIXELS) throw new BadData(`${width}x${height} is too large to show`);
    const known = ENCODINGS[encoding];
    if (!known) throw new BadData(`encoding "${encoding}" is not shown (${Object.keys(ENCODINGS).join(", ")})`);
    const [bytesPerPixel, red, green, blue] = known;
    const rowBytes = Number.isInteger(step) && step >= width * bytesPerPixel ? step : width * bytesPerPixel;
    const data = bytesOf(msg.data, "data");
    if (data.length < rowBytes * (height - 1) + width * bytesPerPixel) {
      throw new BadData(`data has ${data.length} bytes, ${rowBytes * height} expected for ${width}x${height} ${encoding}`);
    }
    const canvas = this.picture;
    if (canvas.width !== width || canvas.height !== height) {
      canvas.width = width;
      canvas.height = height;
    }
    const ctx = canvas.getContext("2d");
    const image = ctx.createImageData(width, height);
    const out = image.data;
    for (let y = 0; y < height; y++) {
      for (let x = 0, i = y * rowBytes, o = y * width * 4; x < width; x++, i += bytesPerPixel, o += 4) {
        out[o] = data[i + red];
        out[o + 1] = data[i + green];
        out[o + 2] = data[i + blue];
        out[o + 3] = 255;
      }
    }
    ctx.putImageData(image, 0, 0);
    this.size = [width, height];
    this.caption.textContent = `${this.topic} · ${width}x${height} ${encoding}`;
  }

  drawn() {
    return { objects: this.frames && this.visible ? 1 : 0, points: [], frames: this.frames, size: this.size };
  }

  dispose() {
    this.figure.remove();
    super.dispose();
  }
}
