// The 3D view (rviz in the dashboard): the TF tree fed by /tf and /tf_static, the fixed frame,
// the simulator's world, the displays added by topic, the camera, and what is remembered.
// Each animation frame it builds one context (fixed frame, what changed in TF, a lookup cached for
// the frame) and lets the world and every display apply their newest data; then the scene draws.

import * as THREE from "three";
import { TopicSocket } from "../api.js";
import { createDisplay, hasDisplay } from "./displays/index.js";
import { DisplaysPanel } from "./panel.js";
import { downloadDocument, loadStored, readDocument, settingsDocument, store } from "./persistence.js";
import { Scene3D } from "./scene.js";
import { TfTree } from "./tf_tree.js";
import { SimWorld } from "./world/index.js";

const SAVE_DELAY_MS = 300;
// The drone and the robots are drawn at least this wide on the canvas: at their true size close
// up, larger when the whole world is in view (a 0.55 m drone in a 30 m arena is a few pixels).
const MIN_MODEL_PX = 40;
const TF_QUEUE = 1000; // /tf is read whole (every edge matters); the core's queue bounds it

export class View3D {
  constructor(elements, { config }) {
    this.el = elements;
    this.tf = new TfTree();
    this.displays = new Map(); // topic -> Display
    this.scene = new Scene3D(elements.canvas, {
      onTick: (now) => this._tick(now),
      // Framed for another shape of canvas (framed while hidden, or the window resized): frame
      // again, unless the user has moved the camera since.
      onResize: () => this._framedUntouched && this.frameWorld({ auto: true }),
    });
    this.world = new SimWorld(config.worlds, this.tf);
    this.scene.add(this.world.root);
    this.fixedFrameChoice = null; // the user's, or null: the tree's default
    this.fixedFrame = null; // what the last frame used
    this.follow = false;
    this._approach = false; // Follow was switched on: bring the camera close at the next frame
    // Which world the camera was set up for (framed, restored, or moved by the user in it): a
    // world that appears and is not that one is framed, so the view opens on it.
    this._cameraWorld = null;
    this._userMoved = false;
    this._framedUntouched = false; // the camera is as the view framed it by itself
    this._seen = { tf: -1, structure: -1 };
    this._sockets = [];
    this._saveTimer = 0;
    this._cameraMoved = false;
    this.panel = new DisplaysPanel(this, elements);
    elements.top.addEventListener("click", () => this.topDown());
    elements.followButton.addEventListener("click", () => this.setFollow(!this.follow, { approach: true }));
    elements.reset.addEventListener("click", () => this.resetCamera());
    this.scene.controls.addEventListener("start", () => {
      this._userMoved = true;
      this._framedUntouched = false;
      this._cameraWorld = this.world.kind() ?? this._cameraWorld;
    });
    this.scene.controls.addEventListener("end", () => this._save());
    // A change made just before a reload or a closed tab is kept: the pending save is written now.
    window.addEventListener("pagehide", () => this._flushSave());
  }

  /** Subscribe to TF and the world, restore the last visit's settings. */
  start() {
    // Read once someone publishes them (the robot world, a user's node): rviz's subscription
    // would otherwise make the core list /tf untyped in a world without TF.
    const tf = (topic, isStatic) =>
      new TopicSocket(topic, { queue: TF_QUEUE, mode: "subscribe", onMessage: (msg) => this.tf.applyMessage(msg, isStatic) }).openWhenPublished();
    this._sockets.push(tf("/tf", false), tf("/tf_static", true));
    this.world.start();
    const stored = loadStored(hasDisplay);
    if (stored) this._apply(stored);
    else this.resetCamera();
    this.panel.render();
  }

  setShown(shown) {
    this.scene.setShown(shown);
  }

  updateGraph(graph) {
    this.panel.updateGraph(graph);
  }

  // -- displays ---------------------------------------------------------------------------------

  addDisplay(topic, type, settings = {}) {
    if (this.displays.has(topic) || !hasDisplay(type)) return null;
    if (type === "tf2_msgs/msg/TFMessage" && [...this.displays.values()].some((d) => d.type === type)) {
      this.panel.showFileResult("refused", "The TF display already shows the frames of /tf and /tf_static.");
      return null;
    }
    const display = createDisplay(topic, type, { color: this.panel.nextColor(), ...settings }, { tf: this.tf, images: this.el.images });
    this.displays.set(topic, display);
    this.scene.add(display.root);
    display.start();
    this.panel.render();
    this._save();
    return display;
  }

  removeDisplay(topic) {
    const display = this.displays.get(topic);
    if (!display) return;
    display.dispose();
    this.displays.delete(topic);
    this.scene.invalidate();
    this.panel.render();
    this._save();
  }

  setDisplayVisible(key, visible) {
    const target = key === "world" ? this.world : this.displays.get(key);
    if (!target) return;
    target.setVisible(visible);
    this.scene.invalidate();
    this._save();
  }

  setDisplayColor(key, color) {
    this.displays.get(key)?.setColor(color);
    this.scene.invalidate();
    this._save();
  }

  setDisplayOption(key, name, value) {
    this.displays.get(key)?.setOption(name, value);
    this.scene.invalidate();
    this._save();
  }

  setGridVisible(visible) {
    this.scene.grid.visible = visible;
    this.scene.invalidate();
    this._save();
  }

  // -- frames and camera ------------------------------------------------------------------------

  /** Use `name` as the fixed frame, or null for the tree's default (the root of its biggest tree). */
  setFixedFrame(name) {
    this.fixedFrameChoice = name || null;
    this._save();
  }

  effectiveFixedFrame() {
    return this.fixedFrameChoice || this.tf.defaultFixedFrame();
  }

  /** What is wrong with the view as a whole (rviz's "Global Status"), or "". */
  globalStatus() {
    const frame = this.effectiveFixedFrame();
    if (this.tf.has(frame)) return "";
    const known = this.tf.frames();
    return known.length
      ? `Fixed frame [${frame}] does not exist. Frames: ${known.join(", ")}.`
      : `Fixed frame [${frame}] does not exist: no frames yet (nothing on /tf, /tf_static or the simulator's topics).`;
  }

  topDown() {
    this.setFollow(false);
    this._framedUntouched = false;
    const target = this.world.followPoint() || new THREE.Vector3();
    this.scene.topDown(new THREE.Vector3(target.x, target.y, 0), this.world.extent() * 2.2);
    this._save();
  }

  /** The world framed (Reset view; Follow stops); before any world is known, a guess from the side. */
  resetCamera() {
    this.setFollow(false);
    if (this.world.kind()) {
      this.frameWorld();
      return;
    }
    const r = this.world.extent();
    this.scene.setCamera([-1.1 * r, -1.1 * r, 0.9 * r], [0, 0, 0]);
    this._save();
  }

  /** Fill the canvas with the world the simulator runs (its arena, or its room), seen from above
   * the south-west corner, as the view opens. */
  frameWorld({ auto = false } = {}) {
    const kind = this.world.kind();
    if (!kind) return;
    const bounds = this.world.bounds();
    const map = new THREE.Matrix4();
    const found = this.tf.lookup(this.effectiveFixedFrame(), "map", null, map);
    if (!found.error) bounds.applyMatrix4(map);
    this.scene.frameBox(bounds);
    this._cameraWorld = kind;
    this._framedUntouched = auto;
    this._save();
  }

  /** Follow the robot (or drone); `approach`: bring the camera close to it too (the button). */
  setFollow(follow, { approach = false } = {}) {
    this.follow = follow;
    if (follow) this._framedUntouched = false;
    this._approach = follow && approach;
    this.el.followButton.setAttribute("aria-pressed", String(follow));
    this._save();
  }

  // -- saving -----------------------------------------------------------------------------------

  document() {
    return settingsDocument({
      fixedFrame: this.fixedFrameChoice,
      camera: { ...this.scene.cameraState(), follow: this.follow, world: this._cameraWorld },
      grid: this.scene.grid.visible,
      world: this.world.visible,
      displays: [...this.displays.values()].map((d) => d.settings()),
    });
  }

  _save() {
    clearTimeout(this._saveTimer);
    this._saveTimer = setTimeout(() => this._flushSave(), SAVE_DELAY_MS);
  }

  _flushSave() {
    if (!this._saveTimer) return;
    clearTimeout(this._saveTimer);
    this._saveTimer = 0;
    store(this.document());
  }

  saveToFile() {
    downloadDocument(this.document());
  }

  /** Replace the displays, frame and camera with a file's; returns [kind, message] for the panel. */
  async loadFromFile(file) {
    let result;
    try {
      result = await readDocument(file, hasDisplay);
    } catch (error) {
      return ["error", `${file.name}: ${error.message}. Nothing was changed.`];
    }
    for (const topic of [...this.displays.keys()]) this.removeDisplay(topic);
    this._apply(result.settings);
    this.panel.render();
    this._save();
    const count = result.settings.displays.length;
    const loaded = `${file.name}: ${count} display${count === 1 ? "" : "s"} loaded`;
    return result.warnings.length ? ["refused", `${loaded}; skipped: ${result.warnings.join("; ")}`] : ["success", loaded];
  }

  _apply(settings) {
    this.fixedFrameChoice = settings.fixedFrame;
    if (settings.camera) {
      this.scene.setCamera(settings.camera.position, settings.camera.target);
      this.setFollow(settings.camera.follow);
      this._cameraWorld = settings.camera.world;
      this._framedUntouched = false;
    }
    this.scene.grid.visible = settings.grid;
    this.world.setVisible(settings.world);
    for (const d of settings.displays) this.addDisplay(d.topic, d.type, d);
  }

  // -- the frame --------------------------------------------------------------------------------

  _tick(nowMs) {
    const tf = this.tf;
    const fixedFrame = this.effectiveFixedFrame();
    const cache = new Map();
    const ctx = {
      now: nowMs / 1000,
      fixedFrame,
      fixedFrameChanged: fixedFrame !== this.fixedFrame,
      tfChanged: tf.version !== this._seen.tf,
      tfStructureChanged: tf.structureVersion !== this._seen.structure,
      /** out = the transform from `frame` at `stamp` into the fixed frame; {matrix, clockNote} or {error}. */
      lookup: (frame, stamp, out) => {
        const key = `${frame}@${stamp}`;
        let found = cache.get(key);
        if (!found) {
          const result = tf.lookup(fixedFrame, frame, stamp, new THREE.Matrix4());
          cache.set(key, (found = result));
        }
        if (found.error) return found;
        out.copy(found.matrix);
        return { matrix: out, clockNote: found.clockNote, ahead: found.ahead };
      },
    };
    this.fixedFrame = fixedFrame;
    this._seen = { tf: tf.version, structure: tf.structureVersion };
    let changed = this.world.update(ctx);
    for (const display of this.displays.values()) {
      try {
        changed = display.update(ctx) || changed;
      } catch (error) {
        // A bug in one display must not stop the others: say it on that display.
        display.setStatus("Error", "error", `internal error: ${error.message}`);
      }
    }
    const kind = this.world.kind();
    if (kind && kind !== this._cameraWorld) {
      if (this._userMoved && this._cameraWorld === null) this._cameraWorld = kind; // moved before: kept
      else this.frameWorld({ auto: true });
    }
    if (this.follow) {
      const point = this.world.followPoint();
      if (point) {
        this.scene.follow(point);
        if (this._approach) this.scene.approach(this.world.followDistance());
        this._approach = false;
      }
    }
    if (this.world.fitModels((point) => this.scene.pixelsPerMetre(point), MIN_MODEL_PX)) changed = true;
    const extent = this.world.extent();
    this.scene.setGrid(Math.ceil(extent * 2.5), 1);
    this.scene.fixedAxes.scale.setScalar(Math.max(0.3, extent / 10));
    if (ctx.tfStructureChanged || ctx.fixedFrameChanged) {
      this.panel.renderFrames(tf.frames(), this.fixedFrameChoice, fixedFrame);
    }
    return changed;
  }

  // -- the debug hook ---------------------------------------------------------------------------

  /** Plain data for `window.skydeck.view3d()`: what is drawn, in the fixed frame; frame times
   * over the last `statsFrames` frames. */
  snapshot({ statsFrames } = {}) {
    return {
      shown: this.scene.shown,
      // The frame the last drawn frame used: a new choice shows here once it is drawn in.
      fixedFrame: this.fixedFrame ?? this.effectiveFixedFrame(),
      fixedFrameChoice: this.fixedFrameChoice,
      globalStatus: this.globalStatus(),
      frames: this.tf.snapshot(),
      camera: {
        ...this.scene.cameraState(),
        follow: this.follow,
        world: this._cameraWorld,
        fov: this.scene.camera.fov, // vertical, degrees
        canvas: [this.el.canvas.clientWidth, this.el.canvas.clientHeight],
      },
      world: this.world.snapshot(),
      grid: this.scene.grid.visible,
      axes: this.scene.axesState(),
      displays: [...this.displays.values()].map((d) => d.snapshot()),
      frameStats: this.scene.stats.summary(statsFrames),
      softwareRendering: this.scene.software,
    };
  }
}
