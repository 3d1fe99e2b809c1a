// The 3D view's controls, as rviz's Displays panel: the fixed frame, "add by topic" from the live
// topics that have a display, and one row per display (show, colour, options, status, remove).
// The list is rebuilt when displays come or go; a row's status only when it changed.

import { DISPLAY_TYPES } from "./displays/index.js";

const TF_TYPE = "tf2_msgs/msg/TFMessage";
const PALETTE = ["#ff5fd2", "#4dd0e1", "#ffd54f", "#aed581", "#ff8a65", "#b39ddb"];
const STATUS_REFRESH_MS = 250;

function element(tag, props = {}, ...children) {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
}

export class DisplaysPanel {
  /** `view` is the View3D: the panel reads its displays and calls its verbs. */
  constructor(view, elements) {
    this.view = view;
    this.el = elements;
    this._topics = new Map(); // live topic -> type, for "add by topic"
    this._optionsKey = "";
    this._framesKey = "";
    this._statusVersions = new Map();
    elements.addForm.addEventListener("submit", (event) => {
      event.preventDefault();
      const topic = elements.addSelect.value;
      if (!topic) return;
      view.addDisplay(topic, this._topics.get(topic), { color: elements.addColor.value });
      elements.addColor.value = this.nextColor();
    });
    elements.fixedFrame.addEventListener("change", () => view.setFixedFrame(elements.fixedFrame.value || null));
    elements.save.addEventListener("click", () => view.saveToFile());
    elements.load.addEventListener("change", async () => {
      const [file] = elements.load.files;
      elements.load.value = "";
      if (file) this.showFileResult(...(await view.loadFromFile(file)));
    });
    elements.addColor.value = this.nextColor();
    setInterval(() => this.refresh(), STATUS_REFRESH_MS);
  }

  nextColor() {
    return PALETTE[this.view.displays.size % PALETTE.length];
  }

  /** The graph changed: offer its topics that have a display and are not shown yet. */
  updateGraph(graph) {
    this._topics = new Map(graph.topics.filter((t) => DISPLAY_TYPES.has(t.type)).map((t) => [t.name, t.type]));
    this.renderOptions();
  }

  renderOptions() {
    // One TF display draws the whole tree: once there is one, /tf and /tf_static have nothing to add.
    const hasTf = [...this.view.displays.values()].some((d) => d.type === TF_TYPE);
    const names = [...this._topics.keys()]
      .filter((name) => !this.view.displays.has(name) && !(hasTf && this._topics.get(name) === TF_TYPE))
      .sort();
    const key = names.map((n) => `${n}:${this._topics.get(n)}`).join("|");
    if (key === this._optionsKey) return;
    this._optionsKey = key;
    const select = this.el.addSelect;
    const current = select.value;
    select.replaceChildren();
    if (!names.length) select.append(new Option("no topics with a display", ""));
    for (const name of names) select.append(new Option(`${name} (${this._topics.get(name).split("/").pop()})`, name));
    if (names.includes(current)) select.value = current;
  }

  /** Rebuild the fixed-frame choices when the tree's frames change. */
  renderFrames(frames, chosen, effective) {
    const key = `${frames.join(",")}|${chosen}|${effective}`;
    if (key === this._framesKey) return;
    this._framesKey = key;
    const select = this.el.fixedFrame;
    select.replaceChildren(new Option(`auto (${effective})`, ""));
    const names = chosen && !frames.includes(chosen) ? [...frames, chosen] : frames;
    for (const name of names) select.append(new Option(frames.includes(name) ? name : `${name} (missing)`, name));
    select.value = chosen || "";
  }

  /** Rebuild the list of displays (after an add, a remove, a load). */
  render() {
    const rows = [this._row("world", this.view.world, { removable: false, colored: false })];
    rows.push(this._gridRow());
    for (const display of this.view.displays.values()) {
      rows.push(this._row(display.topic, display, { removable: true, colored: display.constructor.colored }));
    }
    this.el.list.replaceChildren(...rows);
    this._statusVersions.clear();
    this.renderOptions();
    this.refresh();
  }

  _gridRow() {
    const li = element("li", { className: "display" });
    li.dataset.display = "grid";
    const visible = element("input", { type: "checkbox", checked: this.view.scene.grid.visible, title: "show" });
    visible.dataset.action = "visible";
    visible.addEventListener("change", () => this.view.setGridVisible(visible.checked));
    const name = element("span", { className: "display-name" }, "Grid");
    li.append(element("div", { className: "display-head" }, visible, name, element("span", { className: "dim small-text" }, "1 m cells")));
    return li;
  }

  _row(key, display, { removable, colored }) {
    const li = element("li", { className: "display" });
    li.dataset.display = key;
    if (removable) {
      li.dataset.topic = display.topic;
      li.dataset.type = display.type;
    }
    const visible = element("input", { type: "checkbox", checked: display.visible, title: "show" });
    visible.dataset.action = "visible";
    visible.addEventListener("change", () => this.view.setDisplayVisible(key, visible.checked));
    const head = element("div", { className: "display-head" }, visible);
    if (colored) {
      const color = element("input", { type: "color", value: display.color, title: "colour" });
      color.dataset.action = "color";
      color.addEventListener("input", () => this.view.setDisplayColor(key, color.value));
      head.append(color);
    }
    head.append(element("span", { className: "display-name mono" }, removable ? display.topic : display.label));
    if (removable) {
      head.append(element("span", { className: "dim small-text" }, display.label));
      const remove = element("button", { type: "button", className: "small ghost", textContent: "×", title: `remove ${display.topic}` });
      remove.dataset.action = "remove";
      remove.addEventListener("click", () => this.view.removeDisplay(key));
      head.append(remove);
    }
    li.append(head);
    const specs = Object.entries((display.constructor && display.constructor.options) || {});
    if (removable && specs.length) li.append(this._options(key, display, specs));
    li.append(element("ul", { className: "display-status" }));
    return li;
  }

  _options(key, display, specs) {
    const box = element("div", { className: "display-options" });
    for (const [name, spec] of specs) {
      const input = element("input", spec.type === "bool" ? { type: "checkbox", checked: display.options[name] } : {
        type: "number",
        value: String(display.options[name]),
        min: String(spec.min),
        max: String(spec.max),
        step: String(spec.step ?? "any"),
      });
      input.dataset.option = name;
      input.addEventListener("change", () => {
        const value = spec.type === "bool" ? input.checked : Number(input.value);
        this.view.setDisplayOption(key, name, value);
      });
      box.append(element("label", {}, input, ` ${spec.label}`));
    }
    return box;
  }

  /** Redraw the status lines of displays whose status changed; the frame rate; the global status. */
  refresh() {
    for (const li of this.el.list.querySelectorAll("li.display")) {
      const key = li.dataset.display;
      const source = key === "world" ? this.view.world : this.view.displays.get(key);
      if (!source) continue;
      if (this._statusVersions.get(key) === source.statuses.version) continue;
      this._statusVersions.set(key, source.statuses.version);
      const status = source.status();
      li.dataset.level = status.level;
      const lines = status.entries.map((entry) => {
        const line = element("li", { textContent: `${entry.key}: ${entry.text}` });
        line.dataset.level = entry.level;
        line.dataset.key = entry.key;
        return line;
      });
      if (status.hidden) lines.push(element("li", { className: "dim", textContent: `and ${status.hidden} more` }));
      li.querySelector(".display-status").replaceChildren(...lines);
    }
    const stats = this.view.scene.stats.summary();
    this.el.fps.textContent = stats.workMs.count ? `${stats.fps.toFixed(0)} fps · ${stats.workMs.p50.toFixed(1)} ms/frame` : "";
    const global = this.view.globalStatus();
    this.el.status.hidden = !global;
    this.el.status.textContent = global;
  }

  /** Say how loading a file went. */
  showFileResult(kind, message) {
    this.el.fileResult.dataset.kind = kind;
    this.el.fileResult.textContent = message;
  }
}
