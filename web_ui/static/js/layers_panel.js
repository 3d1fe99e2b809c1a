// The Layers tab: choose a drawable topic from the graph, give it a colour, add or remove it.

import { isDrawable } from "./layers.js";

export class LayersPanel {
  constructor({ layers, select, color, form, list }) {
    this.layers = layers;
    this.select = select;
    this.color = color;
    this.list = list;
    this._types = new Map(); // drawable topic -> type, from the graph
    this._lastCounts = "";
    form.addEventListener("submit", (event) => {
      event.preventDefault();
      const topic = select.value;
      if (!topic) return;
      this.layers.add(topic, this._types.get(topic), color.value);
      color.value = this.layers.nextColor();
    });
    layers.addEventListener("change", () => this._renderIfChanged());
    this._renderOptions();
    this._render();
  }

  updateGraph(graph) {
    const types = new Map(graph.topics.filter((t) => isDrawable(t.type)).map((t) => [t.name, t.type]));
    const before = [...this._types.entries()].join();
    this._types = types;
    if ([...types.entries()].join() !== before) this._renderOptions();
  }

  _renderOptions() {
    const current = this.select.value;
    this.select.replaceChildren();
    const names = [...this._types.keys()].sort();
    if (!names.length) this.select.append(new Option("no drawable topics yet", ""));
    for (const name of names) {
      const type = this._types.get(name).split("/").pop();
      this.select.append(new Option(`${name} (${type})`, name));
    }
    if (names.includes(current)) this.select.value = current;
  }

  _renderIfChanged() {
    // Frames arrive at 10 Hz per layer: rebuild the list only when what it shows changes.
    const key = this.layers
      .list()
      .map((l) => `${l.topic}:${l.points.length}:${l.frame}:${l.messages > 0}`)
      .join("|");
    if (key !== this._lastCounts) this._render();
    this._lastCounts = key;
  }

  _render() {
    this.list.replaceChildren();
    const layers = this.layers.list();
    if (!layers.length) {
      const li = document.createElement("li");
      li.className = "dim";
      li.textContent = "No layers. The drone, boxes, track and tour are always drawn.";
      this.list.append(li);
    }
    for (const layer of layers) {
      const li = document.createElement("li");
      li.dataset.topic = layer.topic;
      const color = document.createElement("input");
      color.type = "color";
      color.value = layer.color;
      color.title = "colour";
      color.addEventListener("input", () => this.layers.setColor(layer.topic, color.value));
      const name = document.createElement("span");
      name.className = "mono";
      name.textContent = layer.topic;
      const info = document.createElement("span");
      info.className = "dim layer-info";
      const frame = layer.frame ? `, frame ${layer.frame}` : "";
      info.textContent = layer.messages
        ? `${layer.points.length} point${layer.points.length === 1 ? "" : "s"}${frame}`
        : "waiting for a message…";
      const remove = document.createElement("button");
      remove.type = "button";
      remove.className = "small ghost";
      remove.textContent = "Remove";
      remove.dataset.action = "remove";
      remove.addEventListener("click", () => this.layers.remove(layer.topic));
      li.append(color, name, info, remove);
      this.list.append(li);
    }
  }
}
