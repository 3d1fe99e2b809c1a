// The 3D view's door: main.js talks to this module, which imports three.js and the view only when
// the 3D tab is first opened (or when the last visit left displays to restore), so the rest of the
// dashboard never waits for, nor breaks on, the 3D library.

import { config } from "../config.js";
import { hasStored } from "./persistence.js";

/** The 3D pane's elements by role (index.html, ids `view3d-*`). */
function elementsOf(root) {
  const $ = (id) => root.querySelector(`#view3d-${id}`);
  return {
    canvas: $("canvas"),
    images: $("images"),
    status: $("status"),
    fps: $("fps"),
    fixedFrame: $("fixed-frame"),
    top: $("top"),
    followButton: $("follow"),
    reset: $("reset"),
    addForm: $("add-form"),
    addSelect: $("add-select"),
    addColor: $("add-color"),
    list: $("displays"),
    save: $("save"),
    load: $("load"),
    fileResult: $("file-result"),
  };
}

export class View3DLoader {
  /** `root`: the 3D pane (#view3d). */
  constructor(root) {
    this.el = elementsOf(root);
    this.view = null;
    this.shown = false;
    this._loading = null;
    this._graph = null;
    if (hasStored()) this.load(); // displays to restore: keep them fed
  }

  /** Import and start the view once; resolves to it, or null when three.js cannot be loaded. */
  load() {
    this._loading ||= import("./view3d.js")
      .then(({ View3D }) => {
        this.view = new View3D(this.el, { config });
        this.view.start();
        if (this._graph) this.view.updateGraph(this._graph);
        this.view.setShown(this.shown);
        return this.view;
      })
      .catch((error) => {
        this.el.status.hidden = false;
        this.el.status.textContent = `The 3D view could not load (${error.message}). Is three.js installed? Run \`make install\`.`;
        return null;
      });
    return this._loading;
  }

  setShown(shown) {
    this.shown = shown;
    if (this.view) this.view.setShown(shown);
    else if (shown) this.load();
  }

  updateGraph(graph) {
    this._graph = graph;
    if (this.view) this.view.updateGraph(graph);
  }

  /** The view's state for `window.skydeck.view3d()`, or null before it has loaded. */
  snapshot(options) {
    return this.view ? this.view.snapshot(options) : null;
  }
}
