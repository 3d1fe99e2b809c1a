// A msgpack decoder (the spec: github.com/msgpack/msgpack/blob/master/spec.md) for the binary
// frames the core sends on `?encoding=msgpack` sockets: maps become plain objects, binary becomes
// a Uint8Array viewing the frame (no copy), strings are UTF-8. Every length is checked against
// what is left of the frame, so a truncated or hostile frame throws instead of allocating.
// Extension types are not used by Skydeck and are refused.

const utf8 = new TextDecoder("utf-8", { fatal: true });

export class MsgpackError extends Error {}

/** The one value in `frame` (ArrayBuffer or Uint8Array); throws MsgpackError when malformed. */
export function decode(frame) {
  const bytes = frame instanceof Uint8Array ? frame : new Uint8Array(frame);
  const reader = new Reader(bytes);
  const value = reader.value(0);
  if (reader.at !== bytes.length) throw new MsgpackError(`${bytes.length - reader.at} bytes after the value`);
  return value;
}

const MAX_DEPTH = 64;

class Reader {
  constructor(bytes) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.at = 0;
  }

  take(n) {
    if (this.at + n > this.bytes.length) {
      throw new MsgpackError(`truncated: ${n} bytes needed at ${this.at}, ${this.bytes.length - this.at} left`);
    }
    const start = this.at;
    this.at += n;
    return start;
  }

  u8() { return this.view.getUint8(this.take(1)); }
  u16() { return this.view.getUint16(this.take(2)); }
  u32() { return this.view.getUint32(this.take(4)); }

  value(depth) {
    if (depth > MAX_DEPTH) throw new MsgpackError(`nested deeper than ${MAX_DEPTH}`);
    const type = this.u8();
    if (type <= 0x7f) return type; // positive fixint
    if (type >= 0xe0) return type - 0x100; // negative fixint
    if (type >= 0x80 && type <= 0x8f) return this.map(type & 0x0f, depth);
    if (type >= 0x90 && type <= 0x9f) return this.array(type & 0x0f, depth);
    if (type >= 0xa0 && type <= 0xbf) return this.str(type & 0x1f);
    const v = this.view;
    switch (type) {
      case 0xc0: return null;
      case 0xc2: return false;
      case 0xc3: return true;
      case 0xc4: return this.bin(this.u8());
      case 0xc5: return this.bin(this.u16());
      case 0xc6: return this.bin(this.u32());
      case 0xca: return v.getFloat32(this.take(4));
      case 0xcb: return v.getFloat64(this.take(8));
      case 0xcc: return this.u8();
      case 0xcd: return this.u16();
      case 0xce: return this.u32();
      case 0xcf: return bigToNumber(v.getBigUint64(this.take(8)));
      case 0xd0: return v.getInt8(this.take(1));
      case 0xd1: return v.getInt16(this.take(2));
      case 0xd2: return v.getInt32(this.take(4));
      case 0xd3: return bigToNumber(v.getBigInt64(this.take(8)));
      case 0xd9: return this.str(this.u8());
      case 0xda: return this.str(this.u16());
      case 0xdb: return this.str(this.u32());
      case 0xdc: return this.array(this.u16(), depth);
      case 0xdd: return this.array(this.u32(), depth);
      case 0xde: return this.map(this.u16(), depth);
      case 0xdf: return this.map(this.u32(), depth);
      default: throw new MsgpackError(`type 0x${type.toString(16)} at ${this.at - 1} is not supported`);
    }
  }

  bin(n) {
    const start = this.take(n);
    return this.bytes.subarray(start, start + n);
  }

  str(n) {
    const start = this.take(n);
    try {
      return utf8.decode(this.bytes.subarray(start, start + n));
    } catch {
      throw new MsgpackError(`a string at ${start} is not UTF-8`);
    }
  }

  array(n, depth) {
    this.fits(n);
    const out = new Array(n);
    for (let i = 0; i < n; i++) out[i] = this.value(depth + 1);
    return out;
  }

  map(n, depth) {
    this.fits(2 * n);
    const out = {};
    for (let i = 0; i < n; i++) {
      const key = this.value(depth + 1);
      if (typeof key !== "string" && typeof key !== "number") throw new MsgpackError("a map key is not a string or number");
      const value = this.value(depth + 1);
      if (key === "__proto__") Object.defineProperty(out, key, { value, enumerable: true, writable: true, configurable: true });
      else out[key] = value;
    }
    return out;
  }

  /** Every element takes at least a byte: a count larger than what is left is a lie (a bomb). */
  fits(count) {
    if (count > this.bytes.length - this.at) {
      throw new MsgpackError(`a container of ${count} elements in ${this.bytes.length - this.at} bytes`);
    }
  }
}

function bigToNumber(big) {
  const n = Number(big);
  if (!Number.isSafeInteger(n)) throw new MsgpackError(`integer ${big} does not fit a JavaScript number`);
  return n;
}
