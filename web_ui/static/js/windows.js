// The Windows tab: the OpenCV windows of programs that `skydeck run` started without a display
// (cv2.imshow, trackbars, mouse callbacks, waitKey; docs/ros.md, "OpenCV windows"). A node with
// windows publishes NODE/opencv/windows (skydeck_opencv/msg/Windows, latched), found in the
// graph by its type; each window there is a panel (window_panel.js) whose images are read only
// while the tab is shown and the page visible. Input goes to NODE/opencv/input.

import { TopicSocket } from "./api.js";
import { InputQueue } from "./window_input.js";
import { WindowPanel } from "./window_panel.js";

export const WINDOWS_TYPE = "skydeck_opencv/msg/Windows";
const DESCRIPTION = "/opencv/windows";
const INPUT = "/opencv/input";

export class WindowsView {
  /** `tab`: the tab's button (its label counts the windows); `list`: where panels go; `empty`: the note shown without any. */
  constructor({ tab, list, empty }) {
    this.tab = tab;
    this.list = list;
    this.empty = empty;
    this.shown = false;
    this.nodes = new Map(); // description topic -> {node, socket, input, panels: Map(image topic -> WindowPanel)}
    document.addEventListener("visibilitychange", () => this._watch());
    this._render();
  }

  /** Follow the nodes that have windows, as the graph lists them. */
  updateGraph(graph) {
    const topics = new Set(
      graph.topics.filter((t) => t.type === WINDOWS_TYPE && t.publishers.length && t.name.endsWith(DESCRIPTION)).map((t) => t.name),
    );
    for (const [topic, entry] of this.nodes) {
      if (topics.has(topic)) continue;
      entry.socket.close();
      for (const panel of entry.panels.values()) panel.close();
      this.nodes.delete(topic);
    }
    for (const topic of topics) {
      if (this.nodes.has(topic)) continue;
      const node = topic.slice(0, -DESCRIPTION.length);
      const entry = { node, input: new InputQueue(node + INPUT), panels: new Map(), socket: null };
      entry.socket = new TopicSocket(topic, { queue: 1, onMessage: (msg) => this._describe(entry, msg) }).open();
      this.nodes.set(topic, entry);
    }
    this._render();
  }

  setShown(shown) {
    this.shown = shown;
    this._watch();
  }

  panels() {
    return [...this.nodes.values()].flatMap((entry) => [...entry.panels.values()]);
  }

  /** The panel showing `topic` (a window's image topic), or null. */
  panel(topic) {
    return this.panels().find((p) => p.description.topic === topic) || null;
  }

  snapshot() {
    return this.panels().map((panel) => {
      const { sent, refused, last, pending } = panel.input;
      return { ...panel.snapshot(), input: { sent, refused, last, pending: pending.length } };
    });
  }

  _describe(entry, msg) {
    const seen = new Set();
    for (const description of msg.windows || []) {
      seen.add(description.topic);
      const panel = entry.panels.get(description.topic);
      if (panel) panel.update(description);
      else entry.panels.set(description.topic, new WindowPanel(entry.node, description, entry.input));
    }
    for (const [topic, panel] of entry.panels) {
      if (seen.has(topic)) continue;
      panel.close();
      entry.panels.delete(topic);
    }
    this._render();
  }

  _render() {
    const panels = this.panels();
    for (const panel of panels) if (panel.el.parentNode !== this.list) this.list.append(panel.el);
    this.empty.hidden = panels.length > 0;
    this.tab.textContent = panels.length ? `Windows (${panels.length})` : "Windows";
    this._watch();
  }

  _watch() {
    const watched = this.shown && document.visibilityState === "visible";
    for (const panel of this.panels()) panel.setWatched(watched);
  }
}
