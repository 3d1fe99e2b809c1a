// Talking to the core (same origin only): fetch with the token, service calls classified for
// display, and topic sockets that reconnect by themselves with backoff.

import { getToken, requestToken } from "./auth.js";
import { CLOSE } from "./config.js";
import { decode as decodeMsgpack } from "./msgpack.js";

const TOKEN_HINT = "token";

/** fetch() on the core, retried once after asking for a token when it answers 401. */
export async function apiFetch(path, options = {}, { userAction = false } = {}) {
  for (let attempt = 0; ; attempt++) {
    const headers = new Headers(options.headers || {});
    const token = getToken();
    if (token) headers.set("Authorization", `Bearer ${token}`);
    const response = await fetch(path, { ...options, headers });
    if (response.status !== 401 || attempt > 0) return response;
    const detail = await detailOf(response);
    if (!(await requestToken(detail || "The core needs an access token.", { userAction }))) return response;
  }
}

async function detailOf(response) {
  try {
    const body = await response.clone().json();
    if (typeof body.detail === "string") return body.detail;
    return JSON.stringify(body.detail ?? body);
  } catch {
    return response.statusText;
  }
}

/** GET a JSON document from the core; throws an Error naming the status and detail. */
export async function getJson(path) {
  const response = await apiFetch(path);
  if (!response.ok) throw new Error(`${response.status}: ${await detailOf(response)}`);
  return response.json();
}

/**
 * Call a service through the gateway. Never throws; the answer is classified:
 * kind "success" (200, success true), "refused" (200, success false), "error" (HTTP error or
 * no core), with a message to show and the HTTP status (0 when the core was not reached).
 */
export async function callService(name, request = {}) {
  let response;
  try {
    response = await apiFetch(
      name,
      { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(request) },
      { userAction: true },
    );
  } catch (error) {
    return { kind: "error", status: 0, message: `core unreachable at ${location.origin}: ${error.message}`, body: null };
  }
  if (!response.ok) {
    return { kind: "error", status: response.status, message: await detailOf(response), body: null };
  }
  let body = null;
  try {
    body = await response.json();
  } catch {
    return { kind: "error", status: response.status, message: "the answer was not JSON", body: null };
  }
  const success = body && body.success !== false;
  const message = body && typeof body.message === "string" ? body.message : JSON.stringify(body);
  return { kind: success ? "success" : "refused", status: response.status, message, body };
}

/** ws://HOST/TOPIC?options for the page's own host. */
export function topicUrl(topic, params = {}) {
  const scheme = location.protocol === "https:" ? "wss:" : "ws:";
  const query = new URLSearchParams();
  for (const [key, value] of Object.entries(params)) {
    if (value !== undefined && value !== null && value !== "") query.set(key, String(value));
  }
  const token = getToken();
  if (token) query.set("token", token);
  const path = topic.split("/").map(encodeURIComponent).join("/");
  const qs = query.toString();
  return `${scheme}//${location.host}${path}${qs ? `?${qs}` : ""}`;
}

const sockets = new Set(); // every live TopicSocket, for the debug hook

// Whether the page's token may read a topic (access.js, in a class): a socket that may not
// waits, "fenced", instead of being refused by the core again and again.
let readable = () => true;
const fenced = new Set();

/** Use `predicate(topic)` to decide what sockets may read; fenced sockets it now allows open. */
export function setReadable(predicate) {
  readable = predicate;
  for (const socket of [...fenced]) {
    if (!readable(socket.topic)) continue;
    fenced.delete(socket);
    socket._wanted = false;
    socket.open();
  }
}

// The topics someone publishes, from the latest graph (null before the first): a socket opened
// with openWhenPublished() waits until its topic is one of them.
let publishedTopics = null;
const waitingForPublisher = new Set();

/** Each new graph (GET /api/graph): the sockets waiting for a publisher of their topic open. */
export function updatePublished(graph) {
  publishedTopics = new Set(graph.topics.filter((t) => t.publishers.length > 0).map((t) => t.name));
  for (const socket of [...waitingForPublisher]) {
    if (publishedTopics.has(socket.topic)) {
      waitingForPublisher.delete(socket);
      socket.open();
    }
  }
}

export function socketStates() {
  return [...sockets].map((s) => ({
    topic: s.topic,
    state: s.state,
    messages: s.messageCount,
    encoding: s.binary ? "msgpack" : "json",
    binaryFrames: s.binaryFrames,
  }));
}

/**
 * One topic as a stream: onMessage(msg) per frame; publish(msg) sends a frame of the topic's
 * type on the same socket (never sent back to it). mode "publish" reads nothing, "subscribe"
 * may not publish. encoding "msgpack" reads binary frames (byte arrays arrive as Uint8Array,
 * not base64: for images); such a socket only reads. Reconnects with exponential backoff (0.5 s .. 10 s) until close().
 * onStatus({state, code, reason}) reports "connecting" | "open" | "closed" | "stopped",
 * "waiting" for a socket opened with openWhenPublished() whose topic nobody publishes yet, and
 * "fenced" for one reading a topic the page's token may not read (setReadable).
 */
export class TopicSocket {
  constructor(topic, { rate, queue, type, mode, encoding, onMessage, onStatus, onError } = {}) {
    this.topic = topic;
    this.binary = encoding === "msgpack";
    this.params = { rate, queue, type, mode: this.binary ? "subscribe" : mode, encoding };
    this.onMessage = onMessage || (() => {});
    this.onStatus = onStatus || (() => {});
    this.onError = onError || (() => {});
    this.state = "stopped";
    this.messageCount = 0;
    this.binaryFrames = 0; // frames that came as msgpack: the encoding the core agreed to
    this.lastMessageAt = 0;
    this._ws = null;
    this._timer = null;
    this._backoffMs = 500;
    this._wanted = false;
  }

  open() {
    if (this._wanted) return this;
    this._wanted = true;
    sockets.add(this);
    if (this.params.mode !== "publish" && !readable(this.topic)) {
      fenced.add(this);
      this._setState("fenced");
      return this;
    }
    this._connect();
    return this;
  }

  /**
   * open() once someone publishes the topic (the graph lists a publisher of it). Reading a name
   * nobody publishes makes the core subscribe to it, so `skydeck topic list -t` would show the
   * dashboard's guess as a topic with no type; a name of another world never opens. State
   * "waiting" meanwhile.
   */
  openWhenPublished() {
    if (this._wanted || waitingForPublisher.has(this)) return this;
    if (publishedTopics && publishedTopics.has(this.topic)) return this.open();
    waitingForPublisher.add(this);
    sockets.add(this);
    this._setState("waiting");
    return this;
  }

  close() {
    this._wanted = false;
    waitingForPublisher.delete(this);
    fenced.delete(this);
    sockets.delete(this);
    clearTimeout(this._timer);
    if (this._ws) {
      this._ws.onclose = null;
      this._ws.close(1000);
      this._ws = null;
    }
    this._setState("stopped");
  }

  /** Send one message; false when the socket is not open right now (the message is dropped). */
  publish(msg) {
    if (this.binary || !this._ws || this._ws.readyState !== WebSocket.OPEN) return false;
    this._ws.send(JSON.stringify(msg));
    return true;
  }

  get isOpen() {
    return this.state === "open";
  }

  _setState(state, code = 0, reason = "") {
    this.state = state;
    this.onStatus({ state, code, reason });
  }

  _connect() {
    if (!this._wanted) return;
    this._setState("connecting");
    let ws;
    try {
      ws = new WebSocket(topicUrl(this.topic, this.params));
    } catch (error) {
      this.onError(`${this.topic}: ${error.message}`);
      this._retry(10_000);
      return;
    }
    this._ws = ws;
    if (this.binary) ws.binaryType = "arraybuffer";
    ws.onopen = () => {
      this._backoffMs = 500;
      this._setState("open");
    };
    ws.onmessage = (event) => {
      let msg;
      try {
        msg = typeof event.data === "string" ? JSON.parse(event.data) : decodeMsgpack(event.data);
      } catch (error) {
        this.onError(`${this.topic}: a frame that does not decode: ${error.message}`);
        return;
      }
      this._backoffMs = 500;
      this.messageCount += 1;
      if (typeof event.data !== "string") this.binaryFrames += 1;
      this.lastMessageAt = performance.now();
      this.onMessage(msg);
    };
    ws.onclose = (event) => this._closed(event.code, event.reason);
  }

  async _closed(code, reason) {
    this._ws = null;
    if (!this._wanted) return;
    this._setState("closed", code, reason);
    if (code === CLOSE.policy && reason.toLowerCase().includes(TOKEN_HINT)) {
      this.onError(`${this.topic}: ${reason}`);
      const given = await requestToken(reason); // only publishing needs it: a user action
      this._retry(given ? 0 : 10_000);
    } else if ([CLOSE.invalid_frame, CLOSE.policy, CLOSE.unsupported, CLOSE.too_big].includes(code)) {
      // The core refused what we sent or asked for: say why, then read the topic again.
      this.onError(`${this.topic} closed (${code}): ${reason}`);
      this._retry(code === CLOSE.policy ? 5000 : 200);
    } else {
      this._retry();
    }
  }

  _retry(delayMs) {
    clearTimeout(this._timer);
    const delay = delayMs ?? this._backoffMs;
    if (delayMs === undefined) this._backoffMs = Math.min(this._backoffMs * 2, 10_000);
    this._timer = setTimeout(() => this._connect(), delay);
  }
}
