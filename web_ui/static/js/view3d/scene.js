// The 3D view's stage: renderer, camera, orbit controls (left drag orbits, right drag pans, wheel
// zooms), the grid and the fixed frame's axes. Coordinates are ROS's (x forward, y left, z up),
// the scene's root is the fixed frame. Draws on animation frames only while shown, and only when
// something changed; every frame's timing is kept for the figures in docs/performance.md.

import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";
import { disposeObject, makeAxes } from "./shapes.js";

const STATS_FRAMES = 600; // about 10 s of frames at 60 Hz

/** Whether WebGL runs on a software rasteriser (no GPU: SwiftShader, llvmpipe), where
 * antialiasing costs a third of the frame rate; it is turned off there. */
function softwareRendering() {
  const gl = document.createElement("canvas").getContext("webgl2");
  if (!gl) return false;
  const info = gl.getExtension("WEBGL_debug_renderer_info");
  const name = String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER));
  gl.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

/** Timing of the last frames: the interval between animation frames, and in each drawn frame our
 * work: applying data to the scene (update) and three.js issuing the draw (draw). */
class FrameStats {
  constructor() {
    this.intervals = [];
    this.work = [];
    this.update = [];
    this.draw = [];
    this.rendered = 0;
    this.ticks = 0;
    this._last = 0;
  }

  record(now, updateMs, drawMs) {
    if (this._last) push(this.intervals, now - this._last);
    this._last = now;
    this.ticks += 1;
    if (drawMs !== null) {
      this.rendered += 1;
      push(this.work, updateMs + drawMs);
      push(this.update, updateMs);
      push(this.draw, drawMs);
    }
  }

  /** A pause (hidden tab): the next interval is not a frame time. */
  pause() {
    this._last = 0;
  }

  /** Percentiles of the last `frames` frames (all kept, by default). */
  summary(frames = STATS_FRAMES) {
    const interval = percentiles(this.intervals.slice(-frames));
    return {
      ticks: this.ticks,
      rendered: this.rendered,
      fps: interval.mean ? 1000 / interval.mean : 0,
      intervalMs: interval,
      workMs: percentiles(this.work.slice(-frames)),
      updateMs: percentiles(this.update.slice(-frames)),
      drawMs: percentiles(this.draw.slice(-frames)),
    };
  }
}

function push(list, value) {
  list.push(value);
  if (list.length > STATS_FRAMES) list.shift();
}

function percentiles(values) {
  if (!values.length) return { count: 0, mean: 0, p50: 0, p95: 0, max: 0 };
  const sorted = [...values].sort((a, b) => a - b);
  const at = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
  const mean = sorted.reduce((sum, v) => sum + v, 0) / sorted.length;
  return { count: sorted.length, mean, p50: at(0.5), p95: at(0.95), max: sorted[sorted.length - 1] };
}

export class Scene3D {
  /** `onTick(now)` runs every animation frame while shown; it returns true when it changed the scene. */
  /** `onResize()` runs when the canvas changes size (after the camera's aspect follows it). */
  constructor(canvas, { onTick, onResize = () => {} }) {
    this.canvas = canvas;
    this.onTick = onTick;
    this.onResize = onResize;
    this.software = softwareRendering();
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: !this.software });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x0e1319);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.05, 1000);
    this.camera.up.set(0, 0, 1); // ROS: z up
    this.camera.position.set(-10, -10, 9);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.screenSpacePanning = false; // pan along the ground, as rviz's orbit view
    this.controls.maxPolarAngle = Math.PI * 0.499;
    this.controls.addEventListener("change", () => this.invalidate());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x334455, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(-3, -5, 10);
    this.scene.add(sun);
    this.fixedAxes = makeAxes(1, 0.03);
    this.scene.add(this.fixedAxes);
    this.grid = null;
    this.setGrid(20, 1);
    this.stats = new FrameStats();
    this.shown = false;
    this._dirty = true;
    this._raf = 0;
    new ResizeObserver(() => this._resize()).observe(canvas.parentElement);
  }

  /** Draw at the next animation frame. */
  invalidate() {
    this._dirty = true;
  }

  add(object) {
    this.scene.add(object);
    this.invalidate();
  }

  remove(object) {
    this.scene.remove(object);
    this.invalidate();
  }

  /** A square grid `size` metres across, lines every `cell` metres, in the fixed frame's xy plane. */
  setGrid(size, cell) {
    if (this.grid && this.grid.userData.size === size && this.grid.userData.cell === cell) return;
    const visible = this.grid ? this.grid.visible : true;
    if (this.grid) {
      this.scene.remove(this.grid);
      disposeObject(this.grid);
    }
    const divisions = Math.max(1, Math.round(size / cell));
    this.grid = new THREE.GridHelper(divisions * cell, divisions, 0x3a4a5c, 0x243140);
    this.grid.rotation.x = Math.PI / 2; // GridHelper lies in xz; ROS's ground is xy
    this.grid.userData = { size, cell };
    this.grid.visible = visible;
    this.scene.add(this.grid);
    this.invalidate();
  }

  setShown(shown) {
    if (shown === this.shown) return;
    this.shown = shown;
    if (shown) {
      this._resize();
      this.invalidate();
      this._raf = requestAnimationFrame(this._frame);
    } else {
      cancelAnimationFrame(this._raf);
      this._raf = 0;
      this.stats.pause();
    }
  }

  /** For the debug hook: whether the fixed frame's axes and the grid are drawn, and where each
   * axis ends (x, y, z in the fixed frame, metres; the axes grow with the world). */
  axesState() {
    this.fixedAxes.updateMatrixWorld(true);
    const tips = this.fixedAxes.children.map((rod) => {
      const tip = new THREE.Vector3(0, 0, 0.5).applyMatrix4(rod.matrixWorld);
      return tip.toArray().map((v) => Math.round(v * 1000) / 1000);
    });
    return { shown: this.fixedAxes.visible && this.fixedAxes.parent === this.scene, tips };
  }

  /** Camera position and orbit target as plain arrays (for the saved view). */
  cameraState() {
    return { position: this.camera.position.toArray(), target: this.controls.target.toArray() };
  }

  setCamera(position, target) {
    this.camera.position.fromArray(position);
    this.controls.target.fromArray(target);
    this.controls.update();
    this.invalidate();
  }

  /** Look straight down on `target` from `height` m, +x to the right and +y up, as the 2D map. */
  topDown(target, height) {
    // A hair south of vertical: orbit controls need a direction to call "up" on the screen.
    this.setCamera([target.x, target.y - height * 1e-3, target.z + height], [target.x, target.y, target.z]);
  }

  /**
   * Look at `box` (a THREE.Box3 in the fixed frame) from the south-west and above, as close as
   * keeps all of it in view: the world fills the canvas (`fill` of its half-width or half-height
   * from the centre, the tighter of the two). Perspective draws the near side larger, so the orbit
   * target (on the box's floor) slides along the view until the box sits in the middle of the
   * canvas, as much above the centre as below.
   */
  frameBox(box, { azimuth = -Math.PI * 0.75, elevation = 0.62, fill = 0.94 } = {}) {
    const centre = box.getCenter(new THREE.Vector3()).setZ(box.min.z);
    const ahead = new THREE.Vector3(Math.cos(azimuth), Math.sin(azimuth), 0).negate(); // away from the camera
    const direction = new THREE.Vector3(
      Math.cos(azimuth) * Math.cos(elevation),
      Math.sin(azimuth) * Math.cos(elevation),
      Math.sin(elevation),
    );
    const corners = [];
    for (const x of [box.min.x, box.max.x])
      for (const y of [box.min.y, box.max.y]) for (const z of [box.min.z, box.max.z]) corners.push(new THREE.Vector3(x, y, z));
    const probe = this.camera.clone();
    const extent = (target, distance) => {
      probe.position.copy(target).addScaledVector(direction, distance);
      probe.lookAt(target);
      probe.updateMatrixWorld(true);
      let [left, right, bottom, top] = [Infinity, -Infinity, Infinity, -Infinity];
      for (const corner of corners) {
        const ndc = corner.clone().project(probe);
        if (ndc.z >= 1) return null; // behind the camera
        [left, right, bottom, top] = [Math.min(left, ndc.x), Math.max(right, ndc.x), Math.min(bottom, ndc.y), Math.max(top, ndc.y)];
      }
      return { left, right, bottom, top };
    };
    const fits = (e) => e !== null && Math.max(-e.left, e.right, -e.bottom, e.top) <= fill;
    // The nearest distance at which the box fits (fitting only gets easier further away).
    const nearest = (target) => {
      let [near, far] = [0.1, 10];
      while (!fits(extent(target, far)) && far < 1e5) far *= 2;
      for (let i = 0; i < 40; i++) {
        const mid = (near + far) / 2;
        if (fits(extent(target, mid))) far = mid;
        else near = mid;
      }
      return far;
    };
    // Slide the target until the box is as far above the centre as below (bisection: sliding it
    // away from the camera lowers the box on the canvas).
    const reach = box.getSize(new THREE.Vector3()).length();
    let [back, forth] = [-reach, reach];
    let target = centre.clone();
    for (let i = 0; i < 30; i++) {
      const shift = (back + forth) / 2;
      target = centre.clone().addScaledVector(ahead, shift);
      const e = extent(target, nearest(target));
      if (e.top + e.bottom > 0) back = shift;
      else forth = shift;
    }
    const distance = nearest(target);
    this.setCamera(target.clone().addScaledVector(direction, distance).toArray(), target.toArray());
  }

  /** Canvas pixels per metre at `point`, at its distance from the camera (the view's scale there). */
  pixelsPerMetre(point) {
    const distance = Math.max(this.camera.position.distanceTo(point), 1e-3);
    const height = this.canvas.clientHeight || this.canvas.height;
    return height / (2 * distance * Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2)));
  }

  /** Bring the camera to `distance` metres from the orbit target, looking from where it looks now. */
  approach(distance) {
    const offset = this.camera.position.clone().sub(this.controls.target);
    if (offset.length() <= distance) return;
    this.camera.position.copy(this.controls.target).addScaledVector(offset.normalize(), distance);
    this.controls.update();
    this.invalidate();
  }

  /** Move the orbit target to `point`, carrying the camera along (the follow view). */
  follow(point) {
    const target = this.controls.target;
    if (target.distanceToSquared(point) < 1e-8) return;
    const delta = point.clone().sub(target);
    target.add(delta);
    this.camera.position.add(delta);
    this.controls.update();
    this.invalidate();
  }

  _frame = (now) => {
    if (!this.shown) return;
    this._raf = requestAnimationFrame(this._frame);
    const start = performance.now();
    const changed = this.onTick(now);
    const updated = performance.now();
    let drawMs = null;
    if ((changed || this._dirty) && this.canvas.width > 1 && this.canvas.height > 1) {
      this.renderer.render(this.scene, this.camera);
      this._dirty = false;
      drawMs = performance.now() - updated;
    }
    this.stats.record(now, updated - start, drawMs);
  };

  _resize() {
    const rect = this.canvas.parentElement.getBoundingClientRect();
    if (rect.width < 2 || rect.height < 2) return;
    this.renderer.setSize(rect.width, rect.height, false);
    this.canvas.style.width = `${rect.width}px`;
    this.canvas.style.height = `${rect.height}px`;
    const aspect = rect.width / rect.height;
    if (Math.abs(aspect - this.camera.aspect) < 1e-3) return;
    this.camera.aspect = aspect;
    this.camera.updateProjectionMatrix();
    this.invalidate();
    this.onResize();
  }
}
