// What a viewer does in an OpenCV window, in OpenCV's terms, sent to the program's node: keys as
// the codes cv2.waitKeyEx returns on Linux (GTK's key symbols for the named keys), mouse events
// as cv2.EVENT_* with cv2.EVENT_FLAG_* flags, trackbar moves. Each goes to the node's
// NODE/opencv/input service (skydeck_opencv/srv/WindowInput), one call at a time and in order;
// mouse moves (or a trackbar's moves) in a row behind a call in flight are folded into the
// newest, so a slow link never queues stale positions.

import { callService } from "./api.js";

// cv2.EVENT_*
export const EVENT = {
  MOUSEMOVE: 0, LBUTTONDOWN: 1, RBUTTONDOWN: 2, MBUTTONDOWN: 3, LBUTTONUP: 4, RBUTTONUP: 5, MBUTTONUP: 6,
  LBUTTONDBLCLK: 7, RBUTTONDBLCLK: 8, MBUTTONDBLCLK: 9, MOUSEWHEEL: 10, MOUSEHWHEEL: 11,
};
// cv2.EVENT_FLAG_*: the buttons' bits are the browser's MouseEvent.buttons bits (left 1, right 2, middle 4).
const FLAG = { CTRLKEY: 8, SHIFTKEY: 16, ALTKEY: 32 };
const WHEEL_STEP = 120; // one notch, as OpenCV reports it (getMouseWheelDelta)

// KeyboardEvent.key -> the key code (GTK's keysyms, as waitKeyEx returns them on Linux; waitKey keeps the low byte).
const NAMED_KEYS = {
  Enter: 13, Escape: 27, Backspace: 8, Tab: 9, Delete: 0xffff, Insert: 0xff63,
  Home: 0xff50, ArrowLeft: 0xff51, ArrowUp: 0xff52, ArrowRight: 0xff53, ArrowDown: 0xff54,
  PageUp: 0xff55, PageDown: 0xff56, End: 0xff57,
};
for (let n = 1; n <= 12; n++) NAMED_KEYS[`F${n}`] = 0xffbe + n - 1;

/** The key code of a keydown, or null for keys a window does not get (modifiers alone, dead keys, Ctrl/Meta shortcuts). */
export function keyCode(event) {
  if (event.ctrlKey || event.metaKey) return null; // the browser's shortcuts stay the browser's
  const chars = [...event.key];
  if (chars.length === 1) return chars[0].codePointAt(0);
  return NAMED_KEYS[event.key] ?? null;
}

/** OpenCV's flags for a mouse event: buttons held and modifier keys. */
export function mouseFlags(event) {
  return (event.buttons & 7) | (event.ctrlKey ? FLAG.CTRLKEY : 0) | (event.shiftKey ? FLAG.SHIFTKEY : 0) | (event.altKey ? FLAG.ALTKEY : 0);
}

/** The OpenCV event of a button press (down) or release (up); button 0 left, 1 middle, 2 right. */
export function buttonEvent(button, kind) {
  const base = { down: EVENT.LBUTTONDOWN, up: EVENT.LBUTTONUP, double: EVENT.LBUTTONDBLCLK }[kind];
  const offset = { 0: 0, 2: 1, 1: 2 }[button];
  return offset === undefined ? null : base + offset;
}

/** A wheel event as OpenCV's: [event, flags] with the signed delta in the flags' high 16 bits. */
export function wheelEvent(event) {
  const horizontal = Math.abs(event.deltaX) > Math.abs(event.deltaY);
  const delta = horizontal ? Math.sign(event.deltaX) * WHEEL_STEP : -Math.sign(event.deltaY) * WHEEL_STEP;
  return [horizontal ? EVENT.MOUSEHWHEEL : EVENT.MOUSEWHEEL, (delta << 16) | mouseFlags(event)];
}

/** One node's input service, called one request at a time, in order. */
export class InputQueue {
  constructor(service) {
    this.service = service;
    this.pending = []; // [{request, fold, onAnswer}]
    this.busy = false;
    this.sent = 0;
    this.refused = 0;
    this.last = null; // {kind, message} of the last answer
  }

  /** Queue `request`; when the last one waiting has the same `fold` key, this one replaces it
   * (order is kept: a move is never folded across a click). */
  send(request, { fold = null, onAnswer = () => {} } = {}) {
    const entry = { request, fold, onAnswer };
    const last = this.pending.length - 1;
    if (fold !== null && last >= 0 && this.pending[last].fold === fold) this.pending[last] = entry;
    else this.pending.push(entry);
    this._pump();
  }

  async _pump() {
    if (this.busy) return;
    this.busy = true;
    while (this.pending.length) {
      const { request, onAnswer } = this.pending.shift();
      const answer = await callService(this.service, request);
      this.sent += 1;
      if (answer.kind !== "success") this.refused += 1;
      this.last = { kind: answer.kind, message: answer.message };
      onAnswer(answer);
    }
    this.busy = false;
  }
}
