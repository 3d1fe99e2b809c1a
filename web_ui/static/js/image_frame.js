// Showing sensor_msgs/Image and CompressedImage in the page, whichever way their bytes came:
// a Uint8Array (a msgpack socket) or base64 text (a JSON one). A raw image is drawn into a
// canvas through ImageData; a JPEG/PNG goes into an <img> through a Blob URL (bytes) or a
// data: URL (base64). The dashboard's camera and the 3D view's image display share it.

export class BadImage extends Error {}

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

/** The bytes of a uint8[] field: as they came (msgpack) or decoded from base64 (JSON). */
export function bytesOf(data, what = "data") {
  if (data instanceof Uint8Array) return data;
  if (typeof data !== "string") throw new BadImage(`${what} is neither bytes nor base64 text`);
  let binary;
  try {
    binary = atob(data);
  } catch {
    throw new BadImage(`${what} is not valid base64`);
  }
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

/** The image type of a CompressedImage's format ("jpeg" or "png"); throws for others. */
export function compressedKind(format) {
  const f = String(format || "").toLowerCase();
  if (f.includes("png")) return "png";
  if (f.includes("jpeg") || f.includes("jpg") || !f) return "jpeg";
  throw new BadImage(`format "${format}" is not jpeg or png`);
}

/** Show a CompressedImage in `img`; returns its kind. Frees the Blob URL of the frame before. */
export function showCompressed(img, msg) {
  const kind = compressedKind(msg.format);
  const data = msg.data;
  if (!data || data.length === 0) throw new BadImage("data is empty");
  const previous = img.dataset.blobUrl;
  if (data instanceof Uint8Array) {
    const url = URL.createObjectURL(new Blob([data], { type: `image/${kind}` }));
    img.dataset.blobUrl = url;
    img.src = url;
  } else if (typeof data === "string") {
    delete img.dataset.blobUrl;
    img.src = `data:image/${kind};base64,${data}`;
  } else {
    throw new BadImage("data is neither bytes nor base64 text");
  }
  if (previous) URL.revokeObjectURL(previous);
  return kind;
}

/** Draw a raw sensor_msgs/Image into `canvas` (resized to fit); returns [width, height]. */
export function drawRaw(canvas, msg) {
  const { width, height, step, encoding } = msg;
  if (!Number.isInteger(width) || !Number.isInteger(height) || width <= 0 || height <= 0) {
    throw new BadImage("width and height must be positive");
  }
  if (width * height > MAX_PIXELS) throw new BadImage(`${width}x${height} is too large to show`);
  const known = ENCODINGS[encoding];
  if (!known) throw new BadImage(`encoding "${encoding}" is not shown (${Object.keys(ENCODINGS).join(", ")})`);
  const [bytesPerPixel, red, green, blue] = known;
  const rowBytes = Number.isInteger(step) && step >= width * bytesPerPixel ? step : width * bytesPerPixel;
  const data = bytesOf(msg.data);
  if (data.length < rowBytes * (height - 1) + width * bytesPerPixel) {
    throw new BadImage(`data has ${data.length} bytes, ${rowBytes * height} expected for ${width}x${height} ${encoding}`);
  }
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
  return [width, height];
}
